#include "verify/coordinate_subspace.hpp"

#include <algorithm>
#include <numeric>

namespace linkbox::verify {

namespace {

bool vanishes_on(const model::Polynomial& p, int k) {
  for (auto& [powers, c] : p.terms()) {
    bool holds_k = false;
    for (auto& [v, e] : powers) holds_k = holds_k || v == k;
    if (!holds_k) return false;  // add_term keeps no exact zero
  }
  return true;
}

// p at x_k = 0, with the variables after k moved down by one.
model::Polynomial restrict_to(const model::Polynomial& p, int k) {
  model::Polynomial r;
  for (auto& [powers, c] : p.terms()) {
    model::Powers q;
    bool holds_k = false;
    for (auto& [v, e] : powers) {
      holds_k = holds_k || v == k;
      q.emplace_back(v > k ? v - 1 : v, e);
    }
    if (!holds_k) r += model::Polynomial::monomial(q, c);
  }
  return r;
}

}  // namespace

std::optional<CoordinateSubspace> coordinate_subspace(const std::vector<model::Polynomial>& equations, size_t n) {
  if (n < 3 || equations.size() < n) return std::nullopt;
  for (int k = 0; k < static_cast<int>(n); ++k) {
    CoordinateSubspace s;
    s.variable = k;
    for (int e = 0; e < static_cast<int>(equations.size()); ++e)
      (vanishes_on(equations[e], k) ? s.vanishing : s.rest).push_back(e);
    if (s.rest.size() + 2 != n) continue;
    std::vector<model::Polynomial> restricted;
    for (int e : s.rest) restricted.push_back(restrict_to(equations[e], k));
    for (int e : s.vanishing) s.slopes.push_back(equations[e].derivative(k));
    s.restricted = std::make_shared<const model::CompiledSystem>(restricted, n - 1);
    return s;
  }
  return std::nullopt;
}

std::vector<int> dropped_for(const CoordinateSubspace& s, size_t v) {
  std::vector<int> dropped;
  for (size_t i = 0; i < s.vanishing.size(); ++i)
    if (i != v) dropped.push_back(s.vanishing[i]);
  return dropped;
}

std::vector<size_t> keep_order(const CoordinateSubspace& s, const Box& point) {
  std::vector<double> steep;
  for (auto& d : s.slopes) steep.push_back(norm(d.eval(point)));
  std::vector<size_t> order(steep.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return steep[a] > steep[b]; });
  return order;
}

bool spans_on_subspace(const CoordinateSubspace& s, const Box& box, int parameter) {
  const int k = s.variable;
  if (parameter == k || k < 0 || k >= static_cast<int>(box.size()) || !zero_in(box[k])) return false;
  Box on_s = box;
  on_s.erase(on_s.begin() + k);
  return newton::arc_over(s.restricted, on_s, parameter > k ? parameter - 1 : parameter).certified;
}

}  // namespace linkbox::verify
