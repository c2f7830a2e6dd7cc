// The pivots of ExactSimplex::Run: the primal simplex step (its ratio test included), the
// dual simplex row and entering variable, and the Farkas multipliers when no variable enters.
#include "prune/lp/dyadic.hpp"
#include "prune/lp/exact_simplex_run.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace linkbox::prune::lp {

namespace {
const bool kTrace = std::getenv("LINKBOX_EXACT_TRACE") != nullptr;
}  // namespace

// Primal simplex: `enter` leaves its bound into the interior and the basic variables
// move along its column; the first to reach a bound leaves (a one-sided `enter` has no
// other bound to flip to). The column, d(basic)/d(enter):
//   enter = x_j: M y = -A[N rows, j], i.e. M' Y = -A'[N rows, j] with y = Y / det;
//   enter = r_i (position a): M y = e_a, i.e. M' Y = e_a with y = 2^shift_a Y / det;
// a basic row q moves by A[q,B] y = 2^-shift_q A'[q,B] y. Each direction is kept as
// dir / (det 2^dir_exp), in alpha and alpha_exp.
void ExactSimplex::Run::primal_column(int v) {
  d.rhs.assign(k, mpz_class());
  int enter_exp = 0;
  if (v < n) {
    for (int a = 0; a < k; ++a) {
      const int i = nonbasic_rows[a];
      for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e)
        if (d.index[e] == v) d.rhs[a] = -d.scaled[e];
    }
  } else {
    d.rhs[row_pos[v - n]] = 1;
    enter_exp = -d.shift[v - n];
  }
  d.lu.solve(d.rhs, d.z);
  if (sgn(d.lu.det()) < 0)
    for (auto& y : d.z) y = -y;
  d.alpha.resize(total);
  d.alpha_exp.assign(total, 0);
  for (int b = 0; b < k; ++b) d.alpha[basic_cols[b]] = d.z[b], d.alpha_exp[basic_cols[b]] = enter_exp;
  for (int i = 0; i < m; ++i) {
    if (st[n + i] != BasisStatus::basic) continue;
    mpz_class& r = d.alpha[n + i];
    r = 0;
    d.alpha_exp[n + i] = d.shift[i] + enter_exp;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
      const int j = d.index[e];
      if (col_pos[j] >= 0) mpz_addmul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), d.z[col_pos[j]].get_mpz_t());
      else if (j == v) mpz_addmul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), det.get_mpz_t());
    }
  }
}

// The primal simplex pivot on `v` (see primal_column). False when no variable stops it
// (unbounded).
bool ExactSimplex::Run::primal_pivot(int v) {
  const bool rising = st[v] == BasisStatus::at_lower;
  primal_column(v);
  // Ratio test: basic u moving toward bound B takes step |num_u - B det 2^num_exp|
  // 2^(dir_exp - num_exp - g) / |dir_u| (det cancels); the smallest step wins.
  int out = -1;
  bool out_to_lower = false;
  mpz_class best_num, best_den, gap, left, right;
  int best_exp = 0;
  if (d.has_lo(v) && d.has_hi(v)) {
    // Its own other bound: a flip, step (hi - lo) = (H - L) / 2^g in the same units.
    set_scaled(best_num, d.hi[v], g);
    set_scaled(t, d.lo[v], g);
    best_num -= t;
    best_den = 1;
    out = v;
  }
  for (int w = 0; w < total; ++w) {
    if (st[w] != BasisStatus::basic) continue;
    int s = sgn(d.alpha[w]);
    if (s == 0) continue;
    if (!rising) s = -s;  // w's direction of motion
    const double bound = s < 0 ? d.lo[w] : d.hi[w];
    if (!std::isfinite(bound)) continue;
    set_scaled_times(t, bound, g + d.num_exp[w], det);
    gap = d.num[w] - t;
    mpz_abs(gap.get_mpz_t(), gap.get_mpz_t());
    const int e_w = d.alpha_exp[w] - d.num_exp[w];
    if (out >= 0) {
      // step_w < best  <=>  gap best_den 2^e_w < best_num |dir_w| 2^best_exp
      mpz_mul(left.get_mpz_t(), gap.get_mpz_t(), best_den.get_mpz_t());
      mpz_mul(right.get_mpz_t(), best_num.get_mpz_t(), d.alpha[w].get_mpz_t());
      mpz_abs(right.get_mpz_t(), right.get_mpz_t());
      if (!less_scaled(left, e_w, right, best_exp, u)) continue;
    }
    out = w, out_to_lower = s < 0;
    best_num = gap;
    best_den = d.alpha[w];
    mpz_abs(best_den.get_mpz_t(), best_den.get_mpz_t());
    best_exp = e_w;
  }
  if (out < 0) return false;  // unbounded: only with infinite column bounds
  if (out == v) {
    st[v] = rising ? BasisStatus::at_upper : BasisStatus::at_lower;
    return true;
  }
  st[v] = BasisStatus::basic;
  st[out] = out_to_lower ? BasisStatus::at_lower : BasisStatus::at_upper;
  return true;
}

