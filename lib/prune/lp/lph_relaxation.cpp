#include "prune/lp/lph_relaxation.hpp"

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

namespace {

// Any double inside the interval works as the LP coefficient; the midpoint keeps the
// remainder (moved to the bounds) small.
double pick_coefficient(const Interval& a) {
  if (a.lower() == a.upper()) return a.lower();
  double m = 0.5 * a.lower() + 0.5 * a.upper();  // no overflow; rounding does not matter
  return std::clamp(m, a.lower(), a.upper());
}

void add_parabolic_rows(LinearProgram& lp, const Box& box, const model::Parabolic& p) {
  const double xl = box[p.x].lower(), xu = box[p.x].upper();
  const Interval minus_one(-1.0);
  // Tangent at t: q >= 2t x - t^2 for every x, because (x - t)^2 >= 0. Any double t is a
  // valid tangent point, so t need not be the exact midpoint of the secant's slope.
  auto tangent = [&](double t) {
    if (!std::isfinite(t)) return;
    add_enclosing_row(lp, box, {{p.x, Interval(2.0) * t}, {p.q, minus_one}}, square(Interval(t)),
                      RowSense::at_most);
  };
  tangent(xl);
  tangent(xu);
  if (!std::isfinite(xl) || !std::isfinite(xu)) return;
  if (xl < xu) tangent(0.5 * xl + 0.5 * xu);
  // Secant: (x - xl)(x - xu) <= 0 on [xl, xu], i.e.  q - (xl + xu) x <= -xl xu.
  const Interval x_lo(xl), x_hi(xu);
  add_enclosing_row(lp, box, {{p.q, Interval(1.0)}, {p.x, -(x_lo + x_hi)}}, -(x_lo * x_hi),
                    RowSense::at_most);
}

void add_hyperbolic_rows(LinearProgram& lp, const Box& box, const model::Hyperbolic& h) {
  const Interval &X = box[h.x], &Y = box[h.y];
  if (!is_finite(X) || !is_finite(Y)) return;
  const Interval xl(X.lower()), xu(X.upper()), yl(Y.lower()), yu(Y.upper()), one(1.0);
  // From (x-xl)(y-yl) >= 0, (xu-x)(yu-y) >= 0: b above two planes;
  // from (x-xl)(yu-y) >= 0, (xu-x)(y-yl) >= 0: b below two planes.
  add_enclosing_row(lp, box, {{h.x, yl}, {h.y, xl}, {h.b, -one}}, xl * yl, RowSense::at_most);
  add_enclosing_row(lp, box, {{h.x, yu}, {h.y, xu}, {h.b, -one}}, xu * yu, RowSense::at_most);
  add_enclosing_row(lp, box, {{h.x, -yu}, {h.y, -xl}, {h.b, one}}, -(xl * yu), RowSense::at_most);
  add_enclosing_row(lp, box, {{h.x, -yl}, {h.y, -xu}, {h.b, one}}, -(xu * yl), RowSense::at_most);
}

}  // namespace

void add_enclosing_row(LinearProgram& lp, const Box& box, std::vector<IntervalTerm> terms,
                       const Interval& rhs, RowSense sense) {
  std::sort(terms.begin(), terms.end(), [](auto& a, auto& b) { return a.var < b.var; });
  std::vector<std::pair<int, double>> row;
  // With true A*, B*:  sum a v = B* + sum (a - A*) v  lies in  rhs + sum (a - A) V.
  Interval bound = rhs;
  for (size_t k = 0; k < terms.size();) {
    const int var = terms[k].var;
    Interval coef = terms[k].coef;
    for (++k; k < terms.size() && terms[k].var == var; ++k) coef += terms[k].coef;
    if (!is_finite(coef)) return;
    const double a = pick_coefficient(coef);
    if (a != 0) row.push_back({var, a});
    const Interval remainder = Interval(a) - coef;
    // A zero remainder contributes nothing; skipping it avoids 0 * inf on an unbounded side.
    if (remainder.lower() != 0 || remainder.upper() != 0) bound += remainder * box[var];
  }
  const double lo = bound.lower(), hi = bound.upper();
  if (std::isnan(lo) || std::isnan(hi)) return;
  const double row_lo = sense == RowSense::at_most ? -kInf : lo;
  const double row_hi = sense == RowSense::at_least ? kInf : hi;
  if (row_lo == -kInf && row_hi == kInf) return;  // constrains nothing
  lp.add_row(row, row_lo, row_hi);
}

LinearProgram build_lph_relaxation(const model::LphSystem& system, const Box& box) {
  LinearProgram lp;
  for (const Interval& v : box) lp.add_column(v.lower(), v.upper());
  for (const model::LinearEquation& eq : system.linear) {
    std::vector<IntervalTerm> terms;
    for (auto& [var, coef] : eq.terms) terms.push_back({var, coef});
    add_enclosing_row(lp, box, std::move(terms), eq.rhs, RowSense::equal);
  }
  for (const model::Parabolic& p : system.parabolic) add_parabolic_rows(lp, box, p);
  for (const model::Hyperbolic& h : system.hyperbolic) add_hyperbolic_rows(lp, box, h);
  // The system's inequalities: half-spaces in the lifted variables (a strict one by its
  // closure, which holds wherever it does).
  for (const model::LinearInequality& in : system.inequalities) {
    std::vector<IntervalTerm> terms;
    for (auto& [var, coef] : in.terms) terms.push_back({var, coef});
    add_enclosing_row(lp, box, std::move(terms), in.rhs, RowSense::at_most);
  }
  return lp;
}

}  // namespace linkbox::prune::lp
