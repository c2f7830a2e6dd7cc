#include "solve/budget.hpp"

#include <ctime>
#include <mutex>

namespace linkbox::solve {

namespace {
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

Budget::Budget(const Params& p)
    : start_(std::chrono::steady_clock::now()),
      time_limit_(p.time_limit),
      cpu_start_(p.cpu_limit > 0 ? process_cpu_seconds() : 0),
      cpu_limit_(p.cpu_limit),
      max_boxes_(p.max_boxes),
      interrupt_(p.interrupt) {}

double Budget::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Budget::cpu_elapsed() const { return process_cpu_seconds() - cpu_start_; }

// The reason a time limit stops the run, or nullptr.
const char* Budget::over_time() const {
  if (time_limit_ > 0 && elapsed() > time_limit_) return "time limit reached";
  if (cpu_limit_ > 0 && cpu_elapsed() > cpu_limit_) return "CPU time limit reached";
  return nullptr;
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
  if ((n & 15) == 0)
    if (const char* why = over_time()) return stop(why);
  return true;
}

bool Budget::stop_now() {
  if (exhausted()) return true;
  if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return !stop("interrupted");
  if (const char* why = over_time()) return !stop(why);
  return false;
}

}  // namespace linkbox::solve
