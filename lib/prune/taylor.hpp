#pragma once
// A linear relaxation from first-order Taylor bounds at the box's corners, in the system's own
// variables (X-Newton's corner relaxation: Araya, Trombettoni, Neveu, 2012). For x in X, c a
// corner of X and J = J(X), the mean value theorem puts each row f of the system between
//   F(c).lo + sum_j a_j (x_j - c_j)  and  F(c).hi + sum_j b_j (x_j - c_j),
// a_j = J_j.lo, b_j = J_j.hi where c_j = X_j.lo (x_j - c_j >= 0), and the other way round where
// c_j = X_j.hi. A root makes both bounds enclose 0: two LP rows per corner whose coefficients
// are the doubles J_j.lo, J_j.hi exactly and whose right-hand sides are rounded outward, so
// the LP's feasible set holds every root in X. Two opposite corners (every lower bound, every
// upper bound); a row whose Jacobian is a point over X (a linear equation) gives the same
// coefficients four times, and one ranged row. Then each variable is minimised and maximised
// (lp/tighten.hpp). Unlike the L/P/H relaxation (lp), it needs no lifting: n columns, however
// the system is written.
#include "model/compiled.hpp"
#include "prune/contractor.hpp"
#include "prune/lp/lp_solver.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

class TaylorRelaxation final : public Contractor {
 public:
  TaylorRelaxation(const std::vector<model::Polynomial>& equations, size_t variables, lp::LpBackend backend,
                   Arith arith, const std::vector<model::Link>& links = {});
  std::string name() const override { return "taylor"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;
  void stop_when(const std::function<bool()>* request) override { stop_ = request; }
  void add_work(Counters& counters) const override;
  // The LP over `box` (columns: the variables, bounded by the box); false when some row's
  // range over the box misses 0 (no root there).
  bool relax(const Box& box, lp::LinearProgram& program);

 private:
  TaylorRelaxation(std::shared_ptr<const model::CompiledSystem> system, lp::LpBackend backend, Arith arith);
  void add_corner_rows(const Box& box, bool upper_corner, lp::LinearProgram& program);
  void find_point_rows();

  std::shared_ptr<const model::CompiledSystem> system_;  // shared read-only by clones
  lp::LpBackend backend_;
  Arith arith_;
  std::unique_ptr<lp::LpSolver> solver_;
  long lps_solved_ = 0;
  double operations_ = 0;  // its own, the LP solver's apart
  const std::function<bool()>* stop_ = nullptr;
  // Scratch: F over the box, J over the box, F at a corner; the corner.
  std::vector<FastInterval> range_, jacobian_, at_corner_;
  std::vector<double> corner_;
  std::vector<char> point_row_;  // per row: every Jacobian entry a point over the box
  std::vector<int> columns_;  // every variable: all are minimised and maximised
};

}  // namespace linkbox::prune
