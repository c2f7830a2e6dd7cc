#include "prune/counted.hpp"

#include <chrono>

namespace linkbox::prune {

Counted::Counted(std::unique_ptr<Contractor> inner, std::vector<int> measured_dims)
    : inner_(std::move(inner)), dims_(std::move(measured_dims)) {}

std::unique_ptr<Counted> Counted::clone_counted() const { return std::make_unique<Counted>(inner_->clone(), dims_); }

Outcome Counted::contract(Box& box) {
  auto t0 = std::chrono::steady_clock::now();
  Box before = box;
  Counters work_before;
  inner_->add_work(work_before);
  // Between calls, live_operations() is the counters alone, also after a call that threw.
  struct Live {
    double& started;
    ~Live() { started = -1; }
  } live{started_};
  started_ = work_before.operations;
  Outcome o = inner_->contract(box);
  Counters work;
  inner_->add_work(work);
  Counters& c = counters_;
  c.calls++;
  c.lps_solved += work.lps_solved - work_before.lps_solved;
  c.lp_iterations += work.lp_iterations - work_before.lp_iterations;
  c.operations += work.operations - work_before.operations;
  c.lp_paths += work.lp_paths;
  c.lp_paths -= work_before.lp_paths;
  c.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (o == Outcome::empty) {
    c.emptied++;
    c.volume_removed += 1;
  } else if (o == Outcome::shrunk) {
    c.volume_removed += 1 - volume_ratio(before, box, dims_);
  }
  return o;
}

double Counted::live_operations() const {
  if (started_ < 0) return counters_.operations;
  Counters now;
  inner_->add_work(now);
  return counters_.operations + now.operations - started_;
}

}  // namespace linkbox::prune
