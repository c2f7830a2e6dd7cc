#include "model/multi_affine.hpp"

#include <stdexcept>

namespace linkbox::model {

MultiAffine MultiAffine::from(const Polynomial& p) {
  if (!p.is_multi_affine()) throw std::invalid_argument("equation is not multi-affine");
  MultiAffine m;
  m.vars = p.variables();
  if (m.vars.size() > 24) throw std::invalid_argument("multi-affine equation in more than 24 variables");
  m.coef.assign(size_t{1} << m.vars.size(), Interval(0.0));
  for (auto& [powers, c] : p.terms()) {
    size_t mask = 0;
    for (auto [v, e] : powers) {
      auto it = std::lower_bound(m.vars.begin(), m.vars.end(), v);
      mask |= size_t{1} << (it - m.vars.begin());
    }
    m.coef[mask] += c;
  }
  return m;
}

Polynomial MultiAffine::to_polynomial() const {
  Polynomial p;
  for (size_t mask = 0; mask < coef.size(); ++mask) {
    Polynomial t = Polynomial::constant(coef[mask]);
    for (size_t j = 0; j < vars.size(); ++j)
      if (mask >> j & 1) t = t * Polynomial::variable(vars[j]);
    p += t;
  }
  return p;
}

}  // namespace linkbox::model
