// The angles of a raw system: which variables are angles, the unit each is modelled in,
// sin and cos of every argument expanded into the angles' cos and sin, and each angle's chart.
#include "model/lifter.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>

namespace linkbox::model::detail {

namespace {

using Function = Application::Function;

// A multiple k of an angle's unit in one argument: cos(k u) has degree |k|.
constexpr double kMaxMultiple = 64;

bool is_trig(Function f) { return f == Function::sin || f == Function::cos || f == Function::tan; }

// p with every y^e replaced by y^(e mod 2) (1 - x^2)^(e div 2): the same polynomial on the
// circle x^2 + y^2 = 1, of degree at most 1 in y.
Polynomial reduce(const Polynomial& p, int x, int y) {
  Polynomial r;
  for (auto& [powers, c] : p.terms()) {
    Powers rest;
    int e = 0;
    for (auto [v, k] : powers) {
      if (v == y) e = k;
      else rest.emplace_back(v, k);
    }
    Polynomial t = Polynomial::monomial(rest, c);
    if (e % 2) t = t * Polynomial::variable(y);
    if (e / 2) t = t * (one() - Polynomial::variable(x).pow(2)).pow(e / 2);
    r += t;
  }
  return r;
}

bool occurs(const Polynomial& p, int v) {
  for (int u : p.variables())
    if (u == v) return true;
  return false;
}

}  // namespace

bool Lifter::is_angle_use(int k) const { return is_trig(raw_.applications[k].function) && !linked_[k]; }

// The sin, cos and tan that are links (lifting.hpp): those whose argument is not affine in the
// declared variables or has a variable that also occurs outside sin, cos and tan (in an
// equation, an inequality, another function's argument or a linked one's), to a fixpoint.
// A case whose trigonometric functions all take angles has none.
void Lifter::find_linked() {
  const int count = static_cast<int>(raw_.applications.size());
  linked_.assign(count, false);
  std::vector<bool> outside(n_, false);
  bool changed = true;
  auto mark = [&](const Polynomial& p) {
    for (int v : p.variables())
      if (v < n_ && !outside[v]) outside[v] = changed = true;
  };
  for (auto& e : raw_.equations) mark(e);
  for (auto& c : raw_.inequalities) mark(c.g);
  while (changed) {
    changed = false;
    for (int k = 0; k < count; ++k) {
      const Application& a = raw_.applications[k];
      if (!is_trig(a.function) || linked_[k]) {
        mark(a.argument);
        mark(a.second);
        continue;
      }
      bool link = a.argument.total_degree() > 1;
      for (int v : a.argument.variables()) link = link || v >= n_ || outside[v];
      if (link) linked_[k] = changed = true;
    }
  }
}

// Variables inside sin, cos and tan are angles; they may occur nowhere else.
void Lifter::find_angles() {
  find_linked();
  angle_of_.assign(n_, -1);
  for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k) {
    const Application& a = raw_.applications[k];
    if (!is_angle_use(k)) continue;
    if (a.argument.total_degree() > 1)
      fail_application(k, text(k) + ": the argument of " + to_string(a.function) +
                              " must be affine in the variables (a*t + b)");
    for (int v : a.argument.variables()) {
      if (v >= n_)
        fail_application(k, text(k) + ": the argument of " + to_string(a.function) +
                                " contains a function of the variables; it must be affine in them (a*t + b)");
      if (angle_of_[v] < 0) {
        angle_of_[v] = static_cast<int>(angles_.size());
        angles_.push_back({});
        angles_.back().angle.variable = v;
      }
      auto& uses = angles_[angle_of_[v]].applications;
      if (uses.empty() || uses.back() != k) uses.push_back(k);
    }
  }
  auto only_inside = [&](const Polynomial& p, const std::string& where) {
    for (int v : p.variables())
      if (v < n_ && angle_of_[v] >= 0)
        fail_variable(v, "variable '" + name(v) + "' is used inside " + text(angles_[angle_of_[v]].applications[0]) +
                             " and outside sin, cos and tan (in " + where + ")");
  };
  for (size_t i = 0; i < raw_.equations.size(); ++i) only_inside(raw_.equations[i], "equation " + std::to_string(i + 1));
  for (auto& c : raw_.inequalities) only_inside(c.g, "\"" + c.name + "\"");
  for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k)
    if (!is_angle_use(k)) {
      only_inside(raw_.applications[k].argument, text(k));
      only_inside(raw_.applications[k].second, text(k));
    }
}

// The coefficient of v in an affine argument.
Interval Lifter::coefficient(const Polynomial& arg, int v) {
  auto it = arg.terms().find(Powers{{v, 1}});
  return it == arg.terms().end() ? Interval(0.0) : it->second;
}

