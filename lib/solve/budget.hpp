#pragma once
// The limits of a run (time, boxes, an interrupt), shared by its sub-problems and threads.
#include "solve/params.hpp"

#include <atomic>
#include <chrono>
#include <string>

namespace linkbox::solve {

class Budget {
 public:
  explicit Budget(const Params& p);
  // Takes one box from the budget; false when a limit is reached.
  bool take_box();
  // Between the costly steps of one box (the LPs of a relaxation): reads the clock and the
  // interrupt, so a limit is honoured within one LP, not one box.
  bool stop_now();
  // Stops the run from outside (another process reached a limit): as if it had been reached here.
  void halt(const char* why) { stop(why); }
  bool exhausted() const { return exhausted_.load(std::memory_order_relaxed); }
  const std::string& reason() const { return reason_; }
  long boxes_taken() const { return taken_.load(); }
  double elapsed() const;
  double cpu_elapsed() const;  // the process's CPU seconds since the budget began

 private:
  bool stop(const char* why);
  const char* over_time() const;
  std::chrono::steady_clock::time_point start_;
  double time_limit_;
  double cpu_start_;
  double cpu_limit_;
  long max_boxes_;
  const std::atomic<int>* interrupt_;
  std::atomic<long> taken_{0};
  std::atomic<bool> exhausted_{false};
  std::string reason_;
};

}  // namespace linkbox::solve
