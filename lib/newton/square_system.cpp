#include "newton/square_system.hpp"

#include <numeric>
#include <stdexcept>

namespace linkbox::newton {

SquareSystem::SquareSystem(std::vector<model::Polynomial> equations, std::vector<int> unknowns,
                           Box base)
    : equations_(std::move(equations)), unknowns_(std::move(unknowns)), base_(std::move(base)) {
  if (equations_.size() != unknowns_.size())
    throw std::invalid_argument("SquareSystem: as many unknowns as equations expected");
  const int n = static_cast<int>(base_.size());
  std::vector<bool> seen(base_.size(), false);
  for (int u : unknowns_) {
    if (u < 0 || u >= n || seen[u]) throw std::invalid_argument("SquareSystem: bad unknown index");
    seen[u] = true;
  }
  for (auto& e : equations_)
    for (int v : e.variables())
      if (v >= n) throw std::invalid_argument("SquareSystem: equation uses a variable beyond the box");
  partials_.resize(equations_.size());
  for (size_t i = 0; i < equations_.size(); ++i)
    for (int u : unknowns_) partials_[i].push_back(equations_[i].derivative(u));
}

SquareSystem SquareSystem::all_unknown(const std::vector<model::Polynomial>& equations, size_t n) {
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  return SquareSystem(equations, std::move(all), Box(n, Interval(0.0)));
}

Box SquareSystem::embed(const Box& x) const {
  Box full = base_;
  for (size_t j = 0; j < unknowns_.size(); ++j) full[unknowns_[j]] = x[j];
  return full;
}

Box SquareSystem::restrict(const Box& full) const {
  Box x;
  for (int u : unknowns_) x.push_back(full[u]);
  return x;
}

IVector SquareSystem::values(const Box& x) const {
  Box full = embed(x);
  IVector f(size());
  for (int i = 0; i < size(); ++i) f(i) = equations_[i].eval(full);
  return f;
}

IMatrix SquareSystem::jacobian(const Box& x) const {
  Box full = embed(x);
  IMatrix j(size(), size());
  for (int i = 0; i < size(); ++i)
    for (int k = 0; k < size(); ++k) j(i, k) = partials_[i][k].eval(full);
  return j;
}

Eigen::VectorXd SquareSystem::values_at(const Eigen::VectorXd& x) const {
  return midpoint(values(point_box(x)));
}

Eigen::MatrixXd SquareSystem::jacobian_at(const Eigen::VectorXd& x) const {
  return midpoint(jacobian(point_box(x)));
}

Box point_box(const Eigen::VectorXd& x) {
  Box b;
  for (Eigen::Index i = 0; i < x.size(); ++i) b.emplace_back(x(i));
  return b;
}

}  // namespace linkbox::newton
