// Builds the lifted system of a raw one from its angles (lifter_angles.cpp): the unknowns,
// the equations and inequalities, the record that maps back (Lifting) and its notes.
#include "model/lifter.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace linkbox::model {

namespace detail {

namespace {

// How far a circle unknown's bound of +-1 is moved out (see add_angle_unknowns).
constexpr double kCircleSlack = 0x1p-20;

// The domain of an unknown that stands for a function of the declared variables (a link's y
// or argument, a quotient), moved out by kCircleSlack relative to its size: its bounds are
// the function's extremes over the domain, which an interior root may reach (cosh(x - 1) = 1
// at x = 1), and a root on the boundary of the lifted domain is not certified in it. Moving
// them out adds no root: every root of the lifted system has these unknowns equal to their
// functions of declared variables, which lie within the bounds before the move.
Interval padded(const Interval& d) {
  const Interval slack = Interval(kCircleSlack) * (Interval(1.0) + Interval(std::max(-d.lower(), d.upper())));
  return Interval((Interval(d.lower()) - slack).lower(), (Interval(d.upper()) + slack).upper());
}

// The link of a sin, cos or tan whose argument is not an angle's (find_linked).
Elementary linked_trig(Application::Function f) {
  using F = Application::Function;
  return f == F::sin ? Elementary::sin : f == F::cos ? Elementary::cos : Elementary::tan;
}

}  // namespace

Polynomial one() { return Polynomial::constant(Interval(1.0)); }

std::string format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

bool within_one(const Interval& x, const Interval& shift, const Interval& period, long& k) {
  const Interval q = (x - shift) / period;
  if (!is_finite(q)) return false;
  const double lo = std::floor(q.lower());
  if (std::fabs(lo) > 1e15 || q.upper() > lo + 1) return false;
  k = static_cast<long>(lo);
  return true;
}

System Lifter::run() {
  find_angles();
  for (size_t j = 0; j < angles_.size(); ++j) choose_unit(j);
  expand();
  for (size_t j = 0; j < angles_.size(); ++j) choose_chart(j);
  build();
  return std::move(out_);
}

Box Lifter::raw_domain() const {
  Box b;
  for (auto& v : raw_.variables) b.push_back(v.domain);
  return b;
}

std::string Lifter::pole_message(int k, const Interval& range) const {
  return text(k) + ": its argument ranges over [" + format(range.lower()) + ", " + format(range.upper()) +
         "] on the domain, which meets a pole of tan (or cannot be shown not to); narrow the domain so that it "
         "stays within one branch (pi/2 + k pi excluded)";
}

void Lifter::build() {
  auto lifting = std::make_shared<Lifting>();
  lifting_ = lifting.get();
  lifting->declared = raw_.variables;
  lifting->applications = raw_.applications;
  symbol_.assign(2 * angles_.size(), Polynomial());
  image_.assign(n_ + raw_.applications.size(), Polynomial());
  done_.assign(raw_.applications.size(), false);
  find_cleared();
  lifting->cleared = cleared_;
  add_declared_unknowns();
  for (auto& use : angles_) lifting->angles.push_back(use.angle);
  add_application_unknowns();
  add_typed_constraints();
  add_angle_constraints();
  for (auto& d : definitions_) {
    out_.equations.push_back(std::move(d.first));
    out_.equation_names.push_back(std::move(d.second));
  }
  out_.lifting = std::move(lifting);
}

// Unknowns: each declared variable in place (an angle as its cos/sin or tan), then one per
// tan or sqrt that needs an equation (add_application_unknowns), in the order they were written.
void Lifter::add_declared_unknowns() {
  for (int v = 0; v < n_; ++v) {
    const int j = angle_of_[v];
    if (j < 0) {
      image_[v] = Polynomial::variable(static_cast<int>(out_.variables.size()));
      add_variable(name(v), raw_.variables[v].domain, {Lifting::Source::Kind::declared, v});
      continue;
    }
    add_angle_unknowns(j);
  }
}

void Lifter::add_angle_unknowns(int j) {
  Lifting::Angle& a = angles_[j].angle;
  const auto next = [&] { return static_cast<int>(out_.variables.size()); };
  if (a.chart == Chart::tan_only) {
    a.tan = next();
    const int k = angles_[j].applications[0];
    image_[n_ + k] = Polynomial::variable(a.tan);
    done_[k] = true;
    add_variable(text(k), rigorous::tan(raw_.applications[k].argument.eval(raw_domain())),
                 {Lifting::Source::Kind::tan_angle, j});
    return;
  }
  // On the circle a bound of +-1 binds nothing (c^2 + s^2 = 1 does), so it is moved out:
  // a root at cos = 1 inside the domain (t = 0 in [-1, 1]) is not on the box's boundary.
  // Without the circle equation (cos or sin alone) the bound is what keeps c real.
  const bool circle = a.chart == Chart::circle;
  auto range = [&](Interval r) {
    if (!circle) return r;
    if (a.full_turn) r = Interval(-1.0, 1.0);
    return Interval(r.lower() <= -1 ? -1 - kCircleSlack : r.lower(), r.upper() >= 1 ? 1 + kCircleSlack : r.upper());
  };
  if (a.chart != Chart::sin_only) {
    a.c = next();
    symbol_[2 * j] = Polynomial::variable(a.c);
    add_variable(angle_name(a, "cos"), range(rigorous::cos(a.domain)), {Lifting::Source::Kind::cos, j});
  }
  if (a.chart != Chart::cos_only) {
    a.s = next();
    symbol_[2 * j + 1] = Polynomial::variable(a.s);
    add_variable(angle_name(a, "sin"), range(rigorous::sin(a.domain)), {Lifting::Source::Kind::sin, j});
  }
}

// Applications in order: sin/cos of angles are their expansions; tan, sqrt, 1/B and links get
// an unknown each, except a 1/B whose divisor is cleared.
void Lifter::add_application_unknowns() {
  for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k) {
    const Application& a = raw_.applications[k];
    if (done_[k]) continue;  // a tan-only angle's unknown (add_angle_unknowns)
    if (cleared_[k]) {
      add_cleared_divisor(k);
      continue;
    }
    if (expanded_[k]) {
      image_[n_ + k] = substituted(a.argument, k);
      continue;
    }
    if (is_angle_use(k) && a.function != Function::tan) {
      const Polynomial e = substitute(a.function == Function::cos ? expansions_[k].re : expansions_[k].im, symbol_);
      if (e.total_degree() >= 2 && multiplied(k)) add_trig_unknown(k, e);
      else image_[n_ + k] = e;
      continue;
    }
    const int index = static_cast<int>(out_.variables.size());
    const Polynomial x = Polynomial::variable(index);
    image_[n_ + k] = x;
    Elementary f;
    if (a.function == Function::tan && !linked_[k]) add_tan_unknown(k, x);
    else if (a.function == Function::sqrt) add_sqrt_unknown(k, x);
    else if (a.function == Function::reciprocal) add_reciprocal_unknown(k, x);
    else if (a.function == Function::base) add_base_unknown(k, x);
    else if (a.function == Function::atan2) add_atan2_unknown(k, index);
    else if (link_function(a.function, f)) add_link_unknown(k, f, index);
    else add_link_unknown(k, linked_trig(a.function), index);
  }
}

