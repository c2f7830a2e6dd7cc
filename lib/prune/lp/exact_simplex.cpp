#include "prune/lp/exact_simplex.hpp"

#include "interval/interval.hpp"

#include <gmpxx.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace linkbox::prune::lp {

// Why integers and not GMP rationals: every mpq operation cancels common factors with a gcd,
// and on these systems the gcds took over half of the exact time (perf, cyclohexane). The LP
// data are doubles, i.e. integers times powers of two, so each row is scaled by a power of two
// to integers and the basis systems are solved fraction-free (Bareiss): every intermediate is
// a minor of the matrix, every division exact, and a solution comes out as integers over one
// common denominator, the determinant. Signs and comparisons need no gcd at all.

namespace {

// Pivots before Bland's rule takes over (it cannot cycle, but it is slow). Measured on the
// rigid 6R's LPs (CLP at tight tolerances, 5354 solves): after 4 pivots the long repairs took
// hundreds of pivots and 110 of them spent a 64-pivot budget; after 50, 2 failed (none on the
// budget) and the exact time fell by a fifth. Without Bland, 8 of them cycled.
constexpr int kBlandAfter = 50;

// LINKBOX_EXACT_TRACE=1: each pivot on stderr (diagnostics).
const bool kTrace = std::getenv("LINKBOX_EXACT_TRACE") != nullptr;

// v = mantissa * 2^exponent with an odd mantissa; 0 for v = 0. v must be finite.
struct Dyadic {
  long mantissa = 0;
  int exponent = 0;
};
Dyadic split(double v) {
  if (v == 0) return {};
  int e = 0;
  const double f = std::frexp(v, &e);  // v = f 2^e, 1/2 <= |f| < 1
  long m = static_cast<long>(std::ldexp(f, 53));  // exact: 53 significant bits
  e -= 53;
  while ((m & 1) == 0) m /= 2, ++e;
  return {m, e};
}

// out = v * 2^shift; requires shift + (the exponent of v's lowest bit) >= 0.
void set_scaled(mpz_class& out, double v, int shift) {
  const Dyadic d = split(v);
  out = d.mantissa;
  if (d.mantissa != 0) mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(d.exponent + shift));
}

// out = v * 2^shift * z, the same as set_scaled then a product, but the product is taken on
// v's 53-bit mantissa before the shift (a product with the shifted number would multiply
// mostly zero limbs).
void set_scaled_times(mpz_class& out, double v, int shift, const mpz_class& z) {
  const Dyadic d = split(v);
  if (d.mantissa == 0) {
    out = 0;
    return;
  }
  mpz_mul_si(out.get_mpz_t(), z.get_mpz_t(), d.mantissa);
  mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(d.exponent + shift));
}

// The exponent of v's lowest bit (v finite, non-zero), as a shift that makes v an integer.
int integer_shift(double v) { return v == 0 ? 0 : std::max(0, -split(v).exponent); }

// log2 |z| (z != 0), enough to rank sizes.
double log2_abs(const mpz_class& z) {
  long e = 0;
  const double d = mpz_get_d_2exp(&e, z.get_mpz_t());
  return std::log2(std::fabs(d)) + static_cast<double>(e);
}

// The largest double <= num / den (den > 0), correctly rounded by MPFR.
double round_down(const mpz_class& num, const mpz_class& den) {
  if (sgn(num) == 0) return 0;
  mpfr_t exact, result;
  mpfr_init2(exact, std::max<mpfr_prec_t>(53, static_cast<mpfr_prec_t>(mpz_sizeinbase(num.get_mpz_t(), 2))));
  mpfr_init2(result, 53);
  mpfr_set_z(exact, num.get_mpz_t(), MPFR_RNDN);  // exact at this precision
  mpfr_div_z(result, exact, den.get_mpz_t(), MPFR_RNDD);
  const double d = mpfr_get_d(result, MPFR_RNDD);
  mpfr_clear(exact);
  mpfr_clear(result);
  return d;
}

// a * 2^ea < b * 2^eb for non-negative integers.
bool less_scaled(const mpz_class& a, int ea, const mpz_class& b, int eb, mpz_class& t) {
  if (ea >= eb) {
    mpz_mul_2exp(t.get_mpz_t(), a.get_mpz_t(), static_cast<mp_bitcnt_t>(ea - eb));
    return t < b;
  }
  mpz_mul_2exp(t.get_mpz_t(), b.get_mpz_t(), static_cast<mp_bitcnt_t>(eb - ea));
  return a < t;
}

}  // namespace

