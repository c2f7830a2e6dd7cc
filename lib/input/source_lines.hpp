#pragma once
// Where each piece of a raw system was written (model/lifting.hpp), so that what the lifter
// refuses (a LiftError) is reported at its line.
#include <cstddef>
#include <vector>

#include "model/lifting.hpp"

namespace linkbox::input {

struct SourceLines {
  std::vector<int> variable, equation, inequality, application;

  // The applications parsed so far and not yet placed were written on `line`.
  void place_applications(size_t count, int line) {
    while (application.size() < count) application.push_back(line);
  }
  // The line of what `e` names: a variable, an application, an equation or an inequality.
  int of(const model::LiftError& e) const {
    if (e.variable >= 0) return variable.at(e.variable);
    if (e.application >= 0) return application.at(e.application);
    if (e.equation >= 0) return equation.at(e.equation);
    if (e.inequality >= 0) return inequality.at(e.inequality);
    return 0;
  }
};

}  // namespace linkbox::input
