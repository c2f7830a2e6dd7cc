#include "distributed/mpi_solve.hpp"

#include "input/input_error.hpp"
#include "interval/rigorous.hpp"
#include "solve/checkpoint.hpp"
#include "solve/share.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <deque>
#include <memory>
#include <mutex>
#include <limits>
#include <map>
#include <thread>

namespace linkbox::distributed {

using nlohmann::json;
using solve::Piece;
using solve::SubCheckpoint;
using solve::SubResult;

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

// Seconds before a search that had nothing to give is asked again.
constexpr double kDryWait = 0.02;

// Pieces and results travel as the checkpoint writes sub-problem states: exact doubles,
// infinities, paths and backoffs, one format to keep right.
std::string piece_text(const Piece& p) {
  SubCheckpoint c;
  c.phase = SubCheckpoint::Phase::searching;
  c.searches = {p.state};
  c.counters = {p.counters};
  return solve::to_json_text(c);
}

std::string result_text(const SubResult& s) {
  SubCheckpoint c;
  c.phase = SubCheckpoint::Phase::finished;
  c.result = s;
  return solve::to_json_text(c);
}

Piece piece_from(const Message& m) {
  SubCheckpoint c = solve::sub_checkpoint_from_text(m.payload);
  Piece p;
  p.subproblem = m.head.at("sub");
  p.strategy = solve::Strategy::parse(m.head.at("strategy").get<std::string>());
  p.race = m.head.value("race", std::vector<std::pair<std::string, double>>{});
  p.state = std::move(c.searches.at(0));
  p.counters = std::move(c.counters.at(0));
  return p;
}

json piece_head(const char* type, const Piece& p) {
  return {{"t", type}, {"sub", p.subproblem}, {"strategy", p.strategy.text()}, {"race", p.race}};
}

// One search slot: a thread that runs the units rank 0 hands it.
struct Slot {
  std::mutex m;
  std::condition_variable cv;
  std::deque<Message> inbox;
  long unit = -1;                  // under m
  std::atomic<bool> steal{false};  // rank 0 asks for a box of `unit`
  long steal_for = -1;             // under m: asked before the unit started
  std::atomic<bool> shares{false};  // `unit`'s search gives or lends boxes
  size_t sub = 0;                   // under m: `unit`'s sub-problem
  bool record = false;              // under m: `unit` searches lent boxes, with records
  solve::Search* lender = nullptr;  // under m: `unit`'s race lent boxes; records go to it
  long lease = 0;       // under m: the lender's boxes lent since its last recall carry this
  long unit_lease = 0;  // under m: a record unit: the lease its records answer
  std::thread thread;
};

// What rank 0 knows of a unit under way.
struct Running {
  long unit;
  size_t sub;
  std::string kind;
  bool shares = false;  // as the rank's last heartbeat said
  double dry_until = 0;  // gave nothing when last asked: not asked again before then (Budget::elapsed)
  int thief = -1;       // a slot waiting for a box of this unit
};

struct SubState {
  int live = 0;  // its units under way (the sub-problem and its subtrees)
  int owner = -1;         // the worker whose race lent boxes: their records go to it
  long owner_unit = -1;   // and its unit
  std::optional<Piece> merged;
  std::optional<SubResult> result;
};

class Process {
 public:
  Process(const formulate::Formulation& f, const solve::RunOptions& options, const World& world)
      : f_(f), options_(options), world_(world), wire_(world), budget_(options.params), death_(world.rank(), "search") {
    unit_options_ = options;
    unit_options_.threads = 1;
    unit_options_.progress = false;
    unit_options_.checkpoint.clear();
    slots_per_rank_ = std::max(1, options.threads);
    for (int k = 0; k < slots_per_rank_; ++k) slots_.push_back(std::make_unique<Slot>());
  }
  std::optional<solve::CaseResult> run(Figures* figures);

