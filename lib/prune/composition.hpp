#pragma once
// Contractors applied in order, each to the box the one before left (IBEX's CtcCompo); the
// first that proves the box empty ends the pass.
#include "prune/contractor.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

class Composition final : public Contractor {
 public:
  explicit Composition(std::vector<std::unique_ptr<Contractor>> members);
  std::string name() const override;  // the members' names, comma-separated
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;
  // A later member only shrinks the box further, so any member's claim carries over.
  bool at_most_one_root() const override { return at_most_one_; }
  void stop_when(const std::function<bool()>* request) override;
  void add_work(Counters& counters) const override;

 private:
  std::vector<std::unique_ptr<Contractor>> members_;
  bool at_most_one_ = false;
};

}  // namespace linkbox::prune
