#include "distributed/coordinator.hpp"

#include "distributed/pieces.hpp"
#include "solve/checkpoint.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace linkbox::distributed {

using nlohmann::json;
using solve::Piece;

namespace {

// Seconds before a search that had nothing to give is asked again.
constexpr double kDryWait = 0.02;

}  // namespace

Coordinator::Coordinator(const formulate::Formulation& f, const solve::RunOptions& options, const World& world,
                         Wire& wire, solve::Budget& budget, int slots_per_rank)
    : f_(f), options_(options), world_(world), wire_(wire), budget_(budget), slots_per_rank_(slots_per_rank) {
  subs_.resize(f_.subproblem_count());
  boxes_.assign(world_.size(), 0);
  queue_.resize(static_cast<size_t>(world_.size()) * slots_per_rank_);
  waiting_.assign(queue_.size(), 0);
  gone_.assign(world_.size(), 0);
}

void Coordinator::handle(const Message& m) {
  const std::string t = m.head.at("t");
  if (t == "idle") {
    // a slot has started: nothing to do but dispatch
  } else if (t == "beat") {
    on_beat(m);
  } else if (t == "stopped") {
    stop(m.head.at("why"));
  } else if (t == "gift") {
    on_gift(m);
  } else if (t == "done") {
    on_done(m);
  } else if (t == "error") {
    on_error(m);
  } else if (t == "bye") {
    on_bye(m);
  }
  dispatch();
  if (!quitting_ && all_done()) {
    quitting_ = true;
    send_all({{"t", "quit"}});
  }
}

void Coordinator::on_beat(const Message& m) {
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
}

void Coordinator::on_gift(const Message& m) {
  Running& victim = queue_[worker_of(m)].front();  // gifts come from the unit that runs
  const int thief = victim.thief;
  victim.thief = -1;
  waiting_[thief] = 0;
  if (m.payload.empty()) {
    // A search down to its last box has nothing to give now; soon it may. Asking again at
    // once would flood rank 0 when every search is nearly done.
    victim.dry_until = budget_.elapsed() + kDryWait;
    return;
  }
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

void Coordinator::on_done(const Message& m) {
  const int w = worker_of(m);
  const Running r = queue_[w].front();
  queue_[w].pop_front();
  if (r.thief >= 0) waiting_[r.thief] = 0;  // asked too late: the unit had ended
  SubState& s = subs_[r.sub];
  if (m.head.value("record", false)) {
    // A lent subtree: its records go to the race that lent it (the race's own result holds
    // everything, so nothing is merged here); dropped once that race is over.
    forward_records(r.sub, m.head.value("lease", 0L), m.payload);
  } else if (m.head.at("whole").get<bool>()) {
    s.result = solve::sub_checkpoint_from_text(m.payload).result;
    // Lent subtrees still searched are no longer wanted: their searches may stop.
    if (s.owner >= 0 && s.live > 1)
      send_all({{"t", "abandon"}, {"sub", r.sub}, {"below", std::numeric_limits<long>::max()}});
  } else {
    Piece piece = piece_from(m);
    if (s.merged) s.merged->merge(std::move(piece));
    else s.merged = std::move(piece);
  }
  if (r.kind != "finish" && --s.live == 0 && s.merged) to_finish_.push_back(r.sub);
}

void Coordinator::on_error(const Message& m) {
  if (!failure_) failure_ = {m.head.at("code").get<int>(), m.head.at("text").get<std::string>()};
  quitting_ = true;
  send_all({{"t", "fail"}, {"code", failure_->first}});
}

void Coordinator::on_bye(const Message& m) {
  gone_[m.from] = 1;
  figures_.traffic += Traffic::from(m.head);
  figures_.boxes += m.head.at("boxes").get<long>();
}

void Coordinator::forward_records(size_t sub, long lease, const std::string& payload) {
  const SubState& s = subs_.at(sub);
  if (s.owner < 0 || s.result) return;
  wire_.send(s.owner / slots_per_rank_,
             {0, {{"t", "records"}, {"slot", s.owner % slots_per_rank_}, {"unit", s.owner_unit}, {"lease", lease}}, payload});
}

void Coordinator::recall(size_t sub, long below) { send_all({{"t", "abandon"}, {"sub", sub}, {"below", below}}); }

void Coordinator::send_unit(int worker, const std::string& kind, size_t sub, json extra, std::string payload) {
  json head = {{"t", "work"}, {"slot", worker % slots_per_rank_}, {"unit", next_unit_}, {"kind", kind}, {"sub", sub}};
  head.update(extra);
  // A subtree, or a sub-problem with one strategy named, never races: it shares from the start.
  // Under "auto" the slot's heartbeat says whether the sub-problem raced.
  const bool shares = kind == "tree" || (kind == "sub" && !options_.strategy.prune.is_auto());
  queue_[worker].push_back({next_unit_++, sub, kind, shares});
  ++figures_.units;
  wire_.send(worker / slots_per_rank_, {0, head, std::move(payload)});
}

void Coordinator::send_all(const json& head) {
  for (int r = 0; r < world_.size(); ++r) wire_.send(r, {0, head, ""});
}

void Coordinator::stop(const std::string& why) {
  if (stopping_) return;
  stopping_ = true;
  budget_.halt(why.c_str());
  send_all({{"t", "stop"}, {"why", why}});
}

// Sub-problems go out in batches queued at each worker, so a slot never waits for its next
// one (a case of many tiny sub-problems runs each in less than a round trip to rank 0); the
// batches shrink as the sub-problems run out (guided self-scheduling), so none is left with a
// long queue at the end. Then a worker with nothing queued gets a box of a running search.
void Coordinator::dispatch() {
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
  steal_for_idle();
}

// Each worker with nothing queued asks the longest-running unit whose search shares: its tree
// has had the longest to grow.
void Coordinator::steal_for_idle() {
  const size_t workers = queue_.size();
  const double now = budget_.elapsed();
  for (size_t w = 0; w < workers; ++w) {
    if (!queue_[w].empty() || waiting_[w]) continue;
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

bool Coordinator::all_done() const {
  for (auto& q : queue_)
    if (!q.empty()) return false;
  return to_finish_.empty() && (next_sub_ == subs_.size() || stopping_);
}

bool Coordinator::over() const {
  if (!quitting_) return false;
  for (char g : gone_)
    if (!g) return false;
  return true;
}

void Coordinator::count_handled(double seconds) {
  ++figures_.handled;
  figures_.handling_seconds += seconds;
}

void Coordinator::progress_line() const {
  size_t finished = 0;
  for (auto& s : subs_) finished += s.result.has_value();
  long boxes = 0;
  for (long b : boxes_) boxes += b;
  std::fprintf(stderr, "linkbox: %zu/%zu sub-problems, %ld boxes, %d ranks x %d threads, %.1f s\n", finished,
               subs_.size(), boxes, world_.size(), slots_per_rank_, budget_.elapsed());
}

solve::CaseResult Coordinator::result(Figures* figures) {
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

}  // namespace linkbox::distributed
