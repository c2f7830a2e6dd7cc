#pragma once
// Bicyclohexane (cases/linkages/bicyclohexane.toml) within a window of joint limits around a
// pose of the independent many-start computation (papers/porta-iterated-lp/
// bicyclohexane-newton.md): a few isolated poses in half a second, where the whole case takes
// half a minute.
#include "tests/cli_run.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace linkbox::test {

inline std::string bicyclohexane_text() {
  std::ifstream in(src("cases/linkages/bicyclohexane.toml"));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The classical chair torsion for bond angle pi - alpha (alpha = 1.23):
// cos w = -cos(pi - alpha) / (1 + cos(pi - alpha)).
inline double chair_torsion() { return std::acos(std::cos(1.23) / (1 - std::cos(1.23))); }

// Ring 1 a chair; ring 2 a boat ('b') or a chair ('c'): the eleven bond torsions.
inline std::map<std::string, double> bicyclohexane_pose(char ring2) {
  const double w = chair_torsion();
  std::map<std::string, double> p = {{"c1-c2", -w}, {"c2-c3", w}, {"c3-c4", -w}, {"c4-c5", w}, {"c5-c6", -w}, {"c6-c1", w}};
  if (ring2 == 'b') p.insert({{"c2-c7", w}, {"c7-c8", 0}, {"c8-c9", -w}, {"c9-c10", w}, {"c10-c1", 0}});
  else p.insert({{"c2-c7", w}, {"c7-c8", -w}, {"c8-c9", w}, {"c9-c10", -w}, {"c10-c1", w}});
  return p;
}

// `text` with every bond torsion limited to within 0.1 of `pose`.
inline std::string bicyclohexane_window(const std::string& text, const std::map<std::string, double>& pose) {
  std::ostringstream s;
  s << text << "\n[joint_limits]\n";
  s.precision(17);
  for (auto& [joint, at] : pose) s << '"' << joint << "\" = [" << at - 0.1 << ", " << at + 0.1 << "]\n";
  return s.str();
}

}  // namespace linkbox::test
