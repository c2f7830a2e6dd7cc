#pragma once
// A polynomial system flattened for fast interval evaluation: the values F(X) and the sparse
// Jacobian J(X) from one table of powers per box, in FastInterval arithmetic. Immutable once
// built, so one instance serves every thread (the table of powers is per thread). Callers run it
// inside one RoundingGuard (outward rounding; see interval.hpp), or without one for the
// unverified float variant. model::Polynomial stays the reference: it is what these tables
// are built from and what tests compare against. Links (model/link.hpp) are rows too, after
// the polynomials: y - f(a), with the Jacobian entries 1 and -f'(a), enclosed through MPFI.
#include "model/link.hpp"
#include "model/polynomial.hpp"

#include <vector>

namespace linkbox::model {

class CompiledSystem {
 public:
  CompiledSystem() = default;
  // `arith` = float_unverified takes midpoint coefficients (the unverified variant).
  CompiledSystem(const std::vector<Polynomial>& equations, size_t variables, Arith arith = Arith::verified)
      : CompiledSystem(equations, {}, variables, arith) {}
  // Rows: the equations, then the links.
  CompiledSystem(const std::vector<Polynomial>& equations, const std::vector<Link>& links, size_t variables,
                 Arith arith = Arith::verified);

  int rows() const { return static_cast<int>(values_.size() + links_.size()); }
  int cols() const { return static_cast<int>(max_degree_.size()); }

  // Nonzero pattern of the Jacobian, row by row: entry e is d f_row(e) / d x_col(e).
  int nonzeros() const { return static_cast<int>(entry_row_.size()); }
  int entry_row(int e) const { return entry_row_[e]; }
  int entry_col(int e) const { return entry_col_[e]; }
  // Variables each equation involves (sorted), e.g. for smear and for sparse products.
  const std::vector<std::vector<int>>& involved() const { return involved_; }

  // Each call fills the table of powers of `x` first; `values` gets rows() entries, `jacobian`
  // nonzeros() entries in pattern order. Both from the same table in evaluate().
  void values(const Box& x, FastInterval* f) const;
  void jacobian(const Box& x, FastInterval* j) const;
  void evaluate(const Box& x, FastInterval* f, FastInterval* j) const;
  // What one values() and one jacobian() cost, counted in interval products and sums
  // (prune::Counters::operations); evaluate() costs both, values_at() about the first.
  double value_operations() const;
  double jacobian_operations() const;
  // What the system compiled from these would count, from the terms' shapes alone (no table
  // built): pricing a box needs the counts of every sub-problem, not its tables.
  struct Shape {
    double value_operations = 0, jacobian_operations = 0;
    int rows = 0, cols = 0, nonzeros = 0;
  };
  static Shape shape_of(const std::vector<Polynomial>& equations, const std::vector<Link>& links, size_t variables);
  // Values at the point y (each coordinate a double), as degenerate intervals.
  void values_at(const double* y, FastInterval* f) const;
  // In plain double with midpoint coefficients, in whatever rounding mode is set: for a
  // float Newton's guesses, never for a proof (several times cheaper than intervals).
  void values_float(const double* y, double* f) const;
  void jacobian_float(const double* y, double* j) const;  // nonzeros() entries

 private:
  struct Term {
    FastInterval coef;
    double mid;  // the coefficient's midpoint, for the float evaluation
    int begin, end;  // factors_[begin, end): (variable, exponent >= 1)
  };
  struct Compiled {
    int begin, end;  // terms_[begin, end)
  };
  Compiled add(const Polynomial& p, Arith arith);
  FastInterval* fill_powers(const Box& x) const;  // into this thread's scratch table
  FastInterval sum(const Compiled& c, const FastInterval* powers) const;
  double sum_operations(const std::vector<Compiled>& sums) const;
  const double* float_powers(const double* y) const;
  double float_sum(const Compiled& c, const double* powers) const;
  void add_links(const std::vector<Link>& links, size_t variables);
  FastInterval link_value(size_t k, const Interval& y, const Interval& a) const;
  FastInterval link_entry(size_t e, const Box& x) const;  // e >= partials_.size()

  std::vector<Term> terms_;
  std::vector<std::pair<int, int>> factors_;
  std::vector<Compiled> values_, partials_;
  std::vector<Link> links_;
  std::vector<std::pair<int, bool>> link_entries_;  // per entry after partials_: (link, column is its y)
  std::vector<int> entry_row_, entry_col_;
  std::vector<std::vector<int>> involved_;
  std::vector<int> max_degree_, power_offset_;  // per variable; x_v^e at power_offset_[v] + e - 1
  int power_count_ = 0;
};

}  // namespace linkbox::model