// Fraction-free LU of a small square integer matrix (Bareiss, with Markowitz pivoting),
// stored densely (k is at most the LP's column count). After step s every live entry is the
// minor a_ij^(s) over the first s pivot rows and columns plus row i and column j; an entry
// that step s does not update only scales, a^(s) = p_s a^(s-1) / p_(s-1). That scaling is
// deferred: each entry remembers the step its value belongs to and is brought forward when
// read, so a step costs only its fill. The factors of M^T are those of M transposed (the
// same minors), so one factorization serves both solves.
class IntegerLu {
 public:
  void resize(int capacity) {
    if (capacity <= capacity_) return;
    capacity_ = capacity;
    a_.assign(static_cast<size_t>(capacity) * capacity, mpz_class());
    nonzero_.assign(static_cast<size_t>(capacity) * capacity, 0);
    step_.assign(static_cast<size_t>(capacity) * capacity, 0);
    row_list_.resize(capacity);
    col_list_.resize(capacity);
  }
  void clear(int k) {
    for (int i = 0; i < k_; ++i)
      for (int j : row_list_[i]) nz(i, j) = kAbsent;
    k_ = k;
    for (int i = 0; i < k; ++i) row_list_[i].clear(), col_list_[i].clear();
  }
  void set(int i, int j, const mpz_class& v) {
    if (sgn(v) == 0) return;
    a(i, j) = v;
    nz(i, j) = kNonzero;
    step(i, j) = 0;
    row_list_[i].push_back(j);
    col_list_[j].push_back(i);
  }
  bool factor();
  // X = det * M^-1 b for integer b (indexed by matrix rows; overwritten); X by matrix
  // columns. The division by det is left to the caller: X / det is the solution.
  void solve(std::vector<mpz_class>& b, std::vector<mpz_class>& x);
  // Z = det * M^-T c for integer c (indexed by matrix columns; overwritten); Z by rows.
  void solve_transpose(std::vector<mpz_class>& c, std::vector<mpz_class>& z);
  const mpz_class& det() const { return p_[k_]; }

 private:
  mpz_class& a(int i, int j) { return a_[static_cast<size_t>(i) * capacity_ + j]; }
  // Per entry: absent (in no list), non-zero, or cancelled to zero by an elimination (still
  // listed in its row and column).
  static constexpr char kAbsent = 0, kNonzero = 1, kCancelled = 2;
  char& nz(int i, int j) { return nonzero_[static_cast<size_t>(i) * capacity_ + j]; }
  int& step(int i, int j) { return step_[static_cast<size_t>(i) * capacity_ + j]; }
  // Entry (i, j) at step t.
  mpz_class& at(int i, int j, int t) {
    mpz_class& e = a(i, j);
    int& h = step(i, j);
    if (h != t) {
      e *= p_[t];
      mpz_divexact(e.get_mpz_t(), e.get_mpz_t(), p_[h].get_mpz_t());
      h = t;
    }
    return e;
  }
  // The same deferred scaling for one entry of a right-hand side.
  void bring(mpz_class& e, int& h, int t) {
    if (h == t) return;
    if (sgn(e) != 0) {
      e *= p_[t];
      mpz_divexact(e.get_mpz_t(), e.get_mpz_t(), p_[h].get_mpz_t());
    }
    h = t;
  }

  int capacity_ = 0, k_ = 0;
  std::vector<mpz_class> a_;
  std::vector<char> nonzero_;
  std::vector<int> step_;
  std::vector<std::vector<int>> row_list_, col_list_;  // columns (rows) ever non-zero
  std::vector<mpz_class> p_;                // p_[0] = 1, p_[s]: pivot of step s (1-based)
  std::vector<int> prow_, pcol_;            // pivot of step s at index s - 1
  std::vector<std::vector<int>> eliminated_;  // rows updated at step s: L entries a(i, pcol)
  std::vector<std::vector<int>> later_;       // pivot row s's columns pivoted later: U entries
  std::vector<int> hist_;
  mpz_class t_;
};

