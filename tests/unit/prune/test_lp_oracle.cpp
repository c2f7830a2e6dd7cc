// The soundness oracle of the LP backends (issue 13): LPs recorded from short searches on the
// bundled cases (prune/lp/lp_record.hpp) are re-solved exactly, and every answer of the safe
// backend (CLP + Neumaier-Shcherbina bound, checked Farkas certificates) must lie on the right
// side of the exact optimum: a minimum never above it, a maximum never below it, and an
// infeasibility claim only on an LP CGAL's exact solver finds empty. The exact optimum comes
// from ExactLp (CLP's basis checked and repaired in rationals) and, on a sample, independently
// from CGAL's QP solver, which must agree with it to the bit. The CI test runs a few searches'
// worth; the hidden one runs a given record (papers/porta-iterated-lp/lp_oracle.py).
#include "formulate/load.hpp"
#include "prune/lp/cgal_lp.hpp"
#include "prune/lp/exact_lp.hpp"
#include "prune/lp/lp_record.hpp"
#include "solve/solve_case.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace linkbox;
using namespace linkbox::prune::lp;

namespace {

struct OracleStats {
  long lps = 0, solves = 0;
  long safe_bounded = 0, safe_infeasible = 0, safe_unknown = 0;
  long exact_infeasible = 0;        // LPs the exact backend finds empty
  long wrong_side = 0;              // a safe bound beyond the exact optimum: must stay 0
  long infeasible_confirmed = 0;    // safe infeasibility claims CGAL confirmed
  long infeasible_refuted = 0;      // ... CGAL refuted: must stay 0
  long missed_infeasible = 0;       // exactly empty LPs the safe backend only bounded (sound)
  long cgal_compared = 0, cgal_mismatch = 0;  // ExactLp vs CGAL on a sample: mismatch must stay 0
  long exact_tighter = 0;           // the exact bound strictly better than the safe one
  prune::LpPaths paths;
  std::vector<double> distance;     // |exact - safe| where both are bounded
  std::vector<double> relative;     // the same over the column's width at the time
  std::vector<std::string> failures;  // the first few wrong answers, for the message
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  return v[i];
}

// Checks every solve of `lps`; CGAL re-solves every `cgal_every`-th bounded one (0: none) and
// every infeasibility claim, at most `cgal_cap` LPs in all.
void check_record(const std::vector<RecordedLp>& lps, long cgal_every, long cgal_cap, OracleStats& st) {
  long bounded_seen = 0, cgal_runs = 0;
  for (const RecordedLp& rec : lps) {
    ++st.lps;
    ExactLp exact;
    exact.load(rec.program);
    LinearProgram lp = rec.program;  // the LP as each solve saw it, for CGAL
    for (const RecordedSolve& s : rec.solves) {
      ++st.solves;
      for (int j = 0; j < lp.num_cols(); ++j)
        if (s.col_lo[j] != lp.col_lo[j] || s.col_hi[j] != lp.col_hi[j]) {
          lp.col_lo[j] = s.col_lo[j], lp.col_hi[j] = s.col_hi[j];
          exact.set_column_bounds(j, s.col_lo[j], s.col_hi[j]);
        }
      const LpBound e = s.sense > 0 ? exact.minimize(s.col) : exact.maximize(s.col);
      const LpBound& a = s.answer;
      auto note = [&](const std::string& what) {
        ++st.wrong_side;
        if (st.failures.size() < 5) {
          std::ostringstream m;
          m.precision(17);
          const LpBound c = to_bound(cgal_minimum(lp, s.col, s.sense), s.sense);  // the arbiter
          m << what << " (lp " << st.lps - 1 << ", col " << s.col << ", sense " << s.sense << ": safe " << a.value
            << ", exact " << e.value << ", cgal " << (c.status == LpStatus::infeasible ? "infeasible" : "") << c.value
            << ")";
          st.failures.push_back(m.str());
        }
      };
      if (e.status == LpStatus::infeasible) ++st.exact_infeasible;
      if (a.status == LpStatus::unknown) {
        ++st.safe_unknown;
        continue;
      }
      if (a.status == LpStatus::infeasible) {
        ++st.safe_infeasible;
        // The claim that discards a box: CGAL must find the LP empty (ExactLp too).
        const ExactOptimum c = cgal_minimum(lp, s.col, s.sense);
        ++cgal_runs;
        if (c.status == LpStatus::infeasible && e.status == LpStatus::infeasible) {
          ++st.infeasible_confirmed;
        } else {
          ++st.infeasible_refuted;
          note("safe infeasible, exact not");
        }
        continue;
      }
      ++st.safe_bounded;
      if (e.status == LpStatus::infeasible) {
        ++st.missed_infeasible;  // any bound holds on an empty LP
      } else if (e.status == LpStatus::bounded) {
        // e.value is the exact optimum rounded outward: the largest double <= a minimum,
        // the smallest >= a maximum; a sound double bound cannot pass it.
        const bool right = s.sense > 0 ? a.value <= e.value : a.value >= e.value;
        if (!right) note("safe bound beyond the exact optimum");
        const double dist = std::fabs(e.value - a.value);
        const double width = s.col_hi[s.col] - s.col_lo[s.col];
        st.distance.push_back(dist);
        st.relative.push_back(width > 0 ? dist / width : 0.0);
        if (dist > 0) ++st.exact_tighter;
      }
      if (cgal_every > 0 && bounded_seen++ % cgal_every == 0 && cgal_runs < cgal_cap) {
        ++cgal_runs;
        ++st.cgal_compared;
        const LpBound c = to_bound(cgal_minimum(lp, s.col, s.sense), s.sense);
        if (c.status != e.status || (c.status == LpStatus::bounded && c.value != e.value)) {
          ++st.cgal_mismatch;
          if (st.failures.size() < 5) {
            std::ostringstream m;
            m.precision(17);
            m << "ExactLp and CGAL disagree (lp " << st.lps - 1 << ", col " << s.col << ", sense " << s.sense
              << ": exact " << e.value << ", cgal " << c.value << ")";
            st.failures.push_back(m.str());
          }
        }
      }
    }
    st.paths += exact.paths();
  }
}

std::string stats_json(const OracleStats& st) {
  std::ostringstream o;
  o.precision(6);
  o << "{\"lps\": " << st.lps << ", \"solves\": " << st.solves << ", \"safe_bounded\": " << st.safe_bounded
    << ", \"safe_infeasible\": " << st.safe_infeasible << ", \"safe_unknown\": " << st.safe_unknown
    << ", \"exact_infeasible\": " << st.exact_infeasible << ", \"wrong_side\": " << st.wrong_side
    << ", \"infeasible_confirmed\": " << st.infeasible_confirmed << ", \"infeasible_refuted\": " << st.infeasible_refuted
    << ", \"missed_infeasible\": " << st.missed_infeasible << ", \"cgal_compared\": " << st.cgal_compared
    << ", \"cgal_mismatch\": " << st.cgal_mismatch << ", \"exact_tighter\": " << st.exact_tighter
    << ", \"paths\": {\"basis\": " << st.paths.basis << ", \"repaired\": " << st.paths.repaired
    << ", \"farkas\": " << st.paths.farkas << ", \"fallback\": " << st.paths.fallback << ", \"pivots\": " << st.paths.pivots
    << "}, \"distance\": {";
  const double qs[] = {0.5, 0.9, 0.99, 1.0};
  const char* names[] = {"p50", "p90", "p99", "max"};
  for (int i = 0; i < 4; ++i) o << (i ? ", " : "") << "\"" << names[i] << "\": " << quantile(st.distance, qs[i]);
  o << "}, \"relative\": {";
  for (int i = 0; i < 4; ++i) o << (i ? ", " : "") << "\"" << names[i] << "\": " << quantile(st.relative, qs[i]);
  o << "}}";
  return o.str();
}

void require_sound(const OracleStats& st) {
  for (const std::string& f : st.failures) UNSCOPED_INFO(f);
  CHECK(st.wrong_side == 0);
  CHECK(st.infeasible_refuted == 0);
  CHECK(st.cgal_mismatch == 0);
}

// Records the LPs of a short search (safe backend) into a temporary file and reads them back.
std::vector<RecordedLp> record_search(const std::string& case_file, double sigma, long max_boxes) {
  char path[] = "/tmp/linkbox-lp-oracle-XXXXXX";
  const int fd = mkstemp(path);
  REQUIRE(fd >= 0);
  close(fd);
  std::remove(path);  // the recorder appends; start empty
  setenv("LINKBOX_LP_RECORD", path, 1);
  {
    formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + case_file);
    solve::RunOptions o;
    o.progress = false;
    o.strategy.prune = solve::Strategy::parse("lp");
    o.params.sigma = sigma;
    o.params.max_boxes = max_boxes;
    solve::solve_case(*c.formulation, o);  // the solvers (and their recorders) end with it
  }
  unsetenv("LINKBOX_LP_RECORD");
  std::vector<RecordedLp> lps = read_lp_record(path);
  std::remove(path);
  return lps;
}

}  // namespace

