#pragma once
// "auto" on a system with several candidates: their searches advance in turns, measured in
// work (boxes of propagation, search.hpp), until one finishes; its boxes are the result, as if
// it had run alone. Turns double. After a first turn each, the candidate whose projected total
// work (work / share of the search tree resolved) is clearly smaller (lead.hpp) gets the turn
// and the others a share of it, so a wrong projection costs a bounded factor; the lead runs
// first. A turn ends at the box where a one-thread depth-first search would end it, whatever
// the thread count (Search::run), so the race is deterministic. One candidate is a race of
// one: its search runs to the end.
//
// Spread over processes, the leader lends boxes (share.hpp): their records come back, so the
// race goes as in one process.
//
// Twins: a candidate whose stages extend another's (hc4,newton/lp extends hc4,newton) makes
// every box what the other makes it until its first stall (prune::Staged::stalls). When the
// shorter one's turn had no stall, and the longer one's turn starts from the same state with
// the same target, the longer one takes the shorter one's state instead of running: the same
// race, without running the same boxes twice.
#include "formulate/formulation.hpp"
#include "solve/search.hpp"
#include "solve/certifier.hpp"
#include "solve/checkpoint.hpp"
#include "solve/pruning.hpp"
#include "solve/share.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkbox::solve {

// A candidate: its contractors, its certifier and (once started) its search.
struct Racer {
  Pruning pruning;
  NaturalCertifier certifier;
  std::unique_ptr<Search> search;
};

std::unique_ptr<Racer> make_racer(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                                  const Strategy& strategy, const StrategyOptions& options);

class Race {
 public:
  // Every racer has its search. `lending`: where a race's leader lends boxes, or nullptr.
  // `twins`: whether twins share their turns (not with lending, nor where every box is logged).
  Race(std::vector<std::unique_ptr<Racer>> racers, Sharing* lending, bool twins = true);
  ~Race();  // whichever way the race ends (an exception too), no record is delivered after
  Race(const Race&) = delete;
  Race& operator=(const Race&) = delete;

  size_t size() const { return racers_.size(); }
  Racer& racer(size_t k) { return *racers_[k]; }
  bool over() const { return at_.winner >= 0; }

  // Where sub-problem i's race stood at a checkpoint (resume), and where it stands.
  void resume(size_t i, const SubCheckpoint& saved);
  SubCheckpoint checkpoint() const;

  // Runs the candidate whose turn it is, on `threads`, up to its turn's target (a race of
  // one: to the end). It may also stop paused (Search::paused) or by a limit; when it
  // finished, it won.
  Search& run_turn(int threads);
  void next_turn();  // the running candidate reached its target
  // Asked before each box of candidate k: whether it should pause to lend a box (see lend).
  bool lend_asked(size_t k);
  // After a pause: lends a box of the running candidate when asked.
  void lend(size_t subproblem);
  // The race is over or stopped: lending ends, and when the lender won, the lent boxes'
  // contractor counters (they worked for it) become its own.
  void end_lending();

  // The winner; after a limit, the candidate that resolved most of the volume.
  Racer& best();
  // Each candidate's strategy and work, the winner last; empty unless several raced and one won.
  std::vector<std::pair<std::string, double>> record();
  const std::vector<std::string>& choices() const { return at_.choices; }
  size_t twin_turns() const { return twin_turns_; }  // turns taken from a twin

 private:
  void start_turn();
  void pick_lead();
  size_t running() const;  // the candidate whose turn it is
  std::string name_of(size_t k) const;
  double target_of(size_t k) const;
  bool copied_twin(size_t k);
  void note_capped(size_t k);
  std::vector<std::unique_ptr<Racer>> racers_;
  // Per candidate: the candidate whose stages its own extend (twins), or -1.
  std::vector<int> extends_;
  // The last turn of a candidate another extends: at its start, its work and stalls, and its target.
  struct TwinTurn {
    int candidate = -1;
    double work = 0, target = 0;
    long stalls = 0;
  } twin_turn_;
  size_t twin_turns_ = 0;
  RacePosition at_;
  Sharing* lending_;
  int lender_ = -1;  // the candidate whose boxes are lent (one only: the first to lend)
};

}  // namespace linkbox::solve
