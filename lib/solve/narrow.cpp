#include "solve/narrow.hpp"

#include <algorithm>

namespace linkbox::solve {

namespace {

// A box the narrowing takes holds a short piece of curve, where each pass of the Taylor
// relaxation past the first few removes a sliver: a pass that keeps over 30% of the volume
// is followed by a split instead of another pass. The user's rho, when lower, is kept.
constexpr double kNarrowRho = 0.3;

// The longest side among the split dimensions, as the search measures a solution box.
double split_width(const Box& b, const std::vector<int>& split_dims) {
  double w = 0;
  for (int d : split_dims) w = std::max(w, width_up(b.at(d)));
  return w;
}

}  // namespace

long narrow(Result& r, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, const Bisector& bisector) {
  if (!(params.narrow > 0) || !(params.narrow < params.sigma)) return 0;
  Params fine = params;
  fine.sigma = params.narrow;
  fine.rho = std::min(params.rho, kNarrowRho);
  Result out;
  long unnarrowed = 0;
  for (size_t k = 0; k < r.solutions.size(); ++k) {
    const bool due = !r.certified[k] && split_width(r.solutions[k], sub.split_dims) > fine.sigma;
    if (!due || budget.exhausted()) {
      unnarrowed += due;
      out.solutions.push_back(std::move(r.solutions[k]));
      out.certified.push_back(r.certified[k]);
      continue;
    }
    Search search(r.solutions[k], contractor, sub.split_dims, fine, budget, nullptr, &bisector);
    const bool finished = search.run(1);
    Result part = search.result();
    if (!finished || !part.complete) {  // stopped by a limit: keep the box as it was
      ++unnarrowed;
      out.solutions.push_back(std::move(r.solutions[k]));
      out.certified.push_back(0);
      continue;
    }
    const double seconds = r.stats.seconds;
    r.stats += part.stats;  // the box was counted as a solution once: its search replaces it
    r.stats.seconds = seconds + part.stats.seconds;
    for (auto& b : part.solutions) {
      out.solutions.push_back(std::move(b));
      out.certified.push_back(0);
    }
  }
  r.solutions = std::move(out.solutions);
  r.certified = std::move(out.certified);
  r.stats.solution = static_cast<long>(r.solutions.size());
  return unnarrowed;
}

}  // namespace linkbox::solve
