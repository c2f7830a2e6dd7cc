#pragma once
// Any polynomial system -> linear / parabolic / hyperbolic form (iterated-LP paper, eq. 5):
// every monomial of degree >= 2 becomes an auxiliary ("dummy") variable defined by one
// q = x^2 or b = x*y, built from lower-degree auxiliaries (x^3 = x*q, x^2 y = y*q,
// x^4 = q^2, ...), each monomial at most once however many equations use it.
#include "interval/box.hpp"
#include "model/lph.hpp"
#include "model/polynomial.hpp"

#include <string>
#include <vector>

namespace linkbox::formulate {

// The original variables keep their indices 0..n-1 and are the primary variables;
// auxiliaries follow, each after the variables it is defined from, with the domain of its
// monomial evaluated over the original domains. linear[k] is equations[k] with every
// monomial replaced by its variable (one linear equation per input equation, constant ones
// included). When `lph_equations` is given it receives the same system as polynomials over
// all variables: the linear equations, then q - x^2, then b - x*y. Each inequality g <= 0
// becomes a linear inequality the same way (its monomials get variables too).
model::LphSystem to_lph(const model::System& system, std::vector<model::Polynomial>* lph_equations = nullptr);

// An L/P/H system as a polynomial system over all its variables, in the order above. The
// linear equations are named `linear_names[k]` when given; the others after what they define.
// Linear inequalities become (non-strict) inequalities of the result.
model::System lph_polynomials(const model::LphSystem& lph, const std::vector<std::string>& linear_names = {});

}  // namespace linkbox::formulate
