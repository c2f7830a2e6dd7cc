#pragma once
// Trapezoid clipping (spherical paper, Section 4.2). The graph of a multi-affine f over a
// box lies in the convex hull of its corner values; projected onto the (x_i, f) plane that
// hull is a trapezoid with vertical sides at the ends of x_i, and x_i can only take values
// where the trapezoid meets f = 0. Corner values are enclosed with outward rounding and
// every clip point is rounded outward, so no root is ever cut.
#include "model/multi_affine.hpp"
#include "prune/contractor.hpp"

namespace linkbox::prune {

class Trapezoid final : public Contractor {
 public:
  // Throws std::invalid_argument if an equation is not multi-affine.
  // Arith::float_unverified is the unverified variant (--arith float): midpoint coefficients
  // and round-to-nearest, so a root can be cut; for comparison only.
  explicit Trapezoid(const std::vector<model::Polynomial>& equations, Arith arith = Arith::verified);
  std::string name() const override { return arith_ == Arith::verified ? "trapezoid" : "trapezoid-float"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<Trapezoid>(*this); }

 private:
  std::vector<model::MultiAffine> equations_;
  std::vector<FastInterval> corners_;  // scratch
  Arith arith_;
  Outcome clip(Box& box);
};

// Clips [lo, hi] to where the trapezoid with left side [min_lo, max_lo] (at x = lo) and
// right side [min_hi, max_hi] (at x = hi) meets f = 0. Returns false when it misses.
// Must run under a RoundingGuard. Exposed for tests.
bool clip_to_trapezoid(double& lo, double& hi, double min_lo, double max_lo, double min_hi, double max_hi);

}  // namespace linkbox::prune