TEST_CASE("LP oracle: every safe bound on the right side of the exact optimum, every infeasibility exact",
          "[lp][lp_oracle]") {
  OracleStats st;
  // A few boxes of each linkage (the widest LPs, the slowest to solve exactly) and the
  // wrist's whole search, which discards boxes on infeasibility; a few seconds in all.
  const struct {
    const char* file;
    double sigma;
    long boxes;
  } runs[] = {{"cases/linkages/6r-rigid.toml", 1e-4, 3},
              {"cases/linkages/cyclohexane.toml", 0.1, 6},
              {"cases/linkages/6r-mobile.toml", 0.1, 4},
              {"cases/spherical/wrist.toml", 1e-4, 0}};  // whole search: its infeasibility claims
  for (const auto& run : runs) {
    const std::vector<RecordedLp> lps = record_search(run.file, run.sigma, run.boxes);
    INFO(run.file);
    REQUIRE(!lps.empty());
    check_record(lps, 150, 5, st);
  }
  std::cout << "LP oracle (CI sample): " << stats_json(st) << "\n";
  CHECK(st.solves > 300);
  CHECK(st.cgal_compared >= 3);
  CHECK(st.safe_infeasible >= 1);  // the wrist's empty boxes
  require_sound(st);
}

// The full set (papers/porta-iterated-lp/lp_oracle.py): LINKBOX_LP_ORACLE_RECORD=<record file>,
// LINKBOX_LP_ORACLE_CGAL_EVERY=<k> (CGAL on every k-th bounded solve; default 200),
// LINKBOX_LP_ORACLE_CGAL_CAP=<n> (at most n CGAL solves; default 200). Prints one line
// "LP oracle: {json}".
TEST_CASE("LP oracle on a record file", "[.][lp_oracle_full]") {
  const char* path = std::getenv("LINKBOX_LP_ORACLE_RECORD");
  REQUIRE(path);
  const char* every = std::getenv("LINKBOX_LP_ORACLE_CGAL_EVERY");
  const char* cap = std::getenv("LINKBOX_LP_ORACLE_CGAL_CAP");
  OracleStats st;
  check_record(read_lp_record(path), every ? std::atol(every) : 200, cap ? std::atol(cap) : 200, st);
  for (const std::string& f : st.failures) std::cout << "LP oracle failure: " << f << "\n";
  std::cout << "LP oracle: " << stats_json(st) << "\n";
  require_sound(st);
}