bool IntegerLu::factor() {
  const int k = k_;
  std::vector<int> row_count(k, 0), col_count(k, 0);
  std::vector<char> row_done(k, 0), col_done(k, 0);
  for (int i = 0; i < k; ++i) row_count[i] = static_cast<int>(row_list_[i].size());
  for (int j = 0; j < k; ++j) col_count[j] = static_cast<int>(col_list_[j].size());
  p_.resize(k + 1);
  p_[0] = 1;
  prow_.assign(k, -1);
  pcol_.assign(k, -1);
  eliminated_.resize(k);
  later_.resize(k);
  for (int s = 1; s <= k; ++s) {
    // Markowitz: the entry minimising (row count - 1)(column count - 1), searched in a few
    // rows and columns of smallest count; a singleton costs nothing and ends the search.
    int r = -1, c = -1;
    long best = -1;
    int min_row = k + 1, min_col = k + 1;
    for (int i = 0; i < k; ++i)
      if (!row_done[i]) min_row = std::min(min_row, row_count[i]);
    for (int j = 0; j < k; ++j)
      if (!col_done[j]) min_col = std::min(min_col, col_count[j]);
    if (min_row == 0 || min_col == 0) return false;  // singular
    auto consider = [&](int i, int j) {
      const long cost = static_cast<long>(row_count[i] - 1) * (col_count[j] - 1);
      if (best < 0 || cost < best) best = cost, r = i, c = j;
    };
    int searched = 0;
    for (int i = 0; i < k && best != 0 && searched < 4; ++i) {
      if (row_done[i] || row_count[i] != min_row) continue;
      ++searched;
      for (int j : row_list_[i])
        if (!col_done[j] && nz(i, j) == kNonzero) consider(i, j);
    }
    searched = 0;
    for (int j = 0; j < k && best != 0 && searched < 4; ++j) {
      if (col_done[j] || col_count[j] != min_col) continue;
      ++searched;
      for (int i : col_list_[j])
        if (!row_done[i] && nz(i, j) == kNonzero) consider(i, j);
    }
    prow_[s - 1] = r, pcol_[s - 1] = c;
    row_done[r] = 1;
    p_[s] = at(r, c, s - 1);
    const mpz_class& ps = p_[s];
    const mpz_class& prev = p_[s - 1];
    std::vector<int>& later = later_[s - 1];
    later.clear();
    for (int j : row_list_[r])
      if (j != c && !col_done[j] && nz(r, j) == kNonzero) later.push_back(j), at(r, j, s - 1), --col_count[j];
    std::vector<int>& rows = eliminated_[s - 1];
    rows.clear();
    for (int i : col_list_[c]) {
      if (row_done[i] || nz(i, c) != kNonzero) continue;
      rows.push_back(i);
      const mpz_class& l = at(i, c, s - 1);  // kept: the L entry of step s
      --row_count[i];
      for (int j : later) {
        mpz_class& e = a(i, j);
        const mpz_class& arj = a(r, j);
        if (nz(i, j) == kNonzero) {
          at(i, j, s - 1);
          e *= ps;  // e = (p_s e - l a_rj) / p_(s-1)
          mpz_submul(e.get_mpz_t(), l.get_mpz_t(), arj.get_mpz_t());
        } else {
          mpz_mul(e.get_mpz_t(), l.get_mpz_t(), arj.get_mpz_t());
          e = -e;
          // An entry that cancelled to zero at an earlier step is listed already: listing it
          // twice would eliminate it twice: a wrong solution (the LU tests in test_lp_exact.cpp).
          if (nz(i, j) == kAbsent) row_list_[i].push_back(j), col_list_[j].push_back(i);
          nz(i, j) = kNonzero;
          ++row_count[i], ++col_count[j];
        }
        mpz_divexact(e.get_mpz_t(), e.get_mpz_t(), prev.get_mpz_t());
        step(i, j) = s;
        if (sgn(e) == 0) nz(i, j) = kCancelled, --row_count[i], --col_count[j];
      }
    }
    col_done[c] = 1;
  }
  return true;
}

void IntegerLu::solve(std::vector<mpz_class>& b, std::vector<mpz_class>& x) {
  const int k = k_;
  // The same elimination on b (an extra column of the matrix), with its own deferred scaling.
  hist_.assign(k, 0);
  for (int s = 1; s <= k; ++s) {
    const int r = prow_[s - 1], c = pcol_[s - 1];
    bring(b[r], hist_[r], s - 1);
    if (sgn(b[r]) == 0) continue;  // the rows below only scale: deferred
    for (int i : eliminated_[s - 1]) {
      bring(b[i], hist_[i], s - 1);
      b[i] *= p_[s];
      mpz_submul(b[i].get_mpz_t(), a(i, c).get_mpz_t(), b[r].get_mpz_t());
      mpz_divexact(b[i].get_mpz_t(), b[i].get_mpz_t(), p_[s - 1].get_mpz_t());
      hist_[i] = s;
    }
  }
  // Back substitution for X = det x: pivot row s reads p_s x_c + sum a_rj x_j = b_r (its
  // values at step s - 1), and det x_j is an integer (Cramer), so each division is exact.
  const mpz_class& d = p_[k];
  x.resize(k);
  for (int s = k; s >= 1; --s) {
    const int r = prow_[s - 1], c = pcol_[s - 1];
    bring(b[r], hist_[r], s - 1);
    mpz_class& v = x[c];
    mpz_mul(v.get_mpz_t(), d.get_mpz_t(), b[r].get_mpz_t());
    for (int j : later_[s - 1])
      if (sgn(x[j]) != 0) mpz_submul(v.get_mpz_t(), a(r, j).get_mpz_t(), x[j].get_mpz_t());
    mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), p_[s].get_mpz_t());
  }
}

void IntegerLu::solve_transpose(std::vector<mpz_class>& c, std::vector<mpz_class>& z) {
  const int k = k_;
  // M^T's elimination with the transposed pivots: step s pivots on column c_s of M and
  // eliminates the columns of pivot row s (later_), with the U entries as multipliers.
  hist_.assign(k, 0);
  for (int s = 1; s <= k; ++s) {
    const int r = prow_[s - 1], cs = pcol_[s - 1];
    bring(c[cs], hist_[cs], s - 1);
    if (sgn(c[cs]) == 0) continue;
    for (int j : later_[s - 1]) {
      bring(c[j], hist_[j], s - 1);
      c[j] *= p_[s];
      mpz_submul(c[j].get_mpz_t(), a(r, j).get_mpz_t(), c[cs].get_mpz_t());
      mpz_divexact(c[j].get_mpz_t(), c[j].get_mpz_t(), p_[s - 1].get_mpz_t());
      hist_[j] = s;
    }
  }
  const mpz_class& d = p_[k];
  z.resize(k);
  for (int s = k; s >= 1; --s) {
    const int r = prow_[s - 1], cs = pcol_[s - 1];
    bring(c[cs], hist_[cs], s - 1);
    mpz_class& v = z[r];
    mpz_mul(v.get_mpz_t(), d.get_mpz_t(), c[cs].get_mpz_t());
    for (int i : eliminated_[s - 1])
      if (sgn(z[i]) != 0) mpz_submul(v.get_mpz_t(), a(i, cs).get_mpz_t(), z[i].get_mpz_t());
    mpz_divexact(v.get_mpz_t(), v.get_mpz_t(), p_[s].get_mpz_t());
  }
}

