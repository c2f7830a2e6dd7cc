#include "model/lph.hpp"

#include <algorithm>
#include <stdexcept>

namespace linkbox::model {

Box LphSystem::domain() const {
  Box b;
  for (auto& v : variables) b.push_back(v.domain);
  return b;
}

Box lift(const LphSystem& lph, Box box) {
  const size_t n = lph.variables.size();
  for (size_t i = box.size(); i < n; ++i) box.push_back(lph.variables[i].domain);
  // Definitions by the variable they define; evaluated in index order, which is definition
  // order for to_lph's systems. Other systems may define a dummy from a later one: repeat
  // until nothing is pending (a cycle of definitions is an error).
  struct Def {
    int target, x, y;  // y < 0: q = x^2
  };
  std::vector<Def> defs;
  for (auto& e : lph.parabolic) defs.push_back({e.q, e.x, -1});
  for (auto& e : lph.hyperbolic) defs.push_back({e.b, e.x, e.y});
  std::sort(defs.begin(), defs.end(), [](const Def& a, const Def& b) { return a.target < b.target; });
  std::vector<bool> known(n, true);
  for (auto& d : defs) known[d.target] = false;
  size_t pending = std::count(known.begin(), known.end(), false);
  for (size_t pass = 0; pending > 0; ++pass) {
    if (pass > defs.size()) throw std::invalid_argument("lift: cyclic dummy definitions");
    for (auto& d : defs) {
      if (known[d.target] || !known[d.x] || (d.y >= 0 && !known[d.y])) continue;
      box[d.target] = d.y < 0 ? boost::numeric::square(box[d.x]) : box[d.x] * box[d.y];
      known[d.target] = true;
      --pending;
    }
  }
  return box;
}

}  // namespace linkbox::model
