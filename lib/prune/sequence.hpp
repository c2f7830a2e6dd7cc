#pragma once
// The contractor a search runs: its members in stages (Staged, with the backoff), the members
// of one stage in order (Composition), each member Counted, so that the counters are per
// member. Stage numbers are per member and non-decreasing; consecutive members with the same
// number form one stage. One stage: every member, every pass.
#include "prune/contractor.hpp"
#include "prune/counted.hpp"
#include "prune/staged.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

class Sequence final : public Contractor {
 public:
  using Backoff = prune::Backoff;

  explicit Sequence(std::vector<std::unique_ptr<Contractor>> members, std::vector<int> measured_dims = {},
                    std::vector<int> stages = {}, double stall = 1.0);
  std::string name() const override { return staged_->name(); }
  Outcome contract(Box& box) override { return staged_->contract(box); }
  Outcome contract(Box& box, Backoff& backoff) { return staged_->contract(box, backoff); }
  std::unique_ptr<Contractor> clone() const override { return clone_sequence(); }
  std::unique_ptr<Sequence> clone_sequence() const;  // its counters start at zero
  bool at_most_one_root() const override { return staged_->at_most_one_root(); }
  void stop_when(const std::function<bool()>* request) override { staged_->stop_when(request); }
  void add_work(Counters& counters) const override { staged_->add_work(counters); }

  // The race's unit of work (solve/search.hpp): what one box of propagation and Newton costs
  // on this sequence's system, in Counters::operations. Kept by clones.
  void set_operations_per_box(double operations) { operations_per_box_ = operations; }
  double operations_per_box() const { return operations_per_box_; }
  double operations() const;  // the members' counters' operations, summed
  double live_operations() const;  // the same, with the call under way (Counted::live_operations)

  // Passes that stalled (Staged::stalls), counted apart from the counters: a box cut short
  // keeps them.
  long stalls() const { return staged_->stalls(); }
  // Whether a member of a stage after the first has run.
  bool ran_later_stages() const;

  std::vector<Counters> counters() const;  // per member
  void add_counters(const Sequence& other);  // same members, e.g. a clone run elsewhere
  void take_counters(Sequence& other);       // a clone's counters and stalls, left at zero
  void set_counters(const std::vector<Counters>& counters);  // a resumed run

 private:
  Sequence(std::vector<std::unique_ptr<Counted>> members, std::vector<int> measured_dims, std::vector<int> stages,
           double stall);

  std::vector<Counted*> members_;  // owned by staged_
  std::unique_ptr<Staged> staged_;
  std::vector<int> dims_;
  std::vector<int> stages_;  // per member
  double stall_;
  double operations_per_box_ = 1;
};

}  // namespace linkbox::prune
