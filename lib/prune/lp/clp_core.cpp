#include "prune/lp/clp_core.hpp"

#include "interval/interval.hpp"

#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

namespace {

constexpr double kLoadOperations = 20000;
constexpr double kElementOperations = 4;

// CLP marks "no bound" with +-COIN_DBL_MAX, not IEEE infinity.
double to_clp(double v) {
  if (v == kInf) return COIN_DBL_MAX;
  if (v == -kInf) return -COIN_DBL_MAX;
  return v;
}

// CLP can cycle or stall on degenerate relaxations (seen on bicyclohexane). A capped solve
// only loses pruning: the N-S bound holds for whatever duals it stopped with. The cap counts
// iterations, not seconds: with setMaximumSeconds CLP reads the process's CPU clock
// (getrusage, a system call) at every iteration, 8% of an LP-bound run (perf, rigid 6R),
// and a cap in seconds would make the pruning depend on the machine's speed.
void cap_effort(ClpSimplex& model) {
  model.setMaximumIterations(200 + 20 * (model.numberRows() + model.numberColumns()));
}

// The elastic LP: rows  row_lo <= A x + e+ - e- <= row_hi,  x in X,  e+-  >= 0, minimizing
// sum(e+ + e-). Its optimum is positive exactly when the original LP is infeasible, and its
// row duals (|y| <= 1 at optimality) are then a Farkas certificate for the original rows.
std::vector<double> elastic_row_duals(const LinearProgram& lp) {
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

BasisStatus from_clp(ClpSimplex::Status s) {
  switch (s) {
    case ClpSimplex::basic: return BasisStatus::basic;
    case ClpSimplex::atLowerBound: return BasisStatus::at_lower;
    case ClpSimplex::atUpperBound: return BasisStatus::at_upper;
    // A fixed variable sits at both bounds; its (equal) lower one names the value.
    case ClpSimplex::isFixed: return BasisStatus::at_lower;
    default: return BasisStatus::other;
  }
}

}  // namespace

ClpCore::ClpCore() = default;
ClpCore::~ClpCore() = default;

void ClpCore::load(const LinearProgram& program) {
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
  // only a candidate Farkas certificate; the backends check it.
  model_->setSpecialOptions(model_->specialOptions() | 32 | 2097152);
  model_->loadProblem(matrix, col_lo.data(), col_hi.data(), objective.data(), row_lo.data(), row_hi.data());
  cap_effort(*model_);
  // No CLP scaling (centred_program.hpp scales rows and columns): with it, CLP called two
  // thirds of the (feasible, as the exact LP showed) relaxations on bicyclohexane primal
  // infeasible, which cost all their pruning.
  model_->scaling(0);
  if (primal_tolerance_ > 0) model_->setPrimalTolerance(primal_tolerance_);
  if (dual_tolerance_ > 0) model_->setDualTolerance(dual_tolerance_);
  objective_col_ = -1;
  operations_ += kLoadOperations + kElementOperations * static_cast<double>(lp.index.size() + n + m);
}

void ClpCore::set_tolerances(double primal, double dual) {
  primal_tolerance_ = primal;
  dual_tolerance_ = dual;
  if (model_) {
    model_->setPrimalTolerance(primal);
    model_->setDualTolerance(dual);
  }
}

void ClpCore::set_column_bounds(int col, double lo, double hi) {
  program_.col_lo[col] = lo;
  program_.col_hi[col] = hi;
  const double u_lo = centring_.to_u(col, lo), u_hi = centring_.to_u(col, hi);
  centred_.col_lo[col] = u_lo;
  centred_.col_hi[col] = u_hi;
  model_->setColumnBounds(col, to_clp(u_lo), to_clp(u_hi));
}

ClpCore::Finish ClpCore::solve(int col, double sense) {
  if (objective_col_ >= 0 && objective_col_ != col) model_->setObjectiveCoefficient(objective_col_, 0.0);
  model_->setObjectiveCoefficient(col, sense);
  objective_col_ = col;
  // Dual simplex from the previous basis: an objective change keeps the basis and CLP
  // restores dual feasibility with bound flips (every column is boxed).
  // Options 1|2|4: keep work areas and the factorization between calls (as OsiClp's
  // resolve does); measured 2-3x faster per LP than a cold dual(0) on 60x180 relaxations.
  model_->dual(0, 1 | 2 | 4);
  iterations_ += model_->numberIterations();
  // The rigorous bound that follows reads every element of the LP once more.
  operations_ += kPivotOperations * (model_->numberIterations() + 1) +
                 kElementOperations * static_cast<double>(program_.index.size() + program_.num_rows());
  switch (model_->status()) {
    case 0: return Finish::optimal;
    case 1: return Finish::infeasible;
    default: return Finish::other;
  }
}

bool ClpCore::primal_feasible() const { return model_->primalFeasible(); }

std::vector<double> ClpCore::duals() const {
  // CLP minimised sense * u = sense * (x - shift) / scale (unit costs suit its absolute
  // tolerances); its duals are those of objective sense * x once multiplied by scale.
  const int m = program_.num_rows();
  std::vector<double> y(model_->dualRowSolution(), model_->dualRowSolution() + m);
  const double scale = objective_col_ >= 0 ? centring_.scale[objective_col_] : 1.0;
  for (double& v : y) v *= scale;
  to_original_rows(centring_, y);
  return y;
}

bool ClpCore::ray(std::vector<double>& y) const {
  std::unique_ptr<double[]> r(model_->infeasibilityRay());
  if (!r) return false;
  y.assign(r.get(), r.get() + program_.num_rows());
  to_original_rows(centring_, y);
  return true;
}

std::vector<double> ClpCore::elastic_duals() const {
  std::vector<double> y = elastic_row_duals(centred_);
  to_original_rows(centring_, y);
  return y;
}

bool ClpCore::point(std::vector<double>& x) const {
  if (!model_ || objective_col_ < 0 || model_->status() != 0) return false;
  const double* u = model_->primalColumnSolution();
  x.resize(program_.num_cols());
  for (int j = 0; j < program_.num_cols(); ++j) x[j] = centring_.shift[j] + centring_.scale[j] * u[j];
  return true;
}

void ClpCore::basis(std::vector<BasisStatus>& cols, std::vector<BasisStatus>& rows) const {
  // The centring maps x to u by a positive scale and rows by positive powers of two, so a
  // variable at its lower bound in CLP's LP is at its lower bound in the loaded one.
  const int n = program_.num_cols(), m = program_.num_rows();
  cols.resize(n);
  rows.resize(m);
  for (int j = 0; j < n; ++j) cols[j] = from_clp(model_->getColumnStatus(j));
  for (int i = 0; i < m; ++i) rows[i] = from_clp(model_->getRowStatus(i));
}

}  // namespace linkbox::prune::lp
