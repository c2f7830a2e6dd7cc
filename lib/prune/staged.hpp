#pragma once
// Contractors in stages, each costlier than the one before: a later stage runs in a pass only
// when the earlier ones stalled, i.e. kept more than `stall` of the volume (over
// `measured_dims`). With one stage it is that stage.
//
// A later stage is costly (the LP relaxation: tens of LPs) and pays only where it removes
// more than a bisection would. Where it fails to, the search backs off: the boxes below skip
// it for 1, then 3, 7, ... levels of the search tree, and one success resets that. The state
// travels down the tree with each box (Backoff), so the boxes do not depend on the order or
// the thread in which they are processed.
#include "prune/contractor.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

struct Backoff {
  int level = 0;  // consecutive failures on the way down
  int skip = 0;   // tree levels still to skip the later stages
  Backoff child() const { return {level, skip > 0 ? skip - 1 : 0}; }
};

class Staged final : public Contractor {
 public:
  Staged(std::vector<std::unique_ptr<Contractor>> stages, std::vector<int> measured_dims, double stall);
  std::string name() const override;  // the stages' names, comma-separated
  Outcome contract(Box& box) override;  // every stage when stalled, no backoff
  Outcome contract(Box& box, Backoff& backoff);
  std::unique_ptr<Contractor> clone() const override;
  bool at_most_one_root() const override { return at_most_one_; }
  void stop_when(const std::function<bool()>* request) override;
  void add_work(Counters& counters) const override;

  // Passes after which one more stage would run if there were one: those whose last stage
  // kept more than `stall` of the volume, outside a backoff. Until the first, a sequence that
  // adds stages after these makes every box what this one makes it.
  long stalls() const { return stalls_; }
  void set_stalls(long n) { stalls_ = n; }

 private:
  std::vector<std::unique_ptr<Contractor>> stages_;
  std::vector<int> dims_;
  double stall_;
  bool at_most_one_ = false;
  long stalls_ = 0;
};

}  // namespace linkbox::prune
