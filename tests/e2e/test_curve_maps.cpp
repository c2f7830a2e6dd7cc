// Certified maps of solution curves (verify/curve_map.hpp): the cases of cases/curves/ give the
// map written in their header under several strategies and sigmas, `linkbox check` re-proves it
// and rejects a tampered one, and what cannot be a proof never reads as one (branches that
// cross, a mechanism that is only nearly mobile, an arc test on a box holding a crossing).
#include "formulate/load.hpp"
#include "newton/arc.hpp"
#include "report/json.hpp"
#include "solve/solve_case.hpp"
#include "solve/strategy.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"
#include "verify/symmetric_map.hpp"
#include "tests/cli_run.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

using namespace linkbox;

namespace {

struct Mapped {
  formulate::LoadedCase c;
  verify::VerifyReport v;
  nlohmann::json j;
};

Mapped solve_text(const std::string& text, const std::string& file, const std::string& prune, double sigma,
                  double narrow = 0) {
  Mapped m{formulate::load_case_text(text, file), {}, {}};
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = sigma;
  o.params.narrow = narrow;
  o.strategy.prune = solve::Strategy::parse(prune);
  const auto r = solve::solve_case(*m.c.formulation, o);
  REQUIRE(r.complete);
  m.v = verify::verify_case(*m.c.formulation, r);
  m.j = report::result_json(m.c.name, m.c.file, *m.c.formulation, o, r);
  report::add_verification(m.j, *m.c.formulation, m.v);
  return m;
}

std::string read(const std::string& path) {
  std::ifstream in(std::string(LINKBOX_SOURCE_DIR) + "/" + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// "# EXPECTED MAP: isolated=0 closed=2 open=0 proved=yes" as key -> value.
std::map<std::string, std::string> expected_map(const std::string& text) {
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("# EXPECTED MAP:([^\n]*)")));
  std::map<std::string, std::string> out;
  const std::string line = m[1];
  const std::regex pair("(\\w+)=(\\w+)");
  for (std::sregex_iterator it(line.begin(), line.end(), pair), end; it != end; ++it)
    out[(*it)[1]] = (*it)[2];
  return out;
}

int proved_maps(const verify::VerifyReport& v) {
  int k = 0;
  for (auto& c : v.clusters) k += c.map && c.map->proved;
  return k;
}

void require_map(const Mapped& m, const std::map<std::string, std::string>& want) {
  const bool proved = want.at("proved") == "yes";
  CHECK(m.v.maps_proved == proved);
  CHECK(m.v.exact == proved);
  CHECK(verify::check_certificates(m.j, *m.c.formulation).failures.empty());
  if (!proved) {
    CHECK(m.v.headline.rfind("exactly", 0) != 0);
    return;
  }
  CHECK(m.v.certified_roots == std::stoi(want.at("isolated")));
  CHECK(m.v.closed_curves == std::stoi(want.at("closed")));
  CHECK(m.v.open_arcs == std::stoi(want.at("open")));
  CHECK(m.v.branches == std::stoi(want.count("branches") ? want.at("branches") : "0"));
  CHECK(m.v.singular_points == std::stoi(want.count("singular") ? want.at("singular") : "0"));
}

}  // namespace

TEST_CASE("curve cases give the map in their header, whatever the strategy", "[verify][map]") {
  const std::string file = GENERATE(as<std::string>{}, "cases/curves/fourbar-grashof.toml",
                                    "cases/curves/fourbar-nongrashof.toml", "cases/curves/fourbar-half-domain.toml",
                                    "cases/curves/circle-3d.toml", "cases/curves/fourbar-parallelogram.toml",
                                    "cases/curves/circle-on-plane.toml", "cases/curves/viviani.toml");
  const std::string prune = GENERATE(as<std::string>{}, "auto", "hc4,newton", "hc4,newton/lp");
  INFO(file << " under " << prune);
  const std::string text = read(file);
  require_map(solve_text(text, file, prune, 0.05), expected_map(text));
}

TEST_CASE("a curve's map does not depend on sigma", "[verify][map]") {
  const double sigma = GENERATE(0.1, 0.03, 0.01);
  INFO("sigma " << sigma);
  const std::string file = "cases/curves/fourbar-grashof.toml";
  const std::string text = read(file);
  require_map(solve_text(text, file, "auto", sigma), expected_map(text));
}