// The dual simplex row of `leave`, alpha_v = d(leave)/d(v) for nonbasic v:
//   as a column x_p (basic position b): rho = M^-T e_b, i.e. M'^T R = e_b, rho_a =
//     2^shift_a R_a / det'; alpha of row a = rho_a, of column j = -sum_a rho_a A[a][j]
//     = -sum_a R_a A'[a][j] / det';
//   as a row r_q (= A[q,B] x_B + A[q,N] x_N): M'^T R = A'[q,B], rho_a =
//     2^(shift_a - shift_q) R_a / det'; alpha of column j = 2^-shift_q (A'[q][j] det'
//     - sum_a R_a A'[a][j]) / det'.
// alpha_v = alpha[v] 2^alpha_exp[v] / det', like the reduced costs.
void ExactSimplex::Run::tableau_row() {
  d.c.assign(k, mpz_class());
  d.alpha.resize(total);
  for (int v = 0; v < total; ++v) d.alpha[v] = 0;
  d.alpha_exp.assign(total, 0);
  row_shift = 0;
  if (leave < n) {
    d.c[col_pos[leave]] = 1;
  } else {
    const int q = leave - n;
    row_shift = d.shift[q];
    for (int e = d.row_start[q]; e < d.row_start[q + 1]; ++e) {
      const int j = d.index[e];
      if (col_pos[j] >= 0) d.c[col_pos[j]] = d.scaled[e];
      else d.alpha[j] = d.scaled[e] * dual_det, d.alpha_exp[j] = -row_shift;
    }
  }
  d.lu.solve_transpose(d.c, d.z);
  if (flip_dual)
    for (auto& v : d.z) v = -v;
  for (int a = 0; a < k; ++a) {
    const int i = nonbasic_rows[a];
    const mpz_class& ra = d.z[a];
    if (sgn(ra) == 0) continue;
    d.alpha[n + i] = ra;
    d.alpha_exp[n + i] = d.shift[i] - row_shift;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
      const int j = d.index[e];
      if (col_pos[j] >= 0) continue;
      mpz_submul(d.alpha[j].get_mpz_t(), ra.get_mpz_t(), d.scaled[e].get_mpz_t());
      d.alpha_exp[j] = -row_shift;
    }
  }
}

// Entering: a nonbasic variable that moves `leave` toward its violated bound; the
// smallest |reduced / alpha| keeps every reduced cost's sign (compared exactly).
// Among equal ratios (the objective is one variable, so most reduced costs are zero and
// ties are the rule) the largest |alpha| moves `leave` furthest; under Bland's rule the
// lowest index. None: `enter` stays -1.
void ExactSimplex::Run::choose_dual_entering() {
  mpz_class best_num, best_den, left, right;
  int best_exp = 0;
  double best_size = 0;
  const bool bland = pivots >= kBlandAfter;
  for (int v = 0; v < total; ++v) {
    if (st[v] == BasisStatus::basic || d.fixed(v)) continue;
    const int s = sgn(d.alpha[v]);
    if (s == 0) continue;
    const bool can_rise = st[v] == BasisStatus::at_lower;  // else it can only fall
    const bool helps = leave_up ? (can_rise ? s > 0 : s < 0) : (can_rise ? s < 0 : s > 0);
    if (!helps) continue;
    // ratio_v = |red_v| / |alpha_v| * 2^(red_exp - alpha_exp); det' cancels.
    const int e_v = d.red_exp[v] - d.alpha_exp[v];
    const double size = log2_abs(d.alpha[v]) + d.alpha_exp[v];
    if (enter >= 0) {
      // ratio_v < best  <=>  |red_v| best_den 2^e_v < best_num |alpha_v| 2^best_exp
      mpz_mul(left.get_mpz_t(), d.red[v].get_mpz_t(), best_den.get_mpz_t());
      mpz_mul(right.get_mpz_t(), best_num.get_mpz_t(), d.alpha[v].get_mpz_t());
      mpz_abs(left.get_mpz_t(), left.get_mpz_t());
      mpz_abs(right.get_mpz_t(), right.get_mpz_t());
      if (!less_scaled(left, e_v, right, best_exp, t)) {
        const bool tie = !less_scaled(right, best_exp, left, e_v, t);
        if (!tie || bland || size <= best_size) continue;
      }
    }
    enter = v;
    best_num = d.red[v];
    best_den = d.alpha[v];
    best_exp = e_v;
    best_size = size;
  }
}

