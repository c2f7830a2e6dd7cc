#pragma once
// Rank 0's coordination of a distributed search (mpi_solve.hpp), in its main thread: it hands
// out units (whole sub-problems in batches, then boxes asked of running searches, then the
// finish of each sub-problem whose boxes went to several slots), merges the pieces, routes a
// race's lent boxes' records back to the race, sums the ranks' boxes against the box limit, and
// ends the run.
#include "distributed/mpi_solve.hpp"
#include "distributed/wire.hpp"
#include "formulate/formulation.hpp"
#include "solve/budget.hpp"
#include "solve/share.hpp"

#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace linkbox::distributed {

class Coordinator {
 public:
  Coordinator(const formulate::Formulation& f, const solve::RunOptions& options, const World& world, Wire& wire,
              solve::Budget& budget, int slots_per_rank);
  // A message for rank 0 as coordinator (a slot's report, a rank's heartbeat or goodbye);
  // then hands out what can be handed out, and ends the run when all is done.
  void handle(const Message& m);
  // A batch of a lent subtree's records, on its way to the race that lent it.
  void forward_records(size_t sub, long lease, const std::string& payload);
  // A race's lender lost the lead: the searches of its lent boxes may stop.
  void recall(size_t sub, long below);

  void count_handled(double seconds);  // a message rank 0's main thread handled, and its time
  bool gone(int rank) const { return gone_[rank]; }  // said goodbye
  bool over() const;  // the run is ended and every rank said goodbye
  // An error in a rank's search: its exit code and text.
  const std::optional<std::pair<int, std::string>>& failure() const { return failure_; }
  void progress_line() const;
  // The run's result, as solve_case gives it, once over.
  solve::CaseResult result(Figures* figures);

 private:
  // What rank 0 knows of a unit under way.
  struct Running {
    long unit;
    size_t sub;
    std::string kind;
    bool shares = false;   // as the rank's last heartbeat said
    double dry_until = 0;  // gave nothing when last asked: not asked again before then (Budget::elapsed)
    int thief = -1;        // a slot waiting for a box of this unit
  };
  struct SubState {
    int live = 0;          // its units under way (the sub-problem and its subtrees)
    int owner = -1;        // the worker whose race lent boxes: their records go to it
    long owner_unit = -1;  // and its unit
    std::optional<solve::Piece> merged;
    std::optional<solve::SubResult> result;
  };

  void on_beat(const Message& m);
  void on_gift(const Message& m);
  void on_done(const Message& m);
  void on_error(const Message& m);
  void on_bye(const Message& m);
  void dispatch();
  void steal_for_idle();
  void stop(const std::string& why);
  void send_unit(int worker, const std::string& kind, size_t sub, nlohmann::json extra, std::string payload);
  void send_all(const nlohmann::json& head);
  int worker_of(const Message& m) const { return m.from * slots_per_rank_ + m.head.at("slot").get<int>(); }
  bool all_done() const;

  const formulate::Formulation& f_;
  const solve::RunOptions& options_;
  const World& world_;
  Wire& wire_;
  solve::Budget& budget_;
  int slots_per_rank_;
  std::vector<SubState> subs_;
  size_t next_sub_ = 0;
  // Per worker (rank x slot): the units sent, in the order it runs them; the front one runs.
  std::vector<std::deque<Running>> queue_;
  std::vector<char> waiting_;  // per worker: asked a running search for a box on its behalf
  std::deque<size_t> to_finish_;
  bool stopping_ = false;
  bool quitting_ = false;
  long next_unit_ = 0;
  std::vector<long> boxes_;  // per rank, as last reported
  std::vector<char> gone_;   // per rank: said goodbye
  std::optional<std::pair<int, std::string>> failure_;  // an error that ends the run
  Figures figures_;
};

}  // namespace linkbox::distributed
