#include "model/lifting.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace linkbox::model {

namespace {

using Function = Application::Function;
using Chart = Lifting::Chart;

// A multiple k of an angle's unit in one argument: cos(k u) has degree |k|.
constexpr double kMaxMultiple = 64;
// How far a circle unknown's bound of +-1 is moved out (see build()).
constexpr double kCircleSlack = 0x1p-20;

bool same_bounds(const Interval& a, const Interval& b) { return a.lower() == b.lower() && a.upper() == b.upper(); }
bool is_trig(Function f) { return f != Function::sqrt; }
Polynomial one() { return Polynomial::constant(Interval(1.0)); }

std::string format(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

// cos and sin of an angle as one complex value: products are angle sums.
struct Complex {
  Polynomial re, im;
  friend Complex operator*(const Complex& a, const Complex& b) {
    return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
  }
};

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

// The k with x in [k*period + shift, (k+1)*period + shift] (closed), if one exists.
bool within_one(const Interval& x, const Interval& shift, const Interval& period, long& k) {
  const Interval q = (x - shift) / period;
  if (!is_finite(q)) return false;
  const double lo = std::floor(q.lower());
  if (std::fabs(lo) > 1e15 || q.upper() > lo + 1) return false;
  k = static_cast<long>(lo);
  return true;
}

// The k with x strictly inside (k pi - pi/2, k pi + pi/2): a branch of tan without a pole.
bool within_tan_branch(const Interval& x, long& k) {
  const Interval pi = rigorous::pi();
  const Interval q = (x + pi / Interval(2.0)) / pi;
  if (!is_finite(q)) return false;
  const double lo = std::floor(q.lower());
  if (std::fabs(lo) > 1e15 || !(q.lower() > lo) || !(q.upper() < lo + 1)) return false;
  k = static_cast<long>(lo);
  return true;
}

// Angle of (c, s) in the plane turned by -centre: within [-pi, pi], except a box across the
// negative axis, which is enclosed around pi (a root on the seam of a full turn is then
// reported at one end, the same for every box that holds it).
Interval turned_angle(const Lifting::Angle& a, const Interval& c, const Interval& s) {
  const Interval &cm = a.cos_centre, &sm = a.sin_centre;
  const Interval x = c * cm + s * sm, y = s * cm - c * sm;
  if (x.upper() < 0) {
    const Interval pi = rigorous::pi();
    Interval theta = pi + rigorous::atan(y / x);  // continuous across the seam: (pi/2, 3pi/2)
    if (theta.lower() > pi.upper()) theta -= Interval(2.0) * pi;
    return theta;
  }
  return rigorous::atan2(y, x);
}

Interval clamp_unit(const Interval& x) {
  Interval r;
  if (!intersect(x, Interval(-1.0, 1.0), r)) throw std::domain_error("a cosine or sine outside [-1, 1]");
  return r;
}

}  // namespace

const char* to_string(Application::Function f) {
  switch (f) {
    case Function::sin: return "sin";
    case Function::cos: return "cos";
    case Function::tan: return "tan";
    case Function::sqrt: return "sqrt";
  }
  return "?";
}

bool same(const Polynomial& a, const Polynomial& b) {
  if (a.terms().size() != b.terms().size()) return false;
  for (auto ia = a.terms().begin(), ib = b.terms().begin(); ia != a.terms().end(); ++ia, ++ib)
    if (ia->first != ib->first || !same_bounds(ia->second, ib->second)) return false;
  return true;
}

Polynomial substitute(const Polynomial& p, const std::vector<Polynomial>& images) {
  Polynomial r;
  for (auto& [powers, c] : p.terms()) {
    Polynomial t = Polynomial::constant(c);
    for (auto [v, e] : powers) t = t * images.at(v).pow(e);
    r += t;
  }
  return r;
}

Box Lifting::to_lifted(const Box& box) const {
  const size_t n = declared.size();
  // Every application's value in order (arguments refer to earlier ones only).
  Box values(n + applications.size(), Interval(0.0));
  std::copy(box.begin(), box.begin() + n, values.begin());
  for (size_t k = 0; k < applications.size(); ++k) {
    const Application& a = applications[k];
    const Interval x = a.argument.eval(values);
    Interval& v = values[n + k];
    switch (a.function) {
      case Function::sin: v = rigorous::sin(x); break;
      case Function::cos: v = rigorous::cos(x); break;
      case Function::tan: v = rigorous::tan(x); break;  // throws at a pole
      case Function::sqrt: {
        Interval nonnegative;
        if (!intersect(x, Interval(0.0, kInf), nonnegative))
          throw std::domain_error(a.text + ": negative argument throughout");
        v = rigorous::sqrt(nonnegative);
        break;
      }
    }
  }
  Box out;
  for (const Source& src : sources) {
    switch (src.kind) {
      case Source::Kind::declared: out.push_back(box[src.index]); break;
      case Source::Kind::cos:
      case Source::Kind::sin: {
        const Angle& a = angles[src.index];
        const Interval u = a.unit * box[a.variable];
        out.push_back(src.kind == Source::Kind::cos ? rigorous::cos(u) : rigorous::sin(u));
        break;
      }
      case Source::Kind::tan_angle: {
        const Angle& a = angles[src.index];
        out.push_back(rigorous::tan(Interval(a.sign) * a.unit * box[a.variable] + a.offset));
        break;
      }
      case Source::Kind::application: out.push_back(values[n + src.index]); break;
    }
  }
  return out;
}

Box Lifting::to_declared(const Box& lifted) const {
  Box out(declared.size());
  for (size_t i = 0; i < sources.size(); ++i)
    if (sources[i].kind == Source::Kind::declared) out[sources[i].index] = lifted[i];
  const Interval pi = rigorous::pi();
  for (const Angle& a : angles) {
    Interval u;
    switch (a.chart) {
      case Chart::circle: u = Interval(a.centre) + turned_angle(a, lifted[a.c], lifted[a.s]); break;
      case Chart::cos_only: {
        // cos decreases on [2j pi, (2j+1) pi] and increases on [(2j-1) pi, 2j pi].
        const Interval r = rigorous::acos(clamp_unit(lifted[a.c]));
        u = a.branch % 2 == 0 ? Interval(static_cast<double>(a.branch)) * pi + r
                              : Interval(static_cast<double>(a.branch + 1)) * pi - r;
        break;
      }
      case Chart::sin_only: {
        const Interval r = rigorous::asin(clamp_unit(lifted[a.s]));
        u = Interval(static_cast<double>(a.branch)) * pi + (a.branch % 2 == 0 ? r : -r);
        break;
      }
      case Chart::tan_only:
        u = Interval(a.sign) * (rigorous::atan(lifted[a.tan]) + Interval(static_cast<double>(a.branch)) * pi - a.offset);
        break;
    }
    out[a.variable] = u / a.unit;
  }
  return out;
}

namespace {

class Lifter {
 public:
  explicit Lifter(const RawSystem& raw) : raw_(raw), n_(static_cast<int>(raw.variables.size())) {}

