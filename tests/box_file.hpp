#pragma once
// Boxes kept for tests in tests/data: one "lower upper" line per variable (hex floats, so
// every bound is the one stored), lines starting with '#' are comments.
#include "interval/box.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace linkbox::test {

inline Box read_box_file(const std::string& name) {
  std::ifstream in(std::string(LINKBOX_SOURCE_DIR) + "/tests/data/" + name);
  Box box;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string lo, hi;
    fields >> lo >> hi;
    box.push_back(Interval(std::strtod(lo.c_str(), nullptr), std::strtod(hi.c_str(), nullptr)));
  }
  return box;
}

}  // namespace linkbox::test
