#include "formulate/to_lph.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace linkbox::formulate {

namespace {

using model::Powers;

class Lifter {
 public:
  explicit Lifter(const model::System& s) : original_(s) {
    for (auto& v : s.variables) out_.variables.push_back(v);
    for (size_t i = 0; i < s.variables.size(); ++i) out_.primary.push_back(static_cast<int>(i));
  }

  // The variable standing for monomial `m` (degree >= 1), created on first use.
  int variable_of(const Powers& m) {
    if (m.size() == 1 && m[0].second == 1) return m[0].first;
    if (auto it = aux_.find(m); it != aux_.end()) return it->second;
    bool all_even = true;
    for (auto [v, e] : m) all_even = all_even && e % 2 == 0;
    int index;
    if (all_even) {
      // m = h^2: one parabola on h's variable (x^2 -> q = x^2, x^4 -> q4 = q^2).
      Powers h = m;
      for (auto& [v, e] : h) e /= 2;
      const int x = variable_of(h);
      index = add_aux(m);
      out_.parabolic.push_back({index, x});
    } else {
      // Split off the lowest-index variable of odd exponent: m = x * rest, x not in `rest`'s
      // variable (rest has an even power of x, so its variable is an auxiliary or another x_j).
      size_t k = 0;
      while (m[k].second % 2 == 0) ++k;
      const int x = m[k].first;
      Powers rest = m;
      if (--rest[k].second == 0) rest.erase(rest.begin() + k);
      const int y = variable_of(rest);
      index = add_aux(m);
      out_.hyperbolic.push_back({index, x, y});
    }
    return index;
  }

  model::LphSystem&& take() { return std::move(out_); }
  model::LphSystem& system() { return out_; }

 private:
  int add_aux(const Powers& m) {
    const int index = static_cast<int>(out_.variables.size());
    Interval domain(1.0);
    std::string name;
    for (auto [v, e] : m) {
      const Interval& d = original_.variables[v].domain;
      domain *= e == 1 ? d : boost::numeric::pow(d, e);
      name += (name.empty() ? "" : "*") + original_.variables[v].name + (e == 1 ? "" : "^" + std::to_string(e));
    }
    out_.variables.push_back({name, domain});
    aux_.emplace(m, index);
    return index;
  }

  const model::System& original_;
  model::LphSystem out_;
  std::map<Powers, int> aux_;
};

}  // namespace

model::LphSystem to_lph(const model::System& system, std::vector<model::Polynomial>* lph_equations) {
  Lifter lifter(system);
  // p as sum coef * v + constant, each monomial replaced by its variable.
  auto linearise = [&](const model::Polynomial& p, std::vector<std::pair<int, Interval>>& terms, Interval& constant) {
    // Distinct monomials get distinct variables; the map only sorts the terms by index.
    std::map<int, Interval> coef;
    constant = Interval(0.0);
    for (auto& [powers, c] : p.terms()) {
      if (powers.empty()) {
        constant += c;
        continue;
      }
      const int v = lifter.variable_of(powers);
      auto [it, fresh] = coef.emplace(v, c);
      if (!fresh) it->second += c;
    }
    for (auto& [v, c] : coef) terms.emplace_back(v, c);
  };
  for (const auto& p : system.equations) {
    model::LinearEquation eq;
    Interval constant;
    linearise(p, eq.terms, constant);
    eq.rhs = -constant;
    lifter.system().linear.push_back(std::move(eq));
  }
  for (const auto& c : system.inequalities) {
    model::LinearInequality in;
    Interval constant;
    linearise(c.g, in.terms, constant);
    in.rhs = -constant;
    in.name = c.name;
    lifter.system().inequalities.push_back(std::move(in));
  }
  model::LphSystem lph = lifter.take();
  if (lph_equations) *lph_equations = lph_polynomials(lph).equations;
  return lph;
}

model::System lph_polynomials(const model::LphSystem& lph, const std::vector<std::string>& linear_names) {
  using model::Polynomial;
  model::System s;
  s.variables = lph.variables;
  for (size_t k = 0; k < lph.linear.size(); ++k) {
    const auto& eq = lph.linear[k];
    Polynomial p = Polynomial::constant(-eq.rhs);
    for (auto& [v, c] : eq.terms) p += Polynomial::variable(v) * c;
    s.equations.push_back(std::move(p));
    s.equation_names.push_back(k < linear_names.size() ? linear_names[k] : "linear " + std::to_string(k + 1));
  }
  for (auto& e : lph.parabolic) {
    s.equations.push_back(Polynomial::variable(e.q) - Polynomial::variable(e.x).pow(2));
    s.equation_names.push_back(lph.variables[e.q].name + " = " + lph.variables[e.x].name + "^2");
  }
  for (auto& e : lph.hyperbolic) {
    s.equations.push_back(Polynomial::variable(e.b) - Polynomial::variable(e.x) * Polynomial::variable(e.y));
    s.equation_names.push_back(lph.variables[e.b].name + " = " + lph.variables[e.x].name + " * " +
                               lph.variables[e.y].name);
  }
  for (auto& in : lph.inequalities) {
    Polynomial g = Polynomial::constant(-in.rhs);
    for (auto& [v, c] : in.terms) g += Polynomial::variable(v) * c;
    s.inequalities.push_back({std::move(g), false, in.name});
  }
  return s;
}

}  // namespace linkbox::formulate