// Whether application k's value is multiplied by an expression with variables, or raised to
// a power, in a typed constraint or an argument.
bool Lifter::multiplied(int k) const {
  const auto in = [v = n_ + k](const Polynomial& p) {
    for (auto& [powers, c] : p.terms()) {
      int degree = 0;
      bool has = false;
      for (auto [x, e] : powers) degree += e, has = has || x == v;
      if (has && degree >= 2) return true;
    }
    return false;
  };
  return std::any_of(raw_.equations.begin(), raw_.equations.end(), in) ||
         std::any_of(raw_.inequalities.begin(), raw_.inequalities.end(), [&](auto& q) { return in(q.g); }) ||
         std::any_of(raw_.applications.begin(), raw_.applications.end(),
                     [&](auto& a) { return in(a.argument) || in(a.second); });
}

// sin or cos of a multiple or a sum of angles that is multiplied: an unknown y with y - E = 0,
// E its expansion in the angles' cos and sin (lifting.hpp).
void Lifter::add_trig_unknown(int k, const Polynomial& expansion) {
  const Application& a = raw_.applications[k];
  const Polynomial y = Polynomial::variable(static_cast<int>(out_.variables.size()));
  add_variable(a.text, enclose(a, argument_range(k)), {Lifting::Source::Kind::application, k});
  definitions_.emplace_back(y - expansion, a.text + " as one unknown");
  image_[n_ + k] = y;
  lifting_->notes.push_back(a.text + " -> an unknown y with y = its expansion in cos and sin of the angles, "
                                     "where it is multiplied (not expanded in the products)");
}

