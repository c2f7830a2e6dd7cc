#include "solve/budget.hpp"

#include <mutex>

namespace linkbox::solve {

Budget::Budget(const Params& p)
    : start_(std::chrono::steady_clock::now()),
      time_limit_(p.time_limit),
      max_boxes_(p.max_boxes),
      interrupt_(p.interrupt) {}

double Budget::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Budget::stop(const char* why) {
  static std::mutex m;
  std::lock_guard lock(m);
  if (!exhausted()) {
    reason_ = why;
    exhausted_.store(true);
  }
  return false;
}

bool Budget::take_box() {
  if (exhausted()) return false;
  long n = taken_.fetch_add(1) + 1;
  if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return stop("interrupted");
  if (max_boxes_ > 0 && n > max_boxes_) return stop("box limit reached");
  // Reading the clock every box is cheap next to a shrink, but not free: every 16th.
  if (time_limit_ > 0 && (n & 15) == 0 && elapsed() > time_limit_) return stop("time limit reached");
  return true;
}

bool Budget::stop_now() {
  if (exhausted()) return true;
  if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return !stop("interrupted");
  if (time_limit_ > 0 && elapsed() > time_limit_) return !stop("time limit reached");
  return false;
}

}  // namespace linkbox::solve
