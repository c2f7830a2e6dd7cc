// The one translation unit that includes CGAL's QP solver (it is heavy to compile).
#include "prune/lp/cgal_lp.hpp"

#include "interval/interval.hpp"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>
#include <gmpxx.h>

#include <cmath>

namespace linkbox::prune::lp {

namespace {

using Program = CGAL::Quadratic_program<double>;

mpq_class to_mpq(const CGAL::Gmpzf& f) {
  // Gmpzf is mantissa * 2^exponent.
  mpq_class q{mpz_class(f.man())};
  long e = f.exp();
  if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
  return q;
}

// Directed rounding of a rational: mpq_get_d truncates toward zero; stepping until the
// exact comparison agrees fixes the side truncation got wrong (one step in practice).
double round_down(const mpq_class& q) {
  double d = mpq_get_d(q.get_mpq_t());
  while (mpq_class(d) > q) d = std::nextafter(d, -kInf);
  return d;
}
double round_up(const mpq_class& q) {
  double d = mpq_get_d(q.get_mpq_t());
  while (mpq_class(d) < q) d = std::nextafter(d, kInf);
  return d;
}

// CGAL wants each row as one of <=, >=, =; a two-sided row becomes two rows.
Program to_cgal(const LinearProgram& lp) {
  Program qp(CGAL::SMALLER, true, 0, false, 0);
  for (int j = 0; j < lp.num_cols(); ++j) {
    qp.set_l(j, std::isfinite(lp.col_lo[j]), std::isfinite(lp.col_lo[j]) ? lp.col_lo[j] : 0.0);
    qp.set_u(j, std::isfinite(lp.col_hi[j]), std::isfinite(lp.col_hi[j]) ? lp.col_hi[j] : 0.0);
  }
  int row = 0;
  auto emit = [&](int r, CGAL::Comparison_result rel, double rhs) {
    auto idx = lp.row_indices(r);
    auto val = lp.row_values(r);
    for (size_t k = 0; k < idx.size(); ++k) qp.set_a(idx[k], row, val[k]);
    qp.set_r(row, rel);
    qp.set_b(row, rhs);
    ++row;
  };
  for (int r = 0; r < lp.num_rows(); ++r) {
    double lo = lp.row_lo[r], hi = lp.row_hi[r];
    if (lo == hi) {
      emit(r, CGAL::EQUAL, lo);
      continue;
    }
    if (std::isfinite(lo)) emit(r, CGAL::LARGER, lo);
    if (std::isfinite(hi)) emit(r, CGAL::SMALLER, hi);
  }
  return qp;
}

}  // namespace

ExactOptimum cgal_minimum(const LinearProgram& lp, int col, double sense) {
  Program qp = to_cgal(lp);
  qp.set_c(col, sense);
  auto solution = CGAL::solve_linear_program(qp, CGAL::Gmpzf());
  ExactOptimum out;
  if (solution.is_infeasible()) {
    out.status = LpStatus::infeasible;
    return out;
  }
  if (!solution.is_optimal()) return out;  // unbounded: only with infinite column bounds
  const mpq_class optimum =
      to_mpq(solution.objective_value_numerator()) / to_mpq(solution.objective_value_denominator());
  out.status = LpStatus::bounded;
  out.down = round_down(optimum);
  out.up = round_up(optimum);
  return out;
}

LpBound to_bound(const ExactOptimum& e, double sense) {
  switch (e.status) {
    case LpStatus::infeasible: return {LpStatus::infeasible, sense > 0 ? kInf : -kInf};
    case LpStatus::unknown: return {LpStatus::bounded, sense > 0 ? -kInf : kInf};
    case LpStatus::bounded: break;
  }
  // max x = -min(-x): the exact minimum of -x rounded down, negated, is max x rounded up.
  return {LpStatus::bounded, sense > 0 ? e.down : -e.down};
}

LpBound CgalLp::minimize(int col) { return to_bound(cgal_minimum(program_, col, 1.0), 1.0); }
LpBound CgalLp::maximize(int col) { return to_bound(cgal_minimum(program_, col, -1.0), -1.0); }

}  // namespace linkbox::prune::lp
