#include "prune/lp/integer_lu.hpp"

#include <algorithm>

namespace linkbox::prune::lp {

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
