#pragma once
// One small interface for every pruning strategy: shrink a box without losing any root.
// A contractor may only answer `empty` when it has *proved* the box holds no root.
#include "interval/box.hpp"
#include "prune/counters.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace linkbox::prune {

enum class Outcome { empty, shrunk, unchanged };

class Contractor {
 public:
  virtual ~Contractor() = default;
  virtual std::string name() const = 0;
  // Shrinks `box` in place. On `empty`, the contents of `box` are unspecified.
  virtual Outcome contract(Box& box) = 0;
  // A fresh contractor of the same kind and settings with its own scratch state, for
  // another thread.
  virtual std::unique_ptr<Contractor> clone() const = 0;
  // Whether the last contract() proved that the box it returned holds at most one root (see
  // IntervalNewton). A hint for the search to try a certificate; never a proof of existence.
  virtual bool at_most_one_root() const { return false; }
  // Asked between the costly steps of one contract() (the LPs of a relaxation): when it
  // returns true, the contractor returns what it has proved so far, so a time limit or an
  // interrupt is honoured within one step. The function must outlive its use.
  virtual void stop_when(const std::function<bool()>* request) { (void)request; }
  // Work done so far by an LP-based contractor (0 for the others), for the counters.
  virtual long lps_solved() const { return 0; }
  virtual long lp_iterations() const { return 0; }
  virtual LpPaths lp_paths() const { return {}; }
};

// Applies its members in order; stops at the first `empty`. Keeps counters per member.
// Members come in stages (stage numbers non-decreasing): a later stage runs in a pass only
// when the earlier ones stalled, i.e. kept more than `stall` of the volume (over
// `measured_dims`). One stage: every member, every pass.
//
// A later stage is costly (the LP relaxation: tens of LPs) and pays only where it removes
// more than a bisection would. Where it fails to, the search backs off: the boxes below skip
// it for 1, then 3, 7, ... levels of the search tree, and one success resets that. The state
// travels down the tree with each box (Backoff), so the boxes do not depend on the order or
// the thread in which they are processed.
class Sequence final : public Contractor {
 public:
  struct Backoff {
    int level = 0;  // consecutive failures on the way down
    int skip = 0;   // tree levels still to skip the later stages
    Backoff child() const { return {level, skip > 0 ? skip - 1 : 0}; }
  };

  explicit Sequence(std::vector<std::unique_ptr<Contractor>> members, std::vector<int> measured_dims = {},
                    std::vector<int> stages = {}, double stall = 1.0);
  std::string name() const override;
  Outcome contract(Box& box) override;  // every stage when stalled, no backoff
  Outcome contract(Box& box, Backoff& backoff);
  std::unique_ptr<Contractor> clone() const override { return clone_sequence(); }
  std::unique_ptr<Sequence> clone_sequence() const;
  bool at_most_one_root() const override { return at_most_one_; }
  void stop_when(const std::function<bool()>* request) override {
    for (auto& m : members_) m->stop_when(request);
  }
  const std::vector<std::unique_ptr<Contractor>>& members() const { return members_; }
  const std::vector<Counters>& counters() const { return counters_; }
  void add_counters(const Sequence& other);  // same members, e.g. a clone run elsewhere
  void set_counters(std::vector<Counters> counters) { counters_ = std::move(counters); }  // a resumed run

 private:
  std::vector<std::unique_ptr<Contractor>> members_;
  std::vector<Counters> counters_;
  std::vector<int> dims_;
  std::vector<int> stages_;  // per member
  double stall_;
  bool at_most_one_ = false;
};

}  // namespace linkbox::prune
