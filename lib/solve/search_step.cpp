#include "solve/search_step.hpp"

#include "solve/search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <stdexcept>

namespace linkbox::solve::detail {

namespace {

// The contractor asks `during` between its costly steps while in scope, then `after` again.
class StopScope {
 public:
  StopScope(prune::Sequence& c, const std::function<bool()>* during, const std::function<bool()>* after)
      : c_(c), after_(after), set_(during != nullptr) {
    if (set_) c_.stop_when(during);
  }
  ~StopScope() {
    if (set_) c_.stop_when(after_);
  }
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  prune::Sequence& c_;
  const std::function<bool()>* after_;
  bool set_;
};

bool has_nan(const Box& box) {
  return std::any_of(box.begin(), box.end(), [](const Interval& x) { return std::isnan(x.lower()) || std::isnan(x.upper()); });
}

// Shrinks until empty, certified, small, or no longer shrinking by more than rho.
// `stop` is asked between passes too: one box can take many passes (see
// papers/decisions/search.md, "NaN bounds").
Verdict shrink(Box& box, prune::Sequence::Backoff& backoff, prune::Sequence& contractor, Certifier* certifier,
               std::span<const int> dims, const Params& params, const bool& cut, const std::function<bool()>& stop,
               double box_cap, Stats& stats) {
  const double operations = contractor.operations();
  // The cap is asked between the contractors' costly steps as well (a relaxation's LPs), so one
  // pass over a large system cannot spend many times the cap.
  bool over_cap = false;
  std::function<bool()> stop_or_cap;
  if (box_cap > 0)
    stop_or_cap = [&] {
      if ((contractor.live_operations() - operations) / contractor.operations_per_box() > box_cap) return over_cap = true;
      return stop();
    };
  const StopScope scope(contractor, stop_or_cap ? &stop_or_cap : nullptr, &stop);
  while (true) {
    if (stop()) return Verdict::stopped;
    if (box_cap > 0 && (contractor.operations() - operations) / contractor.operations_per_box() > box_cap)
      return Verdict::capped;
    Box before = box;
    stats.shrinks++;
    const prune::Outcome outcome = contractor.contract(box, backoff);
    if (cut) return Verdict::stopped;
    if (over_cap) return Verdict::capped;
    if (outcome == prune::Outcome::empty) return Verdict::empty;
    // A NaN bound (an overflow in the unverified float variant) proves nothing: the box as it
    // was before the pass is split.
    if (has_nan(box)) {
      box = std::move(before);
      return max_width(box, dims) <= params.sigma ? Verdict::solution : Verdict::split;
    }
    if (certifier && contractor.at_most_one_root()) {
      stats.certify_calls++;
      if (certifier->certify(box)) return Verdict::certified;
    }
    const double size = max_width(box, dims);
    if (size <= params.sigma) return Verdict::solution;
    if (volume_ratio(before, box, dims) > params.rho) return Verdict::split;
  }
}

char outcome_of(Verdict v) {
  return v == Verdict::empty ? 'e' : v == Verdict::solution ? 's' : v == Verdict::certified ? 'c' : 'x';
}

Verdict verdict_of(char outcome) {
  return outcome == 'e' ? Verdict::empty
         : outcome == 's' ? Verdict::solution
         : outcome == 'c' ? Verdict::certified
                          : Verdict::split;
}

}  // namespace

Processed process(const Setup& setup, const LogPlace& log, prune::Sequence& c, Certifier* certify, Node node,
                  bool& cut, const std::function<bool()>& stop, double box_cap) {
  Processed p;
  const std::vector<prune::Counters> counters_before = c.counters();
  Node taken = node;
  p.stats.processed++;
  p.volume = volume_ratio(setup.start, node.box, setup.split_dims);
  const double operations = c.operations();
  const auto shrink_start = log.log ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  p.verdict = shrink(node.box, node.backoff, c, certify, setup.split_dims, setup.params, cut, stop, box_cap, p.stats);
  const Verdict v = p.verdict;
  if (log.log && v != Verdict::stopped && v != Verdict::capped)
    log.log->add({log.subproblem, log.candidate, node.path, v == Verdict::empty ? 'e' : v == Verdict::split ? 'x' : 's',
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - shrink_start).count()});
  p.work = std::max(1.0, (c.operations() - operations) / c.operations_per_box()) + (v == Verdict::solution ? kSolutionWork : 0);
  if (v == Verdict::stopped || v == Verdict::capped) {
    c.set_counters(counters_before);  // its work undone in the counts
    // Capped, it keeps what its passes removed (each bound a pass tightened holds, even when
    // the pass was cut between its LPs) and its work, unless a bound is NaN.
    p.node = v == Verdict::capped && !has_nan(node.box) ? std::move(node) : std::move(taken);
    p.stats = {};
    return p;
  }
  if (v == Verdict::empty) {
    p.stats.empty++;
  } else if (v == Verdict::solution || v == Verdict::certified) {
    p.stats.solution++;
    p.stats.certified += v == Verdict::certified;
  } else {
    p.stats.split++;
    const int depth = static_cast<int>(node.path.size());
    const int dim = setup.bisector ? setup.bisector->choose(node.box, depth) : widest_dimension(node.box, setup.split_dims);
    auto [a, b] = bisect(node.box, dim);
    p.halves = {{std::move(a), node.path + '0', node.backoff.child()}, {std::move(b), node.path + '1', node.backoff.child()}};
    p.dim = dim;
  }
  p.node = std::move(node);
  return p;
}

SearchState::Record record_of(const Processed& p) {
  const Verdict v = p.verdict;
  SearchState::Record r{p.node.path, outcome_of(v), p.work, p.volume, p.stats, {}, -1, {}};
  if (v != Verdict::empty) r.box = p.node.box;
  if (v == Verdict::split) r.dim = p.dim, r.backoff = p.node.backoff;
  return r;
}

Processed replay(SearchState::Record r) {
  Processed p;
  p.verdict = verdict_of(r.outcome);
  p.node.path = r.path;
  p.node.box = std::move(r.box);
  p.work = r.work;
  p.volume = r.volume;
  p.stats = r.stats;
  if (p.verdict == Verdict::split) {
    if (r.dim < 0 || r.dim >= static_cast<int>(p.node.box.size())) throw std::logic_error("a split record without its side");
    auto [a, b] = bisect(p.node.box, r.dim);
    p.halves = {{std::move(a), r.path + '0', r.backoff.child()}, {std::move(b), r.path + '1', r.backoff.child()}};
    p.dim = r.dim;
  }
  return p;
}

}  // namespace linkbox::solve::detail