void Lifter::add_tan_unknown(int k, const Polynomial& x) {
  const Application& a = raw_.applications[k];
  long branch;
  const Interval range = a.argument.eval(raw_domain());
  if (!within_tan_branch(range, branch)) fail_application(k, pole_message(k, range));
  add_variable(a.text, rigorous::tan(range), {Lifting::Source::Kind::application, k});
  definitions_.emplace_back(x * substitute(expansions_[k].re, symbol_) - substitute(expansions_[k].im, symbol_),
                            a.text + " * cos = sin");
  lifting_->notes.push_back(a.text + " -> an unknown t with t cos(...) = sin(...) (no pole in the domain)");
}

// The domain of r: [0, sqrt of the argument's upper bound over the domain].
void Lifter::add_sqrt_unknown(int k, const Polynomial& x) {
  const Application& a = raw_.applications[k];
  Interval range;
  try {
    range = argument_range(k);
    if (range.upper() < 0) throw std::domain_error("sqrt");
  } catch (const std::domain_error&) {
    fail_application(k, a.text + ": its argument is negative on the whole domain, so the square root is never "
                                 "real");
  }
  if (!is_finite(range)) fail_application(k, a.text + ": its argument is not bounded on the domain");
  add_variable(a.text, Interval(0.0, range.upper()), {Lifting::Source::Kind::application, k});
  definitions_.emplace_back(x.pow(2) - substituted(a.argument, k), a.text + "^2 = its argument");
  lifting_->notes.push_back(a.text + " -> an unknown r >= 0 with r^2 = its argument");
}

// q with q B = 1 (lifting.hpp says why the roots correspond one to one); its domain is
// 1/(range of B), bounded: a range that holds 0 or is unbounded is cleared (find_cleared).
void Lifter::add_reciprocal_unknown(int k, const Polynomial& x) {
  const Application& a = raw_.applications[k];
  Interval range;
  try {
    range = argument_range(k);
  } catch (const std::domain_error& e) {
    fail_application(k, a.text + ": the divisor is not defined on the domain (" + e.what() + ")");
  }
  add_variable(a.text, padded(Interval(1.0) / range), {Lifting::Source::Kind::application, k});
  definitions_.emplace_back(x * substituted(a.argument, k) - one(), a.text + " * divisor = 1");
  lifting_->notes.push_back(a.text + " -> an unknown q with q * divisor = 1 (the divisor is away from 0 on the domain)");
}

// b with b - A = 0; its domain is A's range over the domain.
void Lifter::add_base_unknown(int k, const Polynomial& x) {
  const Application& a = raw_.applications[k];
  add_variable(a.text, padded(argument_range(k)), {Lifting::Source::Kind::application, k});
  definitions_.emplace_back(x - substituted(a.argument, k), a.text + " as one unknown");
  lifting_->notes.push_back(a.text + " -> an unknown b with b = it, where it is raised to a power or multiplied (not expanded)");
}

