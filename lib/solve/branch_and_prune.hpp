#pragma once
// Algorithm 1 of the iterated-LP paper (the same scheme as Section 4 of the spherical one):
// shrink a box until it is empty, small (a solution box) or no longer shrinks by more than
// rho, then bisect it (its widest split dimension, or as a Bisector chooses).
#include "prune/sequence.hpp"
#include "solve/bisector.hpp"
#include "solve/certifier.hpp"
#include "solve/result.hpp"

#include <atomic>
#include <chrono>
#include <functional>
#include <span>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::solve {

enum class Order { depth_first, breadth_first };

struct Params {
  double sigma = 1e-4;  // a box whose longest split side is <= sigma is a solution box
  double rho = 0;       // stop shrinking when volume(after)/volume(before) > rho; 0: auto (rho_for)
  Order order = Order::depth_first;
  double time_limit = 0;  // seconds; 0 = none
  long max_boxes = 0;     // processed boxes over the whole run; 0 = none
  // When set and non-zero (a signal arrived), the run stops as if a limit were reached, with
  // stop reason "interrupted".
  const std::atomic<int>* interrupt = nullptr;
};

// rho when the user gave none: the papers' 0.99 on the spherical formulation (their method
// and tables); 0.8 elsewhere. A pass of propagation and Newton that removes less than a fifth
// of the box costs more than the bisection it delays: boxes +5-15%, CPU -25-50% (Eco9 3.5 ->
// 2.7 s, Caprasse 0.50 -> 0.37 s, rigid 6R 0.72 -> 0.39 s, hc4,newton).
constexpr double kPapersRho = 0.99;
constexpr double kAutoRho = 0.8;
inline double rho_for(double rho, bool spherical) { return rho > 0 ? rho : spherical ? kPapersRho : kAutoRho; }

// Shared by the sub-problems of one run (and its threads): time and box-count limits.
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

 private:
  bool stop(const char* why);
  std::chrono::steady_clock::time_point start_;
  double time_limit_;
  long max_boxes_;
  const std::atomic<int>* interrupt_;
  std::atomic<long> taken_{0};
  std::atomic<bool> exhausted_{false};
  std::string reason_;
};

// A search's whole state between two boxes: what a checkpoint stores (solve/checkpoint.hpp).
struct SearchState {
  struct Node {  // a box and its place in the search tree: '0' = lower half, '1' = upper half
    Box box;
    std::string path;
    prune::Sequence::Backoff backoff;  // inherited from the parent (see Sequence)
  };
  struct Found {
    std::string path;
    Box box;
    bool certified = false;
  };
  // One box as the search committed it, for another search to replay: a lent subtree's boxes
  // come back to the lender as these (Search::lend, Search::deliver).
  struct Record {
    std::string path;
    char outcome = 'e';  // 'e' empty, 's' solution, 'c' certified solution, 'x' split
    double work = 0, volume = 0;
    Stats stats;
    Box box;       // a solution's box; a split's box before bisection
    int dim = -1;  // split: the side bisected (the halves follow, as one process makes them)
    prune::Sequence::Backoff backoff;  // split: the box's, its halves take its child()
  };
  std::vector<Node> pending;  // in list order (the back is taken first depth-first)
  std::vector<Found> solutions;
  std::vector<Record> records;  // when recording (Search::record_boxes), in commit order
  Stats stats;
  double work = 0;
  double volume_done = 0;
};

struct Result {
  std::vector<Box> solutions;
  std::vector<char> certified;  // per solution: the certifier proved exactly one root in it
  Stats stats;
  bool complete = true;  // false when a limit stopped the search: unexplored boxes remain
  std::vector<Box> pending;  // the unexplored boxes when incomplete
  double volume_left = 0;    // their share of the start box's volume (split dimensions)
};

