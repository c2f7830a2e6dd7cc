#include "solve/progress.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace linkbox::solve {

Ticker::Ticker(bool progress, const std::vector<Tally>& tallies, const Budget& budget, Checkpointer& checkpoints)
    : progress_(progress), tallies_(tallies), budget_(budget), checkpoints_(checkpoints) {
  checkpoints_.tick(0);  // the first generation starts at once; the file follows the first deposits
  if (progress_ || checkpoints_.enabled()) thread_ = std::thread([this] { run(); });
}

Ticker::~Ticker() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Ticker::run() {
  std::unique_lock lock(m_);
  while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) {
    checkpoints_.tick(budget_.elapsed());
    if (progress_) print_line();
  }
}

void Ticker::print_line() {
  size_t finished = 0;
  long pending = 0;
  double done = 0;
  for (auto& t : tallies_) {
    const bool f = t.finished.load();
    finished += f;
    pending += f ? 0 : t.pending.load();
    done += f ? 1 : t.done.load();
  }
  // Pending boxes near roots or on a curve hold a sliver of the volume: below what the
  // tally (1 - pending volume) resolves, it reads "<0.001%", never 0 while boxes remain.
  // A race that turns to another candidate starts its tally afresh: what an earlier line
  // showed as explored stays so.
  const double left = std::min(shown_left_, 100 * std::max(0.0, 1 - done / static_cast<double>(tallies_.size())));
  shown_left_ = left;
  char volume[32];
  if (pending > 0 && left < 1e-3) std::snprintf(volume, sizeof volume, "<0.001%%");
  else std::snprintf(volume, sizeof volume, "%.3g%%", left);
  std::fprintf(stderr, "linkbox: %zu/%zu sub-problems, %ld boxes taken, %ld pending, %s of the volume left, %.1f s\n",
               finished, tallies_.size(), budget_.boxes_taken(), pending, volume, budget_.elapsed());
}

}  // namespace linkbox::solve
