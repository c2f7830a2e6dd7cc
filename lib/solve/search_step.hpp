#pragma once
// Inside a Search (search.hpp): one box's step of Algorithm 1. The box is shrunk, then settled
// (empty, a solution) or bisected; what the step made of it is committed later, in the
// search's order (search.cpp, lookahead.cpp), or replayed from a record another search sent.
#include "solve/bisector.hpp"
#include "solve/box_log.hpp"
#include "solve/budget.hpp"
#include "solve/certifier.hpp"
#include "solve/params.hpp"
#include "solve/search_state.hpp"

#include <functional>
#include <utility>
#include <vector>

namespace linkbox::solve::detail {

using Node = SearchState::Node;

// What is searched, and how: fixed for the search's life.
struct Setup {
  prune::Sequence& contractor;
  Certifier* certifier;  // optional: asked about every box the contractors say holds at most one root
  const Bisector* bisector;  // optional: none bisects the widest split side
  Box start;
  std::vector<int> split_dims;
  Params params;
  Budget& budget;
};

// Where the search logs its boxes (none when `log` is null): the run's log and its place in it.
struct LogPlace {
  BoxLog* log = nullptr;
  size_t subproblem = 0;
  int candidate = 0;
};

// stopped: a limit or an interrupt came while the box was being shrunk; it goes back to the
// list as it was taken, so a resumed search does exactly what an unbroken one would.
// capped: the box's own work passed the run's cap; it goes back to the list as its passes
// left it, its work counted, and the run ends there.
enum class Verdict { empty, certified, solution, split, stopped, capped };

// One box shrunk, and what its turn in the search does with it.
struct Processed {
  Verdict verdict = Verdict::stopped;
  Node node;  // the box: as taken when stopped (it goes back to the list), else as shrunk so far
  double volume = 0;  // its share of the start box (split dims), as taken
  double work = 0;
  Stats stats;  // this box's counts
  std::pair<Node, Node> halves;  // when split
  int dim = -1;                  // the side bisected
};

// Shrinks `node` with `c` (and `certify`, when given) and bisects it when it is to be split.
// `stop` is asked between the contractor's costly steps; `cut` is set when it said stop.
// `box_cap` > 0: the box is capped once its work (boxes of propagation, search.hpp) passes
// it, asked between passes of the contractors and between the costly steps of a pass (the
// operations counted so far, Sequence::live_operations), so whether it is depends on the box alone.
Processed process(const Setup& setup, const LogPlace& log, prune::Sequence& c, Certifier* certify, Node node,
                  bool& cut, const std::function<bool()>& stop, double box_cap);

// A processed box as a record for its lender, and a record as the box its lender would have
// processed (the halves of a split made again, as one process makes them).
SearchState::Record record_of(const Processed& p);
Processed replay(SearchState::Record r);

}  // namespace linkbox::solve::detail