  System run() {
    find_angles();
    for (size_t j = 0; j < angles_.size(); ++j) choose_unit(j);
    expand();
    for (size_t j = 0; j < angles_.size(); ++j) choose_chart(j);
    build();
    return std::move(out_);
  }

 private:
  struct AngleUse {
    Lifting::Angle angle;
    std::vector<int> applications;  // trig applications it occurs in
  };

  [[noreturn]] void fail_variable(int v, const std::string& m) const { throw LiftError(m, v, -1); }
  [[noreturn]] void fail_application(int k, const std::string& m) const { throw LiftError(m, -1, k); }
  const std::string& name(int v) const { return raw_.variables[v].name; }
  const std::string& text(int k) const { return raw_.applications[k].text; }

  // Variables inside sin, cos and tan are angles; they may occur nowhere else.
  void find_angles() {
    angle_of_.assign(n_, -1);
    for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k) {
      const Application& a = raw_.applications[k];
      if (!is_trig(a.function)) continue;
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
                               " and outside sin, cos and tan (in " + where +
                               "): a variable in sin, cos or tan must occur only there, as an angle, because t and "
                               "cos(t) are not related by a polynomial (bound an angle by its domain)");
    };
    for (size_t i = 0; i < raw_.equations.size(); ++i) only_inside(raw_.equations[i], "equation " + std::to_string(i + 1));
    for (auto& c : raw_.inequalities) only_inside(c.g, "\"" + c.name + "\"");
    for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k)
      if (!is_trig(raw_.applications[k].function)) only_inside(raw_.applications[k].argument, text(k));
  }

  // The coefficient of v in an affine argument.
  static Interval coefficient(const Polynomial& arg, int v) {
    auto it = arg.terms().find(Powers{{v, 1}});
    return it == arg.terms().end() ? Interval(0.0) : it->second;
  }

  // The unit w > 0 of angle j: every coefficient of its variable is an integer multiple k of
  // it (exactly: k * w equals the coefficient's bounds), so cos(k u) is a polynomial in
  // cos(u), sin(u). The largest such w of the form (smallest coefficient) / d, d = 1, 2, ...:
  // 2 and 3 give 1, 1/2 and 3/4 give 1/4. A coefficient that is not a double (1/3) can only
  // be the unit, used alone or with exactly equal ones.
  void choose_unit(size_t j) {
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
  static long multiple_of(const Interval& a, const Interval& unit) {
    if (same_bounds(a, unit)) return 1;
    if (same_bounds(a, -unit)) return -1;
    const double q = std::round(median(a) / median(unit));
    if (unit.lower() != unit.upper() || q == 0 || std::fabs(q) > kMaxMultiple) return 0;
    return same_bounds(Interval(q) * unit, a) ? static_cast<long>(q) : 0;
  }

  // The multiple of angle variable v's unit that coefficient a is (choose_unit made sure).
  long multiple(int v, const Interval& a) const { return multiple_of(a, angles_[angle_of_[v]].angle.unit); }

  // tan(a*t + b) as the angle's only use is modelled as itself; everything else is expanded
  // into polynomials in symbols cos(u_j) = 2j, sin(u_j) = 2j + 1.
  void expand() {
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
      if (!is_trig(a.function)) continue;
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

  Box raw_domain() const {
    Box b;
    for (auto& v : raw_.variables) b.push_back(v.domain);
    return b;
  }

  std::string pole_message(int k, const Interval& range) const {
    return text(k) + ": its argument ranges over [" + format(range.lower()) + ", " + format(range.upper()) +
           "] on the domain, which meets a pole of tan (or cannot be shown not to); narrow the domain so that it "
           "stays within one branch (pi/2 + k pi excluded)";
  }

  // What angle j's uses need: c alone, s alone, or both on the circle.
  void choose_chart(size_t j) {
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

  void add_variable(const std::string& name, const Interval& domain, Lifting::Source source) {
    out_.variables.push_back({name, domain});
    lifting_->sources.push_back(source);
  }

  std::string angle_name(const Lifting::Angle& a, const char* f) const {
    const std::string& t = name(a.variable);
    return std::string(f) + "(" + (same_bounds(a.unit, Interval(1.0)) ? t : format(median(a.unit)) + "*" + t) + ")";
  }

  void build() {
    auto lifting = std::make_shared<Lifting>();
    lifting_ = lifting.get();
    lifting->declared = raw_.variables;
    lifting->applications = raw_.applications;
    const Interval pi = rigorous::pi();

    // Unknowns: each declared variable in place (an angle as its cos/sin or tan), then one per
    // tan or sqrt that needs an equation, in the order they were written.
    std::vector<Polynomial> symbol(2 * angles_.size());  // cos(u_j), sin(u_j) as lifted variables
    std::vector<Polynomial> image(n_ + raw_.applications.size());
    std::vector<bool> done(raw_.applications.size(), false);
    for (int v = 0; v < n_; ++v) {
      const int j = angle_of_[v];
      if (j < 0) {
        image[v] = Polynomial::variable(static_cast<int>(out_.variables.size()));
        add_variable(name(v), raw_.variables[v].domain, {Lifting::Source::Kind::declared, v});
        continue;
      }
      Lifting::Angle& a = angles_[j].angle;
      const auto next = [&] { return static_cast<int>(out_.variables.size()); };
      if (a.chart == Chart::tan_only) {
        a.tan = next();
        const int k = angles_[j].applications[0];
        image[n_ + k] = Polynomial::variable(a.tan);
        done[k] = true;
        add_variable(text(k), rigorous::tan(raw_.applications[k].argument.eval(raw_domain())),
                     {Lifting::Source::Kind::tan_angle, j});
        continue;
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
        symbol[2 * j] = Polynomial::variable(a.c);
        add_variable(angle_name(a, "cos"), range(rigorous::cos(a.domain)), {Lifting::Source::Kind::cos, j});
      }
      if (a.chart != Chart::cos_only) {
        a.s = next();
        symbol[2 * j + 1] = Polynomial::variable(a.s);
        add_variable(angle_name(a, "sin"), range(rigorous::sin(a.domain)), {Lifting::Source::Kind::sin, j});
      }
    }
    for (auto& use : angles_) lifting->angles.push_back(use.angle);

    // Applications in order: sin/cos are their expansions; tan and sqrt get an unknown each.
    std::vector<std::pair<Polynomial, std::string>> definitions;
    for (int k = 0; k < static_cast<int>(raw_.applications.size()); ++k) {
      const Application& a = raw_.applications[k];
      if (done[k]) continue;  // tan only, above
      if (a.function == Function::sin || a.function == Function::cos) {
        image[n_ + k] = substitute(a.function == Function::cos ? expansions_[k].re : expansions_[k].im, symbol);
        continue;
      }
      const int index = static_cast<int>(out_.variables.size());
      const Polynomial x = Polynomial::variable(index);
      image[n_ + k] = x;
      if (a.function == Function::tan) {
        long branch;
        const Interval range = a.argument.eval(raw_domain());
        if (!within_tan_branch(range, branch)) fail_application(k, pole_message(k, range));
        add_variable(a.text, rigorous::tan(range), {Lifting::Source::Kind::application, k});
        definitions.emplace_back(x * substitute(expansions_[k].re, symbol) - substitute(expansions_[k].im, symbol),
                                 a.text + " * cos = sin");
        lifting_->notes.push_back(a.text + " -> an unknown t with t cos(...) = sin(...) (no pole in the domain)");
      } else {
        // The domain of r: [0, sqrt of the argument's upper bound over the domain].
        Interval range;
        try {
          range = argument_range(k);
        } catch (const std::domain_error&) {
          fail_application(k, a.text + ": its argument is negative on the whole domain, so the square root is never "
                                       "real");
        }
        if (!is_finite(range)) fail_application(k, a.text + ": its argument is not bounded on the domain");
        add_variable(a.text, Interval(0.0, range.upper()), {Lifting::Source::Kind::application, k});
        definitions.emplace_back(x.pow(2) - substitute(a.argument, image), a.text + "^2 = its argument");
        lifting_->notes.push_back(a.text + " -> an unknown r >= 0 with r^2 = its argument");
      }
    }

    // Equations and inequalities as typed, then what defines the new unknowns.
    for (size_t i = 0; i < raw_.equations.size(); ++i) {
      Polynomial p = substitute(raw_.equations[i], image);
      if (p.is_constant())
        throw LiftError("equation " + std::to_string(i + 1) +
                            " is constant once sin and cos are expanded (an identity such as sin(t)^2 + cos(t)^2 = 1, "
                            "or a contradiction)",
                        -1, -1, static_cast<int>(i));
      out_.equations.push_back(std::move(p));
      out_.equation_names.push_back(i < raw_.equation_names.size() ? raw_.equation_names[i] : "");
    }
    for (size_t i = 0; i < raw_.inequalities.size(); ++i) {
      const Inequality& c = raw_.inequalities[i];
      Inequality lifted = c;
      lifted.g = substitute(c.g, image);
      if (lifted.g.is_constant())
        throw LiftError("inequality \"" + c.name + "\" is constant once sin and cos are expanded", -1, -1, -1,
                        static_cast<int>(i));
      out_.inequalities.push_back(std::move(lifted));
    }
    std::vector<std::string> angle_notes;
    for (auto& a : lifting->angles) {
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
        out_.inequalities.push_back(std::move(arc));
        note += " (its domain, less than a turn, as the inequality \"domain of " + t + "\")";
      } else if (a.full_turn) {
        note += " (a full turn)";
      }
      angle_notes.push_back(note);
    }
    lifting->notes.insert(lifting->notes.begin(), angle_notes.begin(), angle_notes.end());
    for (auto& d : definitions) {
      out_.equations.push_back(std::move(d.first));
      out_.equation_names.push_back(std::move(d.second));
    }
    out_.lifting = std::move(lifting);
  }

  // The range of application k's argument over the domain, through the forward map.
  Interval argument_range(int k) const {
    Box values = raw_domain();
    values.resize(n_ + k + 1, Interval(0.0));
    for (int i = 0; i < k; ++i) {
      const Application& a = raw_.applications[i];
      const Interval x = a.argument.eval(values);
      switch (a.function) {
        case Function::sin: values[n_ + i] = rigorous::sin(x); break;
        case Function::cos: values[n_ + i] = rigorous::cos(x); break;
        case Function::tan: values[n_ + i] = rigorous::tan(x); break;
        case Function::sqrt: {
          Interval nonnegative;
          if (!intersect(x, Interval(0.0, kInf), nonnegative)) throw std::domain_error("sqrt");
          values[n_ + i] = rigorous::sqrt(nonnegative);
          break;
        }
      }
    }
    const Interval range = raw_.applications[k].argument.eval(values);
    if (range.upper() < 0) throw std::domain_error("sqrt");
    return range;
  }

  const RawSystem& raw_;
  const int n_;
  std::vector<int> angle_of_;  // per declared variable: its angle, or -1
  std::vector<AngleUse> angles_;
  std::vector<Complex> expansions_;  // per application: cos + i sin of its argument (trig only)
  System out_;
  Lifting* lifting_ = nullptr;
};

}  // namespace

System lift(const RawSystem& raw) {
  if (raw.applications.empty()) {
    System s;
    s.variables = raw.variables;
    s.equations = raw.equations;
    s.equation_names = raw.equation_names;
    s.inequalities = raw.inequalities;
    return s;
  }
  return Lifter(raw).run();
}

}  // namespace linkbox::model
