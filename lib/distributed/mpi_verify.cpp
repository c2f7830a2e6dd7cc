#include "distributed/mpi_verify.hpp"

#include "input/input_error.hpp"
#include "interval/rigorous.hpp"
#include "verify/cluster_json.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <mutex>
#include <thread>

namespace linkbox::distributed {

using nlohmann::json;

namespace {

// The phase's messages are named apart from the search's ("v-"): a rank still in the search
// (rank 0 waiting for the others' goodbyes) and a rank already here may hear from each other.
class Phase {
 public:
  Phase(const formulate::Formulation& f, const verify::VerifyOptions& options, const World& world)
      : f_(f), options_(options), world_(world), wire_(world), death_(world.rank(), "verify") {
    threads_ = std::max(1, options.threads);
  }
  std::optional<verify::VerifyReport> run(const solve::CaseResult* result, Figures* figures);

 private:
  // ---- verifying threads (they never call MPI)
  void thread_main() {
    while (true) {
      std::unique_lock lock(m_);
      cv_.wait(lock, [&] { return quit_ || !todo_.empty(); });
      if (todo_.empty()) return;
      auto [k, task] = std::move(todo_.front());
      todo_.pop_front();
      lock.unlock();
      death_.step();
      Message out{0, {{"t", "v-report"}, {"k", k}}, ""};
      try {
        out.payload = verify::report_json(verify::verify_cluster(f_, task, options_)).dump();
      } catch (const input::InputError& e) {
        out.head = {{"t", "v-error"}, {"code", 2}, {"text", e.what()}};
      } catch (const std::invalid_argument& e) {
        out.head = {{"t", "v-error"}, {"code", 2}, {"text", std::string("linkbox: ") + e.what()}};
      } catch (const std::exception& e) {
        out.head = {{"t", "v-error"}, {"code", 1}, {"text", std::string("linkbox: internal error: ") + e.what()}};
      }
      post(0, std::move(out));
    }
  }
  void post(int to, Message m) { outbox_.post(to, std::move(m)); }
  // Ends this rank's threads once they finish the cluster in hand; `drop`: the clusters queued too.
  void quit(bool drop) {
    std::lock_guard lock(m_);
    quit_ = true;
    if (drop) todo_.clear();
    cv_.notify_all();
  }

  // ---- every rank's main thread
  void handle(Message m);
  // ---- rank 0
  void dispatch();
  void end(bool failed) {
    if (quitting_) return;
    quitting_ = true;
    for (int r = 1; r < world_.size(); ++r)
      wire_.send(r, {0, {{"t", failed ? "v-fail" : "v-quit"}, {"code", failed ? failure_->first : 0}}, ""});
    quit(failed);
  }

  const formulate::Formulation& f_;
  const verify::VerifyOptions& options_;
  const World& world_;
  Wire wire_;
  TestDeath death_;
  int threads_ = 1;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::pair<size_t, verify::ClusterTask>> todo_;  // under m_
  bool quit_ = false;                                        // under m_
  std::atomic<int> alive_{0};
  Outbox outbox_;
  bool quitting_ = false;
  bool leaving_ = false;
  std::optional<std::pair<int, std::string>> failure_;

