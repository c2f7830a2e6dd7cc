#include "input/unbounded_domain.hpp"

namespace linkbox::input {

std::string assumed_bound(const std::string& name, const std::string& lower, const std::string& upper) {
  return name + " in [" + (lower.empty() ? "-1e8" : lower) + ", " + (upper.empty() ? "1e8" : upper) + "]";
}

}  // namespace linkbox::input
