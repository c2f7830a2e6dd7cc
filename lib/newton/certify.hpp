#pragma once
// Certification of roots: float Newton from a cluster's centre, epsilon-inflation, then an
// interval Newton test (Krawczyk or Hansen-Sengupta) that proves existence and uniqueness,
// then tightening. The result keeps what a reviewer needs to re-check it without trusting
// any float step: the box X and the preconditioner C (see recheck_*).
#include "model/polynomial.hpp"
#include "newton/interval_newton.hpp"

#include <Eigen/Core>

#include <vector>

namespace linkbox::newton {

enum class Status { certified, unverified };

enum class Reason {
  none,               // certified
  not_square,         // equation count does not match the unknowns, or a bad index
  non_finite,         // NaN/inf in the input box or during evaluation
  singular_jacobian,  // the float Jacobian at the approximate root cannot be inverted
  inflation_failed,   // no inflated box passed the test (double root, ill-conditioned, none)
  singular_in_box,    // PROVED: the interval Jacobian over the cluster holds a singular matrix
  outside_hull,       // Newton led to a root that is not in the given hull
  outside_domain,     // the certified root lies outside the domain (beyond the allowed slack)
  no_root,            // PROVED: the Newton image of the hull misses it, so it holds no root
};
const char* to_string(Reason r);

struct NewtonOptions {
  Method method = Method::krawczyk;
  int newton_steps = 40;         // float Newton iterations at most
  int inflation_steps = 12;      // epsilon-inflation rounds at most
  double inflation = 0.1;        // each round widens X by this fraction of its width ...
  int tighten_steps = 30;        // X <- K(X) rounds after success, at most
  double singular_rcond = 1e-14; // float Jacobians with a smaller reciprocal condition
                                 // number count as singular
  double hull_margin = 1.0;      // the float root may lie this many hull widths outside it
  // The caller's tolerance at the domain boundary: the certified box may leave the domain by
  // domain_slack * (1 + side width) per side; it is then flagged on_domain_boundary. 0 makes
  // any box leaving the domain fail with outside_domain.
  double domain_slack = 1e-9;
};

struct Certificate {
  Status status = Status::unverified;
  Reason reason = Reason::none;
  Method method = Method::krawczyk;
  // Certified: F has exactly one root in `box`, and the Newton image `image` (strictly
  // inside `box`) contains it. Otherwise the last box tried, for diagnosis.
  Box box;
  Box image;
  Eigen::MatrixXd preconditioner;  // C, re-used as is by recheck
  std::vector<double> point;       // float approximation of the root
  bool on_domain_boundary = false; // `box` leaves the domain (within the slack)
  bool root_in_domain = false;     // `image` inside the domain: the root provably is too
  bool unique_in_hull = false;     // proved: no other root in hull(given hull, box)
  int fixed_variable = -1;         // curve crossings: the variable held at box[fixed_variable]
};

// Certifies a root of the square system `f` (n equations in n variables) near the cluster
// `hull` (size n). `domain` is the search domain (empty = unbounded). Tries the hull itself
// first (which can also prove it root-free), then Newton from its centre.
Certificate certify_root(const std::vector<model::Polynomial>& f, const Box& hull,
                         const Box& domain = {}, const NewtonOptions& options = {});
// The same on a system built once (every variable unknown), for callers that certify many
// boxes of one system.
Certificate certify_root(const SquareSystem& f, const Box& hull, const Box& domain = {},
                         const NewtonOptions& options = {});

// Curve crossing: `f` has n-1 equations in n variables (a curve). Fixes variable `parameter`
// at the midpoint of its side of `box` and certifies that exactly one point of the curve
// lies on that hyperplane inside `box` (the domain; hull too). parameter = -1 tries the
// variables in order of how well conditioned the remaining system is at the box centre.
// Boxes in the result are full-size, with box[parameter] degenerate.
Certificate certify_curve_crossing(const std::vector<model::Polynomial>& f, const Box& box,
                                   int parameter = -1, const NewtonOptions& options = {});
// The same on `f` compiled once over box.size() variables, for callers that try many boxes.
Certificate certify_curve_crossing(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box,
                                   int parameter = -1, const NewtonOptions& options = {});

// Re-checks from (F, box, C) alone, all in interval arithmetic with y = midpoint(box):
// true when the Newton image lies strictly inside `box`, i.e. exactly one root in `box`.
bool recheck_krawczyk(const std::vector<model::Polynomial>& f, const Box& box,
                      const Eigen::MatrixXd& c);
bool recheck_hansen_sengupta(const std::vector<model::Polynomial>& f, const Box& box,
                             const Eigen::MatrixXd& c);
// Same for a crossing: box[parameter] is the (degenerate) fixed value.
bool recheck_curve_crossing(const std::vector<model::Polynomial>& f, const Box& box,
                            int parameter, const Eigen::MatrixXd& c,
                            Method method = Method::krawczyk);
// Re-checks a proof of emptiness: the Newton image of `box` misses it.
bool recheck_exclusion(const std::vector<model::Polynomial>& f, const Box& box, const Eigen::MatrixXd& c,
                       Method method = Method::krawczyk);
// Re-checks a certified result with its own method, box, C and fixed variable.
bool recheck(const std::vector<model::Polynomial>& f, const Certificate& cert);

}  // namespace linkbox::newton
