#include "formulate/linear_elimination.hpp"

#include "input/input_error.hpp"

#include <set>

namespace linkbox::formulate {

using model::Polynomial;

namespace {

// p with variable `var` replaced by the polynomial r.
Polynomial substitute(const Polynomial& p, int var, const Polynomial& r) {
  Polynomial out;
  for (auto& [powers, c] : p.terms()) {
    Polynomial term = Polynomial::constant(c);
    for (auto [v, e] : powers) term = term * (v == var ? r.pow(e) : Polynomial::variable(v).pow(e));
    out += term;
  }
  return out;
}

size_t nonlinear_monomials(const std::vector<NamedEquation>& eqs) {
  std::set<model::Powers> m;
  for (auto& eq : eqs)
    for (auto& [powers, c] : eq.p.terms()) {
      int degree = 0;
      for (auto [v, e] : powers) degree += e;
      if (degree >= 2) m.insert(powers);
    }
  return m.size();
}

}  // namespace

std::vector<Affine> eliminate_linear(std::vector<NamedEquation>& eqs, std::vector<model::Variable>& vars, const std::string& file) {
  std::vector<Affine> as(vars.size());
  for (size_t v = 0; v < vars.size(); ++v) as[v].variable = static_cast<int>(v);
  auto eliminate = [&](size_t k, int x, const Interval& offset, int y, const Interval& scale) {
    const Polynomial r = y < 0 ? Polynomial::constant(offset)
                               : Polynomial::constant(offset) + Polynomial::variable(y) * scale;
    eqs.erase(eqs.begin() + k);
    for (auto& eq : eqs) eq.p = substitute(eq.p, x, r);
    for (auto& a : as)
      if (a.variable == x) a = y < 0 ? Affine{-1, Interval(1.0), a.offset + a.scale * offset}
                                     : Affine{y, a.scale * scale, a.offset + a.scale * offset};
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = 0; k < eqs.size() && !changed; ++k) {
      const NamedEquation& eq = eqs[k];
      if (eq.p.total_degree() != 1) continue;
      const std::vector<int> v = eq.p.variables();
      if (v.size() > 2) continue;
      auto coef = [&](int var) { return eq.p.terms().at(model::Powers{{var, 1}}); };
      const Interval k0 = eq.p.constant_term();
      if (v.size() == 1) {
        const Interval c = coef(v[0]);
        if (zero_in(c)) continue;
        Interval x = -k0 / c;
        if (!intersect(x, vars[v[0]].domain, x))
          throw input::InputError(file, eq.line,
                             "the linkage cannot be assembled: '" + eq.name + "' puts " + vars[v[0]].name +
                                 " outside its range");
        eliminate(k, v[0], x, -1, Interval(0.0));
        changed = true;
        continue;
      }
      const bool first = norm(coef(v[0])) >= norm(coef(v[1]));
      const int x = first ? v[0] : v[1], y = first ? v[1] : v[0];
      const Interval cx = coef(x), cy = coef(y);
      if (zero_in(cx)) continue;
      const Interval offset = -k0 / cx, scale = -cy / cx;
      std::vector<NamedEquation> trial = eqs;
      trial.erase(trial.begin() + k);
      const size_t before = nonlinear_monomials(trial);
      const Polynomial r = Polynomial::constant(offset) + Polynomial::variable(y) * scale;
      for (auto& t : trial) t.p = substitute(t.p, x, r);
      if (nonlinear_monomials(trial) > before) continue;
      // y only where x = offset + scale y lies in x's domain.
      if (!zero_in(scale)) {
        const Interval allowed = (vars[x].domain - offset) / scale;
        if (!intersect(vars[y].domain, allowed, vars[y].domain))
          throw input::InputError(file, eq.line,
                             "the linkage cannot be assembled: '" + eq.name + "' puts " + vars[x].name +
                                 " outside its range");
      }
      eliminate(k, x, offset, y, scale);
      changed = true;
    }
  }
  return as;
}

}  // namespace linkbox::formulate
