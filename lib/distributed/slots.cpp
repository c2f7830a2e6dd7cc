#include "distributed/slots.hpp"

#include "distributed/pieces.hpp"
#include "input/input_error.hpp"
#include "interval/rigorous.hpp"
#include "solve/checkpoint.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <thread>

namespace linkbox::distributed {

using nlohmann::json;
using solve::Piece;

// One search slot: a thread that runs the units rank 0 hands it.
struct Slots::Slot {
  std::mutex m;
  std::condition_variable cv;
  std::deque<Message> inbox;
  long unit = -1;                  // under m
  std::atomic<bool> steal{false};  // rank 0 asks for a box of `unit`
  long steal_for = -1;             // under m: asked before the unit started
  std::atomic<bool> shares{false};  // `unit`'s search gives or lends boxes
  size_t sub = 0;                   // under m: `unit`'s sub-problem
  bool record = false;              // under m: `unit` searches lent boxes, with records
  solve::Lender* lender = nullptr;  // under m: `unit`'s race lent boxes; records go to it
  long lease = 0;       // under m: the lender's boxes lent since its last recall carry this
  long unit_lease = 0;  // under m: a record unit: the lease its records answer
  std::thread thread;
};

// What slot k's searches ask between two boxes (solve/lending.hpp): rank 0's requests for
// boxes, answered through messages.
class Slots::Sharing final : public solve::Sharing {
 public:
  Sharing(Slots& slots, int k) : slots_(slots), k_(k), s_(*slots.slots_[k]) {}
  bool asked() override {
    s_.shares.store(true, std::memory_order_relaxed);
    slots_.death_.step();
    return s_.steal.load(std::memory_order_relaxed);
  }
  bool give(size_t i, const solve::Strategy& strategy, solve::Lender& search) override {
    s_.steal.store(false);
    auto node = search.give();
    Piece gift{i, strategy, {}, {}, {}, {}};
    const bool gave = node.has_value();
    if (gave) gift.state.pending.push_back(std::move(*node));
    json head = piece_head("gift", gift);
    head["slot"] = k_;
    {
      std::lock_guard lock(s_.m);
      head["record"] = s_.record;  // a subtree of a lent box: its pieces keep records too
      head["lease"] = s_.unit_lease;
    }
    slots_.post({0, head, gave ? piece_text(gift) : ""});
    return gave;
  }
  // A race's leader: the box stays in its list; the records of its subtree come back to this
  // slot (Slots::records) and go to `search`.
  bool lend(size_t i, const solve::Strategy& strategy, solve::Lender& search) override {
    s_.steal.store(false);
    const auto node = search.lend();
    Piece gift{i, strategy, {}, {}, {}, {}};
    if (node) gift.state.pending.push_back(*node);
    long lease;
    {
      std::lock_guard lock(s_.m);
      s_.lender = &search;
      lease = s_.lease;
    }
    json head = piece_head("gift", gift);
    head["slot"] = k_;
    head["lend"] = true;
    head["lease"] = lease;
    slots_.post({0, head, node ? piece_text(gift) : ""});
    return node.has_value();
  }
  void recall() override {
    std::lock_guard lock(s_.m);
    s_.lender = nullptr;
    ++s_.lease;  // records of the boxes lent so far are dropped on arrival
    slots_.post({0, {{"t", "recall"}, {"sub", s_.sub}, {"below", s_.lease}}, ""});
  }
  void end_lending() override {
    std::lock_guard lock(s_.m);
    s_.lender = nullptr;
    ++s_.lease;
  }
  void send_records(size_t i, std::vector<solve::SearchState::Record> records) override {
    long lease;
    {
      std::lock_guard lock(s_.m);
      lease = s_.unit_lease;
    }
    Piece part{i, {}, {}, {}, {}, {}};
    part.state.records = std::move(records);
    slots_.post({0, {{"t", "records"}, {"sub", i}, {"lease", lease}}, piece_text(part)});
  }
  bool abandoned() override {
    size_t sub;
    long lease;
    {
      std::lock_guard lock(s_.m);
      if (!s_.record) return false;
      sub = s_.sub;
      lease = s_.unit_lease;
    }
    std::lock_guard lock(slots_.abandoned_m_);
    const auto it = slots_.abandoned_.find(sub);
    return it != slots_.abandoned_.end() && lease < it->second;
  }

