#pragma once
// Inside a Search (search.hpp): look-ahead mode, for a run cut at a work limit with several
// threads (a race's turn), and lending. The search advances exactly as with one thread: boxes
// are committed (counted, their halves listed, their solutions kept) one at a time in
// depth-first order, so it stops at the same box with the same state. Every thread shrinks the
// first box in that order that nobody holds, the list's top or, while another thread has the
// top, a box after it (a listed one, or a half of a box shrunk ahead), and keeps the result
// until the top reaches it. What a box becomes does not depend on who shrinks it or when, so
// the tree is the one-thread tree. The threads shrink ahead only while the work committed and
// held stays below the limit: a turn leaves at most one box per thread ahead of its end, the
// waste when a raced candidate loses. A lent box is one held elsewhere: its record comes back
// (deliver) and is committed in its turn like a box shrunk ahead.
#include "solve/search_core.hpp"

#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace linkbox::solve::detail {

class Lookahead {
 public:
  // Runs `core` on `threads` threads until its work reaches `work_limit` or the top box passes
  // `box_cap` (0: none), as one thread would.
  void run(SearchCore& core, int threads, double work_limit, double box_cap);
  bool lent() const { return lent_; }  // some box was lent: runs to a limit come here
  void clear();                        // a new state: nothing ahead, nothing lent

  // Lending (solve/lending.hpp, Lender): `pending` is the core's list, between runs.
  std::optional<Node> lend(const std::deque<Node>& pending);
  void deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters);
  // Takes every lent box back: the front shrinks them itself (records still on the way would
  // only repeat what it finds; the caller stops taking them).
  void unlend();
  std::vector<prune::Counters> delivered_counters() const;  // summed over deliver()

 private:
  class Run;
  void reopen_capped();
  // A box processed ahead of its turn in depth-first order, or one a thread is shrinking, or
  // a child of such a box waiting for a thread.
  struct Ahead {
    // remote: lent (or below a lent box), its record not back yet. capped: it passed this
    // run's cap; the run ends when it reaches the top, where it is listed as its passes left
    // it; one that does not reach it is shrunk again next run, from the box as taken.
    enum class Mark { open, busy, done, remote, capped } mark = Mark::open;
    Node node;       // open; capped: as taken
    Processed done;  // done; capped: as far as it got
    bool delivered = false;  // done by another search (not in work_)
    bool listed = false;     // capped: the box is in the list (else `node` holds it)
  };
  // Boxes beyond the depth-first front, by path, kept across runs (a race's turns); `open_`
  // indexes the open ones, `work_` sums the done ones' work.
  std::map<std::string, Ahead> ahead_;
  std::set<std::string> open_;
  double work_ = 0;
  bool lent_ = false;
  std::vector<prune::Counters> delivered_counters_;
  // Guards the above, and the core during a run, against deliver() from another thread.
  mutable std::mutex m_;
  std::condition_variable cv_;
};

}  // namespace linkbox::solve::detail
