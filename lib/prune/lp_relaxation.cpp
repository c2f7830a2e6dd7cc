#include "prune/lp_relaxation.hpp"

#include "prune/lp/lph_relaxation.hpp"
#include "prune/lp/tighten.hpp"

#include <optional>

namespace linkbox::prune {

namespace {

// x restricted to the set {x : x^2 in q}, i.e. to -sqrt(q) U sqrt(q), as one interval.
std::optional<Interval> roots_of_square(const Interval& x, const Interval& q) {
  if (q.upper() < 0) return std::nullopt;
  const Interval root = sqrt(Interval(std::max(q.lower(), 0.0), q.upper()));
  Interval positive, negative;
  const bool has_positive = intersect(x, root, positive);
  const bool has_negative = intersect(x, -root, negative);
  if (has_positive && has_negative) return hull(positive, negative);
  if (has_positive) return positive;
  if (has_negative) return negative;
  return std::nullopt;
}

// Replaces `box` by its contraction and says whether anything moved.
Outcome finish(Box& box, Box&& contracted) {
  bool changed = false;
  for (size_t i = 0; i < box.size(); ++i)
    changed |= contracted[i].lower() != box[i].lower() || contracted[i].upper() != box[i].upper();
  box = std::move(contracted);
  return changed ? Outcome::shrunk : Outcome::unchanged;
}

// Narrows box[var] to its intersection with `range`; false when empty. Sets `moved` when
// the interval changed.
bool narrow(Box& box, int var, const Interval& range, bool& moved) {
  Interval out;
  if (!intersect(box[var], range, out)) return false;
  if (out.lower() != box[var].lower() || out.upper() != box[var].upper()) moved = true;
  box[var] = out;
  return true;
}

}  // namespace

bool propagate_products(const model::LphSystem& system, Box& box) {
  constexpr int kPasses = 4;  // products chain through shared variables; a few passes suffice
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (const model::Parabolic& p : system.parabolic) {
      if (!narrow(box, p.q, square(box[p.x]), moved)) return false;
      std::optional<Interval> x = roots_of_square(box[p.x], box[p.q]);
      if (!x || !narrow(box, p.x, *x, moved)) return false;
    }
    for (const model::Hyperbolic& h : system.hyperbolic) {
      if (!narrow(box, h.b, box[h.x] * box[h.y], moved)) return false;
      // Division is only sound and useful when the divisor excludes zero.
      if (excludes_zero(box[h.y]) && !narrow(box, h.x, box[h.b] / box[h.y], moved)) return false;
      if (excludes_zero(box[h.x]) && !narrow(box, h.y, box[h.b] / box[h.x], moved)) return false;
    }
    if (!moved) break;
  }
  return true;
}

bool linear_equations_possible(const model::LphSystem& system, const Box& box) {
  for (const model::LinearEquation& eq : system.linear) {
    Interval sum(0.0);
    for (auto& [var, coef] : eq.terms) sum += coef * box[var];
    Interval common;
    if (!intersect(sum, eq.rhs, common)) return false;
  }
  return true;
}

LpRelaxation::LpRelaxation(const model::LphSystem& system, lp::LpBackend backend, lp::Order order)
    : LpRelaxation(std::make_shared<const model::LphSystem>(system), backend, order) {}

LpRelaxation::LpRelaxation(std::shared_ptr<const model::LphSystem> system, lp::LpBackend backend, lp::Order order)
    : system_(std::move(system)), backend_(backend), order_(order), solver_(lp::make_lp_solver(backend)) {}

std::string LpRelaxation::name() const { return "lp-" + lp::to_string(backend_); }

std::unique_ptr<Contractor> LpRelaxation::clone() const {
  return std::unique_ptr<Contractor>(new LpRelaxation(system_, backend_, order_));
}

void LpRelaxation::add_work(Counters& counters) const {
  counters.lps_solved += lps_solved_;
  counters.lp_iterations += solver_->iterations();
  counters.operations += solver_->operations();
  counters.lp_paths += solver_->paths();
}

Outcome LpRelaxation::contract(Box& box) {
  Box work = box;
  if (!propagate_products(*system_, work)) return Outcome::empty;
  if (!linear_equations_possible(*system_, work)) return Outcome::empty;

  if (system_->primary.empty()) return finish(box, std::move(work));
  solver_->load(lp::build_lph_relaxation(*system_, work));
  if (!lp::tighten_columns(*solver_, system_->primary, work, lps_solved_, stop_, order_)) return Outcome::empty;
  return finish(box, std::move(work));
}

}  // namespace linkbox::prune