// t = atan2(Y, X) with c = cos(t), s = sin(t), X s - Y c = 0 and X c + Y s > 0 (lifting.hpp
// says why these hold exactly at t = atan2(Y, X) and nowhere else, and when -pi < t <= pi is
// added). t is unknown `t`, added here, with c and s after it.
void Lifter::add_atan2_unknown(int k, int t) {
  const Application& a = raw_.applications[k];
  Interval range;
  try {
    range = enclose_over(a, values_before(k));
  } catch (const std::domain_error& e) {
    fail_application(k, a.text + ": not defined anywhere on the domain (" + e.what() + ")");
  }
  const Interval domain = padded(range);
  add_variable(a.text, domain, {Lifting::Source::Kind::application, k});
  const int c = static_cast<int>(out_.variables.size());
  add_variable("cos(" + a.text + ")", padded(rigorous::cos(range)), {Lifting::Source::Kind::angle_cos, k});
  add_variable("sin(" + a.text + ")", padded(rigorous::sin(range)), {Lifting::Source::Kind::angle_sin, k});
  out_.links.push_back({Elementary::cos, c, t, "cos(" + a.text + ")"});
  out_.links.push_back({Elementary::sin, c + 1, t, "sin(" + a.text + ")"});
  const Polynomial y = substituted(a.argument, k), x = substituted(a.second, k);
  const Polynomial cos_t = Polynomial::variable(c), sin_t = Polynomial::variable(c + 1);
  definitions_.emplace_back(x * sin_t - y * cos_t, a.text + ": (cos, sin) parallel to (x, y)");
  add_inequality(-(x * cos_t + y * sin_t), true, a.text + ": (cos, sin) along (x, y), not 0");
  std::string cut;
  if (domain.upper() - domain.lower() > 6.28) {  // may hold two points 2 pi apart
    const Polynomial pi = Polynomial::constant(rigorous::pi()), tp = Polynomial::variable(t);
    add_inequality(-tp - pi, true, a.text + " > -pi");
    add_inequality(tp - pi, false, a.text + " <= pi");
    cut = ", and -pi < t <= pi (its arguments' ranges cross the cut)";
  }
  lifting_->notes.push_back(a.text + " -> an unknown t with the links cos(t), sin(t), (cos t, sin t) parallel to "
                                     "(x, y) and pointing its way" + cut);
}

void Lifter::add_inequality(const Polynomial& g, bool strict, const std::string& name) {
  Inequality q;
  q.g = g;
  q.strict = strict;
  q.name = name;
  out_.inequalities.push_back(std::move(q));
}

// y = f(a): y is unknown `y` (added here), a the argument's unknown (argument_unknown).
void Lifter::add_link_unknown(int k, Elementary f, int y) {
  const Application& app = raw_.applications[k];
  Interval range, value;
  try {
    range = argument_range(k);
    long branch;
    if (f == Elementary::tan && !within_tan_branch(range, branch)) fail_application(k, pole_message(k, range));
    value = image(f, range);
  } catch (const std::domain_error&) {
    fail_application(k, app.text + ": its argument is outside the domain of " + to_string(f) +
                            " on the whole domain, so it is never defined");
  }
  if (!is_finite(range) || !is_finite(value))
    fail_application(k, app.text + ": its value is not bounded on the domain (the argument ranges over [" +
                            format(range.lower()) + ", " + format(range.upper()) +
                            "]); narrow the domain so that it is");
  add_variable(app.text, padded(value), {Lifting::Source::Kind::application, k});
  const int a = argument_unknown(k, f, range);
  out_.links.push_back({f, y, a, app.text});
  lifting_->notes.push_back(app.text + " -> an unknown y and the link y = " + to_string(f) +
                            "(its argument), enclosed through MPFI (not a polynomial equation)");
}

