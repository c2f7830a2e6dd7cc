#include "prune/hc4.hpp"

#include "interval/root.hpp"
#include "prune/links.hpp"

#include <cmath>

namespace linkbox::prune {

namespace {

FastInterval power(const FastInterval& x, int e) { return e == 1 ? x : boost::numeric::pow(x, e); }

// Narrows x to {v in x : v^e in p}; false when that set is empty. Any e >= 1: the real
// e-th roots are enclosed by root::nth_root (outward rounded).
bool project_power(Interval& x, const FastInterval& p, int e) {
  double lo = x.lower(), hi = x.upper();
  if (e == 1) {
    lo = std::max(lo, p.lower());
    hi = std::min(hi, p.upper());
  } else if (!std::isfinite(p.lower()) || !std::isfinite(p.upper())) {
    return true;  // nth_root needs finite bounds; nothing to learn anyway
  } else if (e % 2 == 1) {
    const FastInterval r = root::nth_root(p, e);  // odd: one increasing branch
    lo = std::max(lo, r.lower());
    hi = std::min(hi, r.upper());
  } else {
    if (p.upper() < 0) return false;
    const FastInterval q(std::max(0.0, p.lower()), p.upper());
    const FastInterval r = e == 2 ? sqrt(q) : root::nth_root(q, e);
    // v in [-r.hi, -r.lo] or [r.lo, r.hi]: keep the hull of what meets x.
    const double in_lo = r.lower(), out = r.upper();
    double nlo = kInf, nhi = -kInf;
    if (hi >= -out && lo <= -in_lo) nlo = std::min(nlo, std::max(lo, -out)), nhi = std::max(nhi, std::min(hi, -in_lo));
    if (hi >= in_lo && lo <= out) nlo = std::min(nlo, std::max(lo, in_lo)), nhi = std::max(nhi, std::min(hi, out));
    lo = nlo, hi = nhi;
  }
  if (!(lo <= hi)) return false;
  x = Interval(lo, hi);
  return true;
}

}  // namespace

Hc4::Hc4(const std::vector<model::Polynomial>& equations, Arith arith, const std::vector<model::Inequality>& inequalities,
         std::vector<model::Link> links)
    : equation_count_(equations.size()), links_(std::move(links)), arith_(arith) {
  auto add = [&](const model::Polynomial& e) {
    std::vector<Term> terms;
    for (auto& [p, c] : e.terms()) terms.push_back({coefficient_for(arith, c), p});
    equations_.push_back(std::move(terms));
  };
  for (auto& e : equations) add(e);
  for (auto& c : inequalities) {
    add(c.g);
    strict_.push_back(c.strict);
  }
  call_operations_ = call_operations_of(equations, inequalities, links_.size());
}

// A term of p factors: p products and two sums forward, and per factor p products and a
// projection backward, each about two interval products; a power adds its pow() and its root
// (a square root; for a higher power, nth_root's libm guess and its checked steps).
double Hc4::call_operations_of(const std::vector<model::Polynomial>& equations,
                               const std::vector<model::Inequality>& inequalities, size_t links) {
  double n = 0;
  auto add = [&](const model::Polynomial& e) {
    for (auto& [powers, coef] : e.terms()) {
      const double p = static_cast<double>(powers.size());
      n += 2 * (3 + p + p * (p + 1));
      for (auto [v, k] : powers) n += k == 2 ? 10 : k > 2 ? 230 : 0;
    }
  };
  for (auto& e : equations) add(e);
  for (auto& c : inequalities) add(c.g);
  return n + model::kLinkOperations * static_cast<double>(links);
}

std::unique_ptr<Contractor> Hc4::clone() const {
  auto c = std::make_unique<Hc4>(*this);
  c->operations_ = 0;
  return c;
}

void Hc4::add_work(Counters& counters) const { counters.operations += operations_; }

Outcome Hc4::contract(Box& box) {
  operations_ += call_operations_;
  return with_rounding(arith_, [&] { return revise(box); });
}

Outcome Hc4::revise(Box& box) {
  bool shrunk = false;
  for (size_t row = 0; row < equations_.size(); ++row) {
    const auto& terms = equations_[row];
    const bool inequality = row >= equation_count_;
    const size_t n = terms.size();
    value_.resize(n);
    prefix_.resize(n + 1);
    suffix_.resize(n + 1);
    for (size_t m = 0; m < n; ++m) {
      FastInterval t = terms[m].coef;
      for (auto [v, e] : terms[m].powers) t *= power(box[v], e);
      value_[m] = t;
    }
    prefix_[0] = suffix_[n] = FastInterval(0.0);
    for (size_t m = 0; m < n; ++m) prefix_[m + 1] = prefix_[m] + value_[m];
    for (size_t m = n; m-- > 0;) suffix_[m] = suffix_[m + 1] + value_[m];
    // A NaN bound in any term reaches the sum; it proves nothing, so the row is skipped.
    if (std::isnan(prefix_[n].lower()) || std::isnan(prefix_[n].upper())) continue;
    if (inequality) {
      // g <= 0 fails throughout when g > 0 (a strict one also when g >= 0).
      const double g = prefix_[n].lower();
      if (strict_[row - equation_count_] ? g >= 0 : g > 0) return Outcome::empty;
    } else if (excludes_zero(prefix_[n])) {
      return Outcome::empty;
    }
    for (size_t m = 0; m < n; ++m) {
      if (terms[m].powers.empty()) continue;
      // This term must cancel the others (equation), or stay at most -others (inequality).
      const FastInterval others = prefix_[m] + suffix_[m + 1];
      const double lo = inequality ? value_[m].lower() : std::max(value_[m].lower(), -others.upper());
      const double hi = std::min(value_[m].upper(), -others.lower());
      if (!(lo <= hi)) return Outcome::empty;
      const FastInterval target(lo, hi);
      for (auto [k, ek] : terms[m].powers) {
        FastInterval divisor = terms[m].coef;
        for (auto [j, ej] : terms[m].powers)
          if (j != k) divisor *= power(box[j], ej);
        if (zero_in(divisor)) continue;
        const Interval before = box[k];
        if (!project_power(box[k], target / divisor, ek)) return Outcome::empty;
        shrunk = shrunk || box[k].lower() != before.lower() || box[k].upper() != before.upper();
      }
    }
  }
  if (!narrow_links(links_, box, shrunk)) return Outcome::empty;
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
