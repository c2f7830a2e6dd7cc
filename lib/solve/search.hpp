#pragma once
// Algorithm 1 of the iterated-LP paper (the same scheme as Section 4 of the spherical one):
// shrink a box until it is empty, small (a solution box) or no longer shrinks by more than
// rho, then bisect it (its widest split dimension, or as a Bisector chooses).
#include "prune/sequence.hpp"
#include "solve/bisector.hpp"
#include "solve/box_log.hpp"
#include "solve/budget.hpp"
#include "solve/certifier.hpp"
#include "solve/lending.hpp"
#include "solve/params.hpp"
#include "solve/result.hpp"
#include "solve/search_state.hpp"

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace linkbox::solve {

// A search's work is counted in boxes of propagation: a box costs its contractors' operations
// (prune::Counters::operations: the system's structure, each LP's size and pivots) over what
// one pass of HC4 and Newton costs on the system (Sequence::operations_per_box), and at least
// 1. So an LP is priced by the system it relaxes, not by a constant (see
// papers/decisions/search.md).
// A solution box that Newton has not certified is work still to come (clustering, Newton on its
// cluster, refinement): a strategy that leaves many such boxes is not cheap, however fast it
// reached them.
constexpr double kSolutionWork = 100;

// A search that can be paused and resumed: run() processes boxes until the search is
// complete, the budget runs out, or its work reaches a limit. Between calls, the pending boxes
// are kept. A run to a work limit stops at the box where one thread stops it: depth-first on
// every thread given (look-ahead mode, lookahead.hpp), breadth-first on one. A run without a
// limit ends with the same result on any thread count.
//
// With threads > 1 a Search processes boxes in parallel with clones of `contractor` (their
// counters are added back into it). Every box is processed the same way whatever the thread
// (the LP backoff travels with the box), and solutions come in search-tree order, so a
// complete search does not depend on the thread count or on scheduling. `certifier`
// (optional) is asked about every box the contractors say holds at most one root; a box it
// certifies is a solution at once. `bisector` (optional; none: the widest split side).
class Search final : public Lender {
 public:
  Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
         Budget& budget, Certifier* certifier = nullptr, const Bisector* bisector = nullptr);
  ~Search() override;
  // True when this search will do no more: it is complete, or the budget stopped it.
  // `box_cap` (with a work limit; 0: none): the run also ends before a box whose own work
  // passes it, and the box stays pending as its passes left it, their work counted (capped() true).
  bool run(int threads = 1, double work_limit = 0, double box_cap = 0);  // 0: no limit
  bool complete() const;  // no box pending: every box resolved
  double work() const;
  // Progress, as the share of the start box resolved (empty or solutions): by its volume over
  // the split dimensions (shrinking resolves volume too), or by the search tree, each
  // bisection splitting what is left of it in two equal halves whatever the volumes (the
  // pending nodes' 2^-depth, from their paths).
  double volume_done() const;
  double tree_done() const;
  // Asked before each box: when it says so, run() returns (with paused() true) and the
  // search can be saved and resumed as if it had never stopped.
  void pause_when(std::function<bool()> request);
  bool paused() const;
  bool capped() const;
  // Live figures for a progress line, stored after every box: pending boxes and the share of
  // the volume outside them.
  void report_to(std::atomic<long>* pending, std::atomic<double>* volume_outside);
  void log_to(BoxLog* log, size_t subproblem, int candidate);
  SearchState state() const;  // between runs
  void set_state(SearchState state);
  Result result();  // once run() returned true

  // Boxes searched elsewhere (solve/lending.hpp), for a search whose turns must end where one
  // process ends them (a race spread over processes).
  std::optional<SearchState::Node> give() override;
  std::optional<SearchState::Node> lend() override;
  void deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters) override;
  // Takes every lent box back: the front shrinks them itself (records still on the way would
  // only repeat what it finds; the caller stops taking them).
  void unlend();
  std::vector<prune::Counters> delivered_counters() const;  // summed over deliver()
  // A search of lent boxes records every box it commits, for its lender.
  void record_boxes();
  size_t recorded() const;  // records kept so far (asked between boxes too)
  std::vector<SearchState::Record> take_records();  // between runs: to send them on early

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace linkbox::solve
