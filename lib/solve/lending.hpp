#pragma once
// One search's boxes searched elsewhere (other processes: distributed/), as plain data both
// ways. A search that does not race gives boxes away; a race's leader lends them instead: a race
// decides by the order in which one process meets the boxes, so the lent boxes' outcomes come
// back to the leader as records (SearchState::Record), and its turns end where one process's
// would. Neither side sees the other's machinery: the search knows no messages, the processes
// no search tree.
#include "prune/counters.hpp"
#include "solve/search_state.hpp"
#include "solve/strategy.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::solve {

// A search as those who take its boxes see it (Search implements it). give and lend between
// runs only.
class Lender {
 public:
  virtual ~Lender() = default;
  // The oldest pending box, taken from the list: in depth-first order the shallowest, so the
  // largest subtree. None when fewer than two are pending.
  virtual std::optional<SearchState::Node> give() = 0;
  // The last box in depth-first order that nobody holds (never the next one), to be searched
  // elsewhere with records on (Search::record_boxes); it stays in the list.
  virtual std::optional<SearchState::Node> lend() = 0;
  // Hands back (any thread, any time) the records of a lent box's search, in any order and in
  // pieces, and the counters of the contractors that made them. The lender's depth-first front
  // takes each record as if it had shrunk the box itself, and waits when it reaches a lent box
  // whose record is not back: so every stop falls where one process's would.
  virtual void deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters) = 0;
};

// Asked between two boxes of a search by the one who runs it: distributed/ implements it.
class Sharing {
 public:
  virtual ~Sharing() = default;
  virtual bool asked() = 0;  // before every box, cheap: true pauses the search for give()
  // The paused search's oldest pending box may be taken (Lender::give), or none: true when
  // one was.
  virtual bool give(size_t subproblem, const Strategy& strategy, Lender& search) = 0;
  // A race's leader lends instead (Lender::lend): the box stays in its list and its subtree's
  // records come back through Lender::deliver, so the race runs as in one process. True when
  // a box was lent. The default lends nothing.
  virtual bool lend(size_t /*subproblem*/, const Strategy& /*strategy*/, Lender& /*search*/) {
    return false;
  }
  // The lender lost the lead: the searches of its lent boxes may stop, and their records, still
  // on the way, are no longer taken (the lender shrinks those boxes itself, Search::unlend).
  virtual void recall() {}
  // The race is over: its searches take no more deliveries.
  virtual void end_lending() {}
  // A search of lent boxes whose records nobody wants any more (the race ended): it may stop.
  virtual bool abandoned() { return false; }
  // A search of lent boxes sends its records on as it goes (the lender's front may be
  // waiting for them), not only with its piece at the end.
  virtual void send_records(size_t /*subproblem*/, std::vector<SearchState::Record> /*records*/) {}
};

}  // namespace linkbox::solve
