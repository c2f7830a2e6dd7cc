#include "solve/bisector.hpp"

#include "model/block_triangular.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace linkbox::solve {

std::string to_string(Bisect b) {
  switch (b) {
    case Bisect::automatic: return "auto";
    case Bisect::widest: return "widest";
    case Bisect::round_robin: return "round-robin";
    case Bisect::smear: return "smear";
  }
  return "?";
}

Bisect parse_bisect(const std::string& name) {
  for (Bisect b : {Bisect::automatic, Bisect::widest, Bisect::round_robin, Bisect::smear})
    if (to_string(b) == name) return b;
  throw std::invalid_argument("unknown bisection rule '" + name + "' (known: auto, widest, round-robin, smear)");
}

namespace {

// Whether each block of `b` (square: every column matched) has a regular Jacobian of its own
// rows at two points of the domain, chosen away from the symmetries a case's domains often
// have. A block square only in its pattern (a circle written twice) has a curve of roots, and
// splitting it first would trace that curve to sigma.
bool regular_blocks(const model::CompiledSystem& c, const model::BlockTriangular& b, const Box& domain) {
  const int n = c.cols();
  std::vector<int> size(n, 0), place(n), row_column(c.rows(), -1);
  for (int k = 0; k < n; ++k) {
    place[k] = size[b.block[k]]++;
    if (b.row[k] >= 0) row_column[b.row[k]] = k;
  }
  std::vector<double> y(n), j(c.nonzeros());
  for (double start : {0.3183, 0.7071}) {
    for (int k = 0; k < n; ++k) {
      if (!is_finite(domain[k])) return false;
      const double t = std::fmod(start + 0.6180339887 * k, 1.0);  // a different place in each side
      y[k] = domain[k].lower() + t * (domain[k].upper() - domain[k].lower());
    }
    c.jacobian_float(y.data(), j.data());
    std::vector<Eigen::MatrixXd> blocks(n);
    for (int k = 0; k < n; ++k) blocks[b.block[k]].setZero(size[b.block[k]], size[b.block[k]]);
    for (int e = 0; e < c.nonzeros(); ++e) {
      const int r = c.entry_row(e), k = c.entry_col(e), own = row_column[r];
      if (own >= 0 && b.block[own] == b.block[k]) blocks[b.block[k]](place[own], place[k]) = j[e];
    }
    for (const Eigen::MatrixXd& a : blocks)
      if (a.size() > 0 && (!a.allFinite() || Eigen::FullPivLU<Eigen::MatrixXd>(a).rank() < a.rows())) return false;
  }
  return true;
}

}  // namespace

Bisector::Bisector(Bisect rule, const formulate::SubProblem& sub, double sigma)
    : rule_(rule), dims_(sub.split_dims), sigma_(sigma) {
  const model::System& system = sub.pruned();
  if (dims_.empty())
    for (size_t i = 0; i < sub.system.variables.size(); ++i) dims_.push_back(static_cast<int>(i));
  if (rule_ == Bisect::automatic) rule_ = sub.clipping ? Bisect::widest : Bisect::smear;
  if (rule_ == Bisect::smear) {
    compiled_ = std::make_shared<const model::CompiledSystem>(system.equations, system.links, system.variables.size());
    const model::BlockTriangular blocks =
        model::block_triangular(compiled_->rows(), compiled_->cols(), model::pattern_of(*compiled_));
    if (compiled_->rows() == compiled_->cols() && blocks.square && blocks.blocks > 1 &&
        regular_blocks(*compiled_, blocks, system.domain()))
      block_ = blocks.block;
  }
}

int Bisector::choose(const Box& box, int depth) const {
  if (rule_ == Bisect::smear)
    if (const int d = smear(box); d >= 0) return d;
  if (rule_ == Bisect::round_robin) {
    const int n = static_cast<int>(dims_.size());
    for (int k = 0; k < n; ++k) {
      const int d = dims_[(depth + k) % n];
      if (box[d].upper() - box[d].lower() > sigma_) return d;
    }
  }
  return widest_dimension(box, dims_);
}

// The first block with a side over sigma; -1 where the system is one block.
int Bisector::first_open_block(const Box& box) const {
  int first = -1;
  for (int d : dims_)
    if (d < static_cast<int>(block_.size()) && box[d].upper() - box[d].lower() > sigma_ &&
        (first < 0 || block_[d] < first))
      first = block_[d];
  return first;
}

// A heuristic, so plain floating point (no rounding mode): a wrong guess costs time only.
int Bisector::smear(const Box& box) const {
  const model::CompiledSystem& c = *compiled_;
  std::vector<FastInterval> j(c.nonzeros());
  c.jacobian(box, j.data());
  std::vector<double> share(c.nonzeros()), row_total(c.rows(), 0.0), score(c.cols(), 0.0);
  for (int e = 0; e < c.nonzeros(); ++e) {
    const int v = c.entry_col(e);
    const double magnitude = std::max(std::fabs(j[e].lower()), std::fabs(j[e].upper()));
    share[e] = magnitude * (box[v].upper() - box[v].lower());
    if (!std::isfinite(share[e])) return -1;
    row_total[c.entry_row(e)] += share[e];
  }
  for (int e = 0; e < c.nonzeros(); ++e)
    if (row_total[c.entry_row(e)] > 0) score[c.entry_col(e)] += share[e] / row_total[c.entry_row(e)];
  // Only among sides at least 1/8 of the widest: smear alone can keep splitting the same
  // few sides while others stay wide and propagation gets no grip (the rigid 6R: 0.9 s with
  // no floor, 0.24 s with 1/4, 0.35 s with 1/16; Eco9 3.0 s with 1/4, 2.9 s with 1/16).
  // Among the sides of the first block (model/block_triangular.hpp) with one over sigma: the
  // blocks after it get their grip from it.
  const int first = first_open_block(box);
  const auto in_scope = [&](int d) { return first < 0 || (d < c.cols() && block_[d] == first); };
  double widest = 0;
  for (int d : dims_)
    if (in_scope(d)) widest = std::max(widest, box[d].upper() - box[d].lower());
  const double floor = std::max(sigma_, widest / 8);
  int best = -1;
  for (int d : dims_)
    if (d < c.cols() && in_scope(d) && box[d].upper() - box[d].lower() > floor && (best < 0 || score[d] > score[best]))
      best = d;
  return best >= 0 && score[best] > 0 ? best : -1;
}

}  // namespace linkbox::solve
