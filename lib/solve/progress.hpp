#pragma once
// The progress of a run on stderr, and the clock of its checkpoints.
#include "solve/search.hpp"
#include "solve/checkpoint.hpp"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace linkbox::solve {

// Live figures of one sub-problem, for the progress line.
struct Tally {
  std::atomic<long> pending{0};
  std::atomic<double> done{0};  // share of its volume outside the pending boxes
  std::atomic<bool> finished{false};
};

// Once a second, on a thread of its own while it lives: a progress line (when `progress`) and
// the checkpoint clock.
class Ticker {
 public:
  Ticker(bool progress, const std::vector<Tally>& tallies, const Budget& budget, Checkpointer& checkpoints);
  ~Ticker();

 private:
  void run();
  void print_line();
  bool progress_;
  double shown_left_ = 100;  // the volume left last printed, in percent: never shown higher
  const std::vector<Tally>& tallies_;
  const Budget& budget_;
  Checkpointer& checkpoints_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace linkbox::solve
