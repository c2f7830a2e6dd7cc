#include "input/unbounded_domain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace linkbox::input {

std::string unbounded_domain_advice(bool lower_infinite, bool upper_infinite, double finite_magnitude) {
  const double m = std::pow(10.0, std::ceil(std::log10(std::max(1000.0, 10 * finite_magnitude))));
  char bound[64];
  std::snprintf(bound, sizeof bound, "%g", m);
  const std::string lo = lower_infinite ? "-" + std::string(bound) : "<its lower bound>";
  const std::string hi = upper_infinite ? std::string(bound) : "<its upper bound>";
  return "linkbox encloses roots in a bounded domain only (unbounded domains are not mapped onto bounded "
         "ones). Give finite bounds that every root of interest satisfies, e.g. [" + lo + ", " + hi +
         "]: a generous bound costs a few more bisections, a root beyond it is not reported";
}

}  // namespace linkbox::input
