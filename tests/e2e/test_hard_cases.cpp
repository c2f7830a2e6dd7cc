// The hard cases of cases/hard/ (each file documents its expected outcome at the top), run
// in the verified mode through the library, plus the strategy comparison script in --quick
// mode. What is checked is what the library may claim: an exact headline only when it is
// true, known roots always enclosed, singular or positive-dimensional solution sets never
// reported as certified isolated roots. Known library defects, when there are any, are pinned
// by tests tagged [!mayfail] (see papers/compare/hard_cases.md): they report but do not fail
// the run.
#include "formulate/load.hpp"
#include "solve/strategy.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace linkbox;

namespace {

struct Run {
  formulate::LoadedCase c;
  solve::CaseResult r;
  verify::VerifyReport v;
  std::vector<Box> outputs;  // every solution box in the output variables
};

Run run_case(const std::string& path, const std::string& prune, double sigma, bool rigorous = true) {
  Run s{formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + path), {}, {}, {}};
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = sigma;
  o.strategy.prune = solve::Strategy::parse(prune);
  o.strategy.arith = rigorous ? Arith::verified : Arith::float_unverified;
  s.r = solve::solve_case(*s.c.formulation, o);
  s.v = verify::verify_case(*s.c.formulation, s.r);
  for (auto& sub : s.r.subproblems)
    for (auto& b : sub.solutions) s.outputs.push_back(s.c.formulation->to_output(sub.index, b));
  return s;
}

// Distance (max norm) from the point p to the box b; angle coordinates modulo 2 pi.
double distance(const Box& b, const std::vector<double>& p, bool angles) {
  double d = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    double best = INFINITY;
    for (int k = angles ? -1 : 0; k <= (angles ? 1 : 0); ++k) {
      const double x = p[i] + k * 2 * M_PI;
      best = std::min(best, std::max({0.0, b[i].lower() - x, x - b[i].upper()}));
    }
    d = std::max(d, best);
  }
  return d;
}

bool angles_of(const Run& s) { return s.c.formulation->outputs_are_angles(); }

// Smallest distance from p to a solution box.
double nearest_box(const Run& s, const std::vector<double>& p) {
  double d = INFINITY;
  for (auto& b : s.outputs) d = std::min(d, distance(b, p, angles_of(s)));
  return d;
}

std::vector<const verify::ClusterReport*> certified(const Run& s) {
  std::vector<const verify::ClusterReport*> r;
  for (auto& c : s.v.clusters)
    if (c.status == verify::ClusterStatus::certified && c.duplicate_of < 0) r.push_back(&c);
  return r;
}

// Number of known roots inside a certified root box.
int roots_in(const Box& root, const std::vector<std::vector<double>>& known, bool angles) {
  int n = 0;
  for (auto& p : known) n += distance(root, p, angles) == 0;
  return n;
}

bool says_exactly(const Run& s) { return s.v.headline.find("exactly") != std::string::npos; }

// The invariants every verified run must keep whatever it could prove: an exact headline
// only with every cluster certified, empty or a proved curve map; certified boxes pairwise
// distinct roots.
void check_honest(const Run& s) {
  INFO(s.v.headline);
  CHECK(s.r.rigorous);
  CHECK(s.v.exact == says_exactly(s));
  if (s.v.exact) {
    CHECK(s.r.complete);
    CHECK(s.v.unverified == 0);
    for (auto& c : s.v.clusters)
      if (c.status == verify::ClusterStatus::curve) CHECK((c.map && c.map->proved));
  }
  const auto roots = certified(s);
  CHECK(static_cast<int>(roots.size()) == s.v.certified_roots);
}