struct ExactSimplex::Data {
  int n = 0, m = 0;
  std::vector<int> row_start, index;
  std::vector<double> value;
  // Row i times 2^shift[i], an integer row (shift: the lowest bit of its coefficients).
  std::vector<mpz_class> scaled;
  std::vector<int> shift;
  // Bounds of the n + m variables (columns, then row activities), +-inf when absent.
  std::vector<double> lo, hi;
  // The rows' own bounds; lo/hi box each row further by the range a_i . x takes over the
  // column box (rounded outward, so implied by the box): with every variable boxed, any
  // reduced cost of the wrong sign is repaired by moving its variable to the other bound,
  // and the dual simplex alone restores optimality. Redundant rows change no optimum.
  std::vector<double> row_lo, row_hi;
  bool implied_stale = true;  // a column bound was widened since the implied ones were set
  std::vector<char> narrow;   // per variable: flipped, not pivoted, when its reduced cost is wrong

  void set_row_bounds() {
    RoundingGuard guard;  // FastInterval rounds outward only inside it
    for (int i = 0; i < m; ++i) {
      double lo_i = row_lo[i], hi_i = row_hi[i];
      if (lo_i == -kInf || hi_i == kInf) {
        FastInterval range(0.0);
        for (int e = row_start[i]; e < row_start[i + 1]; ++e) {
          const int j = index[e];
          if (!std::isfinite(lo[j]) || !std::isfinite(hi[j])) {
            range = FastInterval(-kInf, kInf);
            break;
          }
          range += FastInterval(value[e]) * FastInterval(lo[j], hi[j]);
        }
        if (lo_i == -kInf && std::isfinite(range.lower())) lo_i = std::min(range.lower(), hi_i);
        if (hi_i == kInf && std::isfinite(range.upper())) hi_i = std::max(range.upper(), lo_i);
      }
      lo[n + i] = lo_i, hi[n + i] = hi_i;
    }
    // Narrow: a row whose bounds are closer than a billionth of the range its activity
    // takes over the box (a linear equation with interval coefficients). Moving it to its
    // other bound barely moves the basic solution.
    narrow.assign(n + m, 0);
    for (int i = 0; i < m; ++i) {
      const double width = row_hi[i] - row_lo[i];
      double range = 0;
      for (int e = row_start[i]; e < row_start[i + 1]; ++e) range += std::fabs(value[e]) * (hi[index[e]] - lo[index[e]]);
      narrow[n + i] = std::isfinite(width) && width <= 1e-9 * range;
    }
    implied_stale = false;
  }

  IntegerLu lu;  // the basis matrix
  // Workspace, kept between solves to spare allocations.
  std::vector<mpz_class> rhs, x, c, z, red, alpha, num;
  std::vector<int> red_exp, alpha_exp, num_exp;
  mpz_class t, u, dual_det, primal_det;

  bool has_lo(int v) const { return lo[v] != -kInf; }
  bool has_hi(int v) const { return hi[v] != kInf; }
  bool fixed(int v) const { return lo[v] == hi[v]; }
};

ExactSimplex::ExactSimplex() : d_(std::make_unique<Data>()) {}
ExactSimplex::~ExactSimplex() = default;

void ExactSimplex::load(const LinearProgram& p) {
  Data& d = *d_;
  d.n = p.num_cols(), d.m = p.num_rows();
  d.row_start = p.row_start;
  d.index = p.index;
  d.value = p.value;
  d.scaled.resize(p.value.size());
  d.shift.assign(d.m, 0);
  for (int i = 0; i < d.m; ++i) {
    int s = 0;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) s = std::max(s, integer_shift(d.value[e]));
    d.shift[i] = s;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) set_scaled(d.scaled[e], d.value[e], s);
  }
  d.lo.resize(d.n + d.m), d.hi.resize(d.n + d.m);
  for (int j = 0; j < d.n; ++j) d.lo[j] = p.col_lo[j], d.hi[j] = p.col_hi[j];
  d.row_lo = p.row_lo;
  d.row_hi = p.row_hi;
  d.implied_stale = true;
  d.lu.resize(d.n);
}

void ExactSimplex::set_column_bounds(int col, double lo, double hi) {
  Data& d = *d_;
  // Narrowing keeps the implied row bounds implied; widening does not.
  if (!(lo >= d.lo[col] && hi <= d.hi[col])) d.implied_stale = true;
  d.lo[col] = lo;
  d.hi[col] = hi;
}

