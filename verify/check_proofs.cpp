#include "verify/check_proofs.hpp"

#include "newton/interval_newton.hpp"
#include "newton/regular_inverse.hpp"

#include <stdexcept>

namespace linkbox::verify {

bool encloses(const Box& outer, const Box& inner) { return outer.size() == inner.size() && contains(outer, inner); }

namespace {

// `F` is a polynomial system or a compiled one: SquareSystem takes either.
template <class F>
std::optional<Box> image_under(const F& f, const newton::Certificate& c) {
  const int n = static_cast<int>(c.box.size()), p = c.fixed_variable;
  if (n == 0 || p >= n || (p >= 0 && !(c.box[p].lower() == c.box[p].upper()))) return std::nullopt;
  std::vector<int> unknowns;
  for (int i = 0; i < n; ++i)
    if (i != p) unknowns.push_back(i);
  try {
    const newton::SquareSystem s(f, unknowns, c.box);
    const newton::NewtonStep step = newton::newton_step(c.method, s, s.restrict(c.box), c.preconditioner);
    if (!step.interior) return std::nullopt;
    return s.embed(step.image);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

}  // namespace

std::optional<Box> proved_image(const std::vector<model::Polynomial>& f, const newton::Certificate& c) {
  return image_under(f, c);
}

std::optional<Box> proved_image(const formulate::NaturalSystem& sys, const newton::Certificate& c) {
  if (sys.links.empty()) return image_under(sys.equations, c);
  if (!sys.compiled || c.fixed_variable >= 0) return std::nullopt;
  return image_under(sys.compiled, c);
}

newton::Certificate certify_natural(const formulate::NaturalSystem& sys, const Box& hull,
                                    const newton::NewtonOptions& options) {
  if (sys.links.empty()) return newton::certify_root(sys.equations, hull, sys.domain, options);
  if (sys.compiled) return newton::certify_root(newton::SquareSystem::all_unknown(sys.compiled), hull, sys.domain, options);
  newton::Certificate c;
  c.method = options.method;
  c.box = hull;
  c.reason = newton::Reason::not_square;
  return c;
}

namespace {

bool unique_over(const newton::SquareSystem& s, const Box& start, const newton::Certificate& c) {
  const Box y = hull(start, c.box);
  if (newton::newton_step(c.method, s, y, c.preconditioner).interior) return true;
  if (newton::at_most_one_root(s, y, c.preconditioner)) return true;
  const Eigen::MatrixXd jm = newton::midpoint(s.jacobian(y));
  const auto cy = newton::regular_inverse(jm, newton::NewtonOptions{}.singular_rcond);
  return cy && newton::at_most_one_root(s, y, *cy);
}

}  // namespace

bool unique_over(const formulate::NaturalSystem& sys, const Box& start, const newton::Certificate& c) {
  if (encloses(c.box, start)) return true;
  if (c.box.size() != start.size() || start.size() != sys.unknowns.size()) return false;
  try {
    return unique_over(sys.compiled ? newton::SquareSystem::all_unknown(sys.compiled)
                                    : newton::SquareSystem::all_unknown(sys.equations, start.size()),
                       start, c);
  } catch (const std::invalid_argument&) {
    return false;
  }
}

bool unique_over(const std::vector<model::Polynomial>& f, const Box& start, const newton::Certificate& c) {
  if (encloses(c.box, start)) return true;
  if (c.box.size() != start.size() || start.size() != f.size()) return false;
  try {
    return unique_over(newton::SquareSystem::all_unknown(f, start.size()), start, c);
  } catch (const std::invalid_argument&) {
    return false;
  }
}

}  // namespace linkbox::verify
