#include "model/link.hpp"

#include "interval/fast_exp.hpp"
#include "interval/fast_trig.hpp"
#include "interval/rigorous.hpp"

#include <cfenv>
#include <cmath>
#include <stdexcept>

namespace linkbox::model {

namespace {

// MPFR rounds its conversions from and to double itself, but nothing promises that every
// path is independent of the processor's mode: contractors call these inside a RoundingGuard
// (upward), so the MPFI calls run in round-to-nearest, the mode they are tested in.
struct Nearest {
  int mode = std::fegetround();
  Nearest() { std::fesetround(FE_TONEAREST); }
  ~Nearest() { std::fesetround(mode); }
  Nearest(const Nearest&) = delete;
  Nearest& operator=(const Nearest&) = delete;
};

const Interval kWhole(-kInf, kInf);

// x ∩ [lo, hi] into x; false (x untouched) when empty.
bool clip(Interval& x, double lo, double hi) {
  const double l = std::max(x.lower(), lo), h = std::min(x.upper(), hi);
  if (!(l <= h)) return false;
  x = Interval(l, h);
  return true;
}

Interval point(double v) { return Interval(v); }

// exp, log, sin and cos in double arithmetic (fast_exp, fast_trig: the same enclosures a few
// ulps wider, without multi-precision), where those answer; MPFI otherwise. These run in the
// caller's rounding mode: the fast ones set their own, MPFI's run inside Nearest.
Interval fast_or_mpfi(const Interval& x, bool (*fast)(const FastInterval&, FastInterval&),
                      Interval (*mpfi)(const Interval&)) {
  {
    RoundingGuard guard;
    FastInterval r;
    if (fast(as_fast(x), r)) return as_protected(r);
  }
  Nearest nearest;
  return mpfi(x);
}

Interval exp(const Interval& x) { return fast_or_mpfi(x, fast_exp::exp, rigorous::exp); }
Interval log(const Interval& x) { return fast_or_mpfi(x, fast_exp::log, rigorous::log); }

fast_trig::SinCos sin_cos(const Interval& x) {
  RoundingGuard guard;
  return fast_trig::sin_cos(as_fast(x));
}

Interval sin(const Interval& x) { return as_protected(sin_cos(x).sin); }
Interval cos(const Interval& x) { return as_protected(sin_cos(x).cos); }

const Interval& half_pi() {
  static const Interval h = rigorous::pi() / Interval(2.0);
  return h;
}

// tan on a box within one branch; the whole line where the box may meet a pole.
Interval tan_on_branch(const Interval& x) {
  long k;
  if (!within_tan_branch(x, k)) return kWhole;
  Nearest nearest;
  return rigorous::tan(x);
}

// {v : f(v) in y} enclosed, for f monotone (cosh: |v|); false when empty. Inside Nearest.
bool preimage(Elementary f, Interval y, Interval& out) {
  const Interval& half_pi = model::half_pi();
  switch (f) {
    case Elementary::exp:
      if (y.upper() <= 0) return false;
      out = Interval(y.lower() > 0 ? log(point(y.lower())).lower() : -kInf, log(point(y.upper())).upper());
      return true;
    case Elementary::log: out = exp(y); return true;
    case Elementary::sinh: out = rigorous::asinh(y); return true;
    case Elementary::asinh: out = rigorous::sinh(y); return true;
    case Elementary::acosh:  // v = cosh(w), w >= 0
      if (!clip(y, 0.0, kInf)) return false;
      out = rigorous::cosh(y);
      return true;
    case Elementary::atanh: out = rigorous::tanh(y); return true;
    case Elementary::cosh:  // |v| = acosh(y), y >= 1
      if (!clip(y, 1.0, kInf)) return false;
      out = rigorous::acosh(y);
      return true;
    case Elementary::tanh:  // tanh(v) in (-1, 1)
      if (y.upper() <= -1 || y.lower() >= 1) return false;
      out = Interval(y.lower() > -1 ? rigorous::atanh(point(y.lower())).lower() : -kInf,
                     y.upper() < 1 ? rigorous::atanh(point(y.upper())).upper() : kInf);
      return true;
    case Elementary::atan:  // atan(v) in (-pi/2, pi/2)
      if (y.upper() <= -half_pi.upper() || y.lower() >= half_pi.upper()) return false;
      out = Interval(y.lower() > -half_pi.lower() ? rigorous::tan(point(y.lower())).lower() : -kInf,
                     y.upper() < half_pi.lower() ? rigorous::tan(point(y.upper())).upper() : kInf);
      return true;
    case Elementary::asin:  // v = sin(w), w in [-pi/2, pi/2] (enclosed outward: sin's range is a superset)
      if (!clip(y, -half_pi.upper(), half_pi.upper())) return false;
      out = sin(y);
      return true;
    case Elementary::acos:  // v = cos(w), w in [0, pi]
      if (!clip(y, 0.0, 2 * half_pi.upper())) return false;
      out = cos(y);
      return true;
    case Elementary::sin:
    case Elementary::cos:
    case Elementary::tan: out = kWhole; return true;  // not monotone (tan: narrow_argument)
  }
  return false;
}

// a's points on its branch of tan whose tangent can be in y: atan(y) + k pi.
bool narrow_tan_argument(const Interval& y, Interval& a) {
  long k;
  if (!within_tan_branch(a, k)) return true;  // may meet a pole: nothing learnt
  Nearest nearest;
  return intersect(a, rigorous::atan(y) + Interval(static_cast<double>(k)) * rigorous::pi(), a);
}

// Narrows a to the points whose image can be in y.
bool narrow_argument(Elementary f, const Interval& y, Interval& a) {
  if (f == Elementary::tan) return narrow_tan_argument(y, a);
  Interval r;
  if (!preimage(f, y, r)) return false;
  if (f != Elementary::cosh) return intersect(a, r, a);
  // |a| in r: the hull of a's parts in [-r.hi, -r.lo] and [r.lo, r.hi].
  Interval neg = a, pos = a;
  const bool n = clip(neg, -r.upper(), -r.lower()), p = clip(pos, r.lower(), r.upper());
  if (!n && !p) return false;
  a = n && p ? hull(neg, pos) : (n ? neg : pos);
  return true;
}

// a narrowed to f's (closed) domain; false when it misses it.
bool to_domain(Elementary f, Interval& a) {
  switch (f) {
    case Elementary::log: return a.upper() > 0 && clip(a, 0.0, kInf);
    case Elementary::acosh: return clip(a, 1.0, kInf);
    case Elementary::atanh:
    case Elementary::asin:
    case Elementary::acos: return clip(a, -1.0, 1.0);
    default: return true;
  }
}

}  // namespace

const char* to_string(Elementary f) {
  switch (f) {
    case Elementary::exp: return "exp";
    case Elementary::log: return "log";
    case Elementary::sinh: return "sinh";
    case Elementary::cosh: return "cosh";
    case Elementary::tanh: return "tanh";
    case Elementary::asinh: return "asinh";
    case Elementary::acosh: return "acosh";
    case Elementary::atanh: return "atanh";
    case Elementary::asin: return "asin";
    case Elementary::acos: return "acos";
    case Elementary::atan: return "atan";
    case Elementary::sin: return "sin";
    case Elementary::cos: return "cos";
    case Elementary::tan: return "tan";
  }
  return "?";
}

bool within_tan_branch(const Interval& x, long& k) {
  const Interval pi = rigorous::pi();
  const Interval q = (x + pi / Interval(2.0)) / pi;
  if (!is_finite(q)) return false;
  const double lo = std::floor(q.lower());
  if (std::fabs(lo) > 1e15 || !(q.lower() > lo) || !(q.upper() < lo + 1)) return false;
  k = static_cast<long>(lo);
  return true;
}

bool within_domain(Elementary f, const Interval& x) {
  switch (f) {
    case Elementary::log: return x.lower() > 0;
    case Elementary::acosh: return x.lower() >= 1;
    case Elementary::atanh: return x.lower() > -1 && x.upper() < 1;
    case Elementary::asin:
    case Elementary::acos: return x.lower() >= -1 && x.upper() <= 1;
    case Elementary::tan: {
      long k;
      return within_tan_branch(x, k);
    }
    default: return true;
  }
}

Interval image(Elementary f, const Interval& x) {
  Interval a = x;
  if (!to_domain(f, a)) throw std::domain_error(std::string(to_string(f)) + ": argument outside the domain");
  switch (f) {
    case Elementary::exp: return exp(a);
    case Elementary::log: return a.lower() > 0 ? log(a) : Interval(-kInf, log(point(a.upper())).upper());
    case Elementary::sin: return sin(a);
    case Elementary::cos: return cos(a);
    case Elementary::tan: return tan_on_branch(a);
    default: break;
  }
  Nearest nearest;
  switch (f) {
    case Elementary::sinh: return rigorous::sinh(a);
    case Elementary::cosh: return rigorous::cosh(a);
    case Elementary::tanh: return rigorous::tanh(a);
    case Elementary::asinh: return rigorous::asinh(a);
    case Elementary::acosh: return rigorous::acosh(a);
    case Elementary::atanh: return rigorous::atanh(a);  // infinite at +-1
    case Elementary::asin: return rigorous::asin(a);
    case Elementary::acos: return rigorous::acos(a);
    case Elementary::atan: return rigorous::atan(a);
    default: return kWhole;
  }
}

Interval derivative(Elementary f, const Interval& x) {
  const Interval one(1.0);
  switch (f) {
    case Elementary::exp: return exp(x);
    case Elementary::sin: return cos(x);
    case Elementary::cos: return -sin(x);
    case Elementary::tan: {
      // Across a pole tan is not continuous, so no slope bound holds there (a mean-value
      // form over such a box would be false): the whole line, as for any box off the domain.
      if (!within_domain(Elementary::tan, x)) return kWhole;
      Interval d = one + boost::numeric::square(tan_on_branch(x));
      clip(d, 1.0, kInf);  // 1 + tan^2 >= 1
      return d;
    }
    default: break;
  }
  Nearest nearest;
  switch (f) {
    case Elementary::log: return x.lower() > 0 ? one / x : kWhole;
    case Elementary::sinh: return rigorous::cosh(x);
    case Elementary::cosh: return rigorous::sinh(x);
    case Elementary::tanh: {
      Interval d = one - boost::numeric::square(rigorous::tanh(x));
      clip(d, 0.0, 1.0);  // 1 - tanh^2 is in (0, 1]
      return d;
    }
    case Elementary::asinh: return one / boost::numeric::sqrt(one + boost::numeric::square(x));
    case Elementary::acosh:
      return x.lower() > 1 ? one / boost::numeric::sqrt(boost::numeric::square(x) - one) : kWhole;
    case Elementary::atanh: {
      if (!(x.lower() > -1 && x.upper() < 1)) return kWhole;
      Interval d = one / (one - boost::numeric::square(x));
      clip(d, 1.0, kInf);  // 1 / (1 - x^2) >= 1
      return d;
    }
    case Elementary::asin:
    case Elementary::acos: {
      if (!(x.lower() > -1 && x.upper() < 1)) return kWhole;
      const Interval d = one / boost::numeric::sqrt(one - boost::numeric::square(x));
      return f == Elementary::asin ? d : -d;
    }
    case Elementary::atan: return one / (one + boost::numeric::square(x));
    default: return kWhole;
  }
}

Interval row_value(const Link& l, const Interval& y, const Interval& a) {
  if (!within_domain(l.f, a)) return kWhole;
  return y - image(l.f, a);
}

Interval row_derivative(const Link& l, const Interval& a) { return -derivative(l.f, a); }

double row_value_float(const Link& l, const double* x) {
  const double a = x[l.a];
  double v = 0;
  switch (l.f) {
    case Elementary::exp: v = std::exp(a); break;
    case Elementary::log: v = std::log(a); break;
    case Elementary::sinh: v = std::sinh(a); break;
    case Elementary::cosh: v = std::cosh(a); break;
    case Elementary::tanh: v = std::tanh(a); break;
    case Elementary::asinh: v = std::asinh(a); break;
    case Elementary::acosh: v = std::acosh(a); break;
    case Elementary::atanh: v = std::atanh(a); break;
    case Elementary::asin: v = std::asin(a); break;
    case Elementary::acos: v = std::acos(a); break;
    case Elementary::atan: v = std::atan(a); break;
    case Elementary::sin: v = std::sin(a); break;
    case Elementary::cos: v = std::cos(a); break;
    case Elementary::tan: v = std::tan(a); break;
  }
  return x[l.y] - v;
}

double row_derivative_float(const Link& l, const double* x) {
  const double a = x[l.a];
  switch (l.f) {
    case Elementary::exp: return -std::exp(a);
    case Elementary::log: return -1 / a;
    case Elementary::sinh: return -std::cosh(a);
    case Elementary::cosh: return -std::sinh(a);
    case Elementary::tanh: return -(1 - std::tanh(a) * std::tanh(a));
    case Elementary::asinh: return -1 / std::sqrt(1 + a * a);
    case Elementary::acosh: return -1 / std::sqrt(a * a - 1);
    case Elementary::atanh: return -1 / (1 - a * a);
    case Elementary::asin: return -1 / std::sqrt(1 - a * a);
    case Elementary::acos: return 1 / std::sqrt(1 - a * a);
    case Elementary::atan: return -1 / (1 + a * a);
    case Elementary::sin: return -std::cos(a);
    case Elementary::cos: return std::sin(a);
    case Elementary::tan: return -(1 + std::tan(a) * std::tan(a));
  }
  return 0;
}

bool narrow(const Link& l, Box& box) {
  Interval& a = box[l.a];
  Interval& y = box[l.y];
  if (!to_domain(l.f, a)) return false;
  if (!intersect(y, image(l.f, a), y)) return false;
  {
    Nearest nearest;
    if (!narrow_argument(l.f, y, a)) return false;
  }
  return intersect(y, image(l.f, a), y);
}

bool may_hold(const Link& l, const Box& box) {
  Interval a = box[l.a], y = box[l.y];
  return to_domain(l.f, a) && intersect(y, image(l.f, a), y);
}

double residual_bound(const std::vector<Link>& links, const Box& box) {
  double r = 0;
  for (const Link& l : links) {
    const Interval a = point(median(box[l.a]));
    if (!within_domain(l.f, a)) continue;
    const Interval v = point(median(box[l.y])) - image(l.f, a);
    r = std::max({r, std::fabs(v.lower()), std::fabs(v.upper())});
  }
  return r;
}

}  // namespace linkbox::model
