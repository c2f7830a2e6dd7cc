#include "model/compiled.hpp"

#include <algorithm>
#include <stdexcept>

namespace linkbox::model {

CompiledSystem::CompiledSystem(const std::vector<Polynomial>& equations, const std::vector<Link>& links,
                               size_t variables, Arith arith)
    : involved_(equations.size()), max_degree_(variables, 1) {
  for (size_t i = 0; i < equations.size(); ++i) {
    const Polynomial& p = equations[i];
    for (int v : p.variables()) {
      if (v < 0 || v >= static_cast<int>(variables))
        throw std::invalid_argument("CompiledSystem: an equation uses a variable beyond the box");
      max_degree_[v] = std::max(max_degree_[v], p.degree_in(v));
      involved_[i].push_back(v);
    }
    values_.push_back(add(p, arith));
  }
  for (size_t i = 0; i < equations.size(); ++i)
    for (int v : involved_[i]) {
      entry_row_.push_back(static_cast<int>(i));
      entry_col_.push_back(v);
      partials_.push_back(add(equations[i].derivative(v), arith));
    }
  add_links(links, variables);
  int offset = 0;
  for (int d : max_degree_) {
    power_offset_.push_back(offset);
    offset += d;
  }
  power_count_ = offset;
}

CompiledSystem::Compiled CompiledSystem::add(const Polynomial& p, Arith arith) {
  Compiled c{static_cast<int>(terms_.size()), 0};
  const NearestScope nearest;  // every term's midpoint under one switch of the rounding mode
  for (auto& [powers, coef] : p.terms()) {
    const Interval k = coefficient_for(arith, coef);
    Term t{as_fast(k), nearest.median(k), static_cast<int>(factors_.size()), 0};
    for (auto [v, e] : powers) factors_.emplace_back(v, e);
    t.end = static_cast<int>(factors_.size());
    terms_.push_back(t);
  }
  c.end = static_cast<int>(terms_.size());
  return c;
}

void CompiledSystem::add_links(const std::vector<Link>& links, size_t variables) {
  for (size_t k = 0; k < links.size(); ++k) {
    const Link& l = links[k];
    if (l.y < 0 || l.a < 0 || l.y >= static_cast<int>(variables) || l.a >= static_cast<int>(variables) || l.y == l.a)
      throw std::invalid_argument("CompiledSystem: a link uses a variable beyond the box");
    const int row = static_cast<int>(values_.size() + k);
    involved_.push_back({std::min(l.y, l.a), std::max(l.y, l.a)});
    for (int v : involved_.back()) {
      entry_row_.push_back(row);
      entry_col_.push_back(v);
      link_entries_.emplace_back(static_cast<int>(k), v == l.y);
    }
    links_.push_back(l);
  }
}

FastInterval CompiledSystem::link_value(size_t k, const Interval& y, const Interval& a) const {
  return as_fast(row_value(links_[k], y, a));
}

FastInterval CompiledSystem::link_entry(size_t e, const Box& x) const {
  const auto [k, is_y] = link_entries_[e - partials_.size()];
  if (is_y) return FastInterval(1.0);
  return as_fast(row_derivative(links_[k], x[links_[k].a]));
}

namespace {
FastInterval* scratch(int size) {
  thread_local std::vector<FastInterval> powers;
  if (static_cast<int>(powers.size()) < size) powers.resize(size);
  return powers.data();
}
}  // namespace

FastInterval* CompiledSystem::fill_powers(const Box& x) const {
  FastInterval* powers = scratch(power_count_);
  for (size_t v = 0; v < max_degree_.size(); ++v) {
    FastInterval* p = powers + power_offset_[v];
    const FastInterval xv(x[v].lower(), x[v].upper());
    p[0] = xv;
    // Each power as such, not as repeated products: x^2 of [-1, 1] is [0, 1], not [-1, 1].
    for (int e = 2; e <= max_degree_[v]; ++e) p[e - 1] = boost::numeric::pow(xv, e);
  }
  return powers;
}

FastInterval CompiledSystem::sum(const Compiled& c, const FastInterval* powers) const {
  FastInterval s(0.0);
  for (int t = c.begin; t < c.end; ++t) {
    const Term& term = terms_[t];
    FastInterval m = term.coef;
    for (int k = term.begin; k < term.end; ++k) {
      const auto [v, e] = factors_[k];
      m *= powers[power_offset_[v] + e - 1];
    }
    s += m;
  }
  return s;
}

double CompiledSystem::sum_operations(const std::vector<Compiled>& sums) const {
  double n = 0;
  for (auto& c : sums)
    for (int t = c.begin; t < c.end; ++t) n += 1 + terms_[t].end - terms_[t].begin;  // its products and the sum
  return n;
}

double CompiledSystem::value_operations() const {
  return power_count_ + sum_operations(values_) + kLinkOperations * static_cast<double>(links_.size());
}

double CompiledSystem::jacobian_operations() const {
  return power_count_ + sum_operations(partials_) + 2 * kLinkOperations * static_cast<double>(links_.size());
}

// A partial derivative has one term per term naming the variable, with one factor fewer where
// its exponent is 1 (Polynomial::derivative merges none: distinct terms stay distinct).
CompiledSystem::Shape CompiledSystem::shape_of(const std::vector<Polynomial>& equations, const std::vector<Link>& links,
                                               size_t variables) {
  std::vector<int> degree(variables, 1);
  double values = 0, partials = 0;
  int nonzeros = 0;
  for (auto& p : equations) {
    for (auto& [powers, coef] : p.terms()) {
      const double factors = static_cast<double>(powers.size());
      values += 1 + factors;
      for (auto [v, e] : powers) {
        if (v < 0 || v >= static_cast<int>(variables))
          throw std::invalid_argument("CompiledSystem: an equation uses a variable beyond the box");
        degree[v] = std::max(degree[v], e);
        partials += 1 + factors - (e == 1);
      }
    }
    nonzeros += static_cast<int>(p.variables().size());
  }
  double powers = 0;
  for (int d : degree) powers += d;
  const double link_count = static_cast<double>(links.size());
  Shape s;
  s.value_operations = powers + values + kLinkOperations * link_count;
  s.jacobian_operations = powers + partials + 2 * kLinkOperations * link_count;
  s.rows = static_cast<int>(equations.size() + links.size());
  s.cols = static_cast<int>(variables);
  s.nonzeros = nonzeros + 2 * static_cast<int>(links.size());
  return s;
}

void CompiledSystem::values(const Box& x, FastInterval* f) const {
  const FastInterval* powers = fill_powers(x);
  for (size_t i = 0; i < values_.size(); ++i) f[i] = sum(values_[i], powers);
  for (size_t k = 0; k < links_.size(); ++k) f[values_.size() + k] = link_value(k, x[links_[k].y], x[links_[k].a]);
}

void CompiledSystem::jacobian(const Box& x, FastInterval* j) const {
  const FastInterval* powers = fill_powers(x);
  for (size_t e = 0; e < partials_.size(); ++e) j[e] = sum(partials_[e], powers);
  for (size_t e = partials_.size(); e < entry_row_.size(); ++e) j[e] = link_entry(e, x);
}

void CompiledSystem::evaluate(const Box& x, FastInterval* f, FastInterval* j) const {
  const FastInterval* powers = fill_powers(x);
  for (size_t i = 0; i < values_.size(); ++i) f[i] = sum(values_[i], powers);
  for (size_t e = 0; e < partials_.size(); ++e) j[e] = sum(partials_[e], powers);
  for (size_t k = 0; k < links_.size(); ++k) f[values_.size() + k] = link_value(k, x[links_[k].y], x[links_[k].a]);
  for (size_t e = partials_.size(); e < entry_row_.size(); ++e) j[e] = link_entry(e, x);
}

void CompiledSystem::values_at(const double* y, FastInterval* f) const {
  FastInterval* powers = scratch(power_count_);
  for (size_t v = 0; v < max_degree_.size(); ++v) {
    FastInterval* p = powers + power_offset_[v];
    p[0] = FastInterval(y[v]);
    for (int e = 2; e <= max_degree_[v]; ++e) p[e - 1] = p[e - 2] * p[0];  // a point: products are as tight
  }
  for (size_t i = 0; i < values_.size(); ++i) f[i] = sum(values_[i], powers);
  for (size_t k = 0; k < links_.size(); ++k)
    f[values_.size() + k] = link_value(k, Interval(y[links_[k].y]), Interval(y[links_[k].a]));
}

const double* CompiledSystem::float_powers(const double* y) const {
  thread_local std::vector<double> powers;
  if (static_cast<int>(powers.size()) < power_count_) powers.resize(power_count_);
  for (size_t v = 0; v < max_degree_.size(); ++v) {
    double* p = powers.data() + power_offset_[v];
    p[0] = y[v];
    for (int e = 2; e <= max_degree_[v]; ++e) p[e - 1] = p[e - 2] * y[v];
  }
  return powers.data();
}

double CompiledSystem::float_sum(const Compiled& c, const double* powers) const {
  double s = 0;
  for (int t = c.begin; t < c.end; ++t) {
    const Term& term = terms_[t];
    double m = term.mid;
    for (int k = term.begin; k < term.end; ++k) m *= powers[power_offset_[factors_[k].first] + factors_[k].second - 1];
    s += m;
  }
  return s;
}

void CompiledSystem::values_float(const double* y, double* f) const {
  const double* powers = float_powers(y);
  for (size_t i = 0; i < values_.size(); ++i) f[i] = float_sum(values_[i], powers);
  for (size_t k = 0; k < links_.size(); ++k) f[values_.size() + k] = row_value_float(links_[k], y);
}

void CompiledSystem::jacobian_float(const double* y, double* j) const {
  const double* powers = float_powers(y);
  for (size_t e = 0; e < partials_.size(); ++e) j[e] = float_sum(partials_[e], powers);
  for (size_t e = partials_.size(); e < entry_row_.size(); ++e) {
    const auto [k, is_y] = link_entries_[e - partials_.size()];
    j[e] = is_y ? 1.0 : row_derivative_float(links_[k], y);
  }
}

}  // namespace linkbox::model
