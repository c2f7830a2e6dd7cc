#include "solve/lead.hpp"

#include <algorithm>

namespace linkbox::solve {

// Progress is the share of the search tree resolved (Search::tree_done), not of the volume:
// contraction removes most of the volume in the first boxes, while the work gathers around
// the solution set, where little volume is left. On volume, a propagation search that had
// cleared nearly all of a curve's neighbourhood looked nearly done and kept the lead (see
// papers/decisions/solve-driver.md).
double projected(const Standing& s) { return s.work / std::max(s.tree, 1e-9); }

// Compared at equal work: one that has run less looks cheaper only because it has not reached
// the hard part yet, while the holder's share now would ask of a challenger that runs an
// eighth of each turn (race.cpp) to be eight times as efficient.
double ahead_of(const Progress& holder, const Standing& challenger) {
  std::pair<double, double> before{0, 0};
  for (auto& p : holder) {
    if (p.first >= challenger.work) {
      const double span = p.first - before.first;
      const double then =
          span > 0 ? before.second + (p.second - before.second) * (challenger.work - before.first) / span : p.second;
      return challenger.tree - then;
    }
    before = p;
  }
  return challenger.tree - before.second;
}

bool cheaper(const Standing& holder, const Standing& challenger) {
  return projected(challenger) * kLeadMargin < projected(holder);
}

// The one furthest ahead, not the cheapest: one merely level with the holder (both crawling
// through the same hard part) is projected cheap only for its smaller work. The choice does
// not depend on the candidates' order.
size_t choose_lead(size_t held, const std::vector<Standing>& now, const Progress& held_progress) {
  size_t lead = held;
  double best = -1;
  for (size_t k = 0; k < now.size(); ++k) {
    // No work counted: it has shown nothing yet, and 0 work would project as cheapest.
    if (k == held || now[k].work <= 0) continue;
    if (std::max(now[k].tree, now[held].tree) < kMinLeadShare) continue;
    const double ahead = ahead_of(held_progress, now[k]);
    if (ahead >= 0 && cheaper(now[held], now[k]) && ahead > best) {
      best = ahead;
      lead = k;
    }
  }
  return lead;
}

}  // namespace linkbox::solve