  // rank 0
  std::vector<verify::ClusterTask> tasks_;
  std::vector<std::optional<verify::ClusterReport>> reports_;
  size_t next_ = 0, received_ = 0;
  std::vector<int> held_;   // per rank: clusters sent, not yet reported
  std::vector<char> gone_;  // per rank: said goodbye
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  bool timed_out_ = false;  // clusters not handed out by options_.time_limit were skipped
  Figures figures_;
};

// Each rank holds at most two clusters per thread: one under way, one ready, so no thread
// waits for a round trip and none is left with a long queue at the end. Rank 0 is served first,
// so a run with few clusters keeps them at home.
void Phase::dispatch() {
  if (quitting_) return;
  if (options_.skip_rest && options_.skip_rest()) {
    // Interrupted twice: the clusters not handed out are reported skipped, here and now.
    for (; next_ < tasks_.size(); ++next_, ++received_) reports_[next_] = verify::verify_cluster(f_, tasks_[next_], options_);
  }
  if (options_.time_limit > 0 && next_ < tasks_.size() &&
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > options_.time_limit) {
    timed_out_ = true;
    for (; next_ < tasks_.size(); ++next_, ++received_)
      reports_[next_] = verify::skipped_cluster(f_, tasks_[next_], "time limit");
  }
  for (int r = 0; r < world_.size() && next_ < tasks_.size(); ++r) {
    json batch = json::array();
    for (; held_[r] < 2 * threads_ && next_ < tasks_.size(); ++held_[r], ++next_)
      batch.push_back({next_, verify::task_json(tasks_[next_])});
    if (!batch.empty()) wire_.send(r, {0, {{"t", "v-clusters"}}, batch.dump()});
  }
  if (received_ == tasks_.size()) end(false);
}

void Phase::handle(Message m) {
  const std::string t = m.head.at("t");
  if (t == "v-clusters") {
    std::deque<std::pair<size_t, verify::ClusterTask>> got;
    try {
      for (auto& x : json::parse(m.payload)) got.emplace_back(x.at(0).get<size_t>(), verify::task_from(x.at(1)));
    } catch (const std::exception& e) {
      world_.fail(std::string("a damaged cluster message from rank 0: ") + e.what());
    }
    std::lock_guard lock(m_);
    for (auto& x : got) todo_.push_back(std::move(x));
    cv_.notify_all();
  } else if (t == "v-quit" || t == "v-fail") {
    if (t == "v-fail") failure_ = {m.head.at("code").get<int>(), ""};
    quitting_ = true;
    quit(t == "v-fail");
  } else if (world_.rank() != 0) {
    // beats, and the search's late messages: only their arrival counts (Wire::silent)
  } else if (t == "v-report") {
    const size_t k = m.head.at("k");
    try {
      reports_.at(k) = verify::report_from(json::parse(m.payload));
    } catch (const std::exception& e) {
      world_.fail("a damaged cluster report from rank " + std::to_string(m.from) + ": " + e.what());
    }
    --held_[m.from];
    ++received_;
    if (m.from != 0) ++figures_.clusters_elsewhere;
    dispatch();
  } else if (t == "v-error") {
    if (!failure_) failure_ = {m.head.at("code").get<int>(), m.head.at("text").get<std::string>()};
    end(true);
  } else if (t == "v-bye") {
    gone_[m.from] = 1;
    figures_.verify_traffic += Traffic::from(m.head);
  }
}

std::optional<verify::VerifyReport> Phase::run(const solve::CaseResult* result, Figures* figures) {
  const auto t0 = std::chrono::steady_clock::now();
  const bool root = world_.rank() == 0;
  if (root) {
    if (result) tasks_ = verify::cluster_tasks(f_, *result, threads_);
    reports_.resize(tasks_.size());
    held_.assign(world_.size(), 0);
    gone_.assign(world_.size(), 0);
    gone_[0] = 1;
    figures_.clusters = static_cast<long>(tasks_.size());
    dispatch();
  }
  std::vector<std::thread> pool;
  alive_ = threads_;
  for (int k = 0; k < threads_; ++k)
    pool.emplace_back([this] {
      thread_main();
      rigorous::release_thread_caches();
      --alive_;
    });
  const double timeout = fault_timeout();
  auto last_beat = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  auto last_line = t0;
  bool said_bye = false;
  while (true) {
    bool active = outbox_.drain(wire_);
    while (auto m = wire_.receive()) {
      handle(std::move(*m));
      active = true;
    }
    if (quitting_ && alive_ == 0) {
      if (!root && !said_bye) {
        // Counted before this message, which the totals then miss: one per rank.
        Traffic x = wire_.traffic();
        ++x.messages;
        json head = {{"t", "v-bye"}};
        x.put(head);
        wire_.send(0, {0, head, ""});
        said_bye = true;
        break;
      }
      if (root && std::all_of(gone_.begin(), gone_.end(), [](char g) { return g; })) break;
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_beat).count() >= kBeat) {
      last_beat = now;
      for (int r = root ? 1 : 0; r < (root ? world_.size() : 1); ++r) {
        if (root && gone_[r]) continue;
        wire_.send(r, {0, {{"t", "v-beat"}}, ""});
        if (wire_.silent(r) > timeout)
          world_.fail("rank " + std::to_string(r) + " sent nothing for " + std::to_string(static_cast<int>(timeout)) +
                      " s while verifying (dead or hung; LINKBOX_MPI_TIMEOUT sets the limit)");
      }
    }
    if (root && options_.progress && now - last_line >= std::chrono::seconds(1)) {
      last_line = now;
      std::fprintf(stderr, "linkbox: verifying: %zu/%zu clusters, %d ranks x %d threads, %.1f s\n", received_,
                   tasks_.size(), world_.size(), threads_, std::chrono::duration<double>(now - t0).count());
    }
    if (!active) outbox_.pause();
  }
  for (auto& t : pool) t.join();
  wire_.flush(timeout);
  if (failure_) {
    if (root) throw Failed(failure_->first, failure_->second);
    throw Ended{failure_->first};
  }
  if (!root || !result) return std::nullopt;
  std::vector<verify::ClusterReport> clusters;
  for (auto& r : reports_) clusters.push_back(std::move(*r));
  verify::VerifyReport report = verify::conclude(f_, std::move(clusters), *result, options_);
  report.timed_out = timed_out_;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  figures_.verify_traffic += wire_.traffic();
  if (figures) {
    figures->clusters = figures_.clusters;
    figures->clusters_elsewhere = figures_.clusters_elsewhere;
    figures->verify_traffic = figures_.verify_traffic;
  }
  return report;
}

}  // namespace

std::optional<verify::VerifyReport> verify_distributed(const formulate::Formulation& formulation,
                                                       const solve::CaseResult* result,
                                                       const verify::VerifyOptions& options, const World& world,
                                                       Figures* figures) {
  Phase p(formulation, options, world);
  return p.run(result, figures);
}

}  // namespace linkbox::distributed
