// `linkbox check` cannot be fooled by a forged result: a property test. A valid result of a
// short bundled case (solved once through the CLI, as a user would) is mutated in many
// seeded random variants of each kind below, and verify::check_certificates (what `linkbox
// check` runs) must report a failure for every one; the result as written must pass. Each
// kind is built so that the mutated result is provably wrong or unproved, not merely
// different (a box shifted by less than its slack can still be a valid certificate):
//
//   root box shifted       the reported root box moved off itself: it misses the root
//   certificate box moved  moved off itself, by at most 1e-6 (roots are apart by far more):
//                          the new box holds no root; crossings move off their hyperplane
//                          only in free variables (along the fixed one a curve may still
//                          cross the box)
//   preconditioner row     each entry changed by 1 to 100 times the largest entry: the
//                          Newton test fails or gives another image than the one stored
//   image changed          moved off itself (misses the root: the root is in the true
//                          image) or one side moved inwards (no longer proved)
//   case parameter         check --case on a case whose parameter differs: every certified
//                          box is shown here, independently of linkbox, to miss every root
//                          of the changed case
//   member dropped         a solution box left out of its cluster, or a cluster left out
//                          with the root count lowered: a box that holds a root uncounted
//   false duplicate        a certified cluster marked the duplicate of another (distinct)
//                          root, the count lowered
#include "formulate/load.hpp"
#include "input/case_hash.hpp"
#include "verify/check.hpp"
#include "verify/check_claims.hpp"
#include "tests/bicyclohexane_window.hpp"
#include "tests/cli_run.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace linkbox;
using nlohmann::json;

