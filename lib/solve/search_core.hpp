#pragma once
// Inside a Search (search.hpp): its parts, grouped by concern, and the steps both of its ways
// of running share: the plain run (search.cpp) and the look-ahead (lookahead.cpp).
#include "solve/search_step.hpp"

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <vector>

namespace linkbox::solve::detail {

// What the commits built: the pending boxes, and what left the list.
struct Committed {
  std::deque<Node> pending;
  std::vector<SearchState::Found> solutions;
  Stats stats;
  double work = 0;
  double volume_done = 0;  // fraction of the start box's volume (split dims) resolved
  double volume_pending = 1;  // and in pending boxes (what shrinking removed is in neither)
  double seconds = 0;
};

// Why a run returned before the search's end.
struct RunControl {
  bool stopped = false;  // by the budget
  std::function<bool()> pause_request;
  bool paused = false;  // the last run() returned on a pause request
  bool capped = false;  // the last run() ended at a box that passed its cap
};

// Live figures for a progress line, stored after every commit (none when null).
struct Tallies {
  std::atomic<long>* pending = nullptr;
  std::atomic<double>* volume_outside = nullptr;  // of the pending boxes
};

// A search of lent boxes keeps a record of every box it commits, for the lender.
struct Records {
  bool on = false;
  std::vector<SearchState::Record> list;
};

// The contractors (and certifiers) of the threads beyond the first: kept across runs (a race
// has many short turns, and a clone of an LP strategy is not free); their counters are handed
// over to the search's own contractor after each run.
struct Crew {
  std::vector<std::unique_ptr<prune::Sequence>> contractors;
  std::vector<std::unique_ptr<Certifier>> certifiers;
};

struct SearchCore {
  Setup setup;
  Committed committed;
  RunControl control;
  Tallies tallies;
  LogPlace log;
  Records records;
  Crew crew;

  Processed process(prune::Sequence& c, Certifier* certify, Node node, bool& cut, const std::function<bool()>& stop,
                    double box_cap) {
    return detail::process(setup, log, c, certify, std::move(node), cut, stop, box_cap);
  }
  // Counts a processed box, lists its halves or keeps its solution (and its record).
  void commit(Processed&& p);
  // Counts the work of a capped box, whose node (as its passes left it) goes back on the list.
  void keep_capped(const Processed& p);
  void publish_volume();  // the volume left, for the progress line
  // Runs boxes in the list's order on `threads` threads, to the end, the budget, a pause or
  // (on one thread) `work_limit` or a box that passes `box_cap` (process()).
  void run(int threads, double work_limit, double box_cap);
  // Runs `worker` on this thread with the search's own contractor and on threads - 1 more
  // with the crew's, then adds their counters to the contractor's.
  void on_threads(int threads, const std::function<void(prune::Sequence&, Certifier*)>& worker);
};

}  // namespace linkbox::solve::detail
