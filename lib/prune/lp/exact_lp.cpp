// The one translation unit that includes CGAL's QP solver (it is heavy to compile).
#include "prune/lp/exact_lp.hpp"

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

enum class Exact { optimal, infeasible, unbounded };

// Exact min of sense * x[col], as a rational.
Exact exact_minimum(const LinearProgram& lp, int col, double sense, mpq_class& optimum) {
  Program qp = to_cgal(lp);
  qp.set_c(col, sense);
  auto solution = CGAL::solve_linear_program(qp, CGAL::Gmpzf());
  if (solution.is_infeasible()) return Exact::infeasible;
  if (!solution.is_optimal()) return Exact::unbounded;  // only with infinite column bounds
  optimum = to_mpq(solution.objective_value_numerator()) / to_mpq(solution.objective_value_denominator());
  return Exact::optimal;
}

}  // namespace

LpBound ExactLp::minimize(int col) {
  mpq_class optimum;
  switch (exact_minimum(program_, col, 1.0, optimum)) {
    case Exact::infeasible: return {LpStatus::infeasible, kInf};
    case Exact::unbounded: return {LpStatus::bounded, -kInf};
    case Exact::optimal: break;
  }
  return {LpStatus::bounded, round_down(optimum)};
}

LpBound ExactLp::maximize(int col) {
  mpq_class optimum;
  switch (exact_minimum(program_, col, -1.0, optimum)) {
    case Exact::infeasible: return {LpStatus::infeasible, -kInf};
    case Exact::unbounded: return {LpStatus::bounded, kInf};
    case Exact::optimal: break;
  }
  return {LpStatus::bounded, round_up(-optimum)};
}

}  // namespace linkbox::prune::lp
