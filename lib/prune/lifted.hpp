#pragma once
// Runs a contractor made for an L/P/H lifting of a system on boxes of the original
// variables: the dummies are enclosed afresh from the box (q = x^2, b = x*y) before each
// call, and only the original variables are written back.
#include "model/lph.hpp"
#include "prune/contractor.hpp"

namespace linkbox::prune {

class Lifted final : public Contractor {
 public:
  Lifted(model::LphSystem lph, size_t original_variables, std::unique_ptr<Contractor> inner);
  std::string name() const override { return inner_->name(); }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;
  void stop_when(const std::function<bool()>* request) override { inner_->stop_when(request); }
  void add_work(Counters& counters) const override { inner_->add_work(counters); }

 private:
  model::LphSystem lph_;
  size_t n_;
  std::unique_ptr<Contractor> inner_;
};

}  // namespace linkbox::prune