TEST_CASE("crossing branches are never one proved curve: the change points are named", "[verify][map]") {
  const std::string file = "cases/curves/fourbar-parallelogram.toml";
  const double sigma = GENERATE(0.1, 0.03, 0.01);
  INFO("sigma " << sigma);
  const Mapped m = solve_text(read(file), file, "auto", sigma);
  REQUIRE(m.v.clusters.size() == 1);
  const auto& map = m.v.clusters[0].map;
  REQUIRE(map);
  CHECK(map->proved);
  // The two change points, (c1, s1, c3, s3) = (+-1, 0, +-1, 0), exact, each a crossing that
  // all four branches reach; no branch is a closed curve.
  REQUIRE(map->singular_points.size() == 2);
  std::set<std::vector<std::string>> points;
  for (auto& p : map->singular_points) {
    points.insert(p.point);
    CHECK(p.kind == verify::SingularKind::crossing);
    CHECK(p.branches == 4);
  }
  CHECK(points == std::set<std::vector<std::string>>{{"1", "0", "1", "0"}, {"-1", "0", "-1", "0"}});
  REQUIRE(map->components.size() == 4);
  for (auto& c : map->components) {
    CHECK_FALSE(c.closed);
    CHECK(c.singular_ends >= 2);
  }
}

TEST_CASE("an avoided crossing has no singular point and no proved map", "[verify][map]") {
  // A constant moved by 1e-8 either way: the parallelogram's modes, or Viviani's two loops,
  // no longer meet.
  const auto [file, from, to] = GENERATE(
      std::tuple<std::string, std::string, std::string>{"cases/curves/fourbar-parallelogram.toml", " - 9\"", " - 9.00000001\""},
      std::tuple<std::string, std::string, std::string>{"cases/curves/fourbar-parallelogram.toml", " - 9\"", " - 8.99999999\""},
      // 9 + 2^-27, a double: the exact test runs, and finds no zero.
      std::tuple<std::string, std::string, std::string>{"cases/curves/fourbar-parallelogram.toml", " - 9\"",
                                                        " - 9.000000007450580596923828125\""},
      std::tuple<std::string, std::string, std::string>{"cases/curves/viviani.toml", "y^2 - 1\"", "y^2 - 1.00000001\""},
      std::tuple<std::string, std::string, std::string>{"cases/curves/viviani.toml", "y^2 - 1\"", "y^2 - 0.99999999\""});
  std::string text = read(file);
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  const Mapped m = solve_text(text, "avoided-crossing.toml", "auto", 0.05);
  INFO(file << " with " << to << ": " << m.v.headline);
  CHECK_FALSE(m.v.maps_proved);
  CHECK(m.v.singular_points == 0);
  for (auto& c : m.v.clusters)
    if (c.map) CHECK(c.map->singular_points.empty());
}

namespace {

// The parallelogram four-bar with its coupler equation written `coupler`.
std::string parallelogram_with(const std::string& coupler) {
  std::string text = read("cases/curves/fourbar-parallelogram.toml");
  const std::string from = "\"(3 + c3 - c1)^2 + (s3 - s1)^2 - 9\"";
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), coupler);
}

}  // namespace

TEST_CASE("decimal coefficients: the change points are proved from the decimals as written", "[verify][map]") {
  // Lengths 0.1 and 0.3: intervals around the decimals for the search, their exact values
  // beside them for the singular points' exact test.
  const std::string text = parallelogram_with("\"(0.3 + 0.1*c3 - 0.1*c1)^2 + (0.1*s3 - 0.1*s1)^2 - 0.09\"");
  const Mapped m = solve_text(text, "decimal-parallelogram.toml", "auto", 0.05);
  INFO(m.v.headline);
  CHECK(m.v.maps_proved);
  CHECK(m.v.singular_points == 2);
  REQUIRE(m.v.clusters.size() == 1);
  REQUIRE(m.v.clusters[0].map);
  CHECK_FALSE(m.v.clusters[0].map->inexact_coefficients);
}

