#pragma once
// The linear / parabolic / hyperbolic ("L/P/H") form of the iterated-LP paper (Section II):
// linear equations in all variables, q = x^2 and b = x*y. Primary variables are split and
// bounded by LPs; dummy variables (q, b) only carry the relaxation.
#include "model/polynomial.hpp"

#include <vector>

namespace linkbox::model {

struct LinearEquation {
  std::vector<std::pair<int, Interval>> terms;  // sum coef * v[index] ...
  Interval rhs;                                 // ... = rhs (interval: rigorous constants)
};

// sum coef * v[index] <= rhs: an inequality of the system, linear in the lifted variables.
struct LinearInequality {
  std::vector<std::pair<int, Interval>> terms;
  Interval rhs;
  std::string name;
};

struct Parabolic {
  int q, x;  // q = x^2
};

struct Hyperbolic {
  int b, x, y;  // b = x * y, x != y
};

struct LphSystem {
  std::vector<Variable> variables;  // primary and dummy, with their domains
  std::vector<int> primary;         // indices of primary variables
  std::vector<LinearEquation> linear;
  std::vector<Parabolic> parabolic;
  std::vector<Hyperbolic> hyperbolic;
  // g <= 0 for each inequality of the system (strict ones too: the closure is what a
  // relaxation can use), with g's monomials replaced by their variables.
  std::vector<LinearInequality> inequalities;

  Box domain() const;
};

// Completes a box (or point) given on the primary variables with enclosures of the dummies
// (q = x^2, b = x*y, evaluated in definition order). Entries of dummies are overwritten; a
// box shorter than the variable list is padded with domains first.
Box lift(const LphSystem& lph, Box box);

}  // namespace linkbox::model
