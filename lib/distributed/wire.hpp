#pragma once
// The MPI job a process belongs to, and the messages its processes exchange. Only the main
// thread calls MPI (MPI_THREAD_FUNNELED): search threads hand their messages to it. Errors come
// back as codes (MPI_ERRORS_RETURN) and end the job with a message, never a hang; a peer that
// stays silent past a timeout is a fault too (the caller decides when, see Wire::heard).
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::distributed {

// Exit code of a run ended by a fault (a rank dead or silent, an MPI error).
constexpr int kFaultExit = 3;
// Rank 0 hears from every rank (and every rank from rank 0) this often, so silence means death.
constexpr double kBeat = 0.2;
// Seconds of silence after which a rank counts as dead: LINKBOX_MPI_TIMEOUT, default 60.
double fault_timeout();

class World {
 public:
  World(int* argc, char*** argv);
  ~World();  // MPI_Finalize
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Prints "linkbox: <why>" and ends every process of the job with `code`.
  [[noreturn]] void fail(const std::string& why, int code = kFaultExit) const;

 private:
  int rank_ = 0;
  int size_ = 1;
};

// A message: a small JSON head (its type under "t") and an optional payload (a sub-problem
// state as solve/checkpoint.hpp writes it).
struct Message {
  int from = 0;
  nlohmann::json head;
  std::string payload;
};

struct Traffic {
  long messages = 0;
  long bytes = 0;
  long beats = 0;  // of the messages: heartbeats (time-driven, not per box)
  long beat_bytes = 0;
  Traffic& operator+=(const Traffic& other);
  // A rank's goodbye carries its traffic to rank 0: these fields of a message head.
  void put(nlohmann::json& head) const;
  static Traffic from(const nlohmann::json& head);
};

class Wire {
 public:
  explicit Wire(const World& world);
  ~Wire();
  // To another rank through MPI; to this rank straight into its own inbox.
  void send(int to, Message m);
  // The next message that arrived, if any.
  std::optional<Message> receive();
  // Completes the sends under way (before MPI_Finalize), failing after `seconds`.
  void flush(double seconds);
  // Seconds since `rank` was last heard from.
  double silent(int rank) const;
  const Traffic& traffic() const { return traffic_; }

 private:
  struct Sending;
  const World& world_;
  std::deque<Message> local_;
  std::vector<std::unique_ptr<Sending>> sending_;
  std::vector<std::chrono::steady_clock::time_point> heard_;
  Traffic traffic_;
  void progress();
};

// Messages a process's other threads hand to its main thread, the only one that calls MPI.
class Outbox {
 public:
  void post(int to, Message m);
  // Sends what was posted through `wire`; true when there was something.
  bool drain(Wire& wire);
  // The main thread's pause between polls: MPI cannot wake a sleeping thread, so it polls
  // every 0.5 ms; a post ends the pause at once.
  void pause();

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::pair<int, Message>> queue_;
};

// Test hook: LINKBOX_MPI_TEST_DIE_RANK=r makes rank r die (LINKBOX_MPI_TEST_DIE_HOW=exit, the
// default) or stop answering (=hang) after LINKBOX_MPI_TEST_DIE_AFTER steps (default 20) of the
// phase LINKBOX_MPI_TEST_DIE_IN names: "search" (boxes; the default) or "verify" (clusters).
class TestDeath {
 public:
  TestDeath(int rank, const std::string& phase);
  void step();

 private:
  long after_ = -1;
  bool hang_ = false;
  std::atomic<long> steps_{0};
};

}  // namespace linkbox::distributed