 private:
  // ---- slots (their own threads; they never call MPI)
  struct Sharing final : solve::Sharing {
    Process& p;
    int k;
    Sharing(Process& p, int k) : p(p), k(k) {}
    bool asked() override {
      Slot& s = *p.slots_[k];
      s.shares.store(true, std::memory_order_relaxed);
      p.death_.step();
      return s.steal.load(std::memory_order_relaxed);
    }
    // The oldest pending box: in depth-first order the shallowest, so the largest subtree.
    bool give(size_t i, const solve::Strategy& strategy, solve::Search& search) override {
      Slot& s = *p.slots_[k];
      s.steal.store(false);
      solve::SearchState st = search.state();
      Piece gift{i, strategy, {}, {}, {}};
      const bool gave = st.pending.size() >= 2;
      if (gave) {
        gift.state.pending.push_back(std::move(st.pending.front()));
        st.pending.erase(st.pending.begin());
        search.set_state(std::move(st));
      }
      json head = piece_head("gift", gift);
      head["slot"] = k;
      {
        std::lock_guard lock(s.m);
        head["record"] = s.record;  // a subtree of a lent box: its pieces keep records too
        head["lease"] = s.unit_lease;
      }
      p.post(0, {0, head, gave ? piece_text(gift) : ""});
      return gave;
    }
    // A race's leader: the box stays in its list; the records of its subtree come back here
    // (handle "records") and go to `search`.
    bool lend(size_t i, const solve::Strategy& strategy, solve::Search& search) override {
      Slot& s = *p.slots_[k];
      s.steal.store(false);
      const auto node = search.lend();
      Piece gift{i, strategy, {}, {}, {}};
      if (node) gift.state.pending.push_back(*node);
      long lease;
      {
        std::lock_guard lock(s.m);
        s.lender = &search;
        lease = s.lease;
      }
      json head = piece_head("gift", gift);
      head["slot"] = k;
      head["lend"] = true;
      head["lease"] = lease;
      p.post(0, {0, head, node ? piece_text(gift) : ""});
      return node.has_value();
    }
    void recall() override {
      Slot& s = *p.slots_[k];
      std::lock_guard lock(s.m);
      s.lender = nullptr;
      ++s.lease;  // records of the boxes lent so far are dropped on arrival
      p.post(0, {0, {{"t", "recall"}, {"sub", s.sub}, {"below", s.lease}}, ""});
    }
    void end_lending() override {
      Slot& s = *p.slots_[k];
      std::lock_guard lock(s.m);
      s.lender = nullptr;
      ++s.lease;
    }
    void send_records(size_t i, std::vector<solve::SearchState::Record> records) override {
      Slot& s = *p.slots_[k];
      long lease;
      {
        std::lock_guard lock(s.m);
        lease = s.unit_lease;
      }
      Piece part{i, {}, {}, {}, {}};
      part.state.records = std::move(records);
      p.post(0, {0, {{"t", "records"}, {"sub", i}, {"lease", lease}}, piece_text(part)});
    }
    bool abandoned() override {
      Slot& s = *p.slots_[k];
      size_t sub;
      long lease;
      {
        std::lock_guard lock(s.m);
        if (!s.record) return false;
        sub = s.sub;
        lease = s.unit_lease;
      }
      std::lock_guard lock(p.abandoned_m_);
      const auto it = p.abandoned_.find(sub);
      return it != p.abandoned_.end() && lease < it->second;
    }
  };

  void post(int to, Message m) { outbox_.post(to, std::move(m)); }

  Message wait(Slot& s) {
    std::unique_lock lock(s.m);
    s.cv.wait(lock, [&] { return !s.inbox.empty(); });
    Message m = std::move(s.inbox.front());
    s.inbox.pop_front();
    return m;
  }

