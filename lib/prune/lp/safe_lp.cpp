#include "prune/lp/safe_lp.hpp"

#include "interval/interval.hpp"
#include "prune/lp/safe_bound.hpp"

#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace linkbox::prune::lp {

namespace {

// CLP marks "no bound" with +-COIN_DBL_MAX, not IEEE infinity.
double to_clp(double v) {
  if (v == kInf) return COIN_DBL_MAX;
  if (v == -kInf) return -COIN_DBL_MAX;
  return v;
}

// CLP can cycle or stall on degenerate relaxations (seen on bicyclohexane). A capped solve
// only loses pruning: the N-S bound holds for whatever duals it stopped with.
void cap_effort(ClpSimplex& model) {
  model.setMaximumIterations(200 + 20 * (model.numberRows() + model.numberColumns()));
  model.setMaximumSeconds(2.0);
}

// The elastic LP: rows  row_lo <= A x + e+ - e- <= row_hi,  x in X,  e+-  >= 0, minimizing
// sum(e+ + e-). Its optimum is positive exactly when the original LP is infeasible, and its
// row duals (|y| <= 1 at optimality) are then a Farkas certificate for the original rows.
std::vector<double> elastic_duals(const LinearProgram& lp) {
  const int n = lp.num_cols(), m = lp.num_rows();
  CoinPackedMatrix matrix(false, 0, 0);
  matrix.setDimensions(0, n + 2 * m);
  std::vector<int> idx;
  std::vector<double> val;
  for (int i = 0; i < m; ++i) {
    auto ri = lp.row_indices(i);
    auto rv = lp.row_values(i);
    idx.assign(ri.begin(), ri.end());
    val.assign(rv.begin(), rv.end());
    idx.push_back(n + i), val.push_back(1.0);
    idx.push_back(n + m + i), val.push_back(-1.0);
    matrix.appendRow(static_cast<int>(idx.size()), idx.data(), val.data());
  }
  std::vector<double> col_lo(n + 2 * m, 0.0), col_hi(n + 2 * m, COIN_DBL_MAX), cost(n + 2 * m, 1.0);
  std::vector<double> row_lo(m), row_hi(m);
  for (int j = 0; j < n; ++j) {
    col_lo[j] = to_clp(lp.col_lo[j]), col_hi[j] = to_clp(lp.col_hi[j]);
    cost[j] = 0;
  }
  for (int i = 0; i < m; ++i) row_lo[i] = to_clp(lp.row_lo[i]), row_hi[i] = to_clp(lp.row_hi[i]);
  ClpSimplex model;
  model.setLogLevel(0);
  model.loadProblem(matrix, col_lo.data(), col_hi.data(), cost.data(), row_lo.data(), row_hi.data());
  cap_effort(model);
  model.primal();
  std::vector<double> y(model.dualRowSolution(), model.dualRowSolution() + m);
  for (double& v : y) v = std::clamp(v, -1.0, 1.0);  // any y is checkable; these are the useful ones
  return y;
}

}  // namespace

bool SafeLp::elastic_certificate() const {
  std::vector<double> y = elastic_duals(centred_);
  to_original_rows(centring_, y);
  return proves_infeasible(program_, y);
}

SafeLp::SafeLp(bool trust_float) : trust_float_(trust_float) {}
SafeLp::~SafeLp() = default;

void SafeLp::load(const LinearProgram& program) {
  program_ = program;
  centred_ = centre_columns(program_, centring_);
  const LinearProgram& lp = centred_;  // what CLP solves; program_ is what gets bounded
  const int n = lp.num_cols(), m = lp.num_rows();
  std::vector<CoinBigIndex> start(lp.row_start.begin(), lp.row_start.end());
  std::vector<int> length(m);
  for (int i = 0; i < m; ++i) length[i] = lp.row_start[i + 1] - lp.row_start[i];
  CoinPackedMatrix matrix(false, n, m, static_cast<CoinBigIndex>(lp.index.size()), lp.value.data(),
                          lp.index.data(), start.data(), length.data());
  std::vector<double> col_lo(n), col_hi(n), row_lo(m), row_hi(m), objective(n, 0.0);
  for (int j = 0; j < n; ++j) col_lo[j] = to_clp(lp.col_lo[j]), col_hi[j] = to_clp(lp.col_hi[j]);
  for (int i = 0; i < m; ++i) row_lo[i] = to_clp(lp.row_lo[i]), row_hi[i] = to_clp(lp.row_hi[i]);

  model_ = std::make_unique<ClpSimplex>();
  model_->setLogLevel(0);
  model_->messageHandler()->setLogLevel(0);
  // 32: keep the infeasibility ray; 2097152: keep it even after many pivots. The ray is
  // only a candidate Farkas certificate; proves_infeasible() checks it.
  model_->setSpecialOptions(model_->specialOptions() | 32 | 2097152);
  model_->loadProblem(matrix, col_lo.data(), col_hi.data(), objective.data(), row_lo.data(), row_hi.data());
  cap_effort(*model_);
  // No CLP scaling (centred_program.hpp scales rows and columns): with it, CLP called two
  // thirds of the (feasible, as the exact LP showed) relaxations on bicyclohexane primal
  // infeasible, which cost all their pruning.
  model_->scaling(0);
  objective_col_ = -1;
}