 private:
  Slots& slots_;
  int k_;
  Slot& s_;
};

Slots::Slots(const formulate::Formulation& f, const solve::RunOptions& options, solve::Budget& budget, int rank,
             Outbox& outbox)
    : f_(f), options_(options), budget_(budget), death_(rank, "search"), outbox_(outbox) {
  options_.threads = 1;
  options_.progress = false;
  options_.checkpoint.clear();
  const int n = std::max(1, options.threads);
  for (int k = 0; k < n; ++k) slots_.push_back(std::make_unique<Slot>());
}

Slots::~Slots() = default;

void Slots::start() {
  for (int k = 0; k < count(); ++k)
    slots_[k]->thread = std::thread([this, k] {
      main(k);
      rigorous::release_thread_caches();
    });
}

void Slots::end() {
  for (int k = 0; k < count(); ++k) work(k, {0, {{"t", "quit"}}, ""});
  for (auto& s : slots_)
    if (s->thread.joinable()) s->thread.join();
}

void Slots::work(int k, Message m) {
  Slot& s = *slots_.at(k);
  std::lock_guard lock(s.m);
  s.inbox.push_back(std::move(m));
  s.cv.notify_one();
}

void Slots::steal(int k, long unit) {
  Slot& s = *slots_.at(k);
  std::lock_guard lock(s.m);
  if (s.unit == unit) s.steal.store(true);
  else s.steal_for = unit;  // queued behind the unit that runs: asked as soon as it starts
}

void Slots::records(int k, long unit, long lease, const std::string& payload) {
  const solve::SubCheckpoint c = solve::sub_checkpoint_from_text(payload);
  Slot& s = *slots_.at(k);
  std::lock_guard lock(s.m);
  if (s.unit == unit && s.lender && s.lease == lease) s.lender->deliver(c.searches.at(0).records, c.counters.at(0));
}

void Slots::abandon(size_t sub, long below) {
  std::lock_guard lock(abandoned_m_);
  long& b = abandoned_[sub];
  b = std::max(b, below);
}

void Slots::beat(json& units, json& shares) const {
  for (auto& s : slots_) {
    std::lock_guard lock(s->m);
    units.push_back(s->unit);
    shares.push_back(s->unit >= 0 && s->shares.load() ? 1 : 0);
  }
}

Message Slots::next(Slot& s) {
  std::unique_lock lock(s.m);
  s.cv.wait(lock, [&] { return !s.inbox.empty(); });
  Message m = std::move(s.inbox.front());
  s.inbox.pop_front();
  return m;
}

void Slots::report_error(int code, const std::string& text) {
  post({0, {{"t", "error"}, {"code", code}, {"text", text}}, ""});
}

void Slots::main(int k) {
  Slot& slot = *slots_[k];
  Sharing sharing(*this, k);
  post({0, {{"t", "idle"}, {"slot", k}}, ""});
  while (true) {
    Message m = next(slot);
    if (m.head.at("t") == "quit") return;
    const long unit = m.head.at("unit");
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
      run_unit(sharing, m, done);
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
    post(std::move(done));
  }
}

void Slots::run_unit(Sharing& sharing, const Message& m, Message& done) {
  const std::string kind = m.head.at("kind");
  const size_t i = m.head.at("sub");
  if (kind == "sub" && budget_.exhausted()) {
    // Queued here when the run stopped: reported as one process reports a sub-problem it
    // never reached, without building its strategy.
    done.payload = result_text(solve::unstarted_subproblem(f_, i));
    done.head["whole"] = true;
  } else if (kind == "finish") {
    done.payload = result_text(solve::finish_subproblem(f_, i, options_, budget_, piece_from(m)));
    done.head["whole"] = true;
  } else {
    Piece piece;
    solve::SubResult s;
    const bool whole = kind == "sub" ? solve::run_subproblem(f_, i, options_, budget_, &sharing, s, piece) : false;
    if (kind == "tree") {
      Piece given = piece_from(m);
      piece = solve::run_subtree(f_, i, options_, budget_, &sharing, given.strategy, std::move(given.state.pending),
                                 m.head.value("record", false));
    }
    done.head["whole"] = whole;
    if (whole) {
      done.payload = result_text(s);
    } else {
      done.head.update(piece_head("done", piece));
      done.payload = piece_text(piece);
    }
  }
}

}  // namespace linkbox::distributed
