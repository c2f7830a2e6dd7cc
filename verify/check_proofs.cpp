#include "verify/check_proofs.hpp"

#include "newton/interval_newton.hpp"

#include <Eigen/LU>

#include <stdexcept>

namespace linkbox::verify {

bool encloses(const Box& outer, const Box& inner) { return outer.size() == inner.size() && contains(outer, inner); }

std::optional<Box> proved_image(const std::vector<model::Polynomial>& f, const newton::Certificate& c) {
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

bool unique_over(const formulate::NaturalSystem& sys, const Box& start, const newton::Certificate& c) {
  if (encloses(c.box, start)) return true;
  if (c.box.size() != start.size() || start.size() != sys.unknowns.size()) return false;
  try {
    const newton::SquareSystem s = sys.compiled ? newton::SquareSystem::all_unknown(sys.compiled)
                                                : newton::SquareSystem::all_unknown(sys.equations, start.size());
    const Box y = hull(start, c.box);
    if (newton::newton_step(c.method, s, y, c.preconditioner).interior) return true;
    if (newton::at_most_one_root(s, y, c.preconditioner)) return true;
    const Eigen::MatrixXd jm = newton::midpoint(s.jacobian(y));
    if (jm.size() == 0 || !jm.allFinite()) return false;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm);
    if (!(lu.rcond() >= newton::NewtonOptions{}.singular_rcond)) return false;
    const Eigen::MatrixXd cy = lu.inverse();
    return cy.allFinite() && newton::at_most_one_root(s, y, cy);
  } catch (const std::invalid_argument&) {
    return false;
  }
}

}  // namespace linkbox::verify