TEST_CASE("a coefficient with no exact value: no singular point is tried, and the run says why and what to write", "[verify][map][cli]") {
  // sqrt(0.09) is 0.3, but its enclosure has no exact rational value: no exact zero can be checked.
  const std::string text = parallelogram_with("\"(sqrt(0.09) + 0.1*c3 - 0.1*c1)^2 + (0.1*s3 - 0.1*s1)^2 - 0.09\"");
  const Mapped m = solve_text(text, "sqrt-parallelogram.toml", "auto", 0.05);
  REQUIRE(m.v.clusters.size() == 1);
  const auto& map = m.v.clusters[0].map;
  REQUIRE(map);
  CHECK_FALSE(map->proved);
  CHECK(map->singular_points.empty());
  CHECK(map->inexact_coefficients);
  CHECK(map->statement.find("have no exact value") != std::string::npos);
  const std::string file = test::scratch("sqrt-parallelogram.toml");
  std::ofstream(file) << text;
  const test::Ran r = test::run_cli("solve " + file + " --threads 1 --quiet");
  CHECK(r.code == 4);
  CHECK(r.out.find("linkbox: next: exact arithmetic") != std::string::npos);
  CHECK(r.out.find("integers or decimals") != std::string::npos);
}

TEST_CASE("a nearly mobile 6R loop is never a proved curve", "[verify][map]") {
  // One link offset moved by 1e-9: the loop is rigid, its solutions are not a curve.
  std::string text = read("cases/linkages/6r-mobile.toml");
  const auto at = text.find("a = 0.5,");
  REQUIRE(at != std::string::npos);
  text.replace(at, 8, "a = 0.500000001,");
  const Mapped m = solve_text(text, "6r-nearly-mobile.toml", "auto", 0.1);
  CHECK(proved_maps(m.v) == 0);
  CHECK_FALSE(m.v.maps_proved);
  CHECK(m.v.headline.rfind("exactly", 0) != 0);
}

TEST_CASE("gimbal lock's redundant closure maps through phi2 = 0, whatever the strategy and sigma", "[verify][map]") {
  const std::string file = "cases/hard/gimbal-lock.toml";
  const auto [prune, sigma] = GENERATE(std::pair<std::string, double>{"auto", 0.01}, std::pair<std::string, double>{"trapezoid", 0.1},
                                       std::pair<std::string, double>{"hc4,newton", 0.03});
  INFO(prune << " at sigma " << sigma);
  const Mapped m = solve_text(read(file), file, prune, sigma);
  require_map(m, {{"isolated", "0"}, {"closed", "1"}, {"open", "0"}, {"proved", "yes"}});
  for (auto& c : m.v.clusters)
    if (c.map) CHECK(c.map->subspace_variable == 1);
}

TEST_CASE("a nearly redundant system is never mapped through a subspace", "[verify][map]") {
  // Constant terms of 1e-9 where the redundant systems have exact zeros: the circle-on-plane's
  // solutions are then isolated, and the wrist, turned by 1e-9 about x, is not locked.
  std::string plane = read("cases/curves/circle-on-plane.toml");
  const auto at = plane.find("\"z*(x - 0.5)\"");
  REQUIRE(at != std::string::npos);
  plane.replace(at, 13, "\"z*(x - 0.5) + 1e-9\"");
  std::string wrist = read("cases/hard/gimbal-lock.toml");
  const auto end = wrist.find("  { axis = [0, 0, 1], angle = \"-0.7\" },");
  REQUIRE(end != std::string::npos);
  wrist.insert(end, "  { axis = [1, 0, 0], angle = \"1e-9\" },\n");
  for (auto& [text, sigma] : {std::pair{plane, 0.05}, std::pair{wrist, 0.01}}) {
    const Mapped m = solve_text(text, "nearly-redundant.toml", "auto", sigma);
    INFO(m.v.headline);
    CHECK(proved_maps(m.v) == 0);
    CHECK(m.v.closed_curves == 0);
    for (auto& c : m.v.clusters) CHECK_FALSE(c.map);
  }
}

namespace {

// The mobile 6R's map: one proved closed curve, nothing else.
void require_one_closed_curve(const Mapped& m) {
  CHECK(m.v.maps_proved);
  CHECK(m.v.closed_curves == 1);
  CHECK(m.v.open_arcs == 0);
  CHECK(m.v.certified_roots == 0);
  CHECK(m.v.unverified == 0);
  CHECK(m.v.headline.rfind("exactly 0 isolated roots and 1 closed curve", 0) == 0);
}

}  // namespace

