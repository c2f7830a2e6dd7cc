#pragma once
// A rank's search slots: --threads threads that run the units rank 0 hands them (a whole
// sub-problem, a subtree given or lent, the finish of a sub-problem) and answer its requests
// for boxes. They never call MPI: their messages go through the rank's Outbox, and the main
// thread hands them theirs through the calls below.
#include "distributed/wire.hpp"
#include "formulate/formulation.hpp"
#include "solve/budget.hpp"
#include "solve/solve_case.hpp"

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace linkbox::distributed {

class Slots {
 public:
  Slots(const formulate::Formulation& f, const solve::RunOptions& options, solve::Budget& budget, int rank,
        Outbox& outbox);
  ~Slots();
  int count() const { return static_cast<int>(slots_.size()); }
  void start();  // each slot's thread; it tells rank 0 it is idle
  void end();    // tells every slot to quit, and waits for them

  // From the main thread, as rank 0's messages arrive:
  void work(int k, Message m);             // a unit for slot k, queued behind the one it runs
  void steal(int k, long unit);            // a box of slot k's `unit` is asked for
  void records(int k, long unit, long lease, const std::string& payload);  // for its race's lender
  void abandon(size_t sub, long below);    // lent boxes of leases below `below` are not wanted
  // What the heartbeat says of the slots: each one's unit (-1: none) and whether its search
  // shares boxes (1) or not yet (0).
  void beat(nlohmann::json& units, nlohmann::json& shares) const;

 private:
  struct Slot;
  class Sharing;
  void main(int k);
  Message next(Slot& s);
  // Runs the unit `m` names; `done`, the message that reports it, takes its result.
  void run_unit(Sharing& sharing, const Message& m, Message& done);
  void post(Message m) { outbox_.post(0, std::move(m)); }
  void report_error(int code, const std::string& text);

  const formulate::Formulation& f_;
  solve::RunOptions options_;  // a unit's: one thread, quiet, no checkpoint
  solve::Budget& budget_;
  TestDeath death_;
  Outbox& outbox_;
  std::vector<std::unique_ptr<Slot>> slots_;
  mutable std::mutex abandoned_m_;
  std::map<size_t, long> abandoned_;  // per sub-problem: lent boxes of leases below this are not wanted
};

}  // namespace linkbox::distributed
