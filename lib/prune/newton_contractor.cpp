#include "prune/newton_contractor.hpp"

#include <Eigen/LU>

#include <stdexcept>

namespace linkbox::prune {

namespace {
newton::SquareSystem make_system(const std::vector<model::Polynomial>& equations, size_t n, Arith arith) {
  if (equations.size() != n)
    throw std::invalid_argument("--prune newton needs a square system; this one has " +
                                std::to_string(equations.size()) + " equations in " + std::to_string(n) + " variables");
  std::vector<model::Polynomial> used;
  for (auto& p : equations) {
    model::Polynomial q;
    for (auto& [powers, c] : p.terms()) q += model::Polynomial::monomial(powers, coefficient_for(arith, c));
    used.push_back(std::move(q));
  }
  return newton::SquareSystem::all_unknown(used, n);
}
}  // namespace

IntervalNewton::IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith,
                               newton::Method method)
    : system_(make_system(equations, variables, arith)), method_(method) {}

Outcome IntervalNewton::contract(Box& box) {
  // Where the Jacobian is singular Newton removes nothing; the plain range test still does.
  const newton::IVector f = system_.values(box);
  for (int i = 0; i < f.size(); ++i)
    if (!zero_in(f(i))) return Outcome::empty;
  const Eigen::MatrixXd jm = newton::midpoint(system_.jacobian(box));
  if (!jm.allFinite()) return Outcome::unchanged;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm);
  if (!(lu.rcond() > 1e-14)) return Outcome::unchanged;
  const Eigen::MatrixXd c = lu.inverse();
  if (!c.allFinite()) return Outcome::unchanged;
  const newton::NewtonStep step = newton::newton_step(method_, system_, box, c);
  if (step.excluded) return Outcome::empty;
  bool shrunk = false;
  for (size_t i = 0; i < box.size(); ++i) {
    Interval x;
    if (!intersect(box[i], step.image[i], x)) return Outcome::empty;
    if (x.lower() != box[i].lower() || x.upper() != box[i].upper()) box[i] = x, shrunk = true;
  }
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