// The unit w > 0 of angle j: every coefficient of its variable is an integer multiple k of
// it (exactly: k * w equals the coefficient's bounds), so cos(k u) is a polynomial in
// cos(u), sin(u). The largest such w of the form (smallest coefficient) / d, d = 1, 2, ...:
// 2 and 3 give 1, 1/2 and 3/4 give 1/4. A coefficient that is not a double (1/3) can only
// be the unit, used alone or with exactly equal ones.
void Lifter::choose_unit(size_t j) {
  AngleUse& use = angles_[j];
  const int v = use.angle.variable;
  Interval smallest;
  double least = kInf;
  for (int k : use.applications) {
    const Interval a = coefficient(raw_.applications[k].argument, v);
    if (zero_in(a)) fail_application(k, text(k) + ": the coefficient of '" + name(v) + "' may be 0");
    const double m = std::min(std::fabs(a.lower()), std::fabs(a.upper()));
    if (m < least) least = m, smallest = a.lower() > 0 ? a : -a;
  }
  bool found = false;
  for (int d = 1; d <= kMaxMultiple && !found; ++d) {
    const Interval unit = d == 1 ? smallest : smallest / Interval(static_cast<double>(d));
    if (d > 1 && unit.lower() != unit.upper()) break;
    found = true;
    for (int k : use.applications)
      found = found && multiple_of(coefficient(raw_.applications[k].argument, v), unit) != 0;
    if (found) use.angle.unit = unit;
  }
  if (!found) {
    std::string list;
    for (int k : use.applications) list += (list.empty() ? "" : ", ") + format(median(coefficient(raw_.applications[k].argument, v)));
    fail_application(use.applications.back(),
                     text(use.applications.back()) + ": the coefficients of '" + name(v) +
                         "' in sin, cos and tan must be integer multiples of one unit, exactly, and at most " +
                         format(kMaxMultiple) + " times it (here " + list + ")");
  }
  const Interval unit = use.angle.unit;
  use.angle.domain = unit * raw_.variables[v].domain;
  const Interval width = Interval(use.angle.domain.upper()) - Interval(use.angle.domain.lower());
  const Interval turn = Interval(2.0) * rigorous::pi();
  if (width.lower() > turn.upper())
    fail_variable(v, "the domain of angle '" + name(v) + "' spans more than a full turn (" +
                         (same_bounds(unit, Interval(1.0)) ? "2*pi" : "2*pi / " + format(median(unit))) +
                         "): its roots are found from cos and sin, which repeat every turn, so give it a domain of at "
                         "most a full turn, e.g. [-pi, pi]");
  use.angle.full_turn = width.upper() >= turn.lower();
  use.angle.centre = median(use.angle.domain);
  use.angle.cos_centre = rigorous::cos(Interval(use.angle.centre));
  use.angle.sin_centre = rigorous::sin(Interval(use.angle.centre));
}

// The integer k with a = k * unit exactly (0: none, or |k| above kMaxMultiple).
long Lifter::multiple_of(const Interval& a, const Interval& unit) {
  if (same_bounds(a, unit)) return 1;
  if (same_bounds(a, -unit)) return -1;
  const double q = std::round(median(a) / median(unit));
  if (unit.lower() != unit.upper() || q == 0 || std::fabs(q) > kMaxMultiple) return 0;
  return same_bounds(Interval(q) * unit, a) ? static_cast<long>(q) : 0;
}

// tan(a*t + b) as the angle's only use is modelled as itself; everything else is expanded
// into polynomials in symbols cos(u_j) = 2j, sin(u_j) = 2j + 1.
void Lifter::expand() {
  expansions_.assign(raw_.applications.size(), {});
  for (size_t j = 0; j < angles_.size(); ++j) {
    AngleUse& use = angles_[j];
    if (use.applications.size() != 1) continue;
    const int k = use.applications[0];
    const Application& a = raw_.applications[k];
    if (a.function != Function::tan || a.argument.variables().size() != 1) continue;
    long branch;
    const Interval range = a.argument.eval(raw_domain());
    if (!within_tan_branch(range, branch)) fail_application(k, pole_message(k, range));
    use.angle.chart = Chart::tan_only;
    use.angle.sign = coefficient(a.argument, use.angle.variable).lower() > 0 ? 1 : -1;
    use.angle.offset = a.argument.constant_term();
    use.angle.branch = branch;
  }
  for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k) {
    const Application& a = raw_.applications[k];
    if (!is_angle_use(k)) continue;
    if (a.function == Function::tan && a.argument.variables().size() == 1 &&
        angles_[angle_of_[a.argument.variables()[0]]].angle.chart == Chart::tan_only)
      continue;
    const Interval b = a.argument.constant_term();
    Complex e{Polynomial::constant(rigorous::cos(b)), Polynomial::constant(rigorous::sin(b))};
    for (int v : a.argument.variables()) {
      const int j = angle_of_[v];
      const long m = multiple(v, coefficient(a.argument, v));
      const Polynomial c = Polynomial::variable(2 * j), s = Polynomial::variable(2 * j + 1);
      const Complex base{c, m > 0 ? s : -s};
      for (long i = 0; i < std::labs(m); ++i) e = e * base;
    }
    // Only what the function uses, so that cos(t) alone does not call for sin(t).
    if (a.function == Function::cos) e.im = Polynomial();
    if (a.function == Function::sin) e.re = Polynomial();
    expansions_[k] = e;
  }
}

// What angle j's uses need: c alone, s alone, or both on the circle.
void Lifter::choose_chart(size_t j) {
  Lifting::Angle& a = angles_[j].angle;
  if (a.chart == Chart::tan_only) return;
  const int c = 2 * static_cast<int>(j), s = c + 1;
  auto reduced = [&](int x, int y) {
    std::vector<Complex> r = expansions_;
    bool y_left = false;
    for (auto& e : r) {
      e.re = reduce(e.re, x, y);
      e.im = reduce(e.im, x, y);
      y_left = y_left || occurs(e.re, y) || occurs(e.im, y);
    }
    return std::make_pair(r, y_left);
  };
  const Interval pi = rigorous::pi(), half_pi = pi / Interval(2.0);
  long branch;
  auto [in_c, s_left] = reduced(c, s);
  if (!s_left && within_one(a.domain, Interval(0.0), pi, branch)) {
    a.chart = Chart::cos_only;
    a.branch = branch;
    expansions_ = std::move(in_c);
    return;
  }
  auto [in_s, c_left] = reduced(s, c);
  if (!c_left && within_one(a.domain, -half_pi, pi, branch)) {
    a.chart = Chart::sin_only;
    a.branch = branch;
    expansions_ = std::move(in_s);
    return;
  }
  a.chart = Chart::circle;
  expansions_ = std::move(in_c);
}

}  // namespace linkbox::model::detail