// The unknown standing for application k's argument A: A itself when it is one unknown, else
// a new one with the equation a - A = 0 and A's range within f's domain.
int Lifter::argument_unknown(int k, Elementary f, const Interval& range) {
  const Polynomial arg = substituted(raw_.applications[k].argument, k);
  if (arg.terms().size() == 1) {
    const auto& [powers, c] = *arg.terms().begin();
    if (powers.size() == 1 && powers[0].second == 1 && same_bounds(c, Interval(1.0))) return powers[0].first;
  }
  Interval domain = range;
  if (f == Elementary::log) intersect(range, Interval(0.0, kInf), domain);
  if (f == Elementary::asin || f == Elementary::acos || f == Elementary::atanh)
    intersect(range, Interval(-1.0, 1.0), domain);
  if (f == Elementary::acosh) intersect(range, Interval(1.0, kInf), domain);
  Interval box = padded(domain);
  long branch;
  if (f == Elementary::tan && !within_tan_branch(box, branch)) box = domain;  // the padding must not reach a pole
  const int a = static_cast<int>(out_.variables.size());
  const std::string& text = raw_.applications[k].text;
  add_variable("argument of " + text, box, {Lifting::Source::Kind::argument, k});
  definitions_.emplace_back(Polynomial::variable(a) - arg, "argument of " + text);
  return a;
}

// p with every application replaced by its image. Sums that are multiplied but never raised
// are expanded here, so the parser's bound on the terms of a product is enforced here too.
Polynomial Lifter::substituted(const Polynomial& p, int application, int equation, int inequality) const {
  constexpr double kMaxTerms = 1e6;
  double terms = 0;
  for (auto& [powers, c] : p.terms()) {
    double t = 1;
    for (auto [v, e] : powers) t *= std::pow(static_cast<double>(std::max<size_t>(image_[v].terms().size(), 1)), e);
    terms += t;
  }
  if (terms > kMaxTerms)
    throw LiftError("expands to more than 1000000 terms once its products of sums are multiplied out", -1,
                    application, equation, inequality);
  return substitute(p, image_);
}

// Equations and inequalities as typed (what defines the new unknowns comes last, in build).
void Lifter::add_typed_constraints() {
  const bool clearing = std::find(cleared_.begin(), cleared_.end(), true) != cleared_.end();
  const std::string once = clearing ? "once sin and cos are expanded and divisors cleared" : "once sin and cos are expanded";
  for (size_t i = 0; i < raw_.equations.size(); ++i) {
    Polynomial p = clear(substituted(raw_.equations[i], -1, static_cast<int>(i)), false, -1);
    if (p.is_constant())
      throw LiftError("equation " + std::to_string(i + 1) + " is constant " + once +
                          " (an identity such as sin(t)^2 + cos(t)^2 = 1, or a contradiction)",
                      -1, -1, static_cast<int>(i));
    out_.equations.push_back(std::move(p));
    out_.equation_names.push_back(i < raw_.equation_names.size() ? raw_.equation_names[i] : "");
  }
  for (size_t i = 0; i < raw_.inequalities.size(); ++i) {
    const Inequality& c = raw_.inequalities[i];
    Inequality lifted = c;
    lifted.g = clear(substituted(c.g, -1, -1, static_cast<int>(i)), true, -1);
    if (lifted.g.is_constant())
      throw LiftError("inequality \"" + c.name + "\" is constant " + once, -1, -1, -1, static_cast<int>(i));
    out_.inequalities.push_back(std::move(lifted));
  }
}

