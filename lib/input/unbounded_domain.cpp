#include "input/unbounded_domain.hpp"

namespace linkbox::input {

std::string assumed_bound(const std::string& name, const std::string& lower, const std::string& upper) {
  const std::string bound = kDefaultBoundText;
  return name + " in [" + (lower.empty() ? "-" + bound : lower) + ", " + (upper.empty() ? bound : upper) + "]";
}

}  // namespace linkbox::input
