#include "prune/lp/exact_simplex_run.hpp"

#include "prune/lp/dyadic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace linkbox::prune::lp {

ExactSimplex::Run::Run(Data& data, int objective, double sign, int budget)
    : d(data),
      n(data.n),
      m(data.m),
      total(data.n + data.m),
      col(objective),
      sense(sign),
      max_pivots(budget),
      t(data.t),
      u(data.u),
      col_pos(data.n, -1),
      row_pos(data.m, -1),
      dual_det(data.dual_det),
      det(data.primal_det) {}

ExactSimplex::Result ExactSimplex::Run::solve(const std::vector<BasisStatus>& cols,
                                              const std::vector<BasisStatus>& rows) {
  if (!start(cols, rows)) return result;
  g = common_shift();
  for (pivots = 0;; ++pivots) {
    result.pivots = pivots;
    if (!index_basis()) return fail(Failure::not_a_vertex);
    if (pivots == 0) result.size = k;
    if (!factor_basis()) return fail(Failure::singular_basis);
    reduced_costs();
    choose_primal_entering();
    basic_solution();
    choose_leaving();
    const bool relaxed = !moved_lo.empty() || !moved_hi.empty();
    if (leave < 0 && enter < 0 && relaxed) {
      restore();
      g = common_shift();
      continue;
    }
    if (leave < 0 && enter < 0) return optimum();
    trace_pivot();
    if (pivots >= max_pivots) return fail(Failure::pivot_budget);
    if (leave >= 0 && enter >= 0) {
      // Neither phase applies: move the violated bounds out to the current values (rounded
      // outward to doubles), run primal simplex pivots, put the bounds back. Once only
      // (see papers/decisions/exact-lp.md): such a basis goes to the caller's fall-back.
      if (relaxed) return fail(Failure::primal_and_dual_infeasible);
      relax_violated_bounds();
      continue;
    }
    if (enter >= 0) {
      if (!primal_pivot(enter)) return fail(Failure::unbounded);
      continue;
    }
    tableau_row();
    choose_dual_entering();
    if (enter < 0) return infeasible();
    trace_dual_pivot();
    st[enter] = BasisStatus::basic;
    st[leave] = leave_up ? BasisStatus::at_lower : BasisStatus::at_upper;
  }
}

// One status per variable, nonbasic ones put at a finite bound. False (with the failure set)
// when the basis is no vertex; false with no failure on a NaN bound.
bool ExactSimplex::Run::start(const std::vector<BasisStatus>& cols, const std::vector<BasisStatus>& rows) {
  st.resize(total);
  for (int j = 0; j < n; ++j) st[j] = cols[j];
  for (int i = 0; i < m; ++i) st[n + i] = rows[i];
  int basic_count = 0;
  for (int v = 0; v < total; ++v) {
    if (std::isnan(d.lo[v]) || std::isnan(d.hi[v])) return false;
    if (st[v] == BasisStatus::basic) {
      ++basic_count;
      continue;
    }
    if (st[v] == BasisStatus::at_lower && !d.has_lo(v)) st[v] = BasisStatus::at_upper;
    else if (st[v] == BasisStatus::at_upper && !d.has_hi(v)) st[v] = BasisStatus::at_lower;
    else if (st[v] == BasisStatus::other) st[v] = d.has_lo(v) ? BasisStatus::at_lower : BasisStatus::at_upper;
    if ((st[v] == BasisStatus::at_lower && !d.has_lo(v)) || (st[v] == BasisStatus::at_upper && !d.has_hi(v))) {
      result.failure = Failure::not_a_vertex;  // a free nonbasic variable
      return false;
    }
  }
  if (basic_count != m) {
    result.failure = Failure::not_a_vertex;
    return false;
  }
  return true;
}

int ExactSimplex::Run::common_shift() const {
  int shift = 0;
  for (int v = 0; v < total; ++v) {
    if (d.has_lo(v)) shift = std::max(shift, integer_shift(d.lo[v]));
    if (d.has_hi(v)) shift = std::max(shift, integer_shift(d.hi[v]));
  }
  return shift;
}

