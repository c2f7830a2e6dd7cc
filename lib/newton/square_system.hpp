#pragma once
// A square polynomial system as interval Newton sees it: n equations solved for n chosen
// unknowns, every other variable held at a fixed (interval) value. Fixing variables is how a
// curve (n-1 equations in n variables) becomes square for a crossing certificate.
#include "model/compiled.hpp"
#include "model/polynomial.hpp"
#include "newton/interval_eigen.hpp"

#include <memory>
#include <vector>

namespace linkbox::newton {

class SquareSystem {
 public:
  // `base` gives every variable its value (only the non-unknowns are read); `unknowns` are
  // the variable indices solved for, as many as `equations`. Throws std::invalid_argument
  // when the counts differ, an index is out of range or an equation names a variable
  // beyond `base`.
  SquareSystem(std::vector<model::Polynomial> equations, std::vector<int> unknowns, Box base);
  // The same from a system compiled once (e.g. a formulation's natural system, shared by
  // every thread): `compiled` has as many rows as `unknowns` and base.size() columns.
  SquareSystem(std::shared_ptr<const model::CompiledSystem> compiled, std::vector<int> unknowns, Box base);

  // Every variable unknown: the plain square system in `n` variables.
  static SquareSystem all_unknown(const std::vector<model::Polynomial>& equations, size_t n);
  static SquareSystem all_unknown(std::shared_ptr<const model::CompiledSystem> compiled);

  int size() const { return static_cast<int>(unknowns_.size()); }
  const std::vector<int>& unknowns() const { return unknowns_; }

  Box embed(const Box& x) const;          // unknowns from x, the rest from base
  Box restrict(const Box& full) const;    // the unknowns' part of a full box

  IVector values(const Box& x) const;     // F(x), x over the unknowns
  IMatrix jacobian(const Box& x) const;   // dF/d(unknowns) over x

  // Float evaluation at a point, in double with midpoint coefficients (fixed variables at
  // their midpoints): guesses for a float Newton, not enclosures.
  Eigen::VectorXd values_at(const Eigen::VectorXd& x) const;
  Eigen::MatrixXd jacobian_at(const Eigen::VectorXd& x) const;

 private:
  std::vector<double> full_point(const Eigen::VectorXd& x) const;  // x at the unknowns, base midpoints elsewhere
  std::vector<int> unknowns_;
  Box base_;
  // Evaluated over all variables of `base`; Jacobian entries of unknowns are picked out.
  std::shared_ptr<const model::CompiledSystem> compiled_;
  std::vector<int> unknown_column_;  // per compiled Jacobian entry: column among the unknowns, or -1
};

Box point_box(const Eigen::VectorXd& x);

}  // namespace linkbox::newton
