#include "prune/trapezoid.hpp"

namespace linkbox::prune {

namespace {
// Lower bound of the zero of the line through (0, a) and (1, b), a and b of opposite sign,
// as a fraction of the way along: a / (a - b).
double fraction_down(double a, double b) {
  FastInterval t = FastInterval(a) / (FastInterval(a) - FastInterval(b));
  return std::max(0.0, t.lower());
}
}  // namespace

bool clip_to_trapezoid(double& lo, double& hi, double min_lo, double max_lo, double min_hi, double max_hi) {
  if ((min_lo > 0 && min_hi > 0) || (max_lo < 0 && max_hi < 0)) return false;
  if (lo == hi) return min_lo <= 0 && 0 <= max_lo;
  FastInterval x0(lo), x1(hi), w = x1 - x0;
  double new_lo = lo, new_hi = hi;
  // The lower edge runs from (lo, min_lo) to (hi, min_hi); where it is above 0 there is no
  // root. Likewise where the upper edge is below 0.
  if (min_lo > 0) new_lo = std::max(new_lo, (x0 + w * fraction_down(min_lo, min_hi)).lower());
  if (max_lo < 0) new_lo = std::max(new_lo, (x0 + w * fraction_down(max_lo, max_hi)).lower());
  if (min_hi > 0) new_hi = std::min(new_hi, (x1 - w * fraction_down(min_hi, min_lo)).upper());
  if (max_hi < 0) new_hi = std::min(new_hi, (x1 - w * fraction_down(max_hi, max_lo)).upper());
  if (new_lo > new_hi) return false;
  lo = new_lo;
  hi = new_hi;
  return true;
}

Trapezoid::Trapezoid(const std::vector<model::Polynomial>& equations, Arith arith) : arith_(arith) {
  for (auto& e : equations) {
    equations_.push_back(model::MultiAffine::from(e));
    for (auto& c : equations_.back().coef) c = coefficient_for(arith, c);
  }
}

Outcome Trapezoid::contract(Box& box) {
  return with_rounding(arith_, [&] { return clip(box); });
}

Outcome Trapezoid::clip(Box& box) {
  bool shrunk = false;
  for (auto& eq : equations_) {
    const size_t k = eq.vars.size(), n = eq.coef.size();
    corners_.assign(eq.coef.begin(), eq.coef.end());
    // Butterfly: substitute each variable by its lower (bit clear) and upper (bit set) end.
    for (size_t j = 0; j < k; ++j) {
      const size_t bit = size_t{1} << j;
      // Scalar * interval: cheaper than interval * interval.
      const double lo = box[eq.vars[j]].lower(), hi = box[eq.vars[j]].upper();
      for (size_t m = 0; m < n; ++m) {
        if (m & bit) continue;
        const FastInterval c0 = corners_[m], c1 = corners_[m | bit];
        corners_[m] = c0 + lo * c1;
        corners_[m | bit] = c0 + hi * c1;
      }
    }
    // An overflowed corner (NaN) would be silently ignored by min/max: skip the equation.
    bool finite = true;
    for (size_t m = 0; m < n; ++m) finite = finite && corners_[m].lower() <= corners_[m].upper();
    if (!finite) continue;
    if (k == 0) {
      if (!zero_in(corners_[0])) return Outcome::empty;
      continue;
    }
    for (size_t j = 0; j < k; ++j) {
      const size_t bit = size_t{1} << j;
      double min_lo = kInf, max_lo = -kInf, min_hi = kInf, max_hi = -kInf;
      for (size_t m = 0; m < n; ++m) {
        const FastInterval& c = corners_[m];
        if (m & bit) min_hi = std::min(min_hi, c.lower()), max_hi = std::max(max_hi, c.upper());
        else min_lo = std::min(min_lo, c.lower()), max_lo = std::max(max_lo, c.upper());
      }
      Interval& x = box[eq.vars[j]];
      double lo = x.lower(), hi = x.upper();
      if (!clip_to_trapezoid(lo, hi, min_lo, max_lo, min_hi, max_hi)) return Outcome::empty;
      if (lo != x.lower() || hi != x.upper()) {
        x = Interval(lo, hi);
        shrunk = true;
      }
    }
  }
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