TEST_CASE("the mobile 6R, narrowed, maps to one proved closed curve", "[verify][map][slow]") {
  // Every solution has theta_i = theta_{i+3}; the loop's symmetry proves the map once the
  // search's contractors narrow its boxes.
  const std::string file = "cases/linkages/6r-mobile.toml";
  const Mapped m = solve_text(read(file), file, "auto", 0.1, verify::kSymmetricPiece);
  require_one_closed_curve(m);
  // check re-proves the map and the clusters emptied through the symmetry, and no more.
  const auto failures = verify::check_certificates(m.j, *m.c.formulation).failures;
  for (auto& why : failures) UNSCOPED_INFO(why);
  CHECK(failures.empty());
  auto rejected = [&](auto&& edit) {
    nlohmann::json j = m.j;
    edit(j);
    return !verify::check_certificates(j, *m.c.formulation).failures.empty();
  };
  CHECK(rejected([](auto& j) { j["verification"]["map"]["closed_curves"] = 2; }));
  CHECK(rejected([](auto& j) {  // a well-formed singular point stated where the symmetry proves none
    for (auto& c : j["clusters"])
      if (c.contains("map"))
        c["map"]["singular_points"] = nlohmann::json::array({{{"chart", 0}, {"box", {{0, 0}}}, {"preconditioner", {0, 0, nlohmann::json::array()}},
                                                              {"normal", nlohmann::json::array()}, {"point", nlohmann::json::array()},
                                                              {"kind", "crossing"}, {"branches", 0}}});
  }));
  CHECK(rejected([](auto& j) {
    for (auto& c : j["clusters"])
      if (c.contains("map") && !c["map"]["arcs"].empty()) {
        for (auto& side : c["map"]["arcs"][0]["box"])  // the arc's box moved by 0.01
          for (auto& end : side) end = end.template get<double>() + 0.01;
        return;
      }
  }));
}

TEST_CASE("the mobile 6R's map is the same under the lp strategy at sigma 0.03", "[verify][map][slow]") {
  const std::string file = "cases/linkages/6r-mobile.toml";
  const Mapped m = solve_text(read(file), file, "lp", 0.03, verify::kSymmetricPiece);
  require_one_closed_curve(m);
}

TEST_CASE("the mobile 6R's map is the same when propagation alone found the boxes", "[verify][map][slow]") {
  // hc4,newton leaves boxes beside the curve's extreme in theta1 whose (u, v) hulls reach the
  // curve: an arc found there lies outside its member, which the map must tell on slices thin
  // enough, or a lone cluster is left holding an arc with no continuation.
  const std::string file = "cases/linkages/6r-mobile.toml";
  const Mapped m = solve_text(read(file), file, "hc4,newton", 0.1, verify::kSymmetricPiece);
  require_one_closed_curve(m);
}

TEST_CASE("with no flags a symmetric loop is narrowed and mapped: cyclohexane's chairs and boat loop",
          "[verify][map][cli][slow]") {
  const std::string out = test::scratch("cyclohexane.json");
  const test::Ran r = test::run_cli("solve " + test::src("cases/linkages/cyclohexane.toml") + " --json " + out);
  REQUIRE(r.code == 0);
  const nlohmann::json j = test::read_json(out);
  CHECK(j["parameters"]["narrow"] == verify::kSymmetricPiece);
  CHECK(j["parameters"]["sources"]["narrow"] == "symmetric loop");
  CHECK(j["headline"].get<std::string>().rfind("exactly 2 isolated roots and 1 closed curve", 0) == 0);
  CHECK(test::run_cli("check " + out).code == 0);
  // Without verification there is no map to narrow for: the search is the plain one.
  REQUIRE(test::run_cli("solve " + test::src("cases/linkages/cyclohexane.toml") + " --no-verify --json " + out).code == 0);
  const nlohmann::json plain = test::read_json(out);
  CHECK(plain["parameters"]["narrow"] == 0);
  // The narrowing runs hc4,newton,taylor whatever the search ran; its work is counted with the
  // search's, by contractor.
  auto taylor_lps = [](const nlohmann::json& result) {
    for (auto& c : result["contractors"])
      if (c["name"] == "taylor") return c["lps_solved"].get<long>();
    return 0L;
  };
  CHECK(taylor_lps(j) > taylor_lps(plain));
}

