#pragma once
// The float half of the safe and exact LP backends: CLP's dual simplex on the centred LP
// (centred_program.hpp), warm-started across the successive objectives of one shrink. It
// only proposes (duals, a basis, a point, candidate Farkas multipliers), always in terms of
// the LP as loaded; the backends decide what is proved.
#include "prune/lp/centred_program.hpp"

#include <memory>
#include <vector>

class ClpSimplex;  // keeps CLP's headers out of every includer

namespace linkbox::prune::lp {

// A variable's place in a simplex basis: a column x_j or a row activity a_i . x.
enum class BasisStatus : unsigned char {
  basic,
  at_lower,  // nonbasic at its lower bound (col_lo / row_lo)
  at_upper,  // nonbasic at its upper bound
  other,     // free or superbasic: not a vertex of the LP
};

class ClpCore {
 public:
  ClpCore();
  ~ClpCore();
  ClpCore(const ClpCore&) = delete;
  ClpCore& operator=(const ClpCore&) = delete;

  void load(const LinearProgram& program);
  void set_column_bounds(int col, double lo, double hi);
  // CLP's primal and dual feasibility tolerances (on the centred LP), kept across loads;
  // CLP's defaults (1e-7) until set. The exact backend tightens them: a basis CLP calls
  // optimal then needs fewer exact pivots.
  void set_tolerances(double primal, double dual);

  enum class Finish {
    optimal,     // CLP says optimal within its tolerances
    infeasible,  // CLP says primal infeasible (unproved)
    other,       // stopped (iteration or time cap) or any other status
  };
  // Dual simplex on min sense * x[col] from the previous basis.
  Finish solve(int col, double sense);
  bool primal_feasible() const;  // CLP's own (toleranced) verdict on the last solve

  // Everything below refers to the LP as loaded (not the centred one CLP sees).
  const LinearProgram& program() const { return program_; }
  // Row multipliers of the last solve's objective sense * x[col].
  std::vector<double> duals() const;
  // CLP's infeasibility ray as row multipliers; false when it kept none. Its sign
  // convention has changed across CLP versions: callers check both signs.
  bool ray(std::vector<double>& y) const;
  // Row multipliers from the elastic (phase-1) LP: a candidate Farkas certificate.
  std::vector<double> elastic_duals() const;
  // The last solve's point; false when that solve did not finish optimal.
  bool point(std::vector<double>& x) const;
  // The last solve's basis, one status per column and per row.
  void basis(std::vector<BasisStatus>& cols, std::vector<BasisStatus>& rows) const;
  long iterations() const { return iterations_; }
  // Each load and each solve priced by its size and pivots (Counters::operations), fitted to
  // measured times (papers/decisions/search.md): a pivot costs about the same on every
  // relaxation measured (CLP's own overhead dominates at these sizes); a load builds a new
  // CLP model.
  double operations() const { return operations_; }
  static constexpr double kPivotOperations = 2000;

 private:
  LinearProgram program_;  // as loaded: the rigorous bounds are computed on this one
  LinearProgram centred_;  // the same LP in centred columns: what CLP solves
  Centring centring_;
  std::unique_ptr<ClpSimplex> model_;
  int objective_col_ = -1;  // the single non-zero of CLP's current objective
  long iterations_ = 0;
  double operations_ = 0;
  double primal_tolerance_ = 0, dual_tolerance_ = 0;  // 0: CLP's defaults
};

}  // namespace linkbox::prune::lp