void ExactSimplex::Run::restore() {
  // Last moved first: a bound moved twice gets its true value back last.
  for (auto it = moved_lo.rbegin(); it != moved_lo.rend(); ++it) d.lo[it->first] = it->second;
  for (auto it = moved_hi.rbegin(); it != moved_hi.rend(); ++it) d.hi[it->first] = it->second;
  moved_lo.clear(), moved_hi.clear();
}

// The basic columns and the nonbasic rows, in order, and each one's position; false when
// their counts differ (not a basis).
bool ExactSimplex::Run::index_basis() {
  basic_cols.clear(), nonbasic_rows.clear();
  std::fill(col_pos.begin(), col_pos.end(), -1);
  std::fill(row_pos.begin(), row_pos.end(), -1);
  for (int j = 0; j < n; ++j)
    if (st[j] == BasisStatus::basic) col_pos[j] = static_cast<int>(basic_cols.size()), basic_cols.push_back(j);
  for (int i = 0; i < m; ++i)
    if (st[n + i] != BasisStatus::basic) row_pos[i] = static_cast<int>(nonbasic_rows.size()), nonbasic_rows.push_back(i);
  k = static_cast<int>(basic_cols.size());
  return k == static_cast<int>(nonbasic_rows.size());
}

// M' = the basis matrix with its rows scaled to integers: M'[a][b] = scaled(Nr[a], Bc[b]).
// False when it is singular.
bool ExactSimplex::Run::factor_basis() {
  d.lu.clear(k);
  for (int a = 0; a < k; ++a) {
    const int i = nonbasic_rows[a];
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) {
      const int b = col_pos[d.index[e]];
      if (b >= 0) d.lu.set(a, b, d.scaled[e]);
    }
  }
  return d.lu.factor();
}

// Duals: M^T w = c_B with c = sense e_col. As M' = S M (S = diag 2^shift), M'^T z = c_B
// and w = S z; with Z = det' z (integers, det' > 0 after a sign flip):
//   a nonbasic row activity's reduced cost is w_a = Z_a 2^shift / det',
//   a nonbasic column's is c_j - sum_a w_a A[a][j] = (c_j det' - sum_a Z_a A'[a][j]) / det'.
// Each is kept as an integer numerator and a power of two over det'.
void ExactSimplex::Run::reduced_costs() {
  dual_det = d.lu.det();
  flip_dual = sgn(dual_det) < 0;
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
}

// Dual feasibility: at a lower bound the reduced cost must be >= 0, at an upper <= 0.
// The reduced costs do not depend on where the nonbasic variables sit, so a boxed one
// with the wrong sign moves to its other bound (CLP leaves near-equality rows, whose
// bounds are closer than its tolerance, at either bound with either sign). A one-sided
// variable with the wrong sign enters the basis by a primal simplex pivot (`enter`).
void ExactSimplex::Run::choose_primal_entering() {
  enter = -1;
  most = 0;
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
}

// The basic solution. With V_v = value * 2^g (integers) for the nonbasic variables,
// M' x' = rhs' where rhs'_a = V_{r_i} 2^shift_i - sum_{nonbasic j} A'[i][j] V_j and
// x' = 2^g x_B; X = det x' (det > 0 after a sign flip), so x_j = X_j / (det 2^g).
// Every column's value as num / (det 2^g); the basic rows' follow in choose_leaving.
void ExactSimplex::Run::basic_solution() {
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
}

// Records each bound basic variable v violates; the most violated one, ranked by size in
// floating point, is to leave (any choice is correct; the size only steers toward few pivots).
void ExactSimplex::Run::check_bounds(int v) {
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
}

// Primal feasibility: the basic columns' values checked, the basic rows' computed and checked.
void ExactSimplex::Run::choose_leaving() {
  leave = -1;
  leave_up = false;
  worst = 0;
  violated.clear();
  for (int j : basic_cols) check_bounds(j);
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
    check_bounds(n + i);
  }
}

// Primal and dual feasible: the basic solution is optimal, its value exact.
ExactSimplex::Result ExactSimplex::Run::optimum() {
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

// Moves each violated bound out to its variable's value (rounded outward to a double); the
// true bounds wait in moved_lo / moved_hi.
void ExactSimplex::Run::relax_violated_bounds() {
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
}

}  // namespace linkbox::prune::lp