TEST_CASE("check rejects a tampered map", "[verify][map][check]") {
  const std::string file = "cases/curves/fourbar-grashof.toml";
  const Mapped m = solve_text(read(file), file, "hc4,newton", 0.05);
  REQUIRE(verify::check_certificates(m.j, *m.c.formulation).failures.empty());
  auto rejected = [&](auto&& edit) {
    nlohmann::json j = m.j;
    edit(j);
    return !verify::check_certificates(j, *m.c.formulation).failures.empty();
  };
  nlohmann::json& map0 = const_cast<nlohmann::json&>(m.j)["clusters"][0]["map"];
  REQUIRE(map0.at("arcs").size() > 2);
  CHECK(rejected([](auto& j) { j["clusters"][0]["map"]["arcs"].erase(1); }));  // a piece left bare
  CHECK(rejected([](auto& j) { j["clusters"][0]["map"]["components"][0]["closed"] = false; }));
  CHECK(rejected([](auto& j) { j["verification"]["map"]["closed_curves"] = 3; }));
  CHECK(rejected([](auto& j) {
    auto& c = j["clusters"][0]["map"]["arcs"][0]["preconditioner"][2];
    c[0] = 0.0, c[1] = 0.0, c[2] = 0.0;
  }));
  CHECK(rejected([](auto& j) {  // the arc's box no longer covers its piece
    auto& b = j["clusters"][0]["map"]["arcs"][0]["box"];
    const int p = j["clusters"][0]["map"]["arcs"][0]["parameter"];
    b[p][0] = j["clusters"][0]["map"]["arcs"][0]["piece"][p][1];
  }));
  CHECK(rejected([](auto& j) { j["clusters"][0]["map"]["equations"] = {0, 1}; }));  // one left out
}

TEST_CASE("check rejects a tampered map through a subspace", "[verify][map][check]") {
  const std::string file = "cases/curves/circle-on-plane.toml";
  const Mapped m = solve_text(read(file), file, "auto", 0.05);
  REQUIRE(verify::check_certificates(m.j, *m.c.formulation).failures.empty());
  size_t at = 0;
  while (at < m.j["clusters"].size() && !m.j["clusters"][at].contains("map")) ++at;
  REQUIRE(at < m.j["clusters"].size());
  auto rejected = [&](auto&& edit) {
    nlohmann::json j = m.j;
    edit(j["clusters"][at]["map"]);
    return !verify::check_certificates(j, *m.c.formulation).failures.empty();
  };
  CHECK(rejected([](auto& map) { map.erase("subspace_variable"); }));  // three equations in three unknowns
  CHECK(rejected([](auto& map) { map["subspace_variable"] = 0; }));   // nothing vanishes on x = 0
  CHECK(rejected([](auto& map) { map["arcs"][0].erase("dropped_equations"); }));
  CHECK(rejected([](auto& map) { map["arcs"][0]["dropped_equations"] = {7}; }));
}

TEST_CASE("arc certificate: a circle's arc is proved, a crossing never", "[newton][map]") {
  const formulate::LoadedCase c = formulate::load_case_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1" ]
)", "circle.toml");
  const auto& sys = c.formulation->natural(0);
  const auto f = std::make_shared<const model::CompiledSystem>(sys.equations, 2);
  const newton::Arc a = newton::certify_arc(f, {Interval(0.6, 0.7), Interval(0.7, 0.8)}, {});
  REQUIRE(a.certified);
  for (auto& end : a.ends) CHECK(zero_in(sys.equations[0].eval(end)));
  // x^2 - y^2 = 0: two lines crossing at the origin; no box holding it has a single arc.
  const formulate::LoadedCase x = formulate::load_case_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 - y^2" ]
)", "cross.toml");
  const auto g = std::make_shared<const model::CompiledSystem>(x.formulation->natural(0).equations, 2);
  for (double lo : {-0.1, -0.013, -0.5})
    for (double w : {0.2, 0.03, 1.0}) {
      const Box b{Interval(lo, lo + w), Interval(lo * 0.7, lo * 0.7 + w)};
      if (contains(b[0], 0.0) && contains(b[1], 0.0)) CHECK_FALSE(newton::certify_arc(g, b, {}).certified);
    }
  // On one line, away from the crossing, it is an arc.
  CHECK(newton::certify_arc(g, {Interval(0.4, 0.5), Interval(0.38, 0.52)}, {}).certified);
}