// No entering variable: every nonbasic variable already sits at the bound that moves
// `leave` toward its own, and it still falls short. The row is an exact consequence of
// r = A x, so no point of the box satisfies the rows.
ExactSimplex::Result ExactSimplex::Run::infeasible() {
  trace_infeasible();
  // The row's multipliers, for the caller to check as a Farkas certificate (ExactLp
  // accepts the verdict only then): leave = sum_a rho_a r_a + (columns), so the rows
  // combine with rho_a (and -1 on a leaving row q) into a row no box point satisfies.
  result.farkas.assign(m, 0.0);
  mpq_class q;
  for (int a = 0; a < k; ++a) {
    if (sgn(d.z[a]) == 0) continue;
    q = mpq_class(d.z[a], dual_det);
    q.canonicalize();
    const int e = d.shift[nonbasic_rows[a]] - row_shift;
    if (e >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(e));
    else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-e));
    result.farkas[nonbasic_rows[a]] = q.get_d();
  }
  if (leave >= n) result.farkas[leave - n] = -1.0;
  result.kind = Result::infeasible;
  return result;
}

void ExactSimplex::Run::trace_pivot() const {
  if (kTrace)
    std::fprintf(stderr, "pivot %d: leave %d (%s, up %d, log2 %.1f) enter %d (%s) k %d\n", pivots, leave,
                 leave < 0 ? "-" : leave < n ? "col" : "row", int(leave_up), worst, enter,
                 enter < 0 ? "-" : enter < n ? "col" : "row", k);
}

void ExactSimplex::Run::trace_dual_pivot() const {
  if (kTrace)
    std::fprintf(stderr, "   dual pivot: enter %d (%s, st %d, narrow %d, red sign %d)\n", enter, enter < n ? "col" : "row",
                 int(st[enter]), int(d.narrow[enter]), sgn(d.red[enter]));
}

void ExactSimplex::Run::trace_infeasible() const {
  if (!kTrace) return;
  mpz_class den;
  mpz_mul_2exp(den.get_mpz_t(), det.get_mpz_t(), static_cast<mp_bitcnt_t>(g + d.num_exp[leave]));
  std::fprintf(stderr, "INFEASIBLE: leave %d value %.17g lo %.17g hi %.17g up %d\n", leave,
               round_down(d.num[leave], den), d.lo[leave], d.hi[leave], int(leave_up));
  for (int v = 0; v < total; ++v) {
    if (st[v] == BasisStatus::basic || sgn(d.alpha[v]) == 0) continue;
    std::fprintf(stderr, "  v %d st %d alpha %d (log2 %.1f) lo %.17g hi %.17g fixed %d\n", v, int(st[v]),
                 sgn(d.alpha[v]), log2_abs(d.alpha[v]) + d.alpha_exp[v], d.lo[v], d.hi[v], int(d.fixed(v)));
  }
  // The tableau row's identity at a random point of the column box.
  std::vector<mpq_class> x(total);
  for (int j = 0; j < n; ++j) x[j] = mpq_class(d.lo[j]) + (mpq_class(d.hi[j]) - mpq_class(d.lo[j])) * mpq_class(j % 7 + 1, 9);
  for (int i = 0; i < m; ++i) {
    x[n + i] = 0;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) x[n + i] += mpq_class(d.value[e]) * x[d.index[e]];
  }
  mpq_class dual_q(dual_det), rhs(d.num[leave], den);
  rhs.canonicalize();
  for (int v = 0; v < total; ++v) {
    if (st[v] == BasisStatus::basic || sgn(d.alpha[v]) == 0) continue;
    mpq_class a(d.alpha[v], dual_det);
    a.canonicalize();
    if (d.alpha_exp[v] >= 0) mpq_mul_2exp(a.get_mpq_t(), a.get_mpq_t(), d.alpha_exp[v]);
    else mpq_div_2exp(a.get_mpq_t(), a.get_mpq_t(), -d.alpha_exp[v]);
    rhs += a * (x[v] - mpq_class(bound_of(v)));
  }
  std::fprintf(stderr, "  identity: leave at point %.17g, row gives %.17g\n", x[leave].get_d(), rhs.get_d());
}

}  // namespace linkbox::prune::lp
