#include "interval/root.hpp"

#include <cmath>

namespace linkbox::root {

namespace {

using F = FastInterval;

// The guess is libm's (within a few ulps whatever the rounding mode); past this many steps
// something is off (overflow, a poor guess) and Boost's iteration answers instead.
constexpr int kSteps = 8;

F power(double r, int e) { return boost::numeric::pow(F(r), e); }

// A double r >= 0 with r^e <= x (x >= 0), as large as the steps allow; false if none found.
bool below(double x, int e, double& out) {
  double r = e == 3 ? std::cbrt(x) : std::pow(x, 1.0 / e);
  if (!(r >= 0) || !std::isfinite(r)) return false;
  int steps = 0;
  while (power(r, e).upper() > x) {
    if (r == 0 || ++steps > kSteps) return false;
    r = std::nextafter(r, 0.0);
  }
  while (steps++ < kSteps) {  // up while the next double is still proved below the root
    const double n = std::nextafter(r, kInf);
    if (power(n, e).upper() > x) break;
    r = n;
  }
  out = r;
  return true;
}

// A double r >= 0 with r^e >= x (x >= 0), as small as the steps allow; false if none found.
bool above(double x, int e, double& out) {
  double r = e == 3 ? std::cbrt(x) : std::pow(x, 1.0 / e);
  if (!(r >= 0) || !std::isfinite(r)) return false;
  int steps = 0;
  while (power(r, e).lower() < x) {
    if (++steps > kSteps) return false;
    r = std::nextafter(r, kInf);
  }
  while (r > 0 && steps++ < kSteps) {  // down while the next double is still proved above it
    const double n = std::nextafter(r, 0.0);
    if (power(n, e).lower() < x) break;
    r = n;
  }
  out = r;
  return true;
}

// Lower and upper bounds of the e-th root of the double x (x >= 0 unless e is odd).
bool root_lower(double x, int e, double& out) {
  if (x >= 0) return below(x, e, out);
  if (!above(-x, e, out)) return false;
  out = -out;
  return true;
}

bool root_upper(double x, int e, double& out) {
  if (x >= 0) return above(x, e, out);
  if (!below(-x, e, out)) return false;
  out = -out;
  return true;
}

}  // namespace

FastInterval nth_root(const FastInterval& p, int e) {
  if (e == 1) return p;
  double lo = 0, hi = 0;
  if (root_lower(p.lower(), e, lo) && root_upper(p.upper(), e, hi)) return F(lo, hi);
  return boost::numeric::nth_root(p, e);
}

}  // namespace linkbox::root
