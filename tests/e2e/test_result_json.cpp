// The per-box bounds of the result JSON (residual at the midpoint, distance of a member to its
// certified root) against what they bound, and `check_certificates` on a curve that winds
// around a whole turn (gimbal lock), whose crossings are each in their own chart.
#include "formulate/load.hpp"
#include "report/json.hpp"
#include "verify/check.hpp"
#include "solve/strategy.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>

using namespace linkbox;
using nlohmann::json;

namespace {

struct Written {
  formulate::LoadedCase c;
  verify::VerifyReport v;
  json j;
};

Written solve_and_write(const std::string& path, double sigma) {
  Written w{formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + path), {}, {}};
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = sigma;
  o.strategy.prune = solve::Strategy::parse("trapezoid");
  const solve::CaseResult r = solve::solve_case(*w.c.formulation, o);
  w.v = verify::verify_case(*w.c.formulation, r);
  w.j = report::result_json(w.c.name, w.c.file, *w.c.formulation, o, r);
  report::add_verification(w.j, *w.c.formulation, w.v);
  return w;
}

Box box_of(const json& j) {
  Box b;
  for (auto& side : j) b.emplace_back(side[0].get<double>(), side[1].get<double>());
  return b;
}

// The solution entry a cluster member [sub-problem, index] names (solutions are listed by
// sub-problem, then index).
const json& solution_of(const json& j, const json& member) {
  size_t first = 0;
  while (j["solutions"][first]["subproblem"] != member[0]) ++first;
  return j["solutions"][first + member[1].get<size_t>()];
}

// f at x in round-to-nearest doubles, coefficients at their centres.
double value_at(const model::Polynomial& p, const std::vector<double>& x) {
  double s = 0;
  for (auto& [powers, c] : p.terms()) {
    double t = median(c);
    for (auto [v, e] : powers)
      for (int k = 0; k < e; ++k) t *= x[v];
    s += t;
  }
  return s;
}

// Per side, the largest and the smallest distance between points of a and b (b shifted by
// whole turns towards a), as plain doubles.
struct Spread {
  double farthest = 0, gap = 0;
};
Spread spread(const Box& a, const Box& b) {
  Spread s;
  for (size_t i = 0; i < a.size(); ++i) {
    const double shift = 2 * M_PI * std::round((median(a[i]) - median(b[i])) / (2 * M_PI));
    const double lo = b[i].lower() + shift, hi = b[i].upper() + shift;
    s.farthest = std::max({s.farthest, hi - a[i].lower(), a[i].upper() - lo});
    s.gap = std::max({s.gap, lo - a[i].upper(), a[i].lower() - hi});
  }
  return s;
}

}  // namespace

TEST_CASE("json: each solution's residual bounds |f| at its midpoint, and tightly", "[json][slow]") {
  for (const char* path : {"cases/spherical/wrist.toml", "cases/hard/gimbal-lock.toml"}) {
    INFO(path);
    const Written w = solve_and_write(path, 1e-3);
    REQUIRE_FALSE(w.j["solutions"].empty());
    for (auto& s : w.j["solutions"]) {
      const auto sub = w.c.formulation->subproblem(s["subproblem"].get<size_t>());
      const Box box = box_of(s["search_box"]);
      std::vector<double> mid;
      for (auto& x : box) mid.push_back(median(x));
      const double residual = s["residual"];
      double largest = 0;
      for (auto& f : sub.system.equations) largest = std::max(largest, std::fabs(value_at(f, mid)));
      CHECK(residual >= largest);
      CHECK(residual <= largest + 1e-14);  // at a point, the enclosure is rounding wide only
      CHECK(residual < 1e-2);              // a solution box of width 1e-3: f nearly vanishes
    }
    for (auto& c : w.j["clusters"]) {
      double largest = 0;
      for (auto& m : c["members"]) largest = std::max(largest, solution_of(w.j, m)["residual"].get<double>());
      CHECK(c["max_residual"].get<double>() == largest);
    }
  }
}

TEST_CASE("json: member distances to the certified root bound the farthest points", "[json]") {
  const Written w = solve_and_write("cases/spherical/wrist.toml", 1e-4);
  REQUIRE(w.v.certified_roots == 2);
  for (auto& c : w.j["clusters"]) {
    if (c["status"] != "certified") continue;
    const Box root = box_of(c["root"]), hull = box_of(c["hull"]);
    REQUIRE(c["distances"].size() == c["members"].size());
    double largest = 0;
    for (size_t k = 0; k < c["members"].size(); ++k) {
      const Box member = box_of(solution_of(w.j, c["members"][k])["box"]);
      const double d = c["distances"][k];
      const Spread sp = spread(member, root);
      CHECK(d >= 0);
      CHECK(d >= sp.farthest - 1e-12);
      CHECK(d <= max_width(member) + max_width(root) + std::max(0.0, sp.gap) + 1e-12);
      largest = std::max(largest, d);
    }
    CHECK(c["max_distance"].get<double>() == largest);
    CHECK(largest <= max_width(hull));
  }
}

TEST_CASE("json: check re-runs every gimbal-lock crossing and arc, each in its own chart", "[json][hard]") {
  Written w = solve_and_write("cases/hard/gimbal-lock.toml", 1e-2);
  REQUIRE(w.v.curves == 1);
  const auto& curve = *std::find_if(w.j["clusters"].begin(), w.j["clusters"].end(),
                                    [](const json& c) { return c["status"] == "curve"; });
  std::set<std::uint64_t> charts;
  for (auto& x : curve["crossings"]) charts.insert(x["chart"].get<std::uint64_t>());
  CHECK(charts.size() >= 2);  // the curve winds around a whole turn
  const verify::CheckOutcome ok = verify::check_certificates(w.j, *w.c.formulation);
  CHECK(ok.failures.empty());
  // Each crossing's certificate, and each arc of the curve's map.
  CHECK(ok.checked == curve["crossings_certified"].get<int>() + static_cast<int>(curve["map"]["arcs"].size()));
  CHECK(ok.checked > 0);
}

TEST_CASE("json: LPs per box and microseconds per LP agree with the LP contractor's counts", "[json][lp]") {
  auto c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/6r-rigid.toml");
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse("hc4,lp");
  o.params.max_boxes = 40;
  const solve::CaseResult r = solve::solve_case(*c.formulation, o);
  const json j = report::result_json(c.name, c.file, *c.formulation, o, r);
  const long boxes = j["stats"]["processed"].get<long>();
  REQUIRE(boxes > 0);
  int with_lps = 0;
  for (const json& k : j["contractors"]) {
    const long lps = k["lps_solved"].get<long>();
    if (lps == 0) {
      CHECK_FALSE(k.contains("us_per_lp"));
      continue;
    }
    ++with_lps;
    CHECK(k["lps_per_box"].get<double>() * static_cast<double>(boxes) == Approx(static_cast<double>(lps)));
    CHECK(k["us_per_lp"].get<double>() * static_cast<double>(lps) == Approx(1e6 * k["seconds"].get<double>()));
    CHECK(k["us_per_lp"].get<double>() > 0);
  }
  CHECK(with_lps == 1);
}