  void slot_main(int k) {
    Slot& slot = *slots_[k];
    Sharing sharing(*this, k);
    post(0, {0, {{"t", "idle"}, {"slot", k}}, ""});
    while (true) {
      Message m = wait(slot);
      if (m.head.at("t") == "quit") return;
      const long unit = m.head.at("unit");
      const std::string kind = m.head.at("kind");
      const size_t i = m.head.at("sub");
      const bool record = m.head.value("record", false);
      {
        std::lock_guard lock(slot.m);
        slot.unit = unit;
        slot.steal = slot.steal_for == unit;
        slot.shares = false;
        slot.sub = i;
        slot.record = record;
        slot.unit_lease = m.head.value("lease", 0L);
        slot.lender = nullptr;
      }
      Message done{0, {{"t", "done"}, {"slot", k}, {"unit", unit}, {"sub", i}, {"record", record},
                       {"lease", m.head.value("lease", 0L)}}, ""};
      try {
        if (kind == "sub" && budget_.exhausted()) {
          // Queued here when the run stopped: reported as one process reports a sub-problem
          // it never reached, without building its strategy.
          done.payload = result_text(solve::unstarted_subproblem(f_, i));
          done.head["whole"] = true;
        } else if (kind == "finish") {
          done.payload = result_text(solve::finish_subproblem(f_, i, unit_options_, budget_, piece_from(m)));
          done.head["whole"] = true;
        } else {
          Piece piece;
          SubResult s;
          const bool whole =
              kind == "sub" ? solve::run_subproblem(f_, i, unit_options_, budget_, &sharing, s, piece) : false;
          if (kind == "tree") {
            Piece given = piece_from(m);
            piece = solve::run_subtree(f_, i, unit_options_, budget_, &sharing, given.strategy,
                                       std::move(given.state.pending), record);
          }
          done.head["whole"] = whole;
          if (whole) {
            done.payload = result_text(s);
          } else {
            done.head.update(piece_head("done", piece));
            done.payload = piece_text(piece);
          }
        }
      } catch (const input::InputError& e) {
        return report_error(2, e.what());
      } catch (const std::invalid_argument& e) {
        return report_error(2, std::string("linkbox: ") + e.what());
      } catch (const std::exception& e) {
        return report_error(1, std::string("linkbox: internal error: ") + e.what());
      }
      {
        std::lock_guard lock(slot.m);
        slot.unit = -1;
        slot.lender = nullptr;
        slot.record = false;
      }
      post(0, std::move(done));
    }
  }

  void report_error(int code, const std::string& text) { post(0, {0, {{"t", "error"}, {"code", code}, {"text", text}}, ""}); }

  void deliver(int k, Message m) {
    Slot& s = *slots_.at(k);
    std::lock_guard lock(s.m);
    s.inbox.push_back(std::move(m));
    s.cv.notify_one();
  }

  // ---- every rank's main thread
  void handle(Message m);
  void end_slots() {
    for (int k = 0; k < slots_per_rank_; ++k) deliver(k, {0, {{"t", "quit"}}, ""});
    for (auto& s : slots_)
      if (s->thread.joinable()) s->thread.join();
  }

  // ---- rank 0
  void coordinate(const Message& m);
  void dispatch();
  void stop(const std::string& why);
  void send_unit(int worker, const std::string& kind, size_t sub, json extra, std::string payload);
  // A lent subtree's records to the race that lent them; dropped once that race is over.
  void forward_records(const SubState& s, long lease, const std::string& payload) {
    if (s.owner < 0 || s.result) return;
    wire_.send(s.owner / slots_per_rank_,
               {0, {{"t", "records"}, {"slot", s.owner % slots_per_rank_}, {"unit", s.owner_unit}, {"lease", lease}}, payload});
  }
  int worker_of(const Message& m) const { return m.from * slots_per_rank_ + m.head.at("slot").get<int>(); }
  bool all_done() const {
    for (auto& q : queue_)
      if (!q.empty()) return false;
    return to_finish_.empty() && (next_sub_ == subs_.size() || stopping_);
  }
  void progress_line();

  const formulate::Formulation& f_;
  const solve::RunOptions& options_;
  solve::RunOptions unit_options_;
  const World& world_;
  Wire wire_;
  solve::Budget budget_;
  TestDeath death_;
  int slots_per_rank_ = 1;
  std::vector<std::unique_ptr<Slot>> slots_;
  Outbox outbox_;
  bool leaving_ = false;     // this rank's part is over
  bool told_stop_ = false;   // rank 0 knows that this rank's budget ran out
  std::optional<std::pair<int, std::string>> failure_;  // an error that ends the run
  std::mutex abandoned_m_;
  std::map<size_t, long> abandoned_;  // per sub-problem: lent boxes of leases below this are not wanted

