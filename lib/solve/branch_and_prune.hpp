#pragma once
// Algorithm 1 of the iterated-LP paper (the same scheme as Section 4 of the spherical one):
// shrink a box until it is empty, small (a solution box) or no longer shrinks by more than
// rho, then bisect it (its widest split dimension, or as a Bisector chooses).
#include "prune/contractor.hpp"
#include "solve/bisector.hpp"
#include "solve/certifier.hpp"
#include "solve/result.hpp"

#include <atomic>
#include <chrono>
#include <span>
#include <memory>
#include <string>
#include <vector>

namespace linkbox::solve {

enum class Order { depth_first, breadth_first };

struct Params {
  double sigma = 1e-4;  // a box whose longest split side is <= sigma is a solution box
  double rho = 0.99;    // stop shrinking when volume(after)/volume(before) > rho
  Order order = Order::depth_first;
  double time_limit = 0;  // seconds; 0 = none
  long max_boxes = 0;     // processed boxes over the whole run; 0 = none
};

// Shared by the sub-problems of one run (and its threads): time and box-count limits.
class Budget {
 public:
  explicit Budget(const Params& p);
  // Takes one box from the budget; false when a limit is reached.
  bool take_box();
  bool exhausted() const { return exhausted_.load(std::memory_order_relaxed); }
  const std::string& reason() const { return reason_; }
  long boxes_taken() const { return taken_.load(); }
  double elapsed() const;

 private:
  std::chrono::steady_clock::time_point start_;
  double time_limit_;
  long max_boxes_;
  std::atomic<long> taken_{0};
  std::atomic<bool> exhausted_{false};
  std::string reason_;
};

struct Result {
  std::vector<Box> solutions;
  std::vector<char> certified;  // per solution: the certifier proved exactly one root in it
  Stats stats;
  bool complete = true;  // false when a limit stopped the search: unexplored boxes remain
  std::vector<Box> pending;  // the unexplored boxes when incomplete
};

// A search that can be paused and resumed: run() processes boxes until the search is done,
// the budget runs out, or `work` (boxes processed + kLpWork per LP solved) reaches a limit.
// Between calls, the pending boxes are kept. Pausing at a work limit is deterministic with
// one thread; with more, where it stops depends on scheduling (the finished result does not).
class Search {
 public:
  Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
         Budget& budget, Certifier* certifier = nullptr, const Bisector* bisector = nullptr);
  ~Search();
  // True when no box is pending (the search is complete, or the budget stopped it).
  bool run(int threads = 1, double work_limit = 0);  // 0: no limit
  double work() const;
  // Share of the start box's volume (over the split dimensions) in boxes already resolved
  // (empty or solutions): a rough progress measure (shrinking resolves volume too).
  double fraction_done() const;
  bool done() const;
  Result result();  // once run() returned true

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// One LP costs about as much as this many boxes of propagation and Newton (0.3-0.4 ms per LP
// against 20-40 us per box on the rigid 6R, Eco9 and planted systems).
constexpr double kLpWork = 15;

// With threads > 1 a Search processes boxes in parallel with clones of `contractor` (their
// counters are added back into it). Every box is processed the same way whatever the thread
// (the LP backoff travels with the box), and solutions come in search-tree order, so a
// finished search does not depend on the thread count or on scheduling. `certifier`
// (optional) is asked about every box the contractors say holds at most one root; a box it
// certifies is a solution at once. `bisector` (optional; none: the widest split side).

}  // namespace linkbox::solve
