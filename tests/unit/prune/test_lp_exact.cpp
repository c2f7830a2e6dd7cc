// The exact LP backend: CLP's basis checked in rationals, repaired by exact pivots, CGAL as
// the fall-back; compared with CGAL's exact QP solver, the independent reference.
#include "prune/lp/cgal_lp.hpp"
#include "prune/lp/clp_core.hpp"
#include "prune/lp/exact_lp.hpp"
#include "prune/lp/exact_simplex.hpp"
#include "prune/lp/integer_lu.hpp"
#include "prune/lp/lp_record.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <random>

using namespace linkbox::prune::lp;

// Diagnostics on a record (LINKBOX_LP_DIAG_RECORD): how far CLP's bases are from exact.
TEST_CASE("exact basis check on recorded LPs: diagnostics", "[.][lp_diag]") {
  const char* path = std::getenv("LINKBOX_LP_DIAG_RECORD");
  REQUIRE(path);
  const auto lps = read_lp_record(path, 0);
  long solves = 0, clean = 0, primal_bad = 0, dual_bad = 0, both_bad = 0, optimal_after = 0, infeasible = 0, failed = 0;
  double clp_s = 0, exact_s = 0;
  long sizes = 0;
  long reasons[6] = {0, 0, 0, 0, 0, 0};
  const long only = std::getenv("LINKBOX_LP_DIAG_ONLY") ? std::atol(std::getenv("LINKBOX_LP_DIAG_ONLY")) : -1;
  for (const RecordedLp& rec : lps) {
    if (only >= 0 && (&rec - lps.data()) != only) continue;
    ClpCore clp;
    clp.set_tolerances(ExactLp::kPrimalTolerance, ExactLp::kDualTolerance);  // as ExactLp runs it
    ExactSimplex exact;
    clp.load(rec.program);
    exact.load(rec.program);
    std::vector<BasisStatus> cols, rows;
    for (const RecordedSolve& s : rec.solves) {
      for (int j = 0; j < rec.program.num_cols(); ++j)
        if (s.col_lo[j] != rec.program.col_lo[j] || s.col_hi[j] != rec.program.col_hi[j]) {
          clp.set_column_bounds(j, s.col_lo[j], s.col_hi[j]);
          exact.set_column_bounds(j, s.col_lo[j], s.col_hi[j]);
        }
      auto t0 = std::chrono::steady_clock::now();
      const auto finish = clp.solve(s.col, s.sense);
      auto t1 = std::chrono::steady_clock::now();
      clp.basis(cols, rows);
      const auto r = exact.solve(s.col, s.sense, cols, rows, std::getenv("LINKBOX_LP_DIAG_PIVOTS") ? std::atoi(std::getenv("LINKBOX_LP_DIAG_PIVOTS")) : ExactLp::kMaxPivots);
      auto t2 = std::chrono::steady_clock::now();
      clp_s += std::chrono::duration<double>(t1 - t0).count();
      exact_s += std::chrono::duration<double>(t2 - t1).count();
      ++solves;
      sizes += r.size;
      if (finish != ClpCore::Finish::optimal) continue;
      if (r.primal_violations && r.dual_violations) ++both_bad;
      else if (r.primal_violations) ++primal_bad;
      else if (r.dual_violations) ++dual_bad;
      else ++clean;
      if (r.kind == ExactSimplex::Result::optimal) {
        ++optimal_after;
        static const long every = std::getenv("LINKBOX_LP_DIAG_CGAL_EVERY") ? std::atol(std::getenv("LINKBOX_LP_DIAG_CGAL_EVERY")) : 0;
        if ((every && optimal_after % every == 0) || (std::getenv("LINKBOX_LP_DIAG_RELAXED") && r.relaxations > 1)) {
          LinearProgram lp = rec.program;
          lp.col_lo = s.col_lo, lp.col_hi = s.col_hi;
          const ExactOptimum e = cgal_minimum(lp, s.col, s.sense);
          if (e.status != LpStatus::bounded || e.down != r.down || e.up != r.up)
            std::cout << "MISMATCH exact " << r.down << " " << r.up << " cgal " << int(e.status) << " " << e.down << " " << e.up
                      << " pivots " << r.pivots << " flips " << r.flips << "\n";
          else
            std::cout << "match\n";
        }
      }
      else if (r.kind == ExactSimplex::Result::infeasible) {
        ++infeasible;
        LinearProgram lp = rec.program;
        lp.col_lo = s.col_lo, lp.col_hi = s.col_hi;
        const ExactOptimum e = cgal_minimum(lp, s.col, s.sense);
        std::vector<double> y = r.farkas;
        bool proved = exact.proves_infeasible(y);
        for (double& v : y) v = -v;
        proved = proved || exact.proves_infeasible(y);
        std::cout << "exact infeasible (certificate " << (proved ? "checked" : "refused") << "); cgal status " << int(e.status) << " value " << e.down << " at lp " << (&rec - lps.data())
                  << " solve " << (&s - rec.solves.data()) << "\n";
      }
      else ++failed, ++reasons[static_cast<int>(r.failure)];
      if (std::getenv("LINKBOX_LP_DIAG_VERBOSE"))
        std::cout << "k=" << r.size << " flips=" << r.flips << " primal_bad=" << r.primal_violations << " dual_bad=" << r.dual_violations
                  << " pivots=" << r.pivots << " kind=" << r.kind << "\n";
    }
  }
  std::cout << "solves " << solves << " clean " << clean << " primal_bad " << primal_bad << " dual_bad " << dual_bad
            << " both " << both_bad << " | optimal " << optimal_after << " infeasible " << infeasible << " failed "
            << failed << " (reasons 1-5: " << reasons[1] << " " << reasons[2] << " " << reasons[3] << " " << reasons[4]
            << " " << reasons[5] << ") | clp " << clp_s << " s exact " << exact_s << " s, mean k " << double(sizes) / solves << "\n";
}