void SafeLp::set_column_bounds(int col, double lo, double hi) {
  program_.col_lo[col] = lo;
  program_.col_hi[col] = hi;
  const double u_lo = centring_.to_u(col, lo), u_hi = centring_.to_u(col, hi);
  centred_.col_lo[col] = u_lo;
  centred_.col_hi[col] = u_hi;
  model_->setColumnBounds(col, to_clp(u_lo), to_clp(u_hi));
}

bool SafeLp::last_point(std::vector<double>& x) const {
  if (!model_ || objective_col_ < 0 || model_->status() != 0) return false;
  const double* u = model_->primalColumnSolution();
  x.resize(program_.num_cols());
  for (int j = 0; j < program_.num_cols(); ++j) x[j] = centring_.shift[j] + centring_.scale[j] * u[j];
  return true;
}

LpBound SafeLp::minimize(int col) { return solve(col, 1.0); }

LpBound SafeLp::maximize(int col) {
  LpBound b = solve(col, -1.0);
  b.value = -b.value;  // max x = -min(-x): a lower bound on -x negates to an upper bound on x
  return b;
}

// Bounds min sense * x[col]; the returned value is in terms of sense * x[col].
LpBound SafeLp::solve(int col, double sense) {
  const double trivial = sense > 0 ? program_.col_lo[col] : -program_.col_hi[col];
  const double other_end = sense > 0 ? program_.col_hi[col] : -program_.col_lo[col];  // max of sense*x
  const std::pair<int, double> objective[] = {{col, sense}};
  const int m = program_.num_rows();

  if (objective_col_ >= 0 && objective_col_ != col) model_->setObjectiveCoefficient(objective_col_, 0.0);
  model_->setObjectiveCoefficient(col, sense);
  objective_col_ = col;
  // Dual simplex from the previous basis: an objective change keeps the basis and CLP
  // restores dual feasibility with bound flips (every column is boxed).
  // Options 1|2|4: keep work areas and the factorization between calls (as OsiClp's
  // resolve does); measured 2-3x faster per LP than a cold dual(0) on 60x180 relaxations.
  model_->dual(0, 1 | 2 | 4);
  iterations_ += model_->numberIterations();

  const LpBound infeasible{LpStatus::infeasible, kInf};
  const bool claims_infeasible = model_->status() == 1;
  if (trust_float_) {
    if (claims_infeasible) return infeasible;
    if (model_->status() != 0) return LpBound{LpStatus::unknown, trivial};
    const double x = centring_.shift[col] + centring_.scale[col] * model_->primalColumnSolution()[col];
    return LpBound{LpStatus::bounded, sense * x};
  }
  if (claims_infeasible) {
    // Its ray's sign convention has changed across CLP versions, so both signs are checked;
    // the check itself is what proves.
    std::unique_ptr<double[]> ray(model_->infeasibilityRay());
    if (ray) {
      std::vector<double> y(ray.get(), ray.get() + m);
      to_original_rows(centring_, y);
      if (proves_infeasible(program_, y)) return infeasible;
      for (double& v : y) v = -v;
      if (proves_infeasible(program_, y)) return infeasible;
    }
  }
  // CLP's rays are often missing or not certificates (about one infeasible LP in ten in the
  // tests), and a stopped or primal-infeasible finish may hide infeasibility: the duals of
  // the elastic (phase-1) LP are then the dependable source.
  if ((claims_infeasible || model_->status() != 0 || !model_->primalFeasible()) && elastic_certificate())
    return infeasible;
  // CLP minimised sense * u = sense * (x - shift) / scale (unit costs suit its absolute
  // tolerances); its duals are those of objective sense * x once multiplied by scale.
  std::vector<double> y(model_->dualRowSolution(), model_->dualRowSolution() + m);
  for (double& v : y) v *= centring_.scale[col];
  to_original_rows(centring_, y);
  double bound = dual_lower_bound(program_, y, objective);
  // A lower bound on sense*x above its largest value in X proves the LP empty.
  if (bound > other_end) return infeasible;
  // Weak duality holds for any y, so even the duals of an unfinished or wrongly
  // "infeasible" solve give a valid bound. Both are valid lower bounds; keep the better one.
  return LpBound{LpStatus::bounded, bound > trivial ? bound : trivial};
}

}  // namespace linkbox::prune::lp
