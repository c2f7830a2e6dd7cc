#include "newton/square_system.hpp"

#include <numeric>
#include <stdexcept>

namespace linkbox::newton {

namespace {

std::shared_ptr<const model::CompiledSystem> compile(const std::vector<model::Polynomial>& equations, size_t n) {
  for (auto& e : equations)
    for (int v : e.variables())
      if (v >= static_cast<int>(n)) throw std::invalid_argument("SquareSystem: equation uses a variable beyond the box");
  return std::make_shared<const model::CompiledSystem>(equations, n);
}

}  // namespace

SquareSystem::SquareSystem(std::vector<model::Polynomial> equations, std::vector<int> unknowns, Box base)
    : SquareSystem(compile(equations, base.size()), std::move(unknowns), base) {}  // base copied: argument order is unspecified

SquareSystem::SquareSystem(std::shared_ptr<const model::CompiledSystem> compiled, std::vector<int> unknowns, Box base)
    : unknowns_(std::move(unknowns)), base_(std::move(base)), compiled_(std::move(compiled)) {
  if (static_cast<size_t>(compiled_->rows()) != unknowns_.size())
    throw std::invalid_argument("SquareSystem: as many unknowns as equations expected");
  if (static_cast<size_t>(compiled_->cols()) != base_.size())
    throw std::invalid_argument("SquareSystem: the system and the box differ in size");
  const int n = static_cast<int>(base_.size());
  std::vector<bool> seen(base_.size(), false);
  for (int u : unknowns_) {
    if (u < 0 || u >= n || seen[u]) throw std::invalid_argument("SquareSystem: bad unknown index");
    seen[u] = true;
  }
  std::vector<int> column(base_.size(), -1);
  for (size_t k = 0; k < unknowns_.size(); ++k) column[unknowns_[k]] = static_cast<int>(k);
  for (int e = 0; e < compiled_->nonzeros(); ++e) unknown_column_.push_back(column[compiled_->entry_col(e)]);
}

SquareSystem SquareSystem::all_unknown(const std::vector<model::Polynomial>& equations, size_t n) {
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  return SquareSystem(equations, std::move(all), Box(n, Interval(0.0)));
}

SquareSystem SquareSystem::all_unknown(std::shared_ptr<const model::CompiledSystem> compiled) {
  std::vector<int> all(compiled->cols());
  std::iota(all.begin(), all.end(), 0);
  const size_t n = all.size();
  return SquareSystem(std::move(compiled), std::move(all), Box(n, Interval(0.0)));
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
  std::vector<FastInterval> v(compiled_->rows());
  {
    RoundingGuard guard;
    compiled_->values(embed(x), v.data());
  }
  IVector f(size());
  for (int i = 0; i < size(); ++i) f(i) = Interval(v[i].lower(), v[i].upper());
  return f;
}

IMatrix SquareSystem::jacobian(const Box& x) const {
  std::vector<FastInterval> d(compiled_->nonzeros());
  {
    RoundingGuard guard;
    compiled_->jacobian(embed(x), d.data());
  }
  IMatrix j = IMatrix::Constant(size(), size(), Interval(0.0));
  for (int e = 0; e < compiled_->nonzeros(); ++e)
    if (const int k = unknown_column_[e]; k >= 0) j(compiled_->entry_row(e), k) = Interval(d[e].lower(), d[e].upper());
  return j;
}

std::vector<double> SquareSystem::full_point(const Eigen::VectorXd& x) const {
  std::vector<double> y;
  for (auto& v : base_) y.push_back(median(v));
  for (size_t j = 0; j < unknowns_.size(); ++j) y[unknowns_[j]] = x(static_cast<Eigen::Index>(j));
  return y;
}

Eigen::VectorXd SquareSystem::values_at(const Eigen::VectorXd& x) const {
  const std::vector<double> y = full_point(x);
  std::vector<double> f(compiled_->rows());
  compiled_->values_float(y.data(), f.data());
  return Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
}

Eigen::MatrixXd SquareSystem::jacobian_at(const Eigen::VectorXd& x) const {
  const std::vector<double> y = full_point(x);
  std::vector<double> d(compiled_->nonzeros());
  compiled_->jacobian_float(y.data(), d.data());
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(size(), size());
  for (int e = 0; e < compiled_->nonzeros(); ++e)
    if (const int k = unknown_column_[e]; k >= 0) j(compiled_->entry_row(e), k) = d[e];
  return j;
}

Box point_box(const Eigen::VectorXd& x) {
  Box b;
  for (Eigen::Index i = 0; i < x.size(); ++i) b.emplace_back(x(i));
  return b;
}

}  // namespace linkbox::newton
