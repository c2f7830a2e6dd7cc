#pragma once
// Linear definitions v = L(x) (a lifted copy of a sum, model/lifter.cpp) substituted out of
// interval Newton, which then works on the other unknowns with G(x) = F(x, L(x)) and the
// chain rule's Jacobian G' = F'_x + F'_v L'. Every root of F in a box X is (x, L(x)) with x a
// root of G in X's other coordinates, so Newton on G loses none of them; it inverts a matrix
// of the system's own size, not of the size with the copies.
#include "model/compiled.hpp"

#include <vector>

namespace linkbox::prune {

class NewtonSubstitution {
 public:
  NewtonSubstitution() = default;  // nothing substituted
  // Substitutes each candidate variable that some degree-1 equation defines with coefficient
  // +-1, where that equation names no other substituted variable and no other definition
  // names it. `system` is compiled from `equations` (then its links).
  NewtonSubstitution(const model::CompiledSystem& system, const std::vector<model::Polynomial>& equations,
                     const std::vector<int>& candidates);

  bool empty() const { return definitions_.empty(); }
  // The reduced system: its rows and columns name the system's.
  int rows() const { return static_cast<int>(rows_.size()); }
  int cols() const { return static_cast<int>(cols_.size()); }
  int row(int i) const { return rows_[i]; }
  int col(int k) const { return cols_[k]; }
  int nonzeros() const { return static_cast<int>(entry_row_.size()); }
  int entry_row(int e) const { return entry_row_[e]; }
  int entry_col(int e) const { return entry_col_[e]; }

  // G'(X) from F'(X) (the system's entries in its pattern order); inside a RoundingGuard.
  void reduce(const FastInterval* jacobian, FastInterval* reduced) const;
  double reduce_operations() const { return static_cast<double>(contributions_.size()); }

  // x with every substituted variable set to L(x) over x's other coordinates.
  void substitute(Box& x) const;
  // Each substituted coordinate of x intersected with L(x), `narrowed` set where one moved:
  // false when one is left empty.
  bool narrow(Box& x, bool& narrowed) const;

 private:
  struct Definition {
    int variable;
    Interval constant;
    std::vector<std::pair<int, Interval>> terms;  // v = constant + sum coef * x_col
  };
  struct Contribution {
    int entry, reduced;
    FastInterval coef;
    bool unit;
  };
  Interval value(const Definition& d, const Box& x) const;
  void build_pattern(const model::CompiledSystem& system, const std::vector<int>& definition_of);

  std::vector<Definition> definitions_;
  std::vector<int> rows_, cols_;
  std::vector<int> entry_row_, entry_col_;
  std::vector<Contribution> contributions_;
};

}  // namespace linkbox::prune
