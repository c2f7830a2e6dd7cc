#include "model/lifting.hpp"

#include "interval/rigorous.hpp"
#include "model/exact_coefficients.hpp"

#include <algorithm>

namespace linkbox::model {

namespace {

using Function = Application::Function;
using Chart = Lifting::Chart;

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
    case Function::reciprocal: return "1/";
    case Function::atan2: return "atan2";
    case Function::base: return "base";
    default: {
      Elementary e;
      if (link_function(f, e)) return to_string(e);
    }
  }
  return "?";
}

bool link_function(Application::Function f, Elementary& out) {
  switch (f) {
    case Function::exp: out = Elementary::exp; return true;
    case Function::log: out = Elementary::log; return true;
    case Function::sinh: out = Elementary::sinh; return true;
    case Function::cosh: out = Elementary::cosh; return true;
    case Function::tanh: out = Elementary::tanh; return true;
    case Function::asinh: out = Elementary::asinh; return true;
    case Function::acosh: out = Elementary::acosh; return true;
    case Function::atanh: out = Elementary::atanh; return true;
    case Function::asin: out = Elementary::asin; return true;
    case Function::acos: out = Elementary::acos; return true;
    case Function::atan: out = Elementary::atan; return true;
    default: return false;
  }
}

Interval enclose(const Application& a, const Interval& x, const Interval& second) {
  switch (a.function) {
    case Function::atan2:
      if (zero_in(x) && zero_in(second)) {
        if (x.lower() == 0 && x.upper() == 0 && second.lower() == 0 && second.upper() == 0)
          throw std::domain_error(a.text + ": both arguments are 0");
        return Interval(-rigorous::pi().upper(), rigorous::pi().upper());
      }
      return rigorous::atan2(x, second);
    case Function::sin: return rigorous::sin(x);
    case Function::cos: return rigorous::cos(x);
    case Function::tan: return rigorous::tan(x);  // throws at a pole
    case Function::sqrt: {
      Interval nonnegative;
      if (!intersect(x, Interval(0.0, kInf), nonnegative))
        throw std::domain_error(a.text + ": negative argument throughout");
      return rigorous::sqrt(nonnegative);
    }
    case Function::reciprocal:
      if (zero_in(x)) throw std::domain_error(a.text + ": the divisor may be 0");
      return Interval(1.0) / x;
    case Function::base: return x;
    default: {
      Elementary e;
      link_function(a.function, e);
      return image(e, x);
    }
  }
}

Interval enclose_over(const Application& a, const Box& values) {
  const bool two = a.function == Function::atan2;
  return enclose(a, a.argument.eval(values), two ? a.second.eval(values) : Interval(1.0));
}

// Equal enclosures of different exact values (decimals alike to 17 digits) are not the same.
bool same(const Polynomial& a, const Polynomial& b) {
  if (a.terms().size() != b.terms().size()) return false;
  for (auto ia = a.terms().begin(), ib = b.terms().begin(); ia != a.terms().end(); ++ia, ++ib) {
    if (ia->first != ib->first || !same_bounds(ia->second, ib->second)) return false;
    if (exact_coefficient(a, ia->first, ia->second) != exact_coefficient(b, ib->first, ib->second)) return false;
  }
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
  for (size_t k = 0; k < applications.size(); ++k)  // a cleared quotient: no unknown, no argument has it
    if (k >= cleared.size() || !cleared[k]) values[n + k] = enclose_over(applications[k], values);
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
      case Source::Kind::argument: out.push_back(applications[src.index].argument.eval(values)); break;
      case Source::Kind::angle_cos: out.push_back(rigorous::cos(values[n + src.index])); break;
      case Source::Kind::angle_sin: out.push_back(rigorous::sin(values[n + src.index])); break;
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

}  // namespace linkbox::model