namespace {

constexpr int kVariants = 25;  // random variants of each mutation kind, per case
constexpr int kCurveVariants = 6;  // for the gimbal lock, whose check re-runs ~1200 crossings

using test::src;
std::string tmp(const std::string& name) { return test::scratch(name); }
int run_cli(const std::string& args) { return test::run_cli(args).code; }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A result of the CLI and the case's formulation; solved once per case per process.
struct Solved {
  std::string case_file, json_file;
  json result;
  std::unique_ptr<formulate::Formulation> formulation;
};

const Solved& solved(const std::string& case_file, const std::string& options = "") {
  static std::map<std::string, std::unique_ptr<Solved>> cache;
  auto& s = cache[case_file];
  if (!s) {
    s = std::make_unique<Solved>();
    s->case_file = case_file;
    s->json_file = tmp(std::filesystem::path(case_file).stem().string() + ".json");
    const int code = run_cli("solve " + case_file + " --quiet " + options + " --json " + s->json_file);
    REQUIRE((code == 0 || code == 4 || code == 5));  // a result was written: exact, unresolved, incomplete
    std::ifstream in(s->json_file);
    s->result = json::parse(in);
    s->formulation = formulate::load_case(case_file).formulation;
  }
  return *s;
}

std::vector<std::string> failures(const json& j, const formulate::Formulation& f) {
  return verify::check_certificates(j, f).failures;
}

using Rng = std::mt19937_64;

size_t pick(Rng& rng, size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }
double uniform(Rng& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
double sign(Rng& rng) { return pick(rng, 2) ? 1.0 : -1.0; }

double lo(const json& side) { return side[0].get<double>(); }
double hi(const json& side) { return side[1].get<double>(); }

// Moves side k of `box` off itself: by more than its width, and at most 1000 widths or
// `at_most` (plus a few ulps, so a degenerate side moves too).
double move_off(json& box, size_t k, Rng& rng, double at_most) {
  const double w = hi(box[k]) - lo(box[k]);
  const double ulps = 8 * std::ldexp(std::max(1.0, std::max(std::fabs(lo(box[k])), std::fabs(hi(box[k])))), -52);
  const double d = sign(rng) * (std::min(w * uniform(rng, 1.01, 1000), at_most) + w + ulps);
  box[k][0] = lo(box[k]) + d;
  box[k][1] = hi(box[k]) + d;
  return d;
}

// Where certificates are: every certified cluster's, and every certified curve crossing's.
struct Site {
  std::string what;
  json::json_pointer at;  // the certificate object
  int fixed = -1;         // a crossing's fixed variable
};

std::vector<Site> certificates(const json& j) {
  std::vector<Site> sites;
  const auto& clusters = j["clusters"];
  for (size_t i = 0; i < clusters.size(); ++i) {
    const std::string c = "/clusters/" + std::to_string(i);
    if (clusters[i]["status"] == "certified") sites.push_back({"cluster " + std::to_string(i), json::json_pointer(c + "/certificate")});
    if (clusters[i]["status"] == "curve")
      for (size_t k = 0; k < clusters[i]["crossings"].size(); ++k)
        if (clusters[i]["crossings"][k]["status"] == "certified")
          sites.push_back({"cluster " + std::to_string(i) + " crossing " + std::to_string(k),
                           json::json_pointer(c + "/crossings/" + std::to_string(k)),
                           clusters[i]["crossings"][k]["fixed_variable"].get<int>()});
    }
  return sites;
}

std::vector<size_t> certified_clusters(const json& j) {
  std::vector<size_t> v;
  for (size_t i = 0; i < j["clusters"].size(); ++i)
    if (j["clusters"][i]["status"] == "certified" && !j["clusters"][i].contains("duplicate_of")) v.push_back(i);
  return v;
}

// One mutation: changes `j`, says what it did; false when the result has nothing to mutate.
using Mutation = std::function<bool(json& j, Rng& rng, std::string& what)>;

bool shift_root_box(json& j, Rng& rng, std::string& what) {
  const auto cs = certified_clusters(j);
  if (cs.empty()) return false;
  const size_t c = cs[pick(rng, cs.size())];
  json& root = j["clusters"][c]["root"];
  const size_t k = pick(rng, root.size());
  const double d = move_off(root, k, rng, 1e-3);
  what = "root box of cluster " + std::to_string(c) + ", side " + std::to_string(k) + " moved by " + std::to_string(d);
  return true;
}

bool move_certificate_box(json& j, Rng& rng, std::string& what) {
  const auto sites = certificates(j);
  if (sites.empty()) return false;
  const Site& s = sites[pick(rng, sites.size())];
  json& box = j[s.at]["box"];
  std::vector<size_t> free;
  for (size_t k = 0; k < box.size(); ++k)
    if (static_cast<int>(k) != s.fixed) free.push_back(k);
  const size_t k = free[pick(rng, free.size())];
  const double d = move_off(box, k, rng, 1e-6);
  what = s.what + ": certificate box side " + std::to_string(k) + " moved by " + std::to_string(d);
  return true;
}

bool change_preconditioner(json& j, Rng& rng, std::string& what) {
  const auto sites = certificates(j);
  if (sites.empty()) return false;
  const Site& s = sites[pick(rng, sites.size())];
  json& m = j[s.at]["preconditioner"];
  double largest = 0;
  for (auto& row : m)
    for (auto& x : row) largest = std::max(largest, std::fabs(x.get<double>()));
  // A whole row: one entry alone can be inert (on a curve crossing, an entry that weighs an
  // equation of the fixed variable only), and the certificate then still proves its root.
  const size_t r = pick(rng, m.size());
  const double by = sign(rng) * largest * std::pow(10.0, uniform(rng, 0, 2));
  for (auto& x : m[r]) x = x.get<double>() + by;
  what = s.what + ": preconditioner row " + std::to_string(r) + " changed by " + std::to_string(by);
  return true;
}

bool change_image(json& j, Rng& rng, std::string& what) {
  const auto sites = certificates(j);
  if (sites.empty()) return false;
  const Site& s = sites[pick(rng, sites.size())];
  json& image = j[s.at]["image"];
  const size_t k = pick(rng, image.size());
  const double w = hi(image[k]) - lo(image[k]);
  if (pick(rng, 2) == 0 || w == 0) {
    const double d = move_off(image, k, rng, 1e-3);
    what = s.what + ": image side " + std::to_string(k) + " moved by " + std::to_string(d);
  } else {
    // At least one ulp: an image a few ulps wide would not change otherwise.
    const double in = w * uniform(rng, 0.01, 0.99);
    if (pick(rng, 2)) image[k][0] = std::max(lo(image[k]) + in, std::nextafter(lo(image[k]), hi(image[k])));
    else image[k][1] = std::min(hi(image[k]) - in, std::nextafter(hi(image[k]), lo(image[k])));
    what = s.what + ": image side " + std::to_string(k) + " narrowed by " + std::to_string(in);
  }
  return true;
}

bool drop_member(json& j, Rng& rng, std::string& what) {
  auto& clusters = j["clusters"];
  if (clusters.empty()) return false;
  if (pick(rng, 2) == 0 || certified_clusters(j).empty()) {
    const size_t c = pick(rng, clusters.size());
    auto& members = clusters[c]["members"];
    const size_t m = pick(rng, members.size());
    what = "member " + std::to_string(m) + " of cluster " + std::to_string(c) + " dropped";
    members.erase(m);
    return true;
  }
  // A whole certified cluster dropped, the count kept consistent.
  const auto cs = certified_clusters(j);
  const size_t c = cs[pick(rng, cs.size())];
  for (auto& other : clusters)  // duplicates name clusters by index: keep them pointing right
    if (other.contains("duplicate_of") && other["duplicate_of"].get<size_t>() > c)
      other["duplicate_of"] = other["duplicate_of"].get<size_t>() - 1;
  clusters.erase(c);
  j["certified_roots"] = j["certified_roots"].get<int>() - 1;
  what = "certified cluster " + std::to_string(c) + " dropped, certified_roots lowered";
  return true;
}

bool false_duplicate(json& j, Rng& rng, std::string& what) {
  const auto cs = certified_clusters(j);
  if (cs.size() < 2) return false;
  const size_t a = pick(rng, cs.size());
  size_t b = pick(rng, cs.size() - 1);
  if (b >= a) ++b;
  j["clusters"][cs[b]]["duplicate_of"] = cs[a];
  j["certified_roots"] = j["certified_roots"].get<int>() - 1;
  what = "cluster " + std::to_string(cs[b]) + " marked a duplicate of cluster " + std::to_string(cs[a]);
  return true;
}

// Applies `variants` seeded variants of `mutate` to the result of `s`; each must be rejected.
// Returns how many variants were applied.
int expect_all_rejected(const Solved& s, const Mutation& mutate, std::uint64_t seed, int variants) {
  Rng rng(seed);
  int applied = 0;
  for (int v = 0; v < variants; ++v) {
    json j = s.result;
    std::string what;
    if (!mutate(j, rng, what)) break;
    REQUIRE(j != s.result);
    ++applied;
    INFO(s.case_file << ", variant " << v << ": " << what);
    CHECK_FALSE(failures(j, *s.formulation).empty());
  }
  return applied;
}

// --- The changed case parameter: the changed cases and their roots, known in closed form. --

// Power sums of three planted numbers: x+y+z, x^2+y^2+z^2, x^3+y^3+z^3 at (a, b, c); the
// roots are the 6 permutations of (a, b, c) (planted-cubic.toml explains why).
std::string planted_case(const std::array<std::string, 3>& v) {
  auto sum = [&](int p) {
    std::string s;
    for (auto& x : v) s += (s.empty() ? "" : " + ") + ("(" + x + ")^" + std::to_string(p));
    return s;
  };
  return "kind = \"polynomial\"\nname = \"planted-mutated\"\n"
         "variables = [\n  { name = \"x\", domain = [-3, 3] },\n  { name = \"y\", domain = [-3, 3] },\n"
         "  { name = \"z\", domain = [-3, 3] },\n]\nequations = [\n  \"x + y + z - (" + sum(1) + ")\",\n"
         "  \"x^2 + y^2 + z^2 - (" + sum(2) + ")\",\n  \"x^3 + y^3 + z^3 - (" + sum(3) + ")\",\n]\n";
}

std::string decimal(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// Whether the point p lies within `margin` of the box (outputs), in every coordinate;
// `angles`: modulo whole turns.
bool near_box(const json& box, const std::vector<double>& p, double margin, bool angles) {
  for (size_t k = 0; k < p.size(); ++k) {
    double x = p[k];
    if (angles) x = std::remainder(x - 0.5 * (lo(box[k]) + hi(box[k])), 2 * M_PI) + 0.5 * (lo(box[k]) + hi(box[k]));
    if (x < lo(box[k]) - margin || x > hi(box[k]) + margin) return false;
  }
  return true;
}

// ZXZ Euler angles (phi1, phi2, phi3) with Rz(phi1) Rx(phi2) Rz(phi3) = R(q), both solutions.
std::vector<std::vector<double>> zxz_angles(std::array<double, 4> q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (auto& x : q) x /= n;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r02 = 2 * (x * z + w * y), r12 = 2 * (y * z - w * x), r22 = 1 - 2 * (x * x + y * y);
  const double r20 = 2 * (x * z - w * y), r21 = 2 * (y * z + w * x);
  const double p1 = std::atan2(r02, -r12), p2 = std::acos(std::clamp(r22, -1.0, 1.0)), p3 = std::atan2(r20, r21);
  return {{p1, p2, p3}, {p1 + M_PI, -p2, p3 + M_PI}};
}

}  // namespace

TEST_CASE("check accepts the results as written, through the library and the CLI", "[check][mutation]") {
  for (auto* c : {"cases/spherical/wrist.toml", "cases/polynomial/planted-cubic.toml"}) {
    const Solved& s = solved(src(c));
    INFO(c);
    CHECK(failures(s.result, *s.formulation).empty());
    CHECK(run_cli("check " + s.json_file) == 0);
    CHECK(s.result["certified_roots"].get<int>() > 0);
  }
  const Solved& g = solved(src("cases/hard/gimbal-lock.toml"), "--sigma 1e-2");
  CHECK(failures(g.result, *g.formulation).empty());
}

TEST_CASE("check rejects every mutation of a valid result", "[check][mutation]") {
  const std::map<std::string, Mutation> kinds = {
      {"root box shifted", shift_root_box},     {"certificate box moved", move_certificate_box},
      {"preconditioner row changed", change_preconditioner}, {"image changed", change_image},
      {"member dropped", drop_member},          {"false duplicate", false_duplicate},
  };
  struct Case {
    std::string file;
    const char* options;
    std::vector<std::string> kinds;  // all of them apply to the case's result
    int variants;
  };
  const std::vector<std::string> all = {"root box shifted", "certificate box moved", "preconditioner row changed",
                                        "image changed", "member dropped", "false duplicate"};
  // The gimbal lock is a curve: certified crossings, no isolated root.
  const std::vector<std::string> crossings = {"certificate box moved", "preconditioner row changed", "image changed",
                                              "member dropped"};
  // Bicyclohexane's poses beside a chair: certified through the loops (verify/coupled_loops.hpp).
  const std::string window = tmp("bicyclohexane-window.toml");
  write_text(window, test::bicyclohexane_window(test::bicyclohexane_text(), test::bicyclohexane_pose('b')));
  for (const Case& c : {Case{src("cases/spherical/wrist.toml"), "", all, kVariants},
                        Case{src("cases/polynomial/planted-cubic.toml"), "", all, kVariants},
                        Case{window, "", all, kVariants},
                        Case{src("cases/hard/gimbal-lock.toml"), "--sigma 1e-2", crossings, kCurveVariants}}) {
    const Solved& s = solved(c.file, c.options);
    std::uint64_t seed = 12;
    for (auto& name : c.kinds) {
      DYNAMIC_SECTION(c.file << ": " << name) {
        CHECK(expect_all_rejected(s, kinds.at(name), ++seed, c.variants) == c.variants);
      }
    }
  }
}

TEST_CASE("check --case rejects a result against a case whose parameter differs", "[check][mutation]") {
  SECTION("planted power sums: one planted number moved") {
    // The result of the case as planted, rewritten from its three numbers: check accepts it.
    const std::array<std::string, 3> planted = {"-1", "0.5", "2"};
    const std::string base = tmp("planted-base.toml");
    write_text(base, planted_case(planted));
    const Solved& s = solved(base);
    REQUIRE(s.result["certified_roots"] == 6);
    REQUIRE(failures(s.result, *s.formulation).empty());
    Rng rng(2024);
    for (int v = 0; v < kVariants; ++v) {
      std::array<double, 3> moved = {-1, 0.5, 2};
      const size_t which = pick(rng, 3);
      const double delta = sign(rng) * std::pow(10.0, uniform(rng, -9, -2));
      moved[which] += delta;
      std::array<std::string, 3> text = planted;
      text[which] = decimal(moved[which]);
      INFO("variant " << v << ": planted number " << which << " is now " << text[which]);
      // Independently of linkbox: every certified box misses every root of the changed case
      // (the permutations of the moved numbers) by far more than rounding.
      std::array<double, 3> p = moved;
      std::sort(p.begin(), p.end());
      for (size_t c : certified_clusters(s.result))
        do {
          CHECK_FALSE(near_box(s.result["clusters"][c]["certificate"]["box"], {p[0], p[1], p[2]}, std::fabs(delta) / 4, false));
        } while (std::next_permutation(p.begin(), p.end()));
      const std::string changed = tmp("planted-changed.toml");
      write_text(changed, planted_case(text));
      CHECK_FALSE(failures(s.result, *formulate::load_case(changed).formulation).empty());
      if (v == 0) CHECK(run_cli("check " + s.json_file + " --case " + changed) == 1);
    }
  }
  SECTION("wrist: the desired orientation turned") {
    const Solved& s = solved(src("cases/spherical/wrist.toml"));
    const std::string text = read_text(s.case_file);
    // The one quaternion factor: "quaternion = [w, x, y, z]".
    const size_t at = text.find("quaternion = [");
    REQUIRE(at != std::string::npos);
    const size_t open = at + 14, close = text.find(']', open);
    REQUIRE(close != std::string::npos);
    REQUIRE(text.find("quaternion = [", close) == std::string::npos);
    std::array<double, 4> q0;
    {
      std::string list = text.substr(open, close - open);
      std::replace(list.begin(), list.end(), ',', ' ');
      std::stringstream in(list);
      for (auto& x : q0) REQUIRE(in >> x);
    }
    // The loop closes at R(q0) (the file's factor is q0^-1): its roots are the ZXZ angles.
    for (auto& root : zxz_angles(q0)) {
      bool found = false;
      for (size_t c : certified_clusters(s.result)) found = found || near_box(s.result["clusters"][c]["root"], root, 1e-9, true);
      REQUIRE(found);  // the closed form is right: both roots are where linkbox certified them
    }
    Rng rng(7);
    for (int v = 0; v < kVariants; ++v) {
      // q0 + eps * u with u orthogonal to q0: another rotation (along q0 only the scale changes).
      std::array<double, 4> u;
      double dot = 0, norm = 0;
      for (auto& x : u) x = uniform(rng, -1, 1);
      for (int i = 0; i < 4; ++i) dot += u[i] * q0[i];
      for (int i = 0; i < 4; ++i) u[i] -= dot * q0[i];
      for (auto& x : u) norm += x * x;
      const double eps = std::pow(10.0, uniform(rng, -7, -2));
      std::array<double, 4> q = q0;
      for (int i = 0; i < 4; ++i) q[i] += eps * u[i] / std::sqrt(norm);
      std::string list;
      for (double x : q) list += (list.empty() ? "" : ", ") + decimal(x);
      INFO("variant " << v << ": quaternion [" << list << "]");
      for (auto& root : zxz_angles(q))
        for (size_t c : certified_clusters(s.result))
          CHECK_FALSE(near_box(s.result["clusters"][c]["root"], root, 1e-9, true));
      const std::string changed = tmp("wrist-changed.toml");
      write_text(changed, text.substr(0, open) + list + text.substr(close));
      CHECK_FALSE(failures(s.result, *formulate::load_case(changed).formulation).empty());
      if (v == 0) CHECK(run_cli("check " + s.json_file + " --case " + changed) == 1);
    }
  }
}

// Planted system 7704 (tests/data/planted/close-7704.toml): two close pairs, 4 roots. A result
// of an earlier build said "exactly 3": a cluster holding two roots was certified around one,
// marked the duplicate of another cluster, and its second root never counted. check must
// reject that result, and today's solve must not state a wrong count.
TEST_CASE("an exact count needs every certified cluster alone in its hull (duplicates too)", "[check]") {
  const std::string c = src("tests/data/planted/close-7704.toml");
  const auto f = formulate::load_case(c).formulation;
  std::ifstream in(src("tests/data/planted/close-7704.result.json"));
  const json forged = json::parse(in);
  REQUIRE(forged["headline"].get<std::string>().rfind("exactly 3", 0) == 0);
  CHECK_FALSE(failures(forged, *f).empty());

  const std::string out = tmp("close-7704.json");
  const int code = run_cli("solve " + c + " --quiet --json " + out);
  REQUIRE((code == 0 || code == 4));  // an exact count, or unresolved clusters
  std::ifstream fresh_in(out);
  const json fresh = json::parse(fresh_in);
  const std::string headline = fresh["headline"];
  if (headline.rfind("exactly", 0) == 0) CHECK(headline.rfind("exactly 4 roots", 0) == 0);
  CHECK(failures(fresh, *f).empty());
}

// Every top-level field of a result, edited, is either caught or one that check declares it
// takes on trust (verify::trusted_fields, printed by `linkbox check`).
namespace {

void edit(json& v) {
  if (v.is_boolean()) v = !v.get<bool>();
  else if (v.is_number_integer()) v = v.get<long>() + 1;
  else if (v.is_number()) v = v.get<double>() * 2 + 1;
  else if (v.is_string()) v = v.get<std::string>() + " (edited)";
  else if (v.is_array() && !v.empty()) v.erase(v.size() - 1);
  else if (v.is_array()) v.push_back(0);
  else if (v.is_object() && !v.empty()) edit(v.begin().value());
}

// Caught: a failure listed, or data too malformed to check (the CLI's exit 2).
bool rejected(const json& m, const formulate::Formulation& f, const std::string& sha = {}) {
  try {
    return !verify::check_certificates(m, f, sha).failures.empty();
  } catch (const json::exception&) {
    return true;
  }
}

bool trusted(const std::string& key) {
  for (auto& t : verify::trusted_fields())
    if (key == t.key) return true;
  return false;
}

}  // namespace

TEST_CASE("check catches an edit of every top-level field, or says it takes that field on trust", "[check][mutation]") {
  for (const char* name : {"cases/spherical/wrist.toml", "cases/curves/fourbar-grashof.toml",
                           "cases/linkages/6r-rigid-limits.toml", "cases/hard/close-roots-unresolved.toml"}) {
    const Solved& s = solved(src(name));
    const std::string sha = input::case_sha256(s.case_file);
    REQUIRE_FALSE(rejected(s.result, *s.formulation, sha));
    for (auto& [key, value] : s.result.items()) {
      std::vector<std::pair<std::string, json>> edits{{key, value}};  // (field named, edited value)
      edit(edits[0].second);
      if (value.is_object())  // each claim of an object (e.g. verification) on its own
        for (auto& [sub, v] : value.items()) {
          json e = value;
          edit(e[sub]);
          edits.emplace_back(key + "." + sub, e);
        }
      for (auto& [field, e] : edits) {
        json m = s.result;
        m[key] = e;
        if (m == s.result) continue;
        INFO(name << ": " << field << " edited, " << key << " = " << e.dump().substr(0, 200));
        CHECK((rejected(m, *s.formulation, sha) || trusted(key) || trusted(field)));
      }
    }
  }
}

TEST_CASE("check rejects a status edited to any other", "[check][mutation]") {
  // Without the symmetric loop's narrowing: each check would re-prove its whole map.
  const Solved& s = solved(src("cases/linkages/cyclohexane.toml"), "--narrow 0");
  for (size_t i = 0; i < s.result["clusters"].size(); ++i)
    for (const char* status : {"certified", "unverified", "curve", "empty", "infeasible"}) {
      if (s.result["clusters"][i]["status"] == status) continue;
      json m = s.result;
      m["clusters"][i]["status"] = status;
      INFO("cluster " << i << " made " << status);
      CHECK(rejected(m, *s.formulation));
    }
}

TEST_CASE("check against another case's file says it is not the case that was solved", "[check][mutation]") {
  const Solved& s = solved(src("cases/spherical/wrist.toml"));
  const auto out = verify::check_certificates(s.result, *s.formulation, input::case_sha256(src("cases/spherical/agile-eye.toml")));
  REQUIRE(out.failures.size() == 1);
  CHECK(out.failures[0].find("not the case that was solved") != std::string::npos);
}
