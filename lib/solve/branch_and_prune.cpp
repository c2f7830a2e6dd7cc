#include "solve/branch_and_prune.hpp"

#include <deque>
#include <mutex>

namespace linkbox::solve {

Stats& Stats::operator+=(const Stats& o) {
  processed += o.processed;
  empty += o.empty;
  solution += o.solution;
  split += o.split;
  shrinks += o.shrinks;
  seconds += o.seconds;
  return *this;
}

Budget::Budget(const Params& p)
    : start_(std::chrono::steady_clock::now()), time_limit_(p.time_limit), max_boxes_(p.max_boxes) {}

double Budget::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Budget::take_box() {
  if (exhausted()) return false;
  long n = taken_.fetch_add(1) + 1;
  const char* why = nullptr;
  if (max_boxes_ > 0 && n > max_boxes_) why = "box limit reached";
  // Reading the clock every box is cheap next to a shrink, but not free: every 16th.
  else if (time_limit_ > 0 && (n & 15) == 0 && elapsed() > time_limit_) why = "time limit reached";
  if (!why) return true;
  static std::mutex m;
  std::lock_guard lock(m);
  if (!exhausted()) {
    reason_ = why;
    exhausted_.store(true);
  }
  return false;
}

Result branch_and_prune(const Box& start, prune::Contractor& contractor, std::span<const int> split_dims,
                        const Params& params, Budget& budget) {
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  std::deque<Box> pending{start};
  while (!pending.empty()) {
    if (!budget.take_box()) {
      r.complete = false;
      break;
    }
    Box box = std::move(pending.back());
    pending.pop_back();
    r.stats.processed++;
    bool empty = false;
    double size = 0;
    while (true) {
      Box before = box;
      r.stats.shrinks++;
      if (contractor.contract(box) == prune::Outcome::empty) {
        empty = true;
        break;
      }
      size = max_width(box, split_dims);
      if (size <= params.sigma || volume_ratio(before, box, split_dims) > params.rho) break;
    }
    if (empty) {
      r.stats.empty++;
    } else if (size <= params.sigma) {
      r.stats.solution++;
      r.solutions.push_back(std::move(box));
    } else {
      r.stats.split++;
      auto [a, b] = bisect(box, widest_dimension(box, split_dims));
      // Depth-first pops from the back: push the upper half first so the lower half is
      // explored first. Breadth-first takes from the front instead (see below).
      if (params.order == Order::depth_first) {
        pending.push_back(std::move(b));
        pending.push_back(std::move(a));
      } else {
        pending.push_front(std::move(a));
        pending.push_front(std::move(b));
      }
    }
  }
  if (!r.complete) r.pending.assign(pending.begin(), pending.end());
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace linkbox::solve