namespace {

// Plain double Gaussian elimination with partial pivoting, for comparison.
std::vector<double> dense_solve(int k, std::vector<double> a, std::vector<double> b) {
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int i = c + 1; i < k; ++i)
      if (std::abs(a[i * k + c]) > std::abs(a[p * k + c])) p = i;
    if (a[p * k + c] == 0) return {};
    for (int j = 0; j < k; ++j) std::swap(a[c * k + j], a[p * k + j]);
    std::swap(b[c], b[p]);
    for (int i = c + 1; i < k; ++i) {
      const double f = a[i * k + c] / a[c * k + c];
      for (int j = c; j < k; ++j) a[i * k + j] -= f * a[c * k + j];
      b[i] -= f * b[c];
    }
  }
  std::vector<double> x(k);
  for (int c = k - 1; c >= 0; --c) {
    double v = b[c];
    for (int j = c + 1; j < k; ++j) v -= a[c * k + j] * x[j];
    x[c] = v / a[c * k + c];
  }
  return x;
}

// Solves M x = b and M^T x = b with the fraction-free LU and checks each solution's residual
// in floating point; returns how many were compared (those singular in floating point are not,
// nor, with `small_entries`, those the LU finds singular: with entries of a few units, double
// elimination of a singular matrix can end on a rounding error instead of a zero pivot).
int check_lu_solves(int k, const std::vector<long>& m, const std::vector<long>& b, bool small_entries) {
  int compared = 0;
  for (bool transpose : {false, true}) {
    std::vector<double> a(static_cast<size_t>(k) * k), rhs(b.begin(), b.end());
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) a[i * k + j] = static_cast<double>(transpose ? m[j * k + i] : m[i * k + j]);
    const auto reference = dense_solve(k, a, rhs);
    const auto x = integer_lu_solve(k, m, b, transpose);
    INFO("k " << k << " transpose " << transpose);
    if (reference.empty() || (small_entries && x.empty())) continue;
    REQUIRE(x.size() == static_cast<size_t>(k));
    // The residual of the exact solution (rounded) in floating point.
    for (int i = 0; i < k; ++i) {
      double r = -rhs[i], scale = std::abs(rhs[i]);
      for (int j = 0; j < k; ++j) r += a[i * k + j] * x[j], scale += std::abs(a[i * k + j] * x[j]);
      CHECK(std::abs(r) <= 1e-9 * (1 + scale));
    }
    ++compared;
  }
  return compared;
}

}  // namespace

TEST_CASE("fraction-free sparse LU solves M x = b and M^T x = b", "[lp_exact]") {
  std::mt19937 rng(11);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int k = 1 + static_cast<int>(rng() % 30);
    const int per_row = 1 + static_cast<int>(rng() % 4);
    std::vector<long> m(static_cast<size_t>(k) * k, 0), b(k);
    // A permuted diagonal keeps most matrices regular; a few extra entries per row couple them.
    std::vector<int> perm(k);
    for (int i = 0; i < k; ++i) perm[i] = i;
    std::shuffle(perm.begin(), perm.end(), rng);
    for (int i = 0; i < k; ++i) {
      m[i * k + perm[i]] = 1 + static_cast<long>(rng() % 1000);
      for (int t = 0; t < per_row; ++t) m[i * k + rng() % k] = static_cast<long>(rng() % 2001) - 1000;
      b[i] = static_cast<long>(rng() % 2001) - 1000;
    }
    INFO("trial " << trial);
    compared += check_lu_solves(k, m, b, false);
  }
  CHECK(compared > 400);
}

TEST_CASE("fraction-free sparse LU stays exact when entries cancel to zero and fill in again", "[lp_exact]") {
  // Entries in {-1, 0, 1, 2}: eliminations cancel exactly (an entry becomes 0) and a later
  // step fills the same place again, as in the LPs' structured rows. Before the LU told such
  // entries from absent ones, it eliminated them twice (721 wrong residuals here).
  std::mt19937 rng(5);
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int k = 3 + static_cast<int>(rng() % 12);
    std::vector<long> m(static_cast<size_t>(k) * k, 0), b(k);
    for (auto& v : m) v = rng() % 3 == 0 ? static_cast<long>(rng() % 4) - 1 : 0;
    for (int i = 0; i < k; ++i) m[i * k + i] += 1, b[i] = static_cast<long>(rng() % 5) - 2;
    INFO("trial " << trial);
    compared += check_lu_solves(k, m, b, true);
  }
  CHECK(compared > 3000);
}
