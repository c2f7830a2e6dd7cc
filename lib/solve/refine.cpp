#include "solve/refine.hpp"

#include <algorithm>
#include <map>

namespace linkbox::solve {

namespace {

constexpr int kRefineRounds = 4;  // sigma/100 each round, down to the floor
constexpr double kRefineFactor = 1e-2;
constexpr double kSigmaFloor = 1e-12;
constexpr double kRefineWork = 2000;  // per box: what cannot be settled within it is left as it was
// Only small groups of touching uncertified boxes are refined: a close pair of roots leaves a
// few, a curve (a mobile linkage, a singular family) leaves a long chain that no sigma
// resolves, and refining it would only multiply the work. A close pair whose Jacobian rows
// scale with the gap leaves a few hundred sigma-boxes; all the refinements of a run together
// get at most twice the search's work, plus kRefineWork per box for small searches.
constexpr size_t kRefineGroup = 1024;
// Along a curve the boxes the curve crosses use up kRefineWork each for nothing. So once
// kRefineProbe of a group's refinements were cut short and none certified a root, the rest of
// the group is left as the search found it (see papers/decisions/solve-driver.md).
constexpr int kRefineProbe = 3;
constexpr size_t kRefineMax = 4000;

// Per solution: the group of touching uncertified boxes it belongs to, or -1 when it is
// certified or its group is too large to refine.
std::vector<int> small_groups(const Result& r) {
  std::vector<size_t> open;
  for (size_t k = 0; k < r.solutions.size(); ++k)
    if (!r.certified[k]) open.push_back(k);
  std::vector<int> result(r.solutions.size(), -1);
  if (open.size() > kRefineMax) return result;
  std::vector<int> group(open.size(), -1);
  std::vector<size_t> size;
  for (size_t a = 0; a < open.size(); ++a) {
    if (group[a] >= 0) continue;
    const int g = static_cast<int>(size.size());
    size.push_back(0);
    std::vector<size_t> stack{a};
    group[a] = g;
    while (!stack.empty()) {
      const size_t x = stack.back();
      stack.pop_back();
      ++size[g];
      for (size_t b = 0; b < open.size(); ++b)
        if (group[b] < 0 && overlaps(r.solutions[open[x]], r.solutions[open[b]])) {
          group[b] = g;
          stack.push_back(b);
        }
    }
  }
  for (size_t a = 0; a < open.size(); ++a)
    if (size[group[a]] <= kRefineGroup) result[open[a]] = group[a];
  return result;
}

// The solutions of one round, with whether each is stuck: its refinement was cut short (a
// smaller sigma would only make its next attempt costlier), so it is not refined again.
struct Round {
  Result out;
  std::vector<char> stuck;
  void keep(Box&& box, char certified, bool is_stuck) {
    out.solutions.push_back(std::move(box));
    out.certified.push_back(certified);
    stuck.push_back(is_stuck);
  }
};

}  // namespace

long refine(Result& r, double search_work, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, Certifier& certifier, const Bisector& bisector) {
  Params fine = params;
  double allowance = 2 * search_work + 20 * kRefineWork;
  std::vector<char> stuck(r.solutions.size(), 0);
  long unrefined = 0;  // in the last round: boxes due for a refinement that a limit stopped
  for (int round = 0; round < kRefineRounds; ++round) {
    unrefined = 0;
    fine.sigma = std::max(fine.sigma * kRefineFactor, kSigmaFloor);
    Round next;
    bool changed = false;
    const std::vector<int> group = small_groups(r);
    std::map<int, std::pair<int, int>> tried;  // per group: refinements cut short, roots certified
    for (size_t k = 0; k < r.solutions.size(); ++k) {
      auto& [cut_short, certified] = tried[group[k]];
      const bool curve = cut_short >= kRefineProbe && certified == 0;  // a curve's group, by its probes
      const bool due =
          !r.certified[k] && group[k] >= 0 && !stuck[k] && !curve && fine.sigma < params.sigma && allowance > 0;
      if (!due || budget.exhausted()) {
        unrefined += due;
        next.keep(std::move(r.solutions[k]), r.certified[k], stuck[k] || curve);
        continue;
      }
      Search search(r.solutions[k], contractor, sub.split_dims, fine, budget, &certifier, &bisector);
      const bool finished = search.run(1, std::min(kRefineWork, allowance));
      allowance -= search.work();
      Result part = search.result();
      cut_short += !finished;
      certified += static_cast<int>(std::count(part.certified.begin(), part.certified.end(), 1));
      if (!finished || !part.complete) {  // stopped by its work or a limit: keep the box as it was
        // Cut by the run's limit, not by its own work, it is not stuck: a resumed run tries it again.
        const bool by_limit = budget.exhausted();
        unrefined += by_limit;
        next.keep(std::move(r.solutions[k]), false, !by_limit);
        continue;
      }
      changed = true;
      const double seconds = r.stats.seconds;
      r.stats += part.stats;  // the box was counted as a solution once: its search replaces it
      r.stats.seconds = seconds + part.stats.seconds;
      for (size_t j = 0; j < part.solutions.size(); ++j) next.keep(std::move(part.solutions[j]), part.certified[j], false);
    }
    r.solutions = std::move(next.out.solutions);
    r.certified = std::move(next.out.certified);
    stuck = std::move(next.stuck);
    if (!changed) break;
  }
  r.stats.solution = static_cast<long>(r.solutions.size());
  r.stats.certified = std::count(r.certified.begin(), r.certified.end(), 1);
  return unrefined;
}

}  // namespace linkbox::solve
