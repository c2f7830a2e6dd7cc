#pragma once
// Linear elimination for a model before it is lifted: variables that a linear equation
// fixes, or ties to another without adding products, are substituted away.
#include "model/polynomial.hpp"

#include <string>
#include <vector>

namespace linkbox::formulate {

// An equation of a model under construction, with the name and case-file line it reports.
struct NamedEquation {
  model::Polynomial p;
  std::string name;
  int line;
};

// x = offset + scale * v[variable], or x = offset when variable < 0.
struct Affine {
  int variable = -1;
  Interval scale{1.0}, offset{0.0};
};

// Eliminates variables through linear equations, until none applies:
//  - c x + k = 0 fixes x (always: the ground makes e.g. d_{g+2}.z = cos(alpha_{g+1}) one);
//  - c x + c' y + k = 0 gives x = -(k + c' y) / c, substituted when that does not add
//    products or squares (so the L/P/H model loses a variable and gains no dummy); x is the
//    one with the larger coefficient, so nothing is multiplied up, and y keeps to the values
//    that put x in its domain.
// The defining equation is consumed. With interval coefficients the substituted system
// contains every system with coefficients in the intervals: nothing is lost. Returns, per
// variable, what it became (itself when kept).
std::vector<Affine> eliminate_linear(std::vector<NamedEquation>& eqs, std::vector<model::Variable>& vars, const std::string& file);

}  // namespace linkbox::formulate