bool ExactSimplex::proves_infeasible(std::span<const double> y) const {
  // The implied row bounds below must be those of the current column box: after a load (or
  // a widening) they still belong to the previous box until refreshed. Reading them stale
  // let a CLP ray "prove" a feasible LP empty (planted cubic; caught by the test suite).
  if (d_->implied_stale) d_->set_row_bounds();
  const Data& d = *d_;
  // For every feasible x, y_i (a_i . x) >= y_i * (the row bound y_i's sign selects); summed,
  // (A^T y) . x >= beta. No x of the box reaches beta: infeasible. Rare (only on CLP's
  // infeasibility verdicts), so plain rationals.
  std::vector<mpq_class> g(d.n);
  mpq_class beta = 0, yi, t;
  bool any = false;
  for (int i = 0; i < d.m && i < static_cast<int>(y.size()); ++i) {
    if (!(y[i] != 0) || !std::isfinite(y[i])) continue;
    const int v = d.n + i;
    const bool positive = y[i] > 0;
    const double bound = positive ? d.lo[v] : d.hi[v];
    if (!std::isfinite(bound)) continue;
    yi = y[i];
    any = true;
    beta += yi * mpq_class(bound);
    for (int k = d.row_start[i]; k < d.row_start[i + 1]; ++k) {
      t = d.value[k];
      g[d.index[k]] += yi * t;
    }
  }
  if (!any) return false;
  mpq_class top = 0;  // max of g . x over the box
  for (int j = 0; j < d.n; ++j) {
    const int s = sgn(g[j]);
    if (s == 0) continue;
    const double bound = s > 0 ? d.hi[j] : d.lo[j];
    if (!std::isfinite(bound)) return false;  // unbounded above
    top += g[j] * mpq_class(bound);
  }
  return top < beta;
}