// Per angle a note of how it is lifted (the notes start with these); a circle's equation and
// arc (add_circle).
void Lifter::add_angle_constraints() {
  std::vector<std::string> angle_notes;
  for (auto& a : lifting_->angles) {
    const std::string& t = name(a.variable);
    if (a.chart == Chart::tan_only) {
      angle_notes.push_back(t + " -> " + text(angles_[angle_of_[a.variable]].applications[0]) +
                            " (its only use; one branch of tan on the domain)");
      continue;
    }
    if (a.chart != Chart::circle) {
      const bool cos_only = a.chart == Chart::cos_only;
      angle_notes.push_back(t + " -> " + angle_name(a, cos_only ? "cos" : "sin") + " (no " +
                            (cos_only ? "sin" : "cos") + " needed: one to one on the domain)");
      continue;
    }
    angle_notes.push_back(add_circle(a));
  }
  lifting_->notes.insert(lifting_->notes.begin(), angle_notes.begin(), angle_notes.end());
}

// c^2 + s^2 = 1 and, for a domain of less than a turn beyond one quadrant, its arc as an
// inequality. Returns the angle's note.
std::string Lifter::add_circle(const Lifting::Angle& a) {
  const std::string& t = name(a.variable);
  const Interval pi = rigorous::pi();
  const Polynomial c = Polynomial::variable(a.c), s = Polynomial::variable(a.s);
  out_.equations.push_back(c.pow(2) + s.pow(2) - one());
  out_.equation_names.push_back(angle_name(a, "cos") + "^2 + " + angle_name(a, "sin") + "^2 = 1");
  std::string note = t + " -> " + angle_name(a, "cos") + ", " + angle_name(a, "sin") + " on the unit circle";
  long quadrant;
  if (!a.full_turn && !within_one(a.domain, Interval(0.0), pi / Interval(2.0), quadrant)) {
    // The arc of the domain: cos(u - m) >= cos(h), i.e. cos(h) - c cos(m) - s sin(m) <= 0.
    const Interval lo(a.domain.lower()), hi(a.domain.upper());
    const Interval m = (lo + hi) / Interval(2.0), h = (hi - lo) / Interval(2.0);
    Inequality arc;
    arc.g = Polynomial::constant(rigorous::cos(h)) - c * rigorous::cos(m) - s * rigorous::sin(m);
    arc.name = "domain of " + t;
    arc.arc = Inequality::Arc{a.c, a.s, rigorous::cos(m), rigorous::sin(m), h, a.domain};
    out_.inequalities.push_back(std::move(arc));
    note += " (its domain, less than a turn, as the inequality \"domain of " + t + "\")";
  } else if (a.full_turn) {
    note += " (a full turn)";
  }
  return note;
}

void Lifter::add_variable(const std::string& name, const Interval& domain, Lifting::Source source) {
  out_.variables.push_back({name, domain});
  lifting_->sources.push_back(source);
}

std::string Lifter::angle_name(const Lifting::Angle& a, const char* f) const {
  const std::string& t = name(a.variable);
  return std::string(f) + "(" + (same_bounds(a.unit, Interval(1.0)) ? t : format(median(a.unit)) + "*" + t) + ")";
}

Box Lifter::values_before(int k) const {
  Box values = raw_domain();
  values.resize(n_ + k + 1, Interval(0.0));
  for (int i = 0; i < k; ++i)  // a cleared quotient has no enclosure, and k's argument has none of them
    if (!cleared_[i]) values[n_ + i] = enclose_over(raw_.applications[i], values);
  return values;
}

// The range of application k's argument over the domain, through the forward map.
Interval Lifter::argument_range(int k) const { return raw_.applications[k].argument.eval(values_before(k)); }

}  // namespace detail

System lift(const RawSystem& raw) {
  System s;
  if (raw.applications.empty()) {
    s.variables = raw.variables;
    s.equations = raw.equations;
    s.equation_names = raw.equation_names;
    s.inequalities = raw.inequalities;
  } else {
    s = detail::Lifter(raw).run();
    if (s.lifting->notes.empty() && s.variables.size() == raw.variables.size())
      s.lifting.reset();  // only sums that were never raised, all expanded: nothing was lifted
  }
  s.interval_constants = raw.interval_constants;
  s.assumed_bounds = raw.assumed_bounds;
  return s;
}

}  // namespace linkbox::model
