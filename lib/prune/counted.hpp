#pragma once
// A contractor and the counters of its calls (a statistics decorator): calls, boxes proved
// empty, time, the share of volume it removes (over `measured_dims`), and the work the
// contractor reports itself (Contractor::add_work), per call.
#include "prune/contractor.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

class Counted final : public Contractor {
 public:
  Counted(std::unique_ptr<Contractor> inner, std::vector<int> measured_dims);
  std::string name() const override { return inner_->name(); }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return clone_counted(); }
  std::unique_ptr<Counted> clone_counted() const;  // its counters start at zero
  bool at_most_one_root() const override { return inner_->at_most_one_root(); }
  void stop_when(const std::function<bool()>* request) override { inner_->stop_when(request); }
  void add_work(Counters& counters) const override { inner_->add_work(counters); }

  const Counters& counters() const { return counters_; }
  // The operations counted so far, the call under way included (its LPs so far).
  double live_operations() const;
  void set_counters(const Counters& counters) { counters_ = counters; }

 private:
  std::unique_ptr<Contractor> inner_;
  std::vector<int> dims_;
  Counters counters_;
  double started_ = -1;  // inside contract(): the inner contractor's operations at its start
};

}  // namespace linkbox::prune
