#pragma once
// Fraction-free LU of a small square integer matrix (Bareiss, with Markowitz pivoting),
// stored densely (k is at most the LP's column count). After step s every live entry is the
// minor a_ij^(s) over the first s pivot rows and columns plus row i and column j; an entry
// that step s does not update only scales, a^(s) = p_s a^(s-1) / p_(s-1). That scaling is
// deferred: each entry remembers the step its value belongs to and is brought forward when
// read, so a step costs only its fill. The factors of M^T are those of M transposed (the
// same minors), so one factorization serves both solves.
//
// Every intermediate is a minor of the matrix and every division exact, so a solution comes
// out as integers over one common denominator, the determinant.
#include <gmpxx.h>

#include <vector>

namespace linkbox::prune::lp {

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

// Test hook: solves M x = b (or M^T x = b) for the k x k integer matrix M (row-major),
// returning x rounded to doubles; empty when M is singular.
std::vector<double> integer_lu_solve(int k, const std::vector<long>& matrix, const std::vector<long>& b,
                                     bool transpose);

}  // namespace linkbox::prune::lp