int run_command(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("hard: roots exactly on sub-problem faces and at phi = pi are found once each", "[hard]") {
  const std::vector<std::vector<double>> known = {{M_PI / 2, M_PI / 2, M_PI}, {-M_PI / 2, -M_PI / 2, 0}};
  for (const char* prune : {"trapezoid", "trapezoid,lp", "newton"}) {
    INFO("prune " << prune);
    Run s = run_case("cases/hard/wrist-faces.toml", prune, 1e-4);
    check_honest(s);
    CHECK(s.r.complete);
    CHECK(s.v.exact);
    CHECK(s.v.certified_roots == 2);
    CHECK(s.v.headline == "exactly 2 roots in the domain, each in its certified box");
    // Each root is found by several sub-problems (it sits on their shared faces): merged.
    CHECK(s.outputs.size() > 2);
    for (auto* c : certified(s)) {
      CHECK(max_width(c->root) < 1e-12);
      CHECK(roots_in(c->root, known, true) == 1);
    }
    for (auto& p : known) CHECK(nearest_box(s, p) == 0);
  }
}

TEST_CASE("hard: two roots 5e-9 apart near 0.01 are certified separately", "[hard]") {
  const std::vector<std::vector<double>> known = {{0.01, 0.0001}, {0.010000005, 0.010000005 * 0.010000005}};
  for (const char* prune : {"newton", "hc4,lp"}) {
    INFO("prune " << prune);
    Run s = run_case("cases/hard/close-roots.toml", prune, 1e-10);
    check_honest(s);
    CHECK(s.r.complete);
    CHECK(s.v.exact);
    CHECK(s.v.certified_roots == 2);
    for (auto* c : certified(s)) CHECK(roots_in(c->root, known, false) == 1);
  }
  // Coarser boxes cannot separate them without Newton: one root certified, never "exactly 1".
  Run coarse = run_case("cases/hard/close-roots.toml", "hc4,lp", 1e-8);
  check_honest(coarse);
  CHECK_FALSE(coarse.v.exact);
  CHECK(coarse.v.certified_roots <= 2);
  for (auto* c : certified(coarse)) CHECK(roots_in(c->root, known, false) == 1);
  // With Newton in the search, uncertified solution boxes are searched again with a smaller
  // sigma: the default sigma (1e-4, 20 000x the gap) gives "exactly 2".
  for (const char* prune : {"auto", "hc4,newton"}) {
    INFO("prune " << prune);
    Run d = run_case("cases/hard/close-roots.toml", prune, 1e-4);
    check_honest(d);
    CHECK(d.v.exact);
    CHECK(d.v.certified_roots == 2);
    for (auto* c : certified(d)) CHECK(roots_in(c->root, known, false) == 1);
  }
}

TEST_CASE("hard: two roots 5e-9 apart near 1/3 are never miscounted", "[hard]") {
  const double a = 1.0 / 3, b = a + 5e-9;
  const std::vector<std::vector<double>> known = {{a, a * a}, {b, b * b}};
  for (double sigma : {1e-8, 1e-9}) {
    INFO("sigma " << sigma);
    Run s = run_case("cases/hard/close-roots-unresolved.toml", "hc4,lp", sigma);
    check_honest(s);
    CHECK(s.r.complete);
    CHECK_FALSE(s.v.exact);
    CHECK(s.v.certified_roots <= 2);
    for (auto* c : certified(s)) CHECK(roots_in(c->root, known, false) == 1);
    // Both roots enclosed (tolerance: 1/3 and b*b are not doubles).
    for (auto& p : known) CHECK(nearest_box(s, p) < 1e-15);
  }
}

TEST_CASE("hard: two isolated roots 5e-9 apart are not reported as a curve", "[hard]") {
  // Was a defect until 3d0c10c: the curve test dropped one equation and certified y = x^2.
  Run s = run_case("cases/hard/close-roots-unresolved.toml", "hc4,lp", 1e-9);
  INFO(s.v.headline);
  CHECK(s.v.curves == 0);
}

TEST_CASE("hard: a double (tangential) root is unverified with a reason, never certified", "[hard]") {
  for (const char* prune : {"hc4", "hc4,lp", "newton"}) {
    INFO("prune " << prune);
    Run s = run_case("cases/hard/tangent-circle-line.toml", prune, 1e-6);
    check_honest(s);
    CHECK(s.r.complete);
    CHECK_FALSE(s.v.exact);
    CHECK_FALSE(says_exactly(s));
    CHECK(s.v.certified_roots == 0);
    CHECK(s.v.unverified >= 1);
    CHECK(nearest_box(s, {0, 0}) == 0);
    for (auto& c : s.v.clusters) {
      CHECK(c.status != verify::ClusterStatus::certified);
      if (c.status == verify::ClusterStatus::unverified) CHECK_FALSE(c.reason.empty());
    }
  }
}

TEST_CASE("hard: a spherical wrist with a 1e-7 twist keeps both ill-conditioned roots", "[hard]") {
  const std::vector<std::vector<double>> known = {{0.4, 1.1, -0.6}, {-0.5415927, 2.0415927, -0.6000001}};
  Run s = run_case("cases/hard/wrist-twist-1e-7.toml", "trapezoid", 1e-8);
  check_honest(s);
  CHECK(s.r.complete);
  CHECK(nearest_box(s, known[0]) == 0);   // exact by construction
  CHECK(nearest_box(s, known[1]) < 1e-6);  // known to ~1e-7
  // Krawczyk cannot prove these in double precision: two clusters that are not certified
  // ("inflation failed") and never an exact count unless both are.
  if (s.v.exact) CHECK(s.v.certified_roots == 2);
  int around = 0;
  for (auto& c : s.v.clusters) around += c.status != verify::ClusterStatus::empty;
  CHECK(around >= 2);
  for (auto* c : certified(s)) CHECK(distance(c->root, known[0], true) < 1e-6);
}

TEST_CASE("hard: isolated ill-conditioned wrist roots are not reported as curves", "[hard]") {
  // Was a defect until 3d0c10c: the Jacobian is rank deficient to working precision and the
  // curve test (one equation dropped) "certified" crossings of a curve that does not exist.
  Run s = run_case("cases/hard/wrist-twist-1e-7.toml", "trapezoid", 1e-8);
  INFO(s.v.headline);
  CHECK(s.v.curves == 0);
}

TEST_CASE("hard: the rigid 6R with 0.0175 twists encloses its 16 configurations", "[hard][linkage][slow]") {
  // cases/linkages/6r-rigid.toml; one configuration is quoted there to 5 decimals.
  Run s = run_case("cases/linkages/6r-rigid.toml", "hc4,lp", 1e-3);
  check_honest(s);
  CHECK(s.r.complete);
  CHECK(nearest_box(s, {-0.13831, -1.81875, 1.13398, 3.08576, 3.01184, -0.67799}) < 1e-4);
  CHECK(s.v.exact);
  CHECK(s.v.certified_roots == 16);  // a general 6R with 16 real configurations
}

TEST_CASE("hard: a 6R loop with links from 1e-3 to 1e3 encloses its known configuration", "[hard][linkage][slow]") {
  Run s = run_case("cases/hard/linkage-scales.toml", "hc4,lp", 1e-3);
  check_honest(s);
  CHECK(s.r.complete);
  const std::vector<double> built = {0.5268071710601236, -0.9, 1.7, 0.4, -2.1, 2.858829408585121};
  CHECK(nearest_box(s, built) < 1e-9);
  CHECK(s.v.exact);
  CHECK(s.v.certified_roots == 12);  // 12 of the at most 16 configurations are real
  int holding = 0;  // the built configuration (closes to 3e-13 in double) in one certified box
  for (auto* c : certified(s)) holding += distance(c->root, built, true) < 1e-9;
  CHECK(holding == 1);
}

TEST_CASE("hard: a 6R loop with a 1e-7 twist encloses its known configuration", "[hard][linkage][.slow]") {
  // About 80 s at sigma 0.1 (about 1 s per box, LP-bound): hidden, run with [.slow].
  Run s = run_case("cases/hard/linkage-twist-1e-7.toml", "hc4,lp", 1e-1);
  check_honest(s);
  CHECK(s.r.complete);
  CHECK(nearest_box(s, {1.3121131790666334, -0.7, 1.1, 0.6, -1.3, 2.27323431584542}) < 1e-9);
  // Measured: "2 certified, 16 unresolved" at sigma 0.1: never exact while clusters remain.
  if (s.v.exact) CHECK(s.v.unverified == 0);
}

TEST_CASE("hard: a 6R loop with a 1e-7 twist stays honest when stopped early", "[hard][linkage]") {
  formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/hard/linkage-twist-1e-7.toml");
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = 1e-1;
  o.params.max_boxes = 4;
  o.strategy.prune = solve::Strategy::parse("hc4,lp");
  solve::CaseResult r = solve::solve_case(*c.formulation, o);
  verify::VerifyReport v = verify::verify_case(*c.formulation, r);
  CHECK_FALSE(r.complete);
  CHECK_FALSE(v.exact);
  CHECK(v.headline.find("incomplete") != std::string::npos);
}

TEST_CASE("hard: a near miss with no real root is proved empty", "[hard]") {
  for (const char* prune : {"hc4", "hc4,lp", "lp", "newton"}) {
    INFO("prune " << prune);
    Run s = run_case("cases/hard/no-root.toml", prune, 1e-8);
    check_honest(s);
    CHECK(s.r.complete);
    CHECK(s.v.exact);
    CHECK(s.v.certified_roots == 0);
    CHECK(s.v.headline == "exactly 0 roots in the domain, each in its certified box");
    for (auto& c : s.v.clusters) CHECK(c.status == verify::ClusterStatus::empty);
  }
}

TEST_CASE("hard: gimbal lock is one proved closed curve, never isolated roots", "[hard]") {
  Run s = run_case("cases/hard/gimbal-lock.toml", "trapezoid", 1e-2);
  check_honest(s);
  CHECK(s.r.complete);
  // The map goes through phi2 = 0, where two closure components vanish.
  CHECK(s.v.exact);
  CHECK(s.v.maps_proved);
  CHECK(s.v.closed_curves == 1);
  CHECK(s.v.open_arcs == 0);
  CHECK(s.v.certified_roots == 0);
  for (auto& c : s.v.clusters) CHECK(c.status != verify::ClusterStatus::certified);
  // The whole circle phi2 = 0, phi1 + phi3 = 0.7 is covered.
  for (int k = 0; k < 64; ++k) {
    const double phi1 = -M_PI + (k + 0.5) * 2 * M_PI / 64;
    CHECK(nearest_box(s, {phi1, 0, 0.7 - phi1}) < 1e-12);
  }
}

TEST_CASE("hard: gimbal lock is reported as a curve cluster", "[hard]") {
  // The cluster wraps the whole circle, so no single half-angle chart holds it: each box is
  // analysed, and its crossing certified, in its own chart.
  Run s = run_case("cases/hard/gimbal-lock.toml", "trapezoid", 1e-2);
  INFO(s.v.headline);
  CHECK(s.v.curves >= 1);
  CHECK(s.v.unverified == 0);
  std::set<std::uint64_t> charts;
  for (auto& c : s.v.clusters) {
    if (c.status != verify::ClusterStatus::curve) continue;
    CHECK(2 * static_cast<size_t>(c.crossings_certified) >= c.crossings.size());
    for (auto& x : c.crossings) {
      if (x.certificate.status != newton::Status::certified) continue;
      charts.insert(x.chart);
      // Re-checks in its own chart, and is a point of the circle phi2 = 0, phi1 + phi3 = 0.7.
      auto eqs = s.c.formulation->natural_system(x.chart).equations;
      REQUIRE(x.dropped_equations.size() == 1);
      eqs.erase(eqs.begin() + x.dropped_equations[0]);
      CHECK(newton::recheck(eqs, x.certificate));
      const Box point = s.c.formulation->natural_to_output(x.chart, x.certificate.box);
      CHECK(max_width(point) < 1e-9);
      const double phi1 = median(point[0]);
      CHECK(distance(point, {phi1, 0, 0.7 - phi1}, true) < 1e-9);
    }
  }
  CHECK(charts.size() >= 2);
}

TEST_CASE("hard: the float variant never states an exact count", "[hard]") {
  struct FloatRun {
    std::string path, prune;
    double sigma;
  };
  const std::vector<FloatRun> cases = {{"cases/hard/wrist-faces.toml", "lp", 1e-4},
                                       {"cases/hard/wrist-faces.toml", "trapezoid", 1e-4},
                                       {"cases/hard/close-roots.toml", "newton", 1e-10},
                                       {"cases/hard/tangent-circle-line.toml", "hc4,lp", 1e-6},
                                       {"cases/hard/no-root.toml", "hc4,lp", 1e-8},
                                       {"cases/hard/gimbal-lock.toml", "trapezoid", 1e-2},
                                       {"cases/hard/wrist-twist-1e-7.toml", "trapezoid", 1e-8}};
  for (auto& f : cases) {
    INFO(f.path << " " << f.prune);
    Run s = run_case(f.path, f.prune, f.sigma, false);
    CHECK_FALSE(s.r.rigorous);
    CHECK_FALSE(s.v.exact);
    CHECK_FALSE(says_exactly(s));
    CHECK(s.v.headline.rfind("UNVERIFIED", 0) == 0);
  }
}

TEST_CASE("compare.py --quick runs every strategy and writes its CSV", "[compare]") {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / ("linkbox-compare-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string build = fs::path(LINKBOX_CLI).parent_path().string();
  // Debian's interpreter (with python3-matplotlib), not whatever python3 comes first on PATH.
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3 " : "python3 ";
  const std::string cmd = python + std::string(LINKBOX_SOURCE_DIR) + "/papers/compare/compare.py --quick --build '" +
                          build + "' --out '" + out.string() + "' > '" + out.string() + ".log' 2>&1";
  INFO(cmd);
  CHECK(run_command(cmd) == 0);
  const fs::path csv = out / "compare.csv";
  REQUIRE(fs::exists(csv));
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  CHECK(header.find("strategy") != std::string::npos);
  int rows = 0;
  while (std::getline(in, line)) rows += !line.empty();
  CHECK(rows >= 8);
  CHECK(fs::exists(out / "compare.md"));
  fs::remove_all(out);
  fs::remove(out.string() + ".log");
}
