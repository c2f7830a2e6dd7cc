#pragma once
// One interface over the LP backends the LP-relaxation contractor can use.
// Every answer is rigorous for the LP exactly as loaded (double data read as rationals):
// a minimum is never above the true LP minimum, a maximum never below the true maximum,
// and `infeasible` is only said when proved. Float solver output alone never decides.
#include "prune/counters.hpp"
#include "prune/lp/linear_program.hpp"

#include <memory>
#include <string>
#include <vector>

namespace linkbox::prune::lp {

enum class LpStatus {
  bounded,     // value is a rigorous bound (possibly weak, e.g. the column's own bound)
  infeasible,  // proved: no point satisfies the rows within the column bounds
  unknown,     // nothing proved; value is the trivial bound (the column's own bound)
};

struct LpBound {
  LpStatus status = LpStatus::unknown;
  // min: value <= true minimum; max: value >= true maximum. For `infeasible`, +inf for a
  // minimum and -inf for a maximum (the optimum of an empty set).
  double value = 0;
};

// safe: CLP + Neumaier-Shcherbina bounds (safe_lp.hpp); exact: CLP's basis checked in
// rationals, CGAL when that fails (exact_lp.hpp); cgal: CGAL's exact QP solver on every LP
// from scratch (cgal_lp.hpp, the independent reference); float: CLP's float answers trusted
// as they are (the unverified variant, for comparison).
enum class LpBackend { safe, exact, float_trusted, cgal };

class LpSolver {
 public:
  virtual ~LpSolver() = default;
  virtual std::string name() const = 0;
  // Takes a private copy; later calls bound columns of this LP.
  virtual void load(const LinearProgram& program) = 0;
  // Tightens (or replaces) the bounds of one column of the loaded LP, e.g. with the result
  // of an earlier minimize/maximize (Algorithm 2 feeds each new bound to the next LP).
  virtual void set_column_bounds(int col, double lo, double hi) = 0;
  virtual LpBound minimize(int col) = 0;
  virtual LpBound maximize(int col) = 0;
  // The (float) optimal point of the last minimize/maximize, in the loaded LP's columns;
  // false when the backend has none or that solve did not finish. Only used to skip LPs
  // (a column already at its bound in a feasible point cannot be tightened there).
  virtual bool last_point(std::vector<double>& /*x*/) const { return false; }
  // Simplex iterations over the solver's lifetime (0 where the backend does not say).
  virtual long iterations() const { return 0; }
  // The work of the loads and solves so far in Counters::operations' unit (0 where the
  // backend does not count it).
  virtual double operations() const { return 0; }
  // How the answers so far were reached (the exact backend; zero elsewhere).
  virtual LpPaths paths() const { return {}; }
};

std::unique_ptr<LpSolver> make_lp_solver(LpBackend backend);
std::string to_string(LpBackend backend);

}  // namespace linkbox::prune::lp
