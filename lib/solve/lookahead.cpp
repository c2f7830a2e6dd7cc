#include "solve/lookahead.hpp"

#include <chrono>
#include <iterator>

namespace linkbox::solve::detail {

// One look-ahead run: what its workers share, under Lookahead::m_.
class Lookahead::Run {
 public:
  Run(Lookahead& ahead, SearchCore& core, double work_limit, double box_cap)
      : la_(ahead), core_(core), limit_(work_limit), cap_(box_cap) {}
  void worker(prune::Sequence& c, Certifier* certify);

 private:
  struct Pick {
    const Node* listed;  // the box when it is a listed one
    std::string path;
  };
  void commit_done_top();
  bool over();
  bool top_is_remote() const;
  std::optional<Pick> next_box() const;
  bool keep(const Pick& pick, Ahead& a, Processed&& p);

  Lookahead& la_;
  SearchCore& core_;
  double limit_;
  double cap_;
  bool over_ = false;
};

void Lookahead::run(SearchCore& core, int threads, double work_limit, double box_cap) {
  {
    std::lock_guard lock(m_);
    reopen_capped();
  }
  Run run(*this, core, work_limit, box_cap);
  core.on_threads(threads, [&](prune::Sequence& c, Certifier* certify) { run.worker(c, certify); });
}

void Lookahead::Run::worker(prune::Sequence& c, Certifier* certify) {
  Budget& budget = core_.setup.budget;
  bool cut = false;
  const std::function<bool()> stop = [&] { return cut = budget.stop_now(); };
  c.stop_when(&stop);
  std::unique_lock lock(la_.m_);
  while (true) {
    commit_done_top();
    if (over()) break;
    // The top was lent and its record is not back: wait, but not past a limit.
    if (top_is_remote()) {
      if (budget.exhausted() || budget.stop_now()) {
        core_.control.stopped = over_ = true;
        break;
      }
      la_.cv_.wait_for(lock, std::chrono::milliseconds(20));
      continue;
    }
    const std::optional<Pick> pick = next_box();
    if (!pick) {
      la_.cv_.wait(lock);
      continue;
    }
    if (!budget.take_box()) {
      core_.control.stopped = over_ = true;
      break;
    }
    Ahead& a = la_.ahead_[pick->path];  // std::map: the reference survives other insertions and erasures
    Node node = pick->listed ? *pick->listed : std::move(a.node);
    if (!pick->listed) la_.open_.erase(pick->path);
    a.mark = Ahead::Mark::busy;
    // A capped box beyond the top is shrunk again next run from the box as taken, as one
    // thread would shrink it: so an open box is kept as taken while a cap may stop it.
    if (cap_ > 0 && !pick->listed) a.node = node;
    lock.unlock();
    Processed p = core_.process(c, certify, std::move(node), cut, stop, cap_);
    lock.lock();
    if (!keep(*pick, a, std::move(p))) break;
    la_.cv_.notify_all();
  }
  la_.cv_.notify_all();
  c.stop_when(nullptr);
}

// Commits the done boxes at the top, in depth-first order.
void Lookahead::Run::commit_done_top() {
  Committed& front = core_.committed;
  RunControl& control = core_.control;
  while (!over_ && !control.stopped && !front.pending.empty() && front.work < limit_) {
    const auto it = la_.ahead_.find(front.pending.back().path);
    const bool capped = it != la_.ahead_.end() && it->second.mark == Ahead::Mark::capped;
    if (!capped && (it == la_.ahead_.end() || it->second.mark != Ahead::Mark::done)) break;
    if (control.pause_request && control.pause_request()) {
      control.paused = true;
      break;
    }
    // As one thread: the pause is asked before the box, which then ends the run, the box
    // listed as its passes left it.
    if (capped) {
      control.capped = over_ = true;
      core_.keep_capped(it->second.done);
      front.pending.back() = std::move(it->second.done.node);
      la_.ahead_.erase(it);
      break;
    }
    front.pending.pop_back();
    if (!it->second.delivered) la_.work_ -= it->second.done.work;
    Processed p = std::move(it->second.done);
    la_.ahead_.erase(it);
    core_.commit(std::move(p));
  }
}

bool Lookahead::Run::over() {
  const Committed& front = core_.committed;
  RunControl& control = core_.control;
  if (control.paused || control.stopped || front.pending.empty() || front.work >= limit_) over_ = true;
  if (over_) return true;
  if (control.pause_request && control.pause_request()) {
    control.paused = over_ = true;
    return true;
  }
  return false;
}

bool Lookahead::Run::top_is_remote() const {
  const auto top = la_.ahead_.find(core_.committed.pending.back().path);
  return top != la_.ahead_.end() && top->second.mark == Ahead::Mark::remote;
}

// The first box in depth-first order that nobody holds, unless it lies beyond the top while
// the work committed and held has reached the limit.
std::optional<Lookahead::Run::Pick> Lookahead::Run::next_box() const {
  const std::deque<Node>& pending = core_.committed.pending;
  const Node* listed = nullptr;
  for (auto k = pending.rbegin(); k != pending.rend() && !listed; ++k)
    if (!la_.ahead_.count(k->path)) listed = &*k;
  const std::string* open = la_.open_.empty() ? nullptr : &*la_.open_.begin();
  if (!listed && !open) return std::nullopt;
  const bool from_list = !open || (listed && listed->path < *open);
  Pick pick{from_list ? listed : nullptr, from_list ? listed->path : *open};
  if (pick.path != pending.back().path && core_.committed.work + la_.work_ >= limit_) return std::nullopt;
  return pick;
}

// Keeps what a worker made of the box it took; false when a limit cut the box short: as if
// never taken, a listed box is still in the list and a half goes back to open.
bool Lookahead::Run::keep(const Pick& pick, Ahead& a, Processed&& p) {
  if (p.verdict == Verdict::stopped) {
    core_.control.stopped = over_ = true;
    if (pick.listed) {
      la_.ahead_.erase(pick.path);
    } else {
      a = Ahead{Ahead::Mark::open, std::move(p.node), {}};
      la_.open_.insert(pick.path);
    }
    return false;
  }
  if (p.verdict == Verdict::capped) {
    // Held, not open: no thread takes it again in this run. A listed box is still listed.
    a = Ahead{Ahead::Mark::capped, pick.listed ? Node{} : std::move(a.node), std::move(p), false, pick.listed != nullptr};
    return true;
  }
  if (p.verdict == Verdict::split)
    for (const Node* half : {&p.halves.first, &p.halves.second})
      if (!la_.ahead_.count(half->path)) {
        la_.ahead_[half->path] = Ahead{Ahead::Mark::open, *half, {}};
        la_.open_.insert(half->path);
      }
  a.mark = Ahead::Mark::done;
  a.node = Node{};
  la_.work_ += p.work;
  a.done = std::move(p);
  return true;
}

// A capped box is shrunk again by the next run, which may have a larger cap or none.
void Lookahead::reopen_capped() {
  for (auto it = ahead_.begin(); it != ahead_.end();) {
    if (it->second.mark != Ahead::Mark::capped) {
      ++it;
    } else if (it->second.listed) {
      it = ahead_.erase(it);  // taken from the list again
    } else {
      it->second.mark = Ahead::Mark::open;
      it->second.done = Processed{};
      open_.insert(it->first);
      ++it;
    }
  }
}

void Lookahead::clear() {
  std::lock_guard lock(m_);
  ahead_.clear();
  open_.clear();
  work_ = 0;
  lent_ = false;
}

std::optional<Node> Lookahead::lend(const std::deque<Node>& pending) {
  std::lock_guard lock(m_);
  // The last box in depth-first order that nobody holds: a listed one (not the top), or a half
  // of a box shrunk ahead.
  const Node* listed = nullptr;
  for (size_t k = 0; k + 1 < pending.size() && !listed; ++k)
    if (!ahead_.count(pending[k].path)) listed = &pending[k];
  const std::string* open = open_.empty() ? nullptr : &*open_.rbegin();
  if (!listed && !open) return std::nullopt;
  lent_ = true;
  if (listed && (!open || listed->path > *open)) {
    ahead_[listed->path].mark = Ahead::Mark::remote;
    return *listed;
  }
  Ahead& a = ahead_[*open];
  Node node = std::move(a.node);
  a.mark = Ahead::Mark::remote;
  open_.erase(std::prev(open_.end()));
  return node;
}

void Lookahead::deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters) {
  std::lock_guard lock(m_);
  for (auto& r : records) {
    Processed p = replay(std::move(r));
    // A record arrives before its parent's when pieces come back out of order; a box someone
    // here holds is not awaited.
    const auto awaited = ahead_.find(p.node.path);
    if (awaited != ahead_.end() && awaited->second.mark != Ahead::Mark::remote) continue;
    if (p.verdict == Verdict::split)
      for (const Node* half : {&p.halves.first, &p.halves.second})
        if (!ahead_.count(half->path)) ahead_[half->path].mark = Ahead::Mark::remote;  // its record is on its way
    Ahead& a = ahead_[p.node.path];
    a.mark = Ahead::Mark::done;
    a.delivered = true;
    a.done = std::move(p);
  }
  if (delivered_counters_.size() < counters.size()) delivered_counters_.resize(counters.size());
  for (size_t k = 0; k < counters.size(); ++k) delivered_counters_[k] += counters[k];
  cv_.notify_all();
}

void Lookahead::unlend() {
  std::lock_guard lock(m_);
  // A remote mark is on a listed box, or on a half of a delivered split (listed once that is
  // committed): either way the box is at hand.
  for (auto it = ahead_.begin(); it != ahead_.end();)
    it = it->second.mark == Ahead::Mark::remote ? ahead_.erase(it) : std::next(it);
}

std::vector<prune::Counters> Lookahead::delivered_counters() const {
  std::lock_guard lock(m_);
  return delivered_counters_;
}

}  // namespace linkbox::solve::detail
