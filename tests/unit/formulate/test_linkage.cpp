// The linkage vector model (iterated-LP paper, Section II) and the natural system that
// certification solves, against configurations built independently: random closed loops
// from random joint axes (DH parameters measured from the geometry, cross-checked by DH
// forward kinematics), the cyclohexane chair, bicyclohexane's chair-chair poses, the planted
// pose of two rings, the bundled cases and the malformed files of tests/data/bad_linkage.
#include "formulate/linkage.hpp"
#include "formulate/to_lph.hpp"
#include "interval/rigorous.hpp"
#include "input/case_file.hpp"
#include "input/linkage_file.hpp"
#include "report/json.hpp"
#include "input/toml_reader.hpp"
#include "verify/check.hpp"
#include "solve/solve_case.hpp"
#include "tests/box_file.hpp"
#include "verify/certify_case.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <random>
#include <sstream>

using namespace linkbox;
using namespace linkbox::formulate;
using namespace linkbox::input;

namespace {

using V3 = std::array<double, 3>;
using M3 = std::array<V3, 3>;  // rows

V3 operator+(V3 u, const V3& v) { return {u[0] + v[0], u[1] + v[1], u[2] + v[2]}; }
V3 operator-(V3 u, const V3& v) { return {u[0] - v[0], u[1] - v[1], u[2] - v[2]}; }
V3 operator*(double s, const V3& v) { return {s * v[0], s * v[1], s * v[2]}; }
double dot(const V3& u, const V3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
V3 cross(const V3& u, const V3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}
double norm(const V3& v) { return std::sqrt(dot(v, v)); }
V3 unit(const V3& v) { return (1 / norm(v)) * v; }
V3 apply(const M3& m, const V3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }
M3 mul(const M3& a, const M3& b) {
  M3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[k][j];
  return r;
}
V3 column(const M3& m, int j) { return {m[0][j], m[1][j], m[2][j]}; }
double det(const V3& c0, const V3& c1, const V3& c2) { return dot(c0, cross(c1, c2)); }

struct Frame {
  M3 r{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  V3 p{0, 0, 0};
};

// One DH step Rz(theta) Tz(d) Tx(a) Rx(alpha).
Frame dh(double theta, double d, double a, double alpha) {
  const double ct = std::cos(theta), st = std::sin(theta), ca = std::cos(alpha), sa = std::sin(alpha);
  const M3 rz{{{ct, -st, 0}, {st, ct, 0}, {0, 0, 1}}}, rx{{{1, 0, 0}, {0, ca, -sa}, {0, sa, ca}}};
  return {mul(rz, rx), {a * ct, a * st, d}};
}
Frame compose(const Frame& f, const Frame& t) { return {mul(f.r, t.r), f.p + apply(f.r, t.p)}; }


struct Line {
  V3 p, u;  // a point and the unit direction (the joint axis d)
};

// Loop entry i as measured: joint i on line `line`, link i along the normal to joint i+1.
struct Entry {
  std::string joint, link;
  int line = 0;
  double a = 0, alpha = 0, d = 0, theta = 0;
  V3 axis{}, normal{};  // d_i, a_i (world)
  bool prismatic = false;
};

// DH parameters and normals of the loop through lines[idx[0]], lines[idx[1]], ...,
// measured from the geometry: a_i along the common normal of axes i and i+1 (its sign and the
// twist flipped at random, so negative lengths and twists occur), d_i between the feet of
// a_{i-1} and a_i on axis i, theta_i from a_{i-1} to a_i about d_i.
std::vector<Entry> measure_loop(const std::vector<Line>& lines, const std::vector<int>& idx, std::mt19937& rng) {
  const size_t n = idx.size();
  std::vector<Entry> e(n);
  std::vector<V3> foot_out(n), foot_in(n);  // feet of a_i on axis i / of a_{i-1} on axis i
  for (size_t i = 0; i < n; ++i) {
    const Line &li = lines[idx[i]], &lj = lines[idx[(i + 1) % n]];
    const V3 c = cross(li.u, lj.u);
    V3 dir = unit(c);
    double alpha = std::atan2(norm(c), dot(li.u, lj.u));
    // t u_i - t' u_j + lambda dir = p_j - p_i  (Cramer)
    const V3 rhs = lj.p - li.p, mu = -1.0 * lj.u;
    const double D = det(li.u, mu, dir);
    const double t = det(rhs, mu, dir) / D, tj = det(li.u, rhs, dir) / D;
    double lambda = det(li.u, mu, rhs) / D;
    if (std::uniform_int_distribution<int>(0, 1)(rng)) dir = -1.0 * dir, lambda = -lambda, alpha = -alpha;
    if (std::abs(lambda) < 1e-9) lambda = 0;  // axes built to meet: an exact zero length
    e[i].line = idx[i];
    e[i].axis = li.u;
    e[i].a = lambda;
    e[i].alpha = alpha;
    e[i].normal = dir;
    foot_out[i] = li.p + t * li.u;
    foot_in[(i + 1) % n] = lj.p + tj * lj.u;
  }
  for (size_t i = 0; i < n; ++i) {
    const V3& u = e[i].axis;
    const V3 &prev = e[(i + n - 1) % n].normal, &next = e[i].normal;
    e[i].d = dot(foot_out[i] - foot_in[i], u);
    e[i].theta = std::atan2(dot(cross(prev, next), u), dot(prev, next));
  }
  return e;
}

// World -> frame of link g of the loop: x = a_g, z = d_{g+1}.
M3 ground_frame(const std::vector<Entry>& e, size_t g) {
  const V3 x = e[g].normal, z = e[(g + 1) % e.size()].axis;
  return {x, cross(z, x), z};
}

// DH forward kinematics from the frame of link g must reproduce every measured axis and
// normal and close the loop: validates the measured parameters against the DH convention
// independently of the formulation.
void check_forward_kinematics(const std::vector<Entry>& e, size_t g) {
  const size_t n = e.size();
  const M3 R = ground_frame(e, g);
  auto near = [](const V3& u, const V3& v) { return norm(u - v) < 1e-9; };
  Frame f;
  for (size_t k = 1; k <= n; ++k) {
    const size_t i = (g + k) % n;
    CHECK(near(column(f.r, 2), apply(R, e[i].axis)));  // z_{i-1} = d_i
    f = compose(f, dh(e[i].theta, e[i].d, e[i].a, e[i].alpha));
    CHECK(near(column(f.r, 0), apply(R, e[i].normal)));  // x_i = a_i
  }
  const Frame identity;
  for (int r = 0; r < 3; ++r) CHECK(near(f.r[r], identity.r[r]));
  CHECK(norm(f.p) < 1e-9);
}

// Parameters are enclosed with a margin of 1e-12: the measured doubles are only near the
// parameters of the exactly closing geometry, and a loop the ground fully determines (3R)
// would otherwise be exactly unassemblable.
Interval around(double x) { return Interval(x - 1e-12, x + 1e-12); }

LinkageLoop make_loop(const std::string& name, const std::vector<Entry>& entries, std::mt19937& rng) {
  LinkageLoop loop;
  loop.name = name;
  loop.line = 1;
  for (auto& e : entries) {
    LoopLink l;
    l.joint = e.joint;
    l.link = e.link;
    l.a = e.a == 0 ? Interval(0.0) : around(e.a);
    l.alpha = around(e.alpha);
    l.prismatic = e.prismatic;
    if (e.prismatic) {
      std::uniform_real_distribution<double> margin(0.0, 1.0);
      l.d = Interval(e.d - margin(rng), e.d + margin(rng));
      l.theta = around(e.theta);
    } else {
      l.d = around(e.d);
    }
    l.line = 2;
    loop.links.push_back(l);
  }
  return loop;
}

int joint_index(const LinkageFormulation& f, const std::string& name) {
  auto& names = f.joint_names();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

// The configuration (ground-frame vectors of every loop, prismatic offsets) as a point of the
// model: primary variables set from the vectors, constants checked against them (when the
// configuration closes), dummies lifted; then widened by `pad`.
Box model_point(const LinkageFormulation& f, const std::vector<std::vector<Entry>>& loops, const M3& R, double pad,
                bool closes = true) {
  const SubProblem sub = f.subproblem(0);
  const size_t n = sub.system.variables.size();
  Box box(n, Interval(0.0));
  std::vector<bool> set(n, false);
  // Coordinates that are variables of their own set the point; the others (constants,
  // eliminated ones) must agree with it.
  std::vector<std::pair<LinkageFormulation::Coordinate, double>> derived;
  auto put = [&](const LinkageFormulation::Coordinate& c, double v) {
    if (!c.is_variable()) {
      derived.push_back({c, v});
      return;
    }
    if (set[c.variable]) CHECK(std::abs(box[c.variable].lower() - v) < 1e-12);
    box[c.variable] = Interval(v);
    set[c.variable] = true;
  };
  for (size_t l = 0; l < loops.size(); ++l)
    for (size_t i = 0; i < loops[l].size(); ++i) {
      const Entry& e = loops[l][i];
      const int j = joint_index(f, e.joint);
      const V3 d = apply(R, e.axis), a = apply(R, e.normal);
      for (int k = 0; k < 3; ++k) put(f.axis(j)[k], d[k]);
      if (auto* nm = f.normal(l, i))
        for (int k = 0; k < 3; ++k) put((*nm)[k], a[k]);
      if (e.prismatic) put(f.offset(j), e.d);
    }
  if (closes)
    for (auto& [c, v] : derived) {
      const Interval x = c.at(box);
      INFO("derived coordinate " << v << " in [" << x.lower() << ", " << x.upper() << "]");
      CHECK(x.lower() - 1e-9 <= v);
      CHECK(v <= x.upper() + 1e-9);
      CHECK(width(x) < 1e-4);
    }
  for (int p : sub.lph->primary) {
    INFO("primary variable " << sub.system.variables[p].name);
    REQUIRE(set[p]);
  }
  box = lift(*sub.lph, box);
  for (auto& x : box) x = Interval(x.lower() - pad, x.upper() + pad);
  return box;
}

void check_equations_hold(const SubProblem& sub, const Box& box) {
  REQUIRE(sub.system.equations.size() == sub.system.equation_names.size());
  for (size_t k = 0; k < sub.system.equations.size(); ++k) {
    INFO("equation " << sub.system.equation_names[k]);
    CHECK(zero_in(sub.system.equations[k].eval(box)));
  }
}

// theta (in (-pi, pi]) lies in the enclosure, modulo 2 pi.
bool angle_in(const Interval& enclosure, double theta) {
  const double two_pi = 2 * M_PI;
  return contains(enclosure, theta) || contains(enclosure, theta + two_pi) || contains(enclosure, theta - two_pi);
}

std::vector<Line> random_lines(std::mt19937& rng, int n, double meet_probability) {
  std::uniform_real_distribution<double> u(-1, 1), coin(0, 1);
  std::normal_distribution<double> g;
  std::vector<Line> lines;
  for (int i = 0; i < n; ++i) {
    Line l{{u(rng), u(rng), u(rng)}, unit({g(rng), g(rng), g(rng)})};
    // Make this axis meet the previous one (a link of length 0) now and then.
    if (i > 0 && coin(rng) < meet_probability) l.p = lines.back().p + u(rng) * lines.back().u;
    lines.push_back(l);
  }
  return lines;
}

input::LinkageCase load_file(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  // Through the case reader, which also takes the [solve] table off.
  return std::get<input::LinkageCase>(input::read_case(path).description);
}

std::string case_path(const std::string& name) { return std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/" + name; }

// The natural system (what certification solves) holds at a configuration given by its
// outputs: every equation's range over the natural box of `out` contains 0, and the box
// maps back onto the outputs. Moving one angle by 0.01 breaks some equation (not vacuous).
void check_natural_system_holds(const LinkageFormulation& f, const Box& out) {
  const std::uint64_t chart = f.chart_for(out);
  const NaturalSystem s = f.natural_system(chart);
  REQUIRE(s.unknowns.size() == out.size());
  const Box natural = f.output_to_natural(chart, out);
  for (size_t k = 0; k < s.equations.size(); ++k) {
    INFO("natural equation " << k);
    CHECK(zero_in(s.equations[k].eval(natural)));
  }
  const Box back = f.natural_to_output(chart, natural);
  for (size_t i = 0; i < out.size(); ++i) CHECK((angle_in(back[i], median(out[i])) || contains(back[i], median(out[i]))));
  const std::vector<std::string> names = f.output_names();
  for (size_t i = 0; i < out.size(); ++i) {
    if (s.unknowns[i] != "t_" + names[i]) continue;  // an offset
    Box moved = out;
    moved[i] += Interval(0.01);
    const Box far = f.output_to_natural(chart, moved);
    bool broken = false;
    for (auto& p : s.equations) broken = broken || !zero_in(p.eval(far));
    INFO("output " << names[i] << " moved by 0.01");
    CHECK(broken);
    break;
  }
}

// Axes and normals of `loop` at the angles theta, by DH forward kinematics from `start`, the
// frame of the link before its first entry (in the ground frame); the loop must close when
// `closes`.
std::vector<Entry> place_loop(const LinkageLoop& loop, const std::vector<double>& theta, const Frame& start,
                              bool closes = true) {
  std::vector<Entry> e(loop.links.size());
  Frame fr = start;
  for (size_t i = 0; i < e.size(); ++i) {
    const LoopLink& l = loop.links[i];
    e[i].joint = l.joint;
    e[i].link = l.link;
    e[i].theta = theta[i];
    e[i].d = median(l.d);
    e[i].axis = column(fr.r, 2);
    fr = compose(fr, dh(theta[i], median(l.d), median(l.a), median(l.alpha)));
    e[i].normal = column(fr.r, 0);
  }
  if (!closes) return e;
  CHECK(norm(fr.p - start.p) < 1e-9);
  for (int k = 0; k < 3; ++k) CHECK(norm(column(fr.r, k) - column(start.r, k)) < 1e-9);
  return e;
}

}  // namespace

TEST_CASE("random closed loops satisfy the linkage equations and give back their angles", "[linkage]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 3 + trial % 6;
    auto lines = random_lines(rng, n, 0.3);
    if (trial % 4 == 1) {
      // Axes 0, 1, 2 in one plane, 0 and 2 on the same side of 1: a_0 and a_1 are opposite and
      // theta_1 = pi (or 0, after the random sign flips): an angle on the cut of atan2.
      std::normal_distribution<double> g;
      const V3 u = lines[1].u, w = unit(cross(u, unit({g(rng), g(rng), g(rng)})));
      const double p = std::uniform_real_distribution<double>(0.3, 2.8)(rng), q = p + 0.2;
      lines[0].u = std::cos(p) * u + std::sin(p) * w;
      lines[2].u = std::cos(q) * u + std::sin(q) * w;
    }
    std::vector<int> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    std::vector<Entry> e = measure_loop(lines, idx, rng);
    const size_t g = std::uniform_int_distribution<size_t>(0, n - 1)(rng);
    check_forward_kinematics(e, g);
    for (int i = 0; i < n; ++i) {
      e[i].joint = "J" + std::to_string(i + 1);
      e[i].link = "L" + std::to_string(i + 1);
      e[i].prismatic = trial % 3 == 2 && std::uniform_int_distribution<int>(0, 2)(rng) == 0;
    }
    LinkageCase c;
    c.name = "random";
    c.file = "random";
    c.ground = e[g].link;
    c.loops.push_back(make_loop("ring", e, rng));
    for (bool keep : {false, true}) {
      INFO("trial " << trial << " n " << n << " ground " << g << " keep_free_normals " << keep);
      const LinkageFormulation f(c, {keep});
      const SubProblem sub = f.subproblem(0);
      REQUIRE(sub.lph);
      CHECK(sub.system.variables.size() == sub.lph->variables.size());
      CHECK(sub.split_dims == sub.lph->primary);
      const Box box = model_point(f, {e}, ground_frame(e, g), 1e-12);
      check_equations_hold(sub, box);

      const Box out = f.to_output(0, box);
      REQUIRE(out.size() == static_cast<size_t>(n));
      REQUIRE(f.output_names().size() == out.size());
      CHECK(f.outputs_are_angles() == std::none_of(e.begin(), e.end(), [](const Entry& x) { return x.prismatic; }));
      for (int i = 0; i < n; ++i) {
        INFO("joint " << e[i].joint << " theta " << e[i].theta << " d " << e[i].d << " output " << out[i].lower()
                      << " " << out[i].upper());
        CHECK(f.output_names()[i] == e[i].joint);
        if (e[i].prismatic) CHECK(contains(out[i], e[i].d));
        else CHECK(angle_in(out[i], e[i].theta));
        CHECK(width(out[i]) < 1e-4);
      }
      check_natural_system_holds(f, out);
      // Offsets are no angles in the charts: even a range across pi + 2 k pi stays as it is.
      Box wide = out;
      for (int i = 0; i < n; ++i)
        if (e[i].prismatic) wide[i] = Interval(e[i].d + 2.0, e[i].d + 6.0);
      if (std::any_of(e.begin(), e.end(), [](const Entry& x) { return x.prismatic; })) {
        const std::uint64_t chart = f.chart_for(wide);
        const Box natural = f.output_to_natural(chart, wide);
        for (int i = 0; i < n; ++i)
          if (e[i].prismatic) {
            CHECK_FALSE(chart >> i & 1);
            CHECK((natural[i].lower() == wide[i].lower() && natural[i].upper() == wide[i].upper()));
          }
      }
      // Not vacuous: moving one primary variable breaks some equation.
      if (sub.lph->primary.empty()) continue;  // e.g. a 3R loop: the ground fixes everything
      Box moved = box;
      moved[sub.lph->primary[0]] += Interval(0.01);
      bool broken = false;
      for (auto& p : sub.system.equations) broken = broken || !zero_in(p.eval(moved));
      CHECK(broken);
    }
  }
}

TEST_CASE("rigorous atan2 encloses the angle, and the whole circle across its cut", "[linkage]") {
  const double pi = M_PI;
  CHECK(contains(rigorous::atan2(Interval(1.0), Interval(1.0)), pi / 4));
  CHECK(contains(rigorous::atan2(Interval(1.0), Interval(0.0)), pi / 2));
  CHECK(contains(rigorous::atan2(Interval(-1.0), Interval(-1.0)), -3 * pi / 4));
  const Interval near_zero = rigorous::atan2(Interval(-1e-9, 1e-9), Interval(1.0));
  CHECK(width(near_zero) < 1e-8);
  CHECK(zero_in(near_zero));
  // Across the negative x axis atan2 jumps: the enclosure is [-pi, pi].
  const Interval cut = rigorous::atan2(Interval(-1e-9, 1e-9), Interval(-1.0));
  CHECK(cut.lower() <= -pi);
  CHECK(cut.upper() >= pi);
}

TEST_CASE("two loops sharing a joint, tied by angle constraints", "[linkage]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    const int n1 = 4 + trial % 3, n2 = 3 + trial % 4;
    // Lines 0..n1-1: loop 1; loop 2 runs through line 0 and lines n1..n1+n2-2.
    const auto lines = random_lines(rng, n1 + n2 - 1, 0.3);
    std::vector<int> idx1(n1), idx2{0};
    std::iota(idx1.begin(), idx1.end(), 0);
    for (int i = 0; i < n2 - 1; ++i) idx2.push_back(n1 + i);
    auto e1 = measure_loop(lines, idx1, rng), e2 = measure_loop(lines, idx2, rng);
    for (int i = 0; i < n1; ++i) e1[i].joint = "J" + std::to_string(i), e1[i].link = "L" + std::to_string(i);
    for (int i = 0; i < n2; ++i) e2[i].joint = "K" + std::to_string(i), e2[i].link = "M" + std::to_string(i);
    // The shared joint joins the same links in both loops (the bridgehead atoms).
    e2[0].joint = e1[0].joint;
    e2[0].link = e1[0].link;
    e2[n2 - 1].link = e1[n1 - 1].link;
    const size_t g = std::uniform_int_distribution<size_t>(0, n1 - 1)(rng);

    LinkageCase c;
    c.file = "two-loops";
    c.ground = e1[g].link;
    c.loops.push_back(make_loop("one", e1, rng));
    c.loops.push_back(make_loop("two", e2, rng));
    auto tie = [&](const Entry& x, const Entry& y) {
      c.angle_constraints.push_back({"", x.joint, y.joint, around(std::acos(dot(x.axis, y.axis))), "", 3});
    };
    tie(e1[1], e2[1]);
    tie(e1[n1 - 1], e2[n2 - 1]);

    INFO("trial " << trial);
    const LinkageFormulation f(c);
    const SubProblem sub = f.subproblem(0);
    const Box box = model_point(f, {e1, e2}, ground_frame(e1, g), 1e-12);
    check_equations_hold(sub, box);

    const auto names = f.output_names();
    const Box out = f.to_output(0, box);
    // n1 + n2 - 1 joints, "J0@two", and the turn of loop two about J0 (the constraints see it).
    REQUIRE(names.size() == static_cast<size_t>(n1 + n2 + 1));
    std::map<std::string, double> expected;
    for (auto& x : e1) expected[x.joint] = x.theta;
    for (size_t i = 1; i < e2.size(); ++i) expected[e2[i].joint] = e2[i].theta;
    expected["J0@two"] = e2[0].theta;
    const V3 &from = e1[n1 - 1].normal, &to = e2[n2 - 1].normal, &axis = e1[0].axis;
    expected["turn[" + e1[n1 - 1].link + "@two]"] = std::atan2(dot(cross(from, to), axis), dot(from, to));
    for (size_t k = 0; k < names.size(); ++k) {
      INFO(names[k]);
      REQUIRE(expected.count(names[k]));
      CHECK(angle_in(out[k], expected[names[k]]));
    }
    check_natural_system_holds(f, out);
  }
}

TEST_CASE("cyclohexane chairs satisfy the bundled case's equations", "[linkage]") {
  const LinkageFormulation f(load_file(case_path("cyclohexane.toml")));
  const auto& loop = f.linkage_case().loops.at(0);
  const double alpha = median(loop.links[0].alpha), bond = median(loop.links[0].d);
  CHECK(alpha == 1.23);
  // Chair: torsions +-(w, -w, w, -w, w, -w), cos w = cos(alpha) / (1 - cos(alpha)) (from the
  // three-fold symmetry of the ring: bond angle pi - alpha at every atom).
  const double w = std::acos(std::cos(alpha) / (1 - std::cos(alpha)));
  CHECK(w == Approx(1.0449).margin(1e-4));
  for (double sign : {1.0, -1.0}) {
    // Forward kinematics from the ground frame (link c1, the last entry): the chair closes.
    std::vector<Entry> e(6);
    Frame fr;
    for (int i = 0; i < 6; ++i) {
      e[i].joint = loop.links[i].joint;
      e[i].link = loop.links[i].link;
      e[i].theta = sign * (i % 2 ? -w : w);
      e[i].axis = column(fr.r, 2);
      fr = compose(fr, dh(e[i].theta, bond, 0.0, alpha));
      e[i].normal = column(fr.r, 0);
      e[i].d = bond;
      e[i].alpha = alpha;
    }
    CHECK(norm(fr.p) < 1e-12);
    CHECK(norm(column(fr.r, 0) - V3{1, 0, 0}) < 1e-12);
    CHECK(norm(column(fr.r, 2) - V3{0, 0, 1}) < 1e-12);
    const M3 identity{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const Box box = model_point(f, {e}, identity, 1e-12);
    check_equations_hold(f.subproblem(0), box);
    const Box out = f.to_output(0, box);
    for (int i = 0; i < 6; ++i) CHECK(angle_in(out[i], e[i].theta));

    // A twisted ring (w off by 0.01) does not close: some equation excludes 0.
    Frame bad;
    std::vector<Entry> b = e;
    for (int i = 0; i < 6; ++i) {
      b[i].axis = column(bad.r, 2);
      bad = compose(bad, dh(sign * (i % 2 ? -w : w + 0.01), bond, 0.0, alpha));
      b[i].normal = column(bad.r, 0);
    }
    const SubProblem sub = f.subproblem(0);
    const Box far = model_point(f, {b}, identity, 1e-12, false);
    bool broken = false;
    for (auto& p : sub.system.equations) broken = broken || !zero_in(p.eval(far));
    CHECK(broken);
  }
}

TEST_CASE("bundled linkage cases parse, with the model sizes reported", "[linkage]") {
  const LinkageCase rigid = load_file(case_path("6r-rigid.toml"));
  CHECK(rigid.name == "6r-rigid");
  CHECK(rigid.ground == "L6");
  REQUIRE(rigid.loops.size() == 1);
  REQUIRE(rigid.loops[0].links.size() == 6);
  CHECK(rigid.loops[0].links[0].joint == "theta1");
  // 0.0175 is enclosed as the decimal, and pi/2 rigorously.
  const Interval twist = rigid.loops[0].links[1].alpha;
  CHECK(twist.lower() <= 0.0175);
  CHECK(0.0175 <= twist.upper());
  CHECK(width(twist) > 0);
  CHECK(contains(rigid.loops[0].links[0].alpha, M_PI / 2));
  CHECK(contains(rigid.loops[0].links[5].a, 1.1353));

  struct Expected {
    const char* file;
    ModelSize size, paper_model;  // default model, keep_free_normals
    size_t outputs;
  };
  const Expected cases[] = {
      // The paper's rigid 6R: 23 primary + 44 dummy; 28 L, 21 P, 23 H. Mobile 6R: 22 + 29.
      {"6r-rigid.toml", {16, 31, 19, 16, 15}, {19, 40, 24, 19, 21}, 6},
      {"6r-mobile.toml", {13, 24, 15, 13, 11}, {19, 40, 24, 19, 21}, 6},
      {"cyclohexane.toml", {10, 18, 10, 10, 8}, {19, 40, 24, 19, 21}, 6},
      // 11 bonds + c1-c2@ring2 + turn[c1@ring2]
      {"bicyclohexane.toml", {22, 41, 23, 22, 19}, {43, 93, 55, 43, 50}, 13},
  };
  for (auto& x : cases) {
    const LinkageCase c = load_file(case_path(x.file));
    const LinkageFormulation f(c), paper(c, {true});
    INFO(x.file << ": " << f.model_size() << " (keeping free normals: " << paper.model_size() << ")");
    CHECK(f.model_size() == x.size);
    CHECK(paper.model_size() == x.paper_model);
    CHECK(f.output_names().size() == x.outputs);
    CHECK(f.outputs_are_angles());
    CHECK(f.kind() == "linkage");
    CHECK(f.subproblem_count() == 1);
  }
}

// Each file's first line reads "# expect <line>: <part of the message>".
TEST_CASE("malformed linkage files are rejected at the offending line", "[linkage]") {
  const std::filesystem::path dir = std::string(LINKBOX_SOURCE_DIR) + "/tests/data/bad_linkage";
  int files = 0;
  for (auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const std::string path = entry.path().string();
    std::ifstream in(path);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string first = text.substr(0, text.find('\n'));
    INFO(path << "\n" << first);
    REQUIRE(first.rfind("# expect ", 0) == 0);
    const size_t colon = first.find(':');
    const int line = std::stoi(first.substr(9, colon - 9));
    const std::string fragment = first.substr(colon + 2);
    try {
      const toml::table root = toml::parse(text, path);
      formulate::LinkageFormulation(input::read_linkage(root, path, text));
      FAIL("accepted");
    } catch (const input::InputError& e) {
      INFO(e.what());
      CHECK(e.line == line);
      CHECK(e.message.find(fragment) != std::string::npos);
      CHECK(std::string(e.what()).rfind(path + ":" + std::to_string(line) + ": ", 0) == 0);
    }
  }
  CHECK(files >= 12);
}

namespace {

Frame about_z(double angle) { return dh(angle, 0, 0, 0); }

// A solve result holding one solution box, as the search would report it (marked incomplete:
// no search ran).
solve::CaseResult one_box(const formulate::Formulation& f, const Box& box) {
  solve::CaseResult r;
  r.subproblems.resize(1);
  r.subproblems[0].solutions.push_back(box);
  r.subproblems[0].residuals.push_back(model::residual_bound(f.subproblem(0).system.equations, box));
  r.complete = false;
  r.stop_reason = "test";
  return r;
}

// The JSON of a verified result, and `linkbox check` on it.
nlohmann::json result_json(const LinkageFormulation& f, const solve::CaseResult& r, const verify::VerifyReport& v) {
  nlohmann::json j = report::result_json("test", "test.toml", f, solve::RunOptions{}, r);
  report::add_verification(j, f, v);
  return j;
}
verify::CheckOutcome check_json(const LinkageFormulation& f, const solve::CaseResult& r, const verify::VerifyReport& v) {
  return verify::check_certificates(result_json(f, r, v), f);
}

// Bicyclohexane with both rings in the chair s (w, -w, w, -w, w, -w) and ring 2 turned by
// `turn` about c1-c2 (then ring 2's angle at c1-c2 equals ring 1's): the axes and normals of
// both rings, and the outputs in the formulation's order (ring 1, ring 2 from c2-c7,
// c1-c2@ring2, the turn).
struct Decalin {
  std::vector<Entry> ring1, ring2;
  Box outputs;
};
Decalin decalin(const LinkageFormulation& f, double sign, double turn, double twist = 0) {
  const double alpha = 1.23;
  const double w = std::acos(std::cos(alpha) / (1 - std::cos(alpha)));
  std::vector<double> theta1, theta2;
  for (int i = 0; i < 6; ++i) theta1.push_back(sign * (i % 2 ? -w : w));
  theta2 = theta1;
  theta2[3] += twist;
  const auto& loops = f.linkage_case().loops;
  Decalin d;
  d.ring1 = place_loop(loops[0], theta1, Frame{});
  d.ring2 = place_loop(loops[1], theta2, about_z(turn), twist == 0);
  for (double t : theta1) d.outputs.push_back(Interval(t));
  for (int i = 1; i < 6; ++i) d.outputs.push_back(Interval(theta2[i]));
  d.outputs.push_back(Interval(theta2[0]));
  d.outputs.push_back(Interval(turn));
  for (auto& x : d.outputs) x = Interval(x.lower() - 1e-12, x.upper() + 1e-12);
  return d;
}

const M3 identity{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

}  // namespace

TEST_CASE("bicyclohexane: 14 natural equations in 13 unknowns, holding at the chair-chair poses", "[linkage][natural]") {
  const LinkageFormulation f(load_file(case_path("bicyclohexane.toml")));
  const NaturalSystem s = f.natural_system(0);
  CHECK(s.equations.size() == 14);  // two ring closures (6 each), two bridgehead constraints
  REQUIRE(s.unknowns.size() == 13);
  CHECK(s.unknowns[11] == "t_c1-c2@ring2");
  CHECK(s.unknowns[12] == "t_turn[c1@ring2]");
  CHECK(s.missing.empty());
  // The bridgehead constraint at c1 fixes the turn: cos(beta) = cos^2(alpha) + sin^2(alpha) cos(turn).
  const double alpha = 1.23, beta = 1.91;
  const double phi = std::acos((std::cos(beta) - std::cos(alpha) * std::cos(alpha)) / std::pow(std::sin(alpha), 2));
  for (double sign : {1.0, -1.0})
    for (double turn : {phi, -phi}) {
      INFO("chair " << sign << " turn " << turn);
      const Decalin d = decalin(f, sign, turn);
      check_natural_system_holds(f, d.outputs);
      // The search model holds there too and reports the same outputs, turn included.
      const Box box = model_point(f, {d.ring1, d.ring2}, identity, 1e-12);
      check_equations_hold(f.subproblem(0), box);
      const Box out = f.to_output(0, box);
      REQUIRE(out.size() == d.outputs.size());
      for (size_t i = 0; i < out.size(); ++i) CHECK(angle_in(out[i], median(d.outputs[i])));
    }
}

TEST_CASE("bicyclohexane clusters: a chair-chair pose is certified through its twin rings, a twisted one is empty",
          "[linkage][natural]") {
  const LinkageFormulation f(load_file(case_path("bicyclohexane.toml")));
  const double alpha = 1.23, beta = 1.91;
  const double phi = std::acos((std::cos(beta) - std::cos(alpha) * std::cos(alpha)) / std::pow(std::sin(alpha), 2));
  const Decalin d = decalin(f, 1, -phi);
  const auto r = one_box(f, model_point(f, {d.ring1, d.ring2}, identity, 1e-9));
  const verify::VerifyReport v = verify::verify_case(f, r);
  REQUIRE(v.clusters.size() == 1);
  const verify::ClusterReport& c = v.clusters[0];
  INFO(c.reason);
  // 13 of the 14 equations have a unique root in the box; the 14th holds there because the
  // two rings are one chair (verify/twin_loops.hpp).
  CHECK(c.status == verify::ClusterStatus::certified);
  CHECK(c.argument == "coupled loops");
  CHECK(c.reason.find("'bridgehead c2' and 'bridgehead c1'") != std::string::npos);
  CHECK(v.certified_roots == 1);
  REQUIRE(c.subsystem.size() == 13);
  std::vector<model::Polynomial> square;
  for (int k : c.subsystem) square.push_back(f.natural_system(c.chart).equations[k]);
  CHECK(newton::recheck(square, c.certificate));
  const nlohmann::json j = result_json(f, r, v);
  const auto checked = verify::check_certificates(j, f);
  CHECK(checked.failures.empty());
  CHECK(checked.checked == 1);
  // What check re-runs is what was recorded: another subsystem, or the cluster called empty
  // by an equation that contains 0 there, fail.
  nlohmann::json other = j;
  other["clusters"][0]["subsystem"][0] = 13;
  const auto other_failures = verify::check_certificates(other, f).failures;
  REQUIRE_FALSE(other_failures.empty());
  CHECK(other_failures[0] == "cluster 0: the proof of its root through its loops does not hold");
  nlohmann::json claimed_empty = j;
  claimed_empty["clusters"][0]["status"] = "empty";
  claimed_empty["clusters"][0]["excluding_equation"] = 0;
  // The false proof fails, and so do the counts and headline recomputed from it.
  const auto failures = verify::check_certificates(claimed_empty, f).failures;
  REQUIRE_FALSE(failures.empty());
  CHECK(failures[0] == "cluster 0: the proof that this cluster holds no root does not hold");

  // One torsion of ring 2 off by 0.01: ring 2 no longer closes, the cluster around it is
  // proved to hold no root.
  const Decalin bad = decalin(f, 1, -phi, 0.01);
  const auto far = one_box(f, model_point(f, {bad.ring1, bad.ring2}, identity, 1e-9, false));
  const verify::VerifyReport w = verify::verify_case(f, far);
  REQUIRE(w.clusters.size() == 1);
  INFO(w.clusters[0].reason);
  CHECK(w.clusters[0].status == verify::ClusterStatus::empty);
  CHECK(w.empty == 1);
  const auto checked_far = check_json(f, far, w);
  CHECK(checked_far.failures.empty());
  CHECK(checked_far.checked == 1);

  // A box the search kept (--sigma 0.1 --rho 0.95 --prune lp) next to a chair-boat root:
  // every natural equation contains 0 on it, a square subsystem's Newton image misses it.
  const Box kept = test::read_box_file("bicyclohexane-empty-box.txt");
  REQUIRE(kept.size() == f.subproblem(0).system.variables.size());
  const auto spurious = one_box(f, kept);
  const verify::VerifyReport x = verify::verify_case(f, spurious);
  REQUIRE(x.clusters.size() == 1);
  INFO(x.clusters[0].reason);
  CHECK(x.clusters[0].status == verify::ClusterStatus::empty);
  CHECK(x.clusters[0].subsystem.size() == 13);
  CHECK(x.clusters[0].excluding_equation == -1);
  CHECK(check_json(f, spurious, x).failures.empty());
}

namespace {
// "#   <key> = (x, y, ...)" or "#   <key> = x" in a case file's comments.
std::vector<double> planted(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find(key + " = ");
    if (line.rfind("#", 0) != 0 || at == std::string::npos) continue;
    std::string list = line.substr(at + key.size() + 3);
    for (char& ch : list)
      if (ch == '(' || ch == ')' || ch == ',') ch = ' ';
    std::istringstream values(list);
    std::vector<double> out;
    for (double x; values >> x;) out.push_back(x);
    return out;
  }
  FAIL("no planted " << key << " in " << file);
  return {};
}
}  // namespace

TEST_CASE("two rings (6R + 7R, cases/linkages/rings-6-7.toml): square natural system, the planted pose certified",
          "[linkage][natural]") {
  const std::string file = case_path("rings-6-7.toml");
  const LinkageFormulation f(load_file(file));
  const std::vector<double> theta1 = planted(file, "ring1 theta"), theta2 = planted(file, "ring2 theta"),
                            turn = planted(file, "turn[A@ring2]");
  REQUIRE(theta1.size() == 6);
  REQUIRE(theta2.size() == 7);
  REQUIRE(turn.size() == 1);
  const NaturalSystem s = f.natural_system(0);
  CHECK(s.equations.size() == 14);
  CHECK(s.unknowns.size() == 14);
  CHECK(f.output_names().back() == "turn[A@ring2]");

  Box planted_out;
  for (double t : theta1) planted_out.push_back(Interval(t - 1e-12, t + 1e-12));
  for (size_t i = 1; i < 7; ++i) planted_out.push_back(Interval(theta2[i] - 1e-12, theta2[i] + 1e-12));
  for (double t : {theta2[0], turn[0]}) planted_out.push_back(Interval(t - 1e-12, t + 1e-12));
  check_natural_system_holds(f, planted_out);

  // A solution box around the planted pose, as the search would find it: certified in the
  // natural system through both loop blocks and the constraints between them.
  const auto& loops = f.linkage_case().loops;
  const auto ring1 = place_loop(loops[0], theta1, Frame{}), ring2 = place_loop(loops[1], theta2, about_z(turn[0]));
  const auto r = one_box(f, model_point(f, {ring1, ring2}, identity, 1e-6));
  const verify::VerifyReport v = verify::verify_case(f, r);
  REQUIRE(v.clusters.size() == 1);
  const verify::ClusterReport& c = v.clusters[0];
  INFO(c.reason);
  REQUIRE(c.status == verify::ClusterStatus::certified);
  CHECK(v.certified_roots == 1);
  CHECK_FALSE(v.exact);  // no search ran
  for (size_t i = 0; i < planted_out.size(); ++i) {
    CHECK(angle_in(c.root[i], median(planted_out[i])));
    CHECK(width(c.root[i]) < 1e-9);
  }
  CHECK(newton::recheck(f.natural_system(c.chart).equations, c.certificate));
  const auto checked = check_json(f, r, v);
  CHECK(checked.failures.empty());
  CHECK(checked.checked == 1);
}

TEST_CASE("loop patterns without a natural system say why, and verification reports it", "[linkage][natural]") {
  std::mt19937 rng(3);
  const auto lines = random_lines(rng, 10, 0.0);
  auto name = [](std::vector<Entry>& e, const std::string& joint, const std::string& link) {
    for (size_t i = 0; i < e.size(); ++i) e[i].joint = joint + std::to_string(i), e[i].link = link + std::to_string(i);
  };
  SECTION("a loop sharing two joints with the loop before it") {
    // Loop two runs through lines 0 and 1 like loop one: joints J0, J1 and links L5 -> L0 -> L1.
    auto e1 = measure_loop(lines, {0, 1, 2, 3, 4, 5}, rng), e2 = measure_loop(lines, {0, 1, 6, 7, 8}, rng);
    name(e1, "J", "L");
    name(e2, "K", "M");
    e2[0].joint = "J0", e2[1].joint = "J1";
    e2[0].link = "L0", e2[1].link = "L1", e2[4].link = "L5";
    if (e2[0].alpha != e1[0].alpha) {
      // Link L0 is one normal for both loops: measured with the other sign here, flip it
      // (a, alpha and the normal change sign, the angles on both sides of it turn by pi).
      e2[0].a = -e2[0].a, e2[0].alpha = -e2[0].alpha, e2[0].normal = -1.0 * e2[0].normal;
      e2[0].theta = std::remainder(e2[0].theta + M_PI, 2 * M_PI);
      e2[1].theta = std::remainder(e2[1].theta + M_PI, 2 * M_PI);
    }
    LinkageCase c;
    c.file = "shared-path";
    c.ground = "L3";
    c.loops.push_back(make_loop("one", e1, rng));
    c.loops.push_back(make_loop("two", e2, rng));
    const LinkageFormulation f(c);
    const NaturalSystem s = f.natural_system(0);
    CHECK(s.equations.empty());
    CHECK(s.missing == "loop 'two' shares 2 joints ('J0', 'J1') with the loops placed before it; only one shared "
                       "joint per loop is supported");
    const Box box = model_point(f, {e1, e2}, ground_frame(e1, 3), 1e-9);
    check_equations_hold(f.subproblem(0), box);
    const verify::VerifyReport v = verify::verify_case(f, one_box(f, box));
    REQUIRE(v.clusters.size() == 1);
    CHECK(v.clusters[0].status == verify::ClusterStatus::unverified);
    CHECK(v.clusters[0].reason == "no natural system to certify in: " + s.missing);
  }
  SECTION("a loop tied to the others by an angle constraint only") {
    auto e1 = measure_loop(lines, {0, 1, 2, 3}, rng), e2 = measure_loop(lines, {4, 5, 6, 7}, rng);
    name(e1, "J", "L");
    name(e2, "K", "M");
    LinkageCase c;
    c.file = "tied";
    c.ground = "L0";
    c.loops.push_back(make_loop("one", e1, rng));
    c.loops.push_back(make_loop("two", e2, rng));
    c.angle_constraints.push_back({"", "J1", "K2", around(std::acos(dot(e1[1].axis, e2[2].axis))), "", 3});
    const LinkageFormulation f(c);
    CHECK(f.natural_system(0).missing.find("loop 'two' shares no joint with the loops placed before it") == 0);
    CHECK(f.chart_for(Box(f.output_names().size(), Interval(3.0))) == 0);
  }
}
