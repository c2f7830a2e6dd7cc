#include "distributed/mpi_solve.hpp"

#include "distributed/coordinator.hpp"
#include "distributed/slots.hpp"

#include <chrono>
#include <optional>
#include <string>

namespace linkbox::distributed {

using nlohmann::json;

json Figures::json() const {
  return {{"ranks", ranks},
          {"threads_per_rank", slots},
          {"messages", traffic.messages},
          {"bytes", traffic.bytes},
          {"heartbeat_messages", traffic.beats},
          {"heartbeat_bytes", traffic.beat_bytes},
          {"units", units},
          {"steals", steals},
          {"boxes_given", boxes_given},
          {"boxes", boxes},
          {"handled", handled},
          {"handling_seconds", handling_seconds},
          {"verification", {{"clusters", clusters},
                            {"clusters_on_other_ranks", clusters_elsewhere},
                            {"messages", verify_traffic.messages},
                            {"bytes", verify_traffic.bytes},
                            {"heartbeat_messages", verify_traffic.beats}}}};
}

namespace {

// One rank's part: its main thread, the only one that calls MPI, passes messages between the
// wire, its slots and (rank 0) the coordinator, and keeps the heartbeat.
class Process {
 public:
  Process(const formulate::Formulation& f, const solve::RunOptions& options, const World& world)
      : options_(options),
        world_(world),
        wire_(world),
        budget_(options.params),
        slots_(f, options, budget_, world.rank(), outbox_) {
    if (root()) coordinator_.emplace(f, options, world, wire_, budget_, slots_.count());
  }
  std::optional<solve::CaseResult> run(Figures* figures);

 private:
  bool root() const { return world_.rank() == 0; }
  bool poll();
  void handle(Message m);
  void leave(const Message& m);
  void heartbeat(double timeout);

  const solve::RunOptions& options_;
  const World& world_;
  Wire wire_;
  solve::Budget budget_;
  Outbox outbox_;
  Slots slots_;
  std::optional<Coordinator> coordinator_;  // rank 0
  bool leaving_ = false;     // this rank's part is over
  bool told_stop_ = false;   // rank 0 knows that this rank's budget ran out
  std::optional<int> failed_;  // the exit code of a run an error ended
};

// Sends what the slots posted and handles what arrived: true when there was something.
bool Process::poll() {
  bool active = outbox_.drain(wire_);
  while (auto m = wire_.receive()) {
    const auto t0 = std::chrono::steady_clock::now();
    handle(std::move(*m));
    const auto t1 = std::chrono::steady_clock::now();
    if (coordinator_) coordinator_->count_handled(std::chrono::duration<double>(t1 - t0).count());
    active = true;
  }
  return active;
}

void Process::handle(Message m) {
  const std::string t = m.head.at("t");
  if (t == "work") {
    const int k = m.head.at("slot");
    slots_.work(k, std::move(m));
  } else if (t == "steal") {
    slots_.steal(m.head.at("slot").get<int>(), m.head.at("unit").get<long>());
  } else if (t == "records" && !m.head.contains("unit")) {
    // rank 0: a batch of a lent subtree's records, on its way to the lender
    coordinator_->forward_records(m.head.at("sub").get<size_t>(), m.head.at("lease").get<long>(), m.payload);
  } else if (t == "recall") {
    // rank 0: the race's lender lost the lead; the searches of its lent boxes may stop
    coordinator_->recall(m.head.at("sub").get<size_t>(), m.head.at("below").get<long>());
  } else if (t == "records") {
    slots_.records(m.head.at("slot").get<int>(), m.head.at("unit").get<long>(), m.head.at("lease").get<long>(),
                   m.payload);
  } else if (t == "abandon") {
    slots_.abandon(m.head.at("sub").get<size_t>(), m.head.at("below").get<long>());
  } else if (t == "stop") {
    budget_.halt(m.head.at("why").get<std::string>().c_str());
    told_stop_ = true;
  } else if (t == "quit" || t == "fail") {
    leave(m);
  } else if (coordinator_) {
    coordinator_->handle(m);
  }
}

// The run is over (or failed): the slots end and the rank says goodbye with its figures.
void Process::leave(const Message& m) {
  if (m.head.at("t") == "fail") {
    budget_.halt("failed");
    if (!failed_) failed_ = m.head.at("code").get<int>();
  }
  slots_.end();
  // Counted before this message, which the totals then miss: one per rank.
  Traffic x = wire_.traffic();
  x.messages += world_.rank() != 0;
  json head = {{"t", "bye"}, {"boxes", budget_.boxes_taken()}};
  x.put(head);
  wire_.send(0, {0, head, ""});
  leaving_ = world_.rank() != 0;
}

// Rank 0 and each other rank hear from each other every kBeat: the ranks' boxes and slots go
// to rank 0, and a rank silent past `timeout` ends the job.
void Process::heartbeat(double timeout) {
  if (root())
    for (int r = 1; r < world_.size(); ++r) wire_.send(r, {0, {{"t", "beat"}}, ""});
  json units = json::array(), shares = json::array();
  slots_.beat(units, shares);
  wire_.send(0, {0, {{"t", "beat"}, {"boxes", budget_.boxes_taken()}, {"units", units}, {"shares", shares}}, ""});
  for (int r = root() ? 1 : 0; r < (root() ? world_.size() : 1); ++r)
    if ((!root() || !coordinator_->gone(r)) && wire_.silent(r) > timeout)
      world_.fail("rank " + std::to_string(r) + " sent nothing for " + std::to_string(static_cast<int>(timeout)) +
                  " s (dead or hung; LINKBOX_MPI_TIMEOUT sets the limit)");
}

std::optional<solve::CaseResult> Process::run(Figures* figures) {
  slots_.start();
  const double timeout = fault_timeout();
  auto last_beat = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  auto last_line = std::chrono::steady_clock::now();
  while (true) {
    const bool active = poll();
    if (leaving_ || (coordinator_ && coordinator_->over())) break;
    if (!told_stop_ && budget_.exhausted()) {
      told_stop_ = true;
      wire_.send(0, {0, {{"t", "stopped"}, {"why", budget_.reason()}}, ""});
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_beat).count() >= kBeat) {
      last_beat = now;
      heartbeat(timeout);
    }
    if (root() && options_.progress && std::chrono::duration<double>(now - last_line).count() >= 1) {
      last_line = now;
      coordinator_->progress_line();
    }
    if (!active) outbox_.pause();
  }
  wire_.flush(timeout);
  if (coordinator_ && coordinator_->failure()) {
    const auto& [code, text] = *coordinator_->failure();
    throw Failed(code, text);
  }
  if (failed_) throw Ended{*failed_};
  if (!root()) return std::nullopt;
  return coordinator_->result(figures);
}

}  // namespace

std::optional<solve::CaseResult> solve_distributed(const formulate::Formulation& formulation,
                                                   const solve::RunOptions& options, const World& world,
                                                   Figures* figures) {
  Process p(formulation, options, world);
  return p.run(figures);
}

}  // namespace linkbox::distributed
