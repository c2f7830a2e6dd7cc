#include "prune/taylor.hpp"

#include "prune/lp/tighten.hpp"

#include <cmath>

namespace linkbox::prune {

namespace {

bool finite(double x) { return std::isfinite(x); }

}  // namespace

TaylorRelaxation::TaylorRelaxation(const std::vector<model::Polynomial>& equations, size_t variables,
                                   lp::LpBackend backend, Arith arith, const std::vector<model::Link>& links)
    : TaylorRelaxation(std::make_shared<const model::CompiledSystem>(equations, links, variables, arith), backend,
                       arith) {}

TaylorRelaxation::TaylorRelaxation(std::shared_ptr<const model::CompiledSystem> system, lp::LpBackend backend,
                                   Arith arith)
    : system_(std::move(system)), backend_(backend), arith_(arith), solver_(lp::make_lp_solver(backend)) {}

std::unique_ptr<Contractor> TaylorRelaxation::clone() const {
  return std::unique_ptr<Contractor>(new TaylorRelaxation(system_, backend_, arith_));
}

void TaylorRelaxation::add_work(Counters& counters) const {
  counters.lps_solved += lps_solved_;
  counters.lp_iterations += solver_->iterations();
  counters.operations += operations_ + solver_->operations();
  counters.lp_paths += solver_->paths();
}

// The rows of one corner, from J(X) in jacobian_ (pattern order). Per row r, with s = x - c:
//   low(r)  = sum_j lo_j s_j, lo_j the bound of J_rj that is smallest times s_j's sign,
//   high(r) = sum_j hi_j s_j;  F(c).lo + low <= f <= F(c).hi + high, and f = 0 at a root, so
//   sum_j lo_j x_j <= sum_j lo_j c_j - F(c).lo   and   sum_j hi_j x_j >= sum_j hi_j c_j - F(c).hi.
// Right-hand sides are computed in outward-rounded Interval arithmetic; a row with a
// coefficient or a bound that is not finite is left out (dropping a row is sound).
void TaylorRelaxation::add_corner_rows(const Box& box, bool upper_corner, lp::LinearProgram& program) {
  const int m = system_->rows(), n = system_->cols();
  corner_.resize(n);
  for (int j = 0; j < n; ++j) corner_[j] = upper_corner ? box[j].upper() : box[j].lower();
  at_corner_.resize(m);
  with_rounding(arith_, [&] { system_->values_at(corner_.data(), at_corner_.data()); });
  // Each entry's two right-hand-side products. They round outward in either arithmetic.
  operations_ += system_->value_operations() + 8.0 * system_->nonzeros();
  std::vector<std::vector<std::pair<int, double>>> low(m), high(m);
  std::vector<FastInterval> low_rhs(m, FastInterval(0.0)), high_rhs(m, FastInterval(0.0));
  RoundingGuard guard;
  for (int e = 0; e < system_->nonzeros(); ++e) {
    const int r = system_->entry_row(e), j = system_->entry_col(e);
    const double a = upper_corner ? jacobian_[e].upper() : jacobian_[e].lower();
    const double b = upper_corner ? jacobian_[e].lower() : jacobian_[e].upper();
    low[r].push_back({j, a});
    high[r].push_back({j, b});
    low_rhs[r] += FastInterval(a) * FastInterval(corner_[j]);
    high_rhs[r] += FastInterval(b) * FastInterval(corner_[j]);
  }
  for (int r = 0; r < m; ++r) {
    if (upper_corner && point_row_[r]) continue;  // the lower corner's ranged row holds it
    const double at_most = (low_rhs[r] - FastInterval(at_corner_[r].lower())).upper();
    const double at_least = (high_rhs[r] - FastInterval(at_corner_[r].upper())).lower();
    auto usable = [](const std::vector<std::pair<int, double>>& row, double bound) {
      if (!finite(bound) || row.empty()) return false;
      for (auto& [j, c] : row)
        if (!finite(c)) return false;
      return true;
    };
    const bool below = usable(low[r], at_most), above = usable(high[r], at_least);
    if (point_row_[r] && below && above) {
      program.add_row(low[r], at_least, at_most);
      continue;
    }
    if (below) program.add_row(low[r], -kInf, at_most);
    if (above) program.add_row(high[r], at_least, kInf);
  }
}

// A row whose Jacobian entries over the box are all points (a linear equation, at least) has
// the same coefficients in its two rows and at both corners: its relaxation is the one slab
// between them, which the lower corner's rows give as a single ranged row.
void TaylorRelaxation::find_point_rows() {
  point_row_.assign(system_->rows(), 1);
  for (int e = 0; e < system_->nonzeros(); ++e)
    if (jacobian_[e].lower() != jacobian_[e].upper()) point_row_[system_->entry_row(e)] = 0;
}

bool TaylorRelaxation::relax(const Box& box, lp::LinearProgram& program) {
  const int m = system_->rows();
  range_.resize(m);
  jacobian_.resize(system_->nonzeros());
  with_rounding(arith_, [&] { system_->evaluate(box, range_.data(), jacobian_.data()); });
  operations_ += system_->value_operations() + system_->jacobian_operations();
  for (const FastInterval& f : range_)
    if (excludes_zero(f)) return false;
  find_point_rows();
  program.clear();
  for (const Interval& x : box) program.add_column(x.lower(), x.upper());
  add_corner_rows(box, false, program);
  add_corner_rows(box, true, program);
  return true;
}

Outcome TaylorRelaxation::contract(Box& box) {
  for (const Interval& x : box)
    if (!finite(x.lower()) || !finite(x.upper())) return Outcome::unchanged;
  lp::LinearProgram program;
  if (!relax(box, program)) return Outcome::empty;
  if (program.num_rows() == 0) return Outcome::unchanged;
  solver_->load(program);
  Box work = box;
  columns_.resize(work.size());
  for (size_t j = 0; j < work.size(); ++j) columns_[j] = static_cast<int>(j);
  if (!lp::tighten_columns(*solver_, columns_, work, lps_solved_, stop_, lp::Order::nearest_bound)) return Outcome::empty;
  bool changed = false;
  for (size_t i = 0; i < box.size(); ++i)
    changed |= work[i].lower() != box[i].lower() || work[i].upper() != box[i].upper();
  box = std::move(work);
  return changed ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
