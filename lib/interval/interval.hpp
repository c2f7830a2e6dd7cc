#pragma once
// The public interval type: Boost.Interval over double with outward rounding.
// Protected operations switch the FPU rounding mode per operation (slow, safe anywhere);
// hot loops use FastInterval inside one RoundingGuard (see lib/README.md, "Decisions").
#include <boost/numeric/interval.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

namespace linkbox {

namespace bi = boost::numeric::interval_lib;

// rounded_arith_opp is the Boost default for double and the one measured sound at -O2
// with -frounding-math, except for sqrt: GCC treats sqrt as pure even under
// -frounding-math and reuses the downward-rounded root as the upper bound (one sqrtsd).
// Hiding the argument behind an empty asm forces one evaluation per rounding mode.
struct RoundedArith : bi::rounded_arith_opp<double> {
  static double opaque(double x) {
    asm volatile("" : "+x"(x));
    return x;
  }
  // Boost's opp policy ends sqrt_down and median in upward mode whatever mode it found:
  // right inside a RoundingGuard (upward anyway), but FastInterval outside one (the float
  // variant) would leave the thread rounding upward for good. These put back the mode.
  double sqrt_down(const double& x) {
    rounding_mode found;
    this->get_rounding_mode(found);
    this->downward();
    const double r = this->force_rounding(std::sqrt(opaque(x)));
    this->set_rounding_mode(found);
    return r;
  }
  double sqrt_up(const double& x) { return this->force_rounding(std::sqrt(opaque(x))); }
  double median(const double& x, const double& y) {
    rounding_mode found;
    this->get_rounding_mode(found);
    this->to_nearest();
    const double r = this->force_rounding((x + y) / 2);
    this->set_rounding_mode(found);
    return r;
  }
};

// checking_base: emptiness is handled explicitly, never by throwing.
using Interval =
    boost::numeric::interval<double, bi::policies<bi::save_state<RoundedArith>, bi::checking_base<double>>>;

// Same arithmetic without per-operation mode switches: only valid while a RoundingGuard lives.
using FastInterval = bi::unprotect<Interval>::type;
using RoundingGuard = Interval::traits_type::rounding;

// Round-to-nearest for one scope, the mode found put back at its end: many midpoints under
// one switch of the mode, where median() of an Interval switches it four times.
class NearestScope {
 public:
  NearestScope() {
    arith_.get_rounding_mode(found_);
    arith_.to_nearest();
  }
  ~NearestScope() { arith_.set_rounding_mode(found_); }
  NearestScope(const NearestScope&) = delete;
  NearestScope& operator=(const NearestScope&) = delete;
  // median(x): NaN for an empty x, else (lower + upper) / 2 rounded to nearest.
  double median(const Interval& x) const {
    if (!(x.lower() <= x.upper())) return std::numeric_limits<double>::quiet_NaN();
    return (x.lower() + x.upper()) / 2;
  }

 private:
  RoundedArith arith_;
  RoundedArith::rounding_mode found_;
};

// The same bounds in the other arithmetic (no rounding: the ends are copied).
inline FastInterval as_fast(const Interval& x) { return FastInterval(x.lower(), x.upper()); }
inline Interval as_protected(const FastInterval& x) { return Interval(x.lower(), x.upper()); }

// How pruning computes: `verified` rounds outward (every exclusion proved); `float_unverified`
// is the same algorithm in round-to-nearest doubles with midpoint coefficients, for
// comparison only (it can cut roots). One typed switch from the command line to each
// contractor.
enum class Arith { verified, float_unverified };
inline const char* to_string(Arith a) { return a == Arith::verified ? "verified" : "float (UNVERIFIED)"; }

// Runs f() inside one RoundingGuard when verified; FastInterval without the guard rounds to
// nearest, which is what the float variant means.
template <class F>
decltype(auto) with_rounding(Arith arith, F&& f) {
  if (arith != Arith::verified) return f();
  RoundingGuard guard;
  return f();
}

// The coefficient a contractor uses: the enclosure, or its midpoint in the float variant.
inline Interval coefficient_for(Arith arith, const Interval& c) {
  return arith == Arith::verified ? c : Interval(median(c));
}

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline Interval hull(const Interval& a, const Interval& b) {
  return Interval(std::min(a.lower(), b.lower()), std::max(a.upper(), b.upper()));
}

// Intersection; returns false (and leaves `out` untouched) when empty.
inline bool intersect(const Interval& a, const Interval& b, Interval& out) {
  double lo = std::max(a.lower(), b.lower()), hi = std::min(a.upper(), b.upper());
  if (!(lo <= hi)) return false;
  out = Interval(lo, hi);
  return true;
}

inline bool is_finite(const Interval& x) {
  return std::isfinite(x.lower()) && std::isfinite(x.upper());
}

// An interval that provably misses 0. NaN bounds (an overflowed evaluation) prove nothing,
// where Boost's !zero_in(x) would take such an interval for an empty one.
template <class I>
bool excludes_zero(const I& x) {
  return x.lower() > 0 || x.upper() < 0;
}

inline bool contains(const Interval& x, double v) { return x.lower() <= v && v <= x.upper(); }

// The same set: equal bounds. Boost's == compares intervals as uncertain numbers instead.
inline bool same_bounds(const Interval& a, const Interval& b) {
  return a.lower() == b.lower() && a.upper() == b.upper();
}

// Rounded-up width; the plain difference could round below the true width.
inline double width_up(const Interval& x) {
  RoundingGuard guard;
  return guard.sub_up(x.upper(), x.lower());
}

}  // namespace linkbox
