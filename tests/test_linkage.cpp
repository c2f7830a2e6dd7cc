// The linkage vector model (iterated-LP paper, Section II) against configurations built
// independently: random closed loops from random joint axes (DH parameters measured from the
// geometry, cross-checked by DH forward kinematics), the cyclohexane chair, the bundled cases
// and the malformed files of tests/data/bad_linkage.
#include "formulate/linkage.hpp"
#include "formulate/to_lph.hpp"
#include "interval/rigorous.hpp"
#include "io/linkage_file.hpp"
#include "io/toml_reader.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <random>

using namespace linkbox;
using namespace linkbox::formulate;

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

formulate::LinkageCase load_file(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const toml::table root = toml::parse(text, path);
  return io::load_linkage(root, path, text);
}

std::string case_path(const std::string& name) { return std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/" + name; }

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
      c.angle_constraints.push_back({"", x.joint, y.joint, around(std::acos(dot(x.axis, y.axis))), 3});
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
    REQUIRE(names.size() == static_cast<size_t>(n1 + n2));  // n1 + n2 - 1 joints + "J0@two"
    std::map<std::string, double> expected;
    for (auto& x : e1) expected[x.joint] = x.theta;
    for (size_t i = 1; i < e2.size(); ++i) expected[e2[i].joint] = e2[i].theta;
    expected["J0@two"] = e2[0].theta;
    for (size_t k = 0; k < names.size(); ++k) {
      INFO(names[k]);
      REQUIRE(expected.count(names[k]));
      CHECK(angle_in(out[k], expected[names[k]]));
    }
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
      {"bicyclohexane.toml", {22, 41, 23, 22, 19}, {43, 93, 55, 43, 50}, 12},  // 11 bonds + c1-c2@ring2
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
      const io::TomlReader reader(path, text);
      io::linkage_formulation(root, reader);
      FAIL("accepted");
    } catch (const io::CaseError& e) {
      INFO(e.what());
      CHECK(e.line == line);
      CHECK(e.message.find(fragment) != std::string::npos);
      CHECK(std::string(e.what()).rfind(path + ":" + std::to_string(line) + ": ", 0) == 0);
    }
  }
  CHECK(files >= 12);
}