// Every box the searches of a run process, to replay the run (papers/benchmarks/scaling.py
// models distributed runs from it: the tree, and what each box cost). Costs two clock reads per
// box when a search logs to one.
class BoxLog {
 public:
  struct Entry {
    size_t subproblem;
    int candidate;     // which raced strategy (0 when one ran)
    std::string path;  // the box's place in the search tree
    char outcome;      // 'e' empty, 's' solution, 'x' split
    double seconds;
  };
  void add(Entry e) {
    std::lock_guard lock(m_);
    entries_.push_back(std::move(e));
  }
  std::vector<Entry> take() {
    std::lock_guard lock(m_);
    return std::move(entries_);
  }

 private:
  std::mutex m_;
  std::vector<Entry> entries_;
};

// A search that can be paused and resumed: run() processes boxes until the search is done,
// the budget runs out, or `work` (boxes processed + kLpWork per LP solved) reaches a limit.
// Between calls, the pending boxes are kept. A run to a work limit stops at the box where one
// thread stops it: depth-first on every thread given (look-ahead mode, branch_and_prune.cpp),
// breadth-first on one. A run without a limit ends with the same result on any thread count.
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
  // The share of the search tree resolved, each bisection splitting what is left of it in
  // two equal halves whatever the volumes: the pending nodes' 2^-depth, from their paths.
  double tree_done() const;
  bool done() const;
  bool finished() const;  // every box resolved: the search is complete
  // Asked before each box: when it says so, run() returns (with paused() true) and the
  // search can be saved and resumed as if it had never stopped.
  void pause_when(std::function<bool()> request);
  bool paused() const;
  // Live figures for a progress line, stored after every box: pending boxes and the share of
  // the volume outside them.
  void report_to(std::atomic<long>* pending, std::atomic<double>* fraction_done);
  void log_to(BoxLog* log, size_t subproblem, int candidate);
  SearchState state() const;  // between runs
  void set_state(SearchState state);

  // Lending, for a search whose turns must end where one process ends them (a race spread over
  // processes). lend() takes the last box in depth-first order that nobody holds (never the
  // next one), to be searched elsewhere with record_boxes() on. deliver() (any thread,
  // any time) hands back that search's records (in any order, in pieces), and the counters
  // of the contractors that made them. The lender's depth-first front takes each record as if
  // it had shrunk the box itself, and waits when it reaches a lent box whose record is not
  // back: so every stop falls where one process's would. Between runs only (lend).
  std::optional<SearchState::Node> lend();
  void deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters);
  // Takes every lent box back: the front shrinks them itself (records still on the way would
  // only repeat what it finds; the caller stops taking them).
  void unlend();
  std::vector<prune::Counters> delivered_counters() const;  // summed over deliver()
  void record_boxes();
  size_t recorded() const;  // records kept so far (asked between boxes too)
  std::vector<SearchState::Record> take_records();  // between runs: to send them on early
  Result result();  // once run() returned true

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// One LP costs about as much as this many boxes of propagation and Newton (0.3-0.4 ms per LP
// against 20-40 us per box on the rigid 6R, Eco9 and planted systems).
constexpr double kLpWork = 15;
// A solution box that Newton has not certified is work still to come: clustering, Newton on
// its cluster, refinement. On a curve (cyclohexane at sigma 0.1) that cost ~4 ms per box
// when this was set, about 100 boxes of propagation; a strategy that leaves many such boxes
// is not cheap, however fast it reached them. Since the curve verification got faster it is
// ~0.6 ms, about 27 boxes of the winning strategy (measured on cyclohexane and bicyclohexane),
// but 20 alone lost bicyclohexane's race to the strategy that left 50 000 such boxes (172 s
// against 40 s): it must change together with the LP's price, which is 2.8-20 boxes by
// system, not kLpWork (issue 9's note).
constexpr double kSolutionWork = 100;

// With threads > 1 a Search processes boxes in parallel with clones of `contractor` (their
// counters are added back into it). Every box is processed the same way whatever the thread
// (the LP backoff travels with the box), and solutions come in search-tree order, so a
// finished search does not depend on the thread count or on scheduling. `certifier`
// (optional) is asked about every box the contractors say holds at most one root; a box it
// certifies is a solution at once. `bisector` (optional; none: the widest split side).

}  // namespace linkbox::solve