  // rank 0
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
  Figures figures_;
};

void Process::send_unit(int worker, const std::string& kind, size_t sub, json extra, std::string payload) {
  json head = {{"t", "work"}, {"slot", worker % slots_per_rank_}, {"unit", next_unit_}, {"kind", kind}, {"sub", sub}};
  head.update(extra);
  // A subtree, or a sub-problem with one strategy named, never races: it shares from the start.
  // Under "auto" the slot's heartbeat says whether the sub-problem raced.
  const bool shares = kind == "tree" || (kind == "sub" && !options_.strategy.prune.is_auto());
  queue_[worker].push_back({next_unit_++, sub, kind, shares});
  ++figures_.units;
  wire_.send(worker / slots_per_rank_, {0, head, std::move(payload)});
}

void Process::stop(const std::string& why) {
  if (stopping_) return;
  stopping_ = true;
  budget_.halt(why.c_str());
  for (int r = 0; r < world_.size(); ++r) wire_.send(r, {0, {{"t", "stop"}, {"why", why}}, ""});
}

// Sub-problems go out in batches queued at each worker, so a slot never waits for its next
// one (the four-loop's 4 096 sub-problems take ~0.2 ms each, less than a round trip to rank 0);
// the batches shrink as the sub-problems run out (guided self-scheduling), so none is left
// with a long queue at the end. Then a worker with nothing queued gets a box of a running search.
void Process::dispatch() {
  if (quitting_) return;
  const size_t workers = queue_.size();
  auto shortest = [&] {
    size_t best = 0;
    for (size_t w = 1; w < workers; ++w)
      if (queue_[w].size() < queue_[best].size()) best = w;
    return static_cast<int>(best);
  };
  while (!to_finish_.empty()) {
    const size_t i = to_finish_.front();
    to_finish_.pop_front();
    Piece& merged = *subs_[i].merged;
    send_unit(shortest(), "finish", i, piece_head("work", merged), piece_text(merged));
    subs_[i].merged.reset();
  }
  if (stopping_) return;
  if (next_sub_ < subs_.size()) {
    const size_t batch = std::clamp<size_t>((subs_.size() - next_sub_) / (4 * workers), 1, 32);
    for (size_t w = 0; w < workers; ++w)
      while (queue_[w].size() < batch && next_sub_ < subs_.size()) {
        subs_[next_sub_].live = 1;
        send_unit(static_cast<int>(w), "sub", next_sub_++, json::object(), "");
      }
    return;
  }
  const double now = budget_.elapsed();
  for (size_t w = 0; w < workers; ++w) {
    if (!queue_[w].empty() || waiting_[w]) continue;
    // Ask the longest-running unit whose search shares: its tree has had the longest to grow.
    Running* victim = nullptr;
    int v = -1;
    for (size_t k = 0; k < workers; ++k) {
      if (queue_[k].empty()) continue;
      Running& r = queue_[k].front();
      if (r.shares && r.dry_until <= now && r.thief < 0 && r.kind != "finish" && (!victim || r.unit < victim->unit)) {
        victim = &r;
        v = static_cast<int>(k);
      }
    }
    if (!victim) return;
    victim->thief = static_cast<int>(w);
    waiting_[w] = 1;
    ++figures_.steals;
    wire_.send(v / slots_per_rank_, {0, {{"t", "steal"}, {"slot", v % slots_per_rank_}, {"unit", victim->unit}}, ""});
  }
}

void Process::coordinate(const Message& m) {
  const std::string t = m.head.at("t");
  if (t == "idle") {
    // a slot has started: nothing to do but dispatch
  } else if (t == "beat") {
    boxes_[m.from] = m.head.at("boxes");
    const auto units = m.head.at("units").get<std::vector<long>>();
    const auto shares = m.head.at("shares").get<std::vector<int>>();
    for (int k = 0; k < slots_per_rank_; ++k) {
      auto& q = queue_[m.from * slots_per_rank_ + k];
      if (!q.empty() && q.front().unit == units[k]) {
        q.front().shares = q.front().shares || shares[k];
      }
    }
    long total = 0;
    for (long b : boxes_) total += b;
    if (options_.params.max_boxes > 0 && total >= options_.params.max_boxes) stop("box limit reached");
  } else if (t == "stopped") {
    stop(m.head.at("why"));
  } else if (t == "gift") {
    Running& victim = queue_[worker_of(m)].front();  // gifts come from the unit that runs
    const int thief = victim.thief;
    victim.thief = -1;
    waiting_[thief] = 0;
    if (m.payload.empty()) {
      // A search down to its last box has nothing to give now; soon it may. Asking again at
      // once would flood rank 0 when every search is nearly done.
      victim.dry_until = budget_.elapsed() + kDryWait;
    } else {
      Piece gift = piece_from(m);
      SubState& s = subs_[gift.subproblem];
      ++s.live;
      figures_.boxes_given += static_cast<long>(gift.state.pending.size());
      json extra = {{"strategy", gift.strategy.text()}};
      if (m.head.value("lend", false)) s.owner = worker_of(m), s.owner_unit = victim.unit;
      if (m.head.value("lend", false) || m.head.value("record", false)) {
        extra["record"] = true;
        extra["lease"] = m.head.value("lease", 0L);
      }
      send_unit(thief, "tree", gift.subproblem, extra, m.payload);
    }
  } else if (t == "done") {
    const int w = worker_of(m);
    const Running r = queue_[w].front();
    queue_[w].pop_front();
    if (r.thief >= 0) waiting_[r.thief] = 0;  // asked too late: the unit had ended
    SubState& s = subs_[r.sub];
    if (m.head.value("record", false)) {
      // A lent subtree: its records go to the race that lent it (the race's own result holds
      // everything, so nothing is merged here); dropped once that race is over.
      forward_records(s, m.head.value("lease", 0L), m.payload);
    } else if (m.head.at("whole").get<bool>()) {
      s.result = solve::sub_checkpoint_from_text(m.payload).result;
      // Lent subtrees still searched are no longer wanted: their searches may stop.
      if (s.owner >= 0 && s.live > 1)
        for (int rank = 0; rank < world_.size(); ++rank)
          wire_.send(rank, {0, {{"t", "abandon"}, {"sub", r.sub}, {"below", std::numeric_limits<long>::max()}}, ""});
    } else {
      Piece piece = piece_from(m);
      if (s.merged) s.merged->merge(std::move(piece));
      else s.merged = std::move(piece);
    }
    if (r.kind != "finish" && --s.live == 0 && s.merged) to_finish_.push_back(r.sub);
  } else if (t == "error") {
    if (!failure_) failure_ = {m.head.at("code").get<int>(), m.head.at("text").get<std::string>()};
    quitting_ = true;
    for (int r = 0; r < world_.size(); ++r) wire_.send(r, {0, {{"t", "fail"}, {"code", failure_->first}}, ""});
  } else if (t == "bye") {
    gone_[m.from] = 1;
    figures_.traffic += Traffic::from(m.head);
    figures_.boxes += m.head.at("boxes").get<long>();
  }
  dispatch();
  if (!quitting_ && all_done()) {
    quitting_ = true;
    for (int r = 0; r < world_.size(); ++r) wire_.send(r, {0, {{"t", "quit"}}, ""});
  }
}

void Process::handle(Message m) {
  const std::string t = m.head.at("t");
  if (t == "work" || t == "steal") {
    const int k = m.head.at("slot");
    if (t == "work") return deliver(k, std::move(m));
    Slot& s = *slots_.at(k);
    std::lock_guard lock(s.m);
    const long unit = m.head.at("unit");
    if (s.unit == unit) s.steal.store(true);
    else s.steal_for = unit;  // queued behind the unit that runs: asked as soon as it starts
  } else if (t == "records" && !m.head.contains("unit")) {
    // rank 0: a batch of a lent subtree's records, on its way to the lender
    forward_records(subs_.at(m.head.at("sub").get<size_t>()), m.head.at("lease").get<long>(), m.payload);
  } else if (t == "recall") {
    // rank 0: the race's lender lost the lead; the searches of its lent boxes may stop
    for (int rank = 0; rank < world_.size(); ++rank)
      wire_.send(rank, {0, {{"t", "abandon"}, {"sub", m.head.at("sub")}, {"below", m.head.at("below")}}, ""});
  } else if (t == "records") {
    const solve::SubCheckpoint c = solve::sub_checkpoint_from_text(m.payload);
    Slot& s = *slots_.at(m.head.at("slot").get<int>());
    std::lock_guard lock(s.m);
    if (s.unit == m.head.at("unit").get<long>() && s.lender && s.lease == m.head.at("lease").get<long>())
      s.lender->deliver(c.searches.at(0).records, c.counters.at(0));
  } else if (t == "abandon") {
    std::lock_guard lock(abandoned_m_);
    long& below = abandoned_[m.head.at("sub").get<size_t>()];
    below = std::max(below, m.head.at("below").get<long>());
  } else if (t == "stop") {
    budget_.halt(m.head.at("why").get<std::string>().c_str());
    told_stop_ = true;
  } else if (t == "quit" || t == "fail") {
    if (t == "fail") {
      budget_.halt("failed");
      if (!failure_) failure_ = {m.head.at("code").get<int>(), ""};
    }
    end_slots();
    // Counted before this message, which the totals then miss: one per rank.
    Traffic x = wire_.traffic();
    x.messages += world_.rank() != 0;
    json head = {{"t", "bye"}, {"boxes", budget_.boxes_taken()}};
    x.put(head);
    wire_.send(0, {0, head, ""});
    leaving_ = world_.rank() != 0;
  } else if (world_.rank() == 0) {
    coordinate(m);
  }
}

void Process::progress_line() {
  size_t finished = 0;
  for (auto& s : subs_) finished += s.result.has_value();
  long boxes = 0;
  for (long b : boxes_) boxes += b;
  std::fprintf(stderr, "linkbox: %zu/%zu sub-problems, %ld boxes, %d ranks x %d threads, %.1f s\n", finished,
               subs_.size(), boxes, world_.size(), slots_per_rank_, budget_.elapsed());
}

std::optional<solve::CaseResult> Process::run(Figures* figures) {
  const bool root = world_.rank() == 0;
  if (root) {
    subs_.resize(f_.subproblem_count());
    boxes_.assign(world_.size(), 0);
    queue_.resize(static_cast<size_t>(world_.size()) * slots_per_rank_);
    waiting_.assign(queue_.size(), 0);
    gone_.assign(world_.size(), 0);
  }
  for (int k = 0; k < slots_per_rank_; ++k)
    slots_[k]->thread = std::thread([this, k] {
      slot_main(k);
      rigorous::release_thread_caches();
    });
  const double timeout = fault_timeout();
  auto last_beat = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  auto last_line = std::chrono::steady_clock::now();
  while (true) {
    bool active = outbox_.drain(wire_);
    while (auto m = wire_.receive()) {
      const auto t0 = std::chrono::steady_clock::now();
      handle(std::move(*m));
      if (root) {
        ++figures_.handled;
        figures_.handling_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
      active = true;
    }
    if (leaving_) break;
    if (root && quitting_) {
      bool all = true;
      for (char g : gone_) all = all && g;
      if (all) break;
    }
    if (!told_stop_ && budget_.exhausted()) {
      told_stop_ = true;
      wire_.send(0, {0, {{"t", "stopped"}, {"why", budget_.reason()}}, ""});
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_beat).count() >= kBeat) {
      last_beat = now;
      if (root) {
        for (int r = 1; r < world_.size(); ++r) wire_.send(r, {0, {{"t", "beat"}}, ""});
      }
      json units = json::array(), shares = json::array();
      for (auto& s : slots_) {
        std::lock_guard lock(s->m);
        units.push_back(s->unit);
        shares.push_back(s->unit >= 0 && s->shares.load() ? 1 : 0);
      }
      wire_.send(0, {0, {{"t", "beat"}, {"boxes", budget_.boxes_taken()}, {"units", units}, {"shares", shares}}, ""});
      for (int r = root ? 1 : 0; r < (root ? world_.size() : 1); ++r)
        if ((!root || !gone_[r]) && wire_.silent(r) > timeout)
          world_.fail("rank " + std::to_string(r) + " sent nothing for " + std::to_string(static_cast<int>(timeout)) +
                      " s (dead or hung; LINKBOX_MPI_TIMEOUT sets the limit)");
    }
    if (root && options_.progress && std::chrono::duration<double>(now - last_line).count() >= 1) {
      last_line = now;
      progress_line();
    }
    if (!active) outbox_.pause();
  }
  wire_.flush(timeout);
  if (failure_) {
    if (root) throw Failed(failure_->first, failure_->second);
    throw Ended{failure_->first};
  }
  if (!root) return std::nullopt;
  solve::CaseResult result;
  result.subproblems.resize(subs_.size());
  for (size_t i = 0; i < subs_.size(); ++i)
    result.subproblems[i] = subs_[i].result ? std::move(*subs_[i].result) : solve::unstarted_subproblem(f_, i);
  solve::summarise(result, options_, budget_);
  figures_.ranks = world_.size();
  figures_.slots = slots_per_rank_;
  if (figures) *figures = figures_;
  return result;
}

}  // namespace

std::optional<solve::CaseResult> solve_distributed(const formulate::Formulation& formulation,
                                                   const solve::RunOptions& options, const World& world,
                                                   Figures* figures) {
  Process p(formulation, options, world);
  return p.run(figures);
}

}  // namespace linkbox::distributed
