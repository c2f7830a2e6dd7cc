// Divisors that may be 0 on the domain (lifting.hpp): cleared from the equations and
// inequalities instead of lifted, and kept from 0 by a strict inequality each.
#include "model/lifter.hpp"

namespace linkbox::model::detail {

namespace {

// Where a cleared divisor's quotient stands while the constraints are built: an index no
// lifted unknown reaches, removed by Lifter::clear before any constraint is kept.
constexpr int kQuotientSymbol = 1 << 28;

// A cleared polynomial with more terms than this is refused rather than built.
constexpr size_t kMaxClearedTerms = 200'000;

}  // namespace

// A reciprocal is cleared when its divisor's range over the domain holds 0 or is unbounded,
// or when its divisor divides by a cleared one. A sum's base that holds a cleared quotient, or
// that is never raised to a power, is expanded in place. Any other function of a cleared quotient is refused: its argument's
// range, which its unknown's domain comes from, is not bounded.
void Lifter::find_cleared() {
  const int count = static_cast<int>(raw_.applications.size());
  cleared_.assign(count, false);
  expanded_.assign(count, false);
  divisors_.assign(count, Polynomial());
  std::vector<bool> holds_cleared(count, false);  // a base whose sum holds a cleared quotient
  for (int k = 0; k < count; ++k) {
    const Application& a = raw_.applications[k];
    bool through_cleared = false;
    for (const Polynomial* p : {&a.argument, &a.second})
      for (int v : p->variables())
        through_cleared = through_cleared || (v >= n_ && (cleared_[v - n_] || holds_cleared[v - n_]));
    if (a.function == Function::base) {
      holds_cleared[k] = through_cleared;
      expanded_[k] = through_cleared || !a.raised;
      continue;
    }
    if (a.function != Function::reciprocal) {
      if (through_cleared)
        fail_application(k, a.text + ": its argument has a divisor that may be 0 on the domain, so its range is "
                                     "not bounded; narrow the domain so that the divisor stays away from 0, or "
                                     "write the quotient as an unknown with its own equation");
      continue;
    }
    if (through_cleared) {
      cleared_[k] = true;
      continue;
    }
    try {
      const Interval range = argument_range(k);
      cleared_[k] = zero_in(range) || !is_finite(range);
    } catch (const std::domain_error&) {
      // Not defined on the domain: add_reciprocal_unknown says so.
    }
  }
}

// 1/B with B possibly 0: no unknown; the constraints are multiplied by powers of B (clear),
// and -B^2 < 0 says B != 0, where the case's expressions are defined.
void Lifter::add_cleared_divisor(int k) {
  const Application& a = raw_.applications[k];
  image_[n_ + k] = Polynomial::variable(kQuotientSymbol + k);
  divisors_[k] = substituted(a.argument, k);
  Inequality nonzero;
  nonzero.g = clear(-divisors_[k].pow(2), true, k);
  nonzero.strict = true;
  nonzero.name = "divisor of " + a.text + " is not 0";
  out_.inequalities.push_back(std::move(nonzero));
  lifting_->notes.push_back(a.text + " -> cleared: its divisor may be 0 on the domain, so each equation is multiplied "
                                     "by a power of it, each inequality by an even one, and \"" +
                            out_.inequalities.back().name + "\" (strict) keeps it from 0");
}

// p with every cleared quotient q_k = 1/B_k removed, last first (B_k may hold earlier
// quotients): p of degree m in q_k becomes B_k^e p, e = m (even: m rounded up to even, so
// that the sign of p is kept where B_k != 0). Where every divisor is nonzero the result is 0
// exactly where p is, and has p's sign when `even`.
Polynomial Lifter::clear(Polynomial p, bool even, int application) const {
  for (int k = static_cast<int>(cleared_.size()) - 1; k >= 0; --k) {
    if (!cleared_[k]) continue;
    const int q = kQuotientSymbol + k;
    const int m = p.degree_in(q);
    if (m == 0) continue;
    std::vector<Polynomial> by_power(m + 1);  // p = sum_j by_power[j] q^j
    for (auto& [powers, c] : p.terms()) {
      Powers rest;
      int j = 0;
      for (auto [v, e] : powers)
        if (v == q) j = e;
        else rest.push_back({v, e});
      by_power[j] += Polynomial::monomial(rest, c);
    }
    const int e = even ? m + m % 2 : m;
    Polynomial cleared, factor = divisors_[k].pow(e - m);
    for (int j = m; j >= 0; --j) {
      cleared += by_power[j] * factor;
      if (j > 0) factor = factor * divisors_[k];
      if (cleared.terms().size() > kMaxClearedTerms)
        fail_application(application < 0 ? k : application,
                         "clearing the divisor of " + raw_.applications[k].text + " expands to too many terms");
    }
    p = std::move(cleared);
  }
  return p;
}

}  // namespace linkbox::model::detail
