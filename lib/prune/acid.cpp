#include "prune/acid.hpp"

#include <algorithm>

namespace linkbox::prune {

Acid::Acid(std::unique_ptr<Contractor> inner, std::vector<int> dims, int slices)
    : inner_(std::move(inner)), dims_(std::move(dims)), slices_(std::max(2, slices)) {}

Acid::Acid(const Acid& other) : inner_(other.inner_->clone()), dims_(other.dims_), slices_(other.slices_) {}

Interval Acid::slice(const Interval& x, int from, int to) const {
  // Both ends of every slice come from this one formula, so neighbouring slices share their
  // boundary exactly and together cover x, whatever the rounding of the formula.
  auto at = [&](int k) {
    if (k <= 0) return x.lower();
    if (k >= slices_) return x.upper();
    return std::min(x.upper(), x.lower() + (x.upper() - x.lower()) * (static_cast<double>(k) / slices_));
  };
  return Interval(at(from), at(to + 1));
}

int Acid::shave(const Box& box, int var, int first, int last, int step, Box& out) {
  for (int k = first; step > 0 ? k <= last : k >= last; k += step) {
    out = box;
    out[var] = slice(box[var], k, k);
    if (inner_->contract(out) != Outcome::empty) return k;
  }
  return -1;
}

Outcome Acid::contract(Box& box) {
  bool shrunk = false;
  Box left, right, middle;
  for (int var : dims_) {
    const Interval x = box[var];
    // Too narrow to slice: the slices would round onto each other.
    if (!(x.upper() - x.lower() > 1e-9 * std::max(1.0, std::max(-x.lower(), x.upper())))) continue;
    const int kl = shave(box, var, 0, slices_ - 1, +1, left);
    if (kl < 0) return Outcome::empty;
    Box result = left;
    const int kr = kl == slices_ - 1 ? -1 : shave(box, var, slices_ - 1, kl + 1, -1, right);
    if (kr >= 0) {
      result = hull(result, right);
      if (kr > kl + 1) {
        middle = box;
        middle[var] = slice(x, kl + 1, kr - 1);
        if (inner_->contract(middle) != Outcome::empty) result = hull(result, middle);
      }
    }
    for (size_t i = 0; i < box.size(); ++i) {
      Interval r;
      if (!intersect(box[i], result[i], r)) return Outcome::empty;
      shrunk = shrunk || r.lower() != box[i].lower() || r.upper() != box[i].upper();
      box[i] = r;
    }
  }
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