ExactSimplex::Result ExactSimplex::solve(int col, double sense, std::vector<BasisStatus> cols,
                                         std::vector<BasisStatus> rows, int max_pivots) {
  Data& d = *d_;
  const int n = d.n, m = d.m, total = n + m;
  Result result;
  if (d.implied_stale) d.set_row_bounds();
  // One status per variable; nonbasic ones put at a finite bound.
  std::vector<BasisStatus> st(total);
  for (int j = 0; j < n; ++j) st[j] = cols[j];
  for (int i = 0; i < m; ++i) st[n + i] = rows[i];
  int basic_count = 0;
  // Every value below is an integer over a power of two 2^g common to all bounds.
  auto common_shift = [&] {
    int shift = 0;
    for (int v = 0; v < total; ++v) {
      if (d.has_lo(v)) shift = std::max(shift, integer_shift(d.lo[v]));
      if (d.has_hi(v)) shift = std::max(shift, integer_shift(d.hi[v]));
    }
    return shift;
  };
  for (int v = 0; v < total; ++v) {
    if (std::isnan(d.lo[v]) || std::isnan(d.hi[v])) return result;
    if (st[v] == BasisStatus::basic) {
      ++basic_count;
      continue;
    }
    if (st[v] == BasisStatus::at_lower && !d.has_lo(v)) st[v] = BasisStatus::at_upper;
    else if (st[v] == BasisStatus::at_upper && !d.has_hi(v)) st[v] = BasisStatus::at_lower;
    else if (st[v] == BasisStatus::other) st[v] = d.has_lo(v) ? BasisStatus::at_lower : BasisStatus::at_upper;
    if ((st[v] == BasisStatus::at_lower && !d.has_lo(v)) || (st[v] == BasisStatus::at_upper && !d.has_hi(v)))
      return result.failure = 1, result;  // a free nonbasic variable: not a vertex
  }
  if (basic_count != m) return result.failure = 1, result;
  auto bound_of = [&](int v) { return st[v] == BasisStatus::at_lower ? d.lo[v] : d.hi[v]; };

  int g = common_shift();
  // Bounds moved out to a primal infeasible basic variable's value, so that primal simplex
  // pivots can run from a basis that is neither primal nor dual feasible (variable, side,
  // true bound); put back once the basis is dual feasible, before the dual simplex.
  std::vector<std::pair<int, double>> moved_lo, moved_hi;
  auto restore = [&] {
    // Last moved first: a bound moved twice gets its true value back last.
    for (auto it = moved_lo.rbegin(); it != moved_lo.rend(); ++it) d.lo[it->first] = it->second;
    for (auto it = moved_hi.rbegin(); it != moved_hi.rend(); ++it) d.hi[it->first] = it->second;
    moved_lo.clear(), moved_hi.clear();
  };
  struct OnExit {
    decltype(restore)& f;
    ~OnExit() { f(); }
  } put_back{restore};  // whichever way this returns, the LP's bounds are its own again
  std::vector<std::pair<int, bool>> violated;
  std::vector<int> basic_cols, nonbasic_rows, col_pos(n, -1), row_pos(m, -1);
  mpz_class& t = d.t;
  mpz_class& u = d.u;
  for (int pivots = 0;; ++pivots) {
    result.pivots = pivots;
    basic_cols.clear(), nonbasic_rows.clear();
    std::fill(col_pos.begin(), col_pos.end(), -1);
    std::fill(row_pos.begin(), row_pos.end(), -1);
    for (int j = 0; j < n; ++j)
      if (st[j] == BasisStatus::basic) col_pos[j] = static_cast<int>(basic_cols.size()), basic_cols.push_back(j);
    for (int i = 0; i < m; ++i)
      if (st[n + i] != BasisStatus::basic) row_pos[i] = static_cast<int>(nonbasic_rows.size()), nonbasic_rows.push_back(i);
    const int k = static_cast<int>(basic_cols.size());
    if (k != static_cast<int>(nonbasic_rows.size())) return result.failure = 1, result;
    if (pivots == 0) result.size = k;

    // M' = the basis matrix with its rows scaled to integers: M'[a][b] = scaled(Nr[a], Bc[b]).
    d.lu.clear(k);
    for (int a = 0; a < k; ++a) {
      const int i = nonbasic_rows[a];
      for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
        const int b = col_pos[d.index[e]];
        if (b >= 0) d.lu.set(a, b, d.scaled[e]);
      }
    }
    if (!d.lu.factor()) return result.failure = 2, result;

    // Duals: M^T w = c_B with c = sense e_col. As M' = S M (S = diag 2^shift), M'^T z = c_B
    // and w = S z; with Z = det' z (integers, det' > 0 after a sign flip):
    //   a nonbasic row activity's reduced cost is w_a = Z_a 2^shift / det',
    //   a nonbasic column's is c_j - sum_a w_a A[a][j] = (c_j det' - sum_a Z_a A'[a][j]) / det'.
    // Each is kept as an integer numerator and a power of two over det'.
    mpz_class& dual_det = d.dual_det;
    dual_det = d.lu.det();
    const bool flip_dual = sgn(dual_det) < 0;
    if (flip_dual) dual_det = -dual_det;
    d.c.assign(k, mpz_class());
    d.z.assign(k, mpz_class());
    if (col_pos[col] >= 0) {
      d.c[col_pos[col]] = sense > 0 ? 1 : -1;
      d.lu.solve_transpose(d.c, d.z);
      if (flip_dual)
        for (auto& v : d.z) v = -v;
    }
    d.red.resize(total);
    d.red_exp.assign(total, 0);
    for (int v = 0; v < total; ++v) d.red[v] = 0;
    if (col_pos[col] < 0) d.red[col] = sense > 0 ? dual_det : mpz_class(-dual_det);
    for (int a = 0; a < k; ++a) {
      const int i = nonbasic_rows[a];
      const mpz_class& za = d.z[a];
      if (sgn(za) == 0) continue;
      d.red[n + i] = za;
      d.red_exp[n + i] = d.shift[i];
      for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
        const int j = d.index[e];
        if (col_pos[j] < 0) mpz_submul(d.red[j].get_mpz_t(), za.get_mpz_t(), d.scaled[e].get_mpz_t());
      }
    }
    // Dual feasibility: at a lower bound the reduced cost must be >= 0, at an upper <= 0.
    // The reduced costs do not depend on where the nonbasic variables sit, so a boxed one
    // with the wrong sign moves to its other bound (CLP leaves near-equality rows, whose
    // bounds are closer than its tolerance, at either bound with either sign). A one-sided
    // variable with the wrong sign enters the basis by a primal simplex pivot below.
    int enter = -1;
    double most = 0;
    for (int v = 0; v < total; ++v) {
      if (st[v] == BasisStatus::basic || d.fixed(v)) continue;
      const int s = sgn(d.red[v]);
      const bool wrong = st[v] == BasisStatus::at_lower ? s < 0 : s > 0;
      if (!wrong) continue;
      if (d.narrow[v] && moved_lo.empty() && moved_hi.empty()) {
        st[v] = st[v] == BasisStatus::at_lower ? BasisStatus::at_upper : BasisStatus::at_lower;
        if (pivots == 0) ++result.flips;
        continue;
      }
      if (pivots == 0) ++result.dual_violations;
      const double size = log2_abs(d.red[v]) + d.red_exp[v];  // Dantzig's choice, roughly
      if (enter < 0 || size > most) enter = v, most = size;
    }

    // The basic solution. With V_v = value * 2^g (integers) for the nonbasic variables,
    // M' x' = rhs' where rhs'_a = V_{r_i} 2^shift_i - sum_{nonbasic j} A'[i][j] V_j and
    // x' = 2^g x_B; X = det x' (det > 0 after a sign flip), so x_j = X_j / (det 2^g).
    d.rhs.resize(k);
    for (int a = 0; a < k; ++a) {
      const int i = nonbasic_rows[a];
      mpz_class& r = d.rhs[a];
      set_scaled(r, bound_of(n + i), g + d.shift[i]);
      for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
        const int j = d.index[e];
        if (col_pos[j] >= 0) continue;
        const double v = bound_of(j);
        if (v == 0) continue;
        set_scaled(t, v, g);
        mpz_submul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), t.get_mpz_t());
      }
    }
    d.lu.solve(d.rhs, d.x);
    mpz_class& det = d.primal_det;
    det = d.lu.det();
    if (sgn(det) < 0) {
      det = -det;
      for (auto& v : d.x) v = -v;
    }
    // Every variable's value as num / (det 2^(g + num_exp)): columns and nonbasic rows with
    // num_exp 0, a basic row i (sum_j A'[i][j] x_j = 2^shift_i r_i) with num_exp shift_i.
    d.num.resize(total);
    d.num_exp.assign(total, 0);
    for (int j = 0; j < n; ++j) {
      if (col_pos[j] >= 0) {
        d.num[j] = d.x[col_pos[j]];
      } else {
        set_scaled_times(d.num[j], bound_of(j), g, det);
      }
    }
    // The most violated basic variable, ranked by size in floating point (any choice is
    // correct; the size only steers toward few pivots).
    int leave = -1;
    bool leave_up = false;  // it must rise to its lower bound
    double worst = 0;
    auto check = [&](int v) {
      // value - bound = (num - B det 2^num_exp) / (det 2^(g + num_exp)), B = bound 2^g.
      for (int side = 0; side < 2; ++side) {
        const double bound = side == 0 ? d.lo[v] : d.hi[v];
        if (!std::isfinite(bound)) continue;
        set_scaled_times(t, bound, g + d.num_exp[v], det);
        u = d.num[v] - t;
        const int s = sgn(u);
        if (side == 0 ? s >= 0 : s <= 0) continue;
        if (pivots == 0) ++result.primal_violations;
        violated.push_back({v, side == 0});
        // After a few pivots, Bland's rule (the lowest index leaves; ties in the ratio test
        // go to the lowest index too): degenerate pivots cannot cycle.
        const double size = log2_abs(u) - d.num_exp[v];
        const bool bland = pivots >= kBlandAfter;
        if (leave < 0 || (!bland && size > worst) || (bland && v < leave))
          leave = v, leave_up = side == 0, worst = size;
      }
    };
    violated.clear();
    for (int j : basic_cols) check(j);
    for (int i = 0; i < m; ++i) {
      if (st[n + i] != BasisStatus::basic) continue;
      mpz_class& r = d.num[n + i];
      d.num_exp[n + i] = d.shift[i];
      r = 0;
      mpz_class& nonbasic_part = u;  // sum over nonbasic columns of A' V, times det once
      nonbasic_part = 0;
      for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
        const int j = d.index[e];
        if (col_pos[j] >= 0) {
          mpz_addmul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), d.num[j].get_mpz_t());
        } else {
          const double v = bound_of(j);
          if (v == 0) continue;
          set_scaled(t, v, g);
          mpz_addmul(nonbasic_part.get_mpz_t(), d.scaled[e].get_mpz_t(), t.get_mpz_t());
        }
      }
      mpz_addmul(r.get_mpz_t(), nonbasic_part.get_mpz_t(), det.get_mpz_t());
      check(n + i);
    }

    if (leave < 0 && enter < 0 && (!moved_lo.empty() || !moved_hi.empty())) {
      restore();
      g = common_shift();
      continue;
    }
    if (leave < 0 && enter < 0) {
      // Primal and dual feasible: the basic solution is optimal, its value exact.
      result.kind = Result::optimal;
      mpz_class& num = t;
      if (col_pos[col] >= 0) {
        num = d.x[col_pos[col]];
        mpz_mul_2exp(u.get_mpz_t(), det.get_mpz_t(), static_cast<mp_bitcnt_t>(g));
        if (sense < 0) num = -num;
        result.down = round_down(num, u);
        num = -num;
        result.up = -round_down(num, u);
      } else {
        const double v = sense * bound_of(col);  // a double: exact
        result.down = result.up = v;
      }
      return result;
    }
    // Primal simplex: `enter` leaves its bound into the interior and the basic variables
    // move along its column; the first to reach a bound leaves (a one-sided `enter` has no
    // other bound to flip to). The column, d(basic)/d(enter):
    //   enter = x_j: M y = -A[N rows, j], i.e. M' Y = -A'[N rows, j] with y = Y / det;
    //   enter = r_i (position a): M y = e_a, i.e. M' Y = e_a with y = 2^shift_a Y / det;
    // a basic row q moves by A[q,B] y = 2^-shift_q A'[q,B] y. Each direction is kept as
    // dir / (det 2^dir_exp).
    auto primal_pivot = [&](int v, std::vector<BasisStatus>& status) {
      const bool rising = status[v] == BasisStatus::at_lower;
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
        if (status[n + i] != BasisStatus::basic) continue;
        mpz_class& r = d.alpha[n + i];
        r = 0;
        d.alpha_exp[n + i] = d.shift[i] + enter_exp;
        for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
          const int j = d.index[e];
          if (col_pos[j] >= 0) mpz_addmul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), d.z[col_pos[j]].get_mpz_t());
          else if (j == v) mpz_addmul(r.get_mpz_t(), d.scaled[e].get_mpz_t(), det.get_mpz_t());
        }
      }
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
        if (status[w] != BasisStatus::basic) continue;
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
        status[v] = rising ? BasisStatus::at_upper : BasisStatus::at_lower;
        return true;
      }
      status[v] = BasisStatus::basic;
      status[out] = out_to_lower ? BasisStatus::at_lower : BasisStatus::at_upper;
      return true;
    };

    if (kTrace)
      std::fprintf(stderr, "pivot %d: leave %d (%s, up %d, log2 %.1f) enter %d (%s) k %d\n", pivots, leave,
                   leave < 0 ? "-" : leave < n ? "col" : "row", int(leave_up), worst, enter,
                   enter < 0 ? "-" : enter < n ? "col" : "row", k);
    if (pivots >= max_pivots) return result.failure = 4, result;
    if (leave >= 0 && enter >= 0) {
      // Neither phase applies: move the violated bounds out to the current values (rounded
      // outward to doubles), run primal simplex pivots, put the bounds back.
      // Once only: moving them again let the values wander (to 1e83 on the rigid 6R) and
      // ended in infeasibility claims CGAL refuted; such a basis goes to CGAL (failure 3).
      // (Seen while the LU still eliminated cancelled entries twice, 804dee1; not re-tried.)
      if (!moved_lo.empty() || !moved_hi.empty()) return result.failure = 3, result;
      ++result.relaxations;
      mpz_class& den = u;
      for (auto [v, below] : violated) {
        mpz_mul_2exp(den.get_mpz_t(), det.get_mpz_t(), static_cast<mp_bitcnt_t>(g + d.num_exp[v]));
        if (below) {
          moved_lo.push_back({v, d.lo[v]});
          d.lo[v] = round_down(d.num[v], den);
        } else {
          moved_hi.push_back({v, d.hi[v]});
          t = -d.num[v];
          d.hi[v] = -round_down(t, den);
        }
      }
      g = common_shift();
      continue;
    }
    if (enter >= 0) {
      if (!primal_pivot(enter, st)) return result.failure = 5, result;
      continue;
    }

    // Dual simplex. The tableau row of `leave`, alpha_v = d(leave)/d(v) for nonbasic v:
    //   as a column x_p (basic position b): rho = M^-T e_b, i.e. M'^T R = e_b, rho_a =
    //     2^shift_a R_a / det'; alpha of row a = rho_a, of column j = -sum_a rho_a A[a][j]
    //     = -sum_a R_a A'[a][j] / det';
    //   as a row r_q (= A[q,B] x_B + A[q,N] x_N): M'^T R = A'[q,B], rho_a =
    //     2^(shift_a - shift_q) R_a / det'; alpha of column j = 2^-shift_q (A'[q][j] det'
    //     - sum_a R_a A'[a][j]) / det'.
    // alpha_v = alpha[v] 2^alpha_exp[v] / det', like the reduced costs.
    d.c.assign(k, mpz_class());
    d.alpha.resize(total);
    for (int v = 0; v < total; ++v) d.alpha[v] = 0;
    d.alpha_exp.assign(total, 0);
    int row_shift = 0;
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
    // Entering: a nonbasic variable that moves `leave` toward its violated bound; the
    // smallest |reduced / alpha| keeps every reduced cost's sign (compared exactly).
    // Among equal ratios (the objective is one variable, so most reduced costs are zero and
    // ties are the rule) the largest |alpha| moves `leave` furthest; under Bland's rule the
    // lowest index.
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
    // No entering variable: every nonbasic variable already sits at the bound that moves
    // `leave` toward its own, and it still falls short. The row is an exact consequence of
    // r = A x, so no point of the box satisfies the rows.
    if (enter < 0) {
      if (kTrace) {
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
    if (kTrace)
      std::fprintf(stderr, "   dual pivot: enter %d (%s, st %d, narrow %d, red sign %d)\n", enter, enter < n ? "col" : "row",
                   int(st[enter]), int(d.narrow[enter]), sgn(d.red[enter]));
    st[enter] = BasisStatus::basic;
    st[leave] = leave_up ? BasisStatus::at_lower : BasisStatus::at_upper;
  }
}

std::vector<double> integer_lu_solve(int k, const std::vector<long>& matrix, const std::vector<long>& b,
                                     bool transpose) {
  IntegerLu lu;
  lu.resize(k);
  lu.clear(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) lu.set(i, j, mpz_class(matrix[static_cast<size_t>(i) * k + j]));
  if (!lu.factor()) return {};
  std::vector<mpz_class> rhs(k), x;
  for (int i = 0; i < k; ++i) rhs[i] = b[i];
  if (transpose) lu.solve_transpose(rhs, x);
  else lu.solve(rhs, x);
  std::vector<double> out(k);
  for (int i = 0; i < k; ++i) {
    mpq_class q(x[i], lu.det());
    q.canonicalize();  // also makes the denominator positive, as GMP requires
    out[i] = q.get_d();
  }
  return out;
}

}  // namespace linkbox::prune::lp
