#include "prune/newton_substitution.hpp"

#include <cmath>
#include <map>

namespace linkbox::prune {

namespace {

bool is_unit(const Interval& c) { return c.lower() == c.upper() && std::fabs(c.lower()) == 1; }

// The variable of a degree-1 term, -1 for the constant.
int variable_of(const model::Powers& powers) { return powers.empty() ? -1 : powers.front().first; }

}  // namespace

NewtonSubstitution::NewtonSubstitution(const model::CompiledSystem& system,
                                       const std::vector<model::Polynomial>& equations,
                                       const std::vector<int>& candidates) {
  const int n = system.cols();
  std::vector<int> definition_of(n, -1);
  std::vector<bool> defining(system.rows(), false), named(n, false);
  for (int v : candidates) {
    if (v < 0 || v >= n || definition_of[v] >= 0 || named[v]) continue;
    for (size_t r = 0; r < equations.size(); ++r) {
      const model::Polynomial& p = equations[r];
      if (defining[r] || p.total_degree() != 1) continue;
      Interval own(0.0);
      bool clash = false;
      for (auto& [powers, c] : p.terms()) {
        const int x = variable_of(powers);
        if (x == v) own = c;
        clash = clash || (x >= 0 && definition_of[x] >= 0);
      }
      if (clash || !is_unit(own)) continue;
      // v = -(p - own v) / own, exactly: own is +-1.
      Definition d{v, Interval(0.0), {}};
      for (auto& [powers, c] : p.terms()) {
        const Interval term = own.lower() > 0 ? -c : c;
        const int x = variable_of(powers);
        if (x < 0) d.constant = term;
        else if (x != v) d.terms.push_back({x, term}), named[x] = true;
      }
      definition_of[v] = static_cast<int>(definitions_.size());
      definitions_.push_back(std::move(d));
      defining[r] = true;
      break;
    }
  }
  if (definitions_.empty()) return;
  for (int r = 0; r < system.rows(); ++r)
    if (!defining[r]) rows_.push_back(r);
  for (int k = 0; k < n; ++k)
    if (definition_of[k] < 0) cols_.push_back(k);
  build_pattern(system, definition_of);
}

// Entry (i, k) of G' sums F'(row i, col k) and F'(row i, v) coef for each v = ... + coef x_k.
void NewtonSubstitution::build_pattern(const model::CompiledSystem& system, const std::vector<int>& definition_of) {
  std::vector<int> reduced_row(system.rows(), -1), reduced_col(system.cols(), -1);
  for (int i = 0; i < rows(); ++i) reduced_row[rows_[i]] = i;
  for (int k = 0; k < cols(); ++k) reduced_col[cols_[k]] = k;
  std::map<std::pair<int, int>, int> index;
  const auto entry = [&](int i, int k) {
    auto [at, added] = index.emplace(std::pair{i, k}, nonzeros());
    if (added) entry_row_.push_back(i), entry_col_.push_back(k);
    return at->second;
  };
  for (int e = 0; e < system.nonzeros(); ++e) {
    const int i = reduced_row[system.entry_row(e)], col = system.entry_col(e);
    if (i < 0) continue;
    if (definition_of[col] < 0) {
      contributions_.push_back({e, entry(i, reduced_col[col]), FastInterval(1.0), true});
      continue;
    }
    for (auto& [x, c] : definitions_[definition_of[col]].terms)
      contributions_.push_back({e, entry(i, reduced_col[x]), as_fast(c), false});
  }
}

void NewtonSubstitution::reduce(const FastInterval* jacobian, FastInterval* reduced) const {
  std::fill(reduced, reduced + nonzeros(), FastInterval(0.0));
  for (const Contribution& c : contributions_)
    reduced[c.reduced] += c.unit ? jacobian[c.entry] : jacobian[c.entry] * c.coef;
}

Interval NewtonSubstitution::value(const Definition& d, const Box& x) const {
  Interval s = d.constant;
  for (auto& [k, c] : d.terms) s += c * x[k];
  return s;
}

void NewtonSubstitution::substitute(Box& x) const {
  for (const Definition& d : definitions_) x[d.variable] = value(d, x);
}

bool NewtonSubstitution::narrow(Box& x, bool& narrowed) const {
  for (const Definition& d : definitions_) {
    Interval& v = x[d.variable];
    const Interval was = v;
    if (!intersect(was, value(d, x), v)) return false;
    narrowed = narrowed || v.lower() != was.lower() || v.upper() != was.upper();
  }
  return true;
}

}  // namespace linkbox::prune
