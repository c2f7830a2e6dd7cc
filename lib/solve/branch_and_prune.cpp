#include "solve/branch_and_prune.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

namespace linkbox::solve {

Stats& Stats::operator+=(const Stats& o) {
  processed += o.processed;
  empty += o.empty;
  solution += o.solution;
  split += o.split;
  shrinks += o.shrinks;
  certified += o.certified;
  certify_calls += o.certify_calls;
  seconds += o.seconds;
  return *this;
}

Budget::Budget(const Params& p)
    : start_(std::chrono::steady_clock::now()),
      time_limit_(p.time_limit),
      max_boxes_(p.max_boxes),
      interrupt_(p.interrupt) {}

double Budget::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Budget::stop(const char* why) {
  static std::mutex m;
  std::lock_guard lock(m);
  if (!exhausted()) {
    reason_ = why;
    exhausted_.store(true);
  }
  return false;
}

bool Budget::take_box() {
  if (exhausted()) return false;
  long n = taken_.fetch_add(1) + 1;
  if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return stop("interrupted");
  if (max_boxes_ > 0 && n > max_boxes_) return stop("box limit reached");
  // Reading the clock every box is cheap next to a shrink, but not free: every 16th.
  if (time_limit_ > 0 && (n & 15) == 0 && elapsed() > time_limit_) return stop("time limit reached");
  return true;
}

bool Budget::stop_now() {
  if (exhausted()) return true;
  if (interrupt_ && interrupt_->load(std::memory_order_relaxed)) return !stop("interrupted");
  if (time_limit_ > 0 && elapsed() > time_limit_) return !stop("time limit reached");
  return false;
}

namespace {

using Node = SearchState::Node;
using Found = SearchState::Found;

// stopped: a limit or an interrupt came while the box was being shrunk; it goes back to the
// list as it was taken, so a resumed search does exactly what an unbroken one would.
enum class Verdict { empty, certified, solution, split, stopped };

// Shrinks until empty, certified, small, or no longer shrinking by more than rho.
// `stop` is asked between passes too: one box can take many passes (a float variant that
// produced NaN bounds used to loop here for good, deaf to SIGTERM).
Verdict shrink(Box& box, prune::Sequence::Backoff& backoff, prune::Sequence& contractor, Certifier* certifier,
               std::span<const int> dims, const Params& params, const bool& cut, const std::function<bool()>& stop,
               Stats& stats) {
  while (true) {
    if (stop()) return Verdict::stopped;
    Box before = box;
    stats.shrinks++;
    const prune::Outcome outcome = contractor.contract(box, backoff);
    if (cut) return Verdict::stopped;
    if (outcome == prune::Outcome::empty) return Verdict::empty;
    // A NaN bound (an overflow in the unverified float variant) proves nothing: the box as it
    // was before the pass is split.
    if (std::any_of(box.begin(), box.end(), [](const Interval& x) { return std::isnan(x.lower()) || std::isnan(x.upper()); })) {
      box = std::move(before);
      return max_width(box, dims) <= params.sigma ? Verdict::solution : Verdict::split;
    }
    if (certifier && contractor.at_most_one_root()) {
      stats.certify_calls++;
      if (certifier->certify(box)) return Verdict::certified;
    }
    const double size = max_width(box, dims);
    if (size <= params.sigma) return Verdict::solution;
    if (volume_ratio(before, box, dims) > params.rho) return Verdict::split;
  }
}

long lps_of(const prune::Sequence& c) {
  long n = 0;
  for (auto& k : c.counters()) n += k.lps_solved;
  return n;
}

// One box shrunk, and what its turn in the search does with it.
struct Processed {
  Verdict verdict = Verdict::stopped;
  Node node;  // the box: as taken when stopped (it goes back to the list), else as shrunk
  double volume = 0;  // its share of the start box (split dims), as taken
  double work = 0;
  Stats stats;  // this box's counts
  std::pair<Node, Node> halves;  // when split
  int dim = -1;                  // the side bisected
};

// A box processed ahead of its turn in depth-first order (look-ahead mode of Search::run),
// or one a helper thread is shrinking, or a child of such a box waiting for a helper.
struct Ahead {
  // remote: lent (or below a lent box), its record not back yet.
  enum class Mark { open, busy, done, remote } mark = Mark::open;
  Node node;       // open
  Processed done;  // done
  bool delivered = false;  // done by another search (not in ahead_work)
};

}  // namespace

struct Search::State {
  State(prune::Sequence& c, std::vector<int> dims, const Params& p, Budget& b, Certifier* cert, const Bisector* bis)
      : contractor(c), split_dims(std::move(dims)), params(p), budget(b), certifier(cert), bisector(bis) {}
  prune::Sequence& contractor;
  std::vector<int> split_dims;
  Params params;
  Budget& budget;
  Certifier* certifier;
  const Bisector* bisector;
  std::deque<Node> pending;
  std::vector<Found> solutions;
  Stats stats;
  double work = 0;
  double volume_done = 0;  // fraction of the start box's volume (split dims) resolved
  double volume_pending = 1;  // and in pending boxes (what shrinking removed is in neither)
  Box start;
  bool stopped = false;  // by the budget
  double seconds = 0;
  std::function<bool()> pause_request;
  bool paused = false;  // the last run() returned on a pause request
  std::atomic<long>* tally_pending = nullptr;
  std::atomic<double>* tally_done = nullptr;
  BoxLog* log = nullptr;
  size_t log_subproblem = 0;
  int log_candidate = 0;
  // Look-ahead mode: boxes beyond the depth-first front, by path, kept across runs (a race's
  // turns); `open_paths` indexes the open ones, `ahead_work` sums the done ones' work.
  std::map<std::string, Ahead> ahead;
  std::set<std::string> open_paths;
  double ahead_work = 0;
  std::vector<std::unique_ptr<prune::Sequence>> helpers;
  std::vector<std::unique_ptr<Certifier>> helper_certifiers;
  // Look-ahead and lending: `m` guards the above against deliver() from another thread.
  std::mutex m;
  std::condition_variable cv;
  bool lent = false;  // some box was lent: runs to a limit go through run_ahead
  bool recording = false;
  std::vector<SearchState::Record> records;
  std::vector<prune::Counters> delivered_counters;

  Processed process(prune::Sequence& c, Certifier* certify, Node node, bool& cut, const std::function<bool()>& stop);
  void commit(Processed&& p);
  void run_ahead(int threads, double work_limit);
  // Runs `worker` on this thread with the search's own contractor and on threads - 1 more
  // with the kept helpers', then adds their counters to the contractor's.
  void on_threads(int threads, const std::function<void(prune::Sequence&, Certifier*)>& worker);
};

Search::Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
               Budget& budget, Certifier* certifier, const Bisector* bisector)
    : s_(new State(contractor, std::move(split_dims), params, budget, certifier, bisector)) {
  s_->start = start;
  s_->pending.push_back({start, "", {}});
}

Search::~Search() = default;

double Search::work() const { return s_->work; }
double Search::fraction_done() const { return s_->volume_done; }
double Search::tree_done() const {
  double pending = 0;
  for (auto& n : s_->pending) pending += std::ldexp(1.0, -static_cast<int>(n.path.size()));
  return 1 - pending;
}
bool Search::done() const { return s_->stopped || s_->pending.empty(); }
bool Search::finished() const { return s_->pending.empty(); }
bool Search::paused() const { return s_->paused; }
void Search::pause_when(std::function<bool()> request) { s_->pause_request = std::move(request); }

void Search::report_to(std::atomic<long>* pending, std::atomic<double>* fraction_done) {
  s_->tally_pending = pending;
  s_->tally_done = fraction_done;
}

void Search::log_to(BoxLog* log, size_t subproblem, int candidate) {
  s_->log = log;
  s_->log_subproblem = subproblem;
  s_->log_candidate = candidate;
}

SearchState Search::state() const {
  SearchState r;
  r.pending.assign(s_->pending.begin(), s_->pending.end());
  r.solutions = s_->solutions;
  r.stats = s_->stats;
  r.stats.seconds = s_->seconds;
  r.work = s_->work;
  r.volume_done = s_->volume_done;
  r.records = s_->records;
  return r;
}

void Search::set_state(SearchState state) {
  s_->pending.assign(std::make_move_iterator(state.pending.begin()), std::make_move_iterator(state.pending.end()));
  s_->solutions = std::move(state.solutions);
  s_->stats = state.stats;
  s_->seconds = state.stats.seconds;
  s_->stats.seconds = 0;
  s_->work = state.work;
  s_->volume_done = state.volume_done;
  s_->records = std::move(state.records);
  s_->volume_pending = 0;
  for (auto& n : s_->pending) s_->volume_pending += volume_ratio(s_->start, n.box, s_->split_dims);
  s_->stopped = false;
  std::lock_guard lock(s_->m);
  s_->ahead.clear();
  s_->open_paths.clear();
  s_->ahead_work = 0;
  s_->lent = false;
}

void Search::record_boxes() { s_->recording = true; }
size_t Search::recorded() const { return s_->records.size(); }
std::vector<SearchState::Record> Search::take_records() { return std::exchange(s_->records, {}); }

std::optional<SearchState::Node> Search::lend() {
  State& st = *s_;
  std::lock_guard lock(st.m);
  // The last box in depth-first order that nobody holds: a listed one (not the top), or a half
  // of a box shrunk ahead.
  const Node* listed = nullptr;
  for (size_t k = 0; k + 1 < st.pending.size() && !listed; ++k)
    if (!st.ahead.count(st.pending[k].path)) listed = &st.pending[k];
  const std::string* open = st.open_paths.empty() ? nullptr : &*st.open_paths.rbegin();
  if (!listed && !open) return std::nullopt;
  st.lent = true;
  if (listed && (!open || listed->path > *open)) {
    st.ahead[listed->path].mark = Ahead::Mark::remote;
    return *listed;
  }
  Ahead& a = st.ahead[*open];
  Node node = std::move(a.node);
  a.mark = Ahead::Mark::remote;
  st.open_paths.erase(std::prev(st.open_paths.end()));
  return node;
}

void Search::deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters) {
  State& st = *s_;
  std::lock_guard lock(st.m);
  for (auto& r : records) {
    Processed p;
    p.verdict = r.outcome == 'e' ? Verdict::empty : r.outcome == 's' ? Verdict::solution : r.outcome == 'c' ? Verdict::certified : Verdict::split;
    p.node.path = r.path;
    p.node.box = std::move(r.box);
    p.work = r.work;
    p.volume = r.volume;
    p.stats = r.stats;
    if (p.verdict == Verdict::split) {
      if (r.dim < 0 || r.dim >= static_cast<int>(p.node.box.size())) throw std::logic_error("a split record without its side");
      auto [a, b] = bisect(p.node.box, r.dim);
      p.halves = {{std::move(a), r.path + '0', r.backoff.child()}, {std::move(b), r.path + '1', r.backoff.child()}};
      p.dim = r.dim;
    }
    // A record arrives before its parent's when pieces come back out of order; a box someone
    // here holds is not awaited.
    const auto awaited = st.ahead.find(r.path);
    if (awaited != st.ahead.end() && awaited->second.mark != Ahead::Mark::remote) continue;
    if (p.verdict == Verdict::split)
      for (const Node* half : {&p.halves.first, &p.halves.second})
        if (!st.ahead.count(half->path)) st.ahead[half->path].mark = Ahead::Mark::remote;  // its record is on its way
    Ahead& a = st.ahead[r.path];
    a.mark = Ahead::Mark::done;
    a.delivered = true;
    a.done = std::move(p);
  }
  if (st.delivered_counters.size() < counters.size()) st.delivered_counters.resize(counters.size());
  for (size_t k = 0; k < counters.size(); ++k) st.delivered_counters[k] += counters[k];
  st.cv.notify_all();
}

void Search::unlend() {
  State& st = *s_;
  std::lock_guard lock(st.m);
  // A remote mark is on a listed box, or on a half of a delivered split (listed once that is
  // committed): either way the box is at hand.
  for (auto it = st.ahead.begin(); it != st.ahead.end();)
    it = it->second.mark == Ahead::Mark::remote ? st.ahead.erase(it) : std::next(it);
}

std::vector<prune::Counters> Search::delivered_counters() const {
  std::lock_guard lock(s_->m);
  return s_->delivered_counters;
}

Processed Search::State::process(prune::Sequence& c, Certifier* certify, Node node, bool& cut,
                                 const std::function<bool()>& stop) {
  Processed p;
  const std::vector<prune::Counters> counters_before = c.counters();
  Node taken = node;
  p.stats.processed++;
  p.volume = volume_ratio(start, node.box, split_dims);
  const long lps = lps_of(c);
  const auto shrink_start = log ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
  p.verdict = shrink(node.box, node.backoff, c, certify, split_dims, params, cut, stop, p.stats);
  const Verdict v = p.verdict;
  if (log && v != Verdict::stopped)
    log->add({log_subproblem, log_candidate, node.path, v == Verdict::empty ? 'e' : v == Verdict::split ? 'x' : 's',
              std::chrono::duration<double>(std::chrono::steady_clock::now() - shrink_start).count()});
  p.work = 1 + kLpWork * static_cast<double>(lps_of(c) - lps) + (v == Verdict::solution ? kSolutionWork : 0);
  if (v == Verdict::stopped) {
    c.set_counters(counters_before);  // its work undone in the counts
    p.node = std::move(taken);
    p.stats = {};
    return p;
  }
  if (v == Verdict::empty) {
    p.stats.empty++;
  } else if (v == Verdict::solution || v == Verdict::certified) {
    p.stats.solution++;
    p.stats.certified += v == Verdict::certified;
  } else {
    p.stats.split++;
    const int depth = static_cast<int>(node.path.size());
    const int dim = bisector ? bisector->choose(node.box, depth) : widest_dimension(node.box, split_dims);
    auto [a, b] = bisect(node.box, dim);
    p.halves = {{std::move(a), node.path + '0', node.backoff.child()}, {std::move(b), node.path + '1', node.backoff.child()}};
    p.dim = dim;
  }
  p.node = std::move(node);
  return p;
}

void Search::State::commit(Processed&& p) {
  const Verdict v = p.verdict;
  if (recording) {
    SearchState::Record r{p.node.path, v == Verdict::empty ? 'e' : v == Verdict::solution ? 's' : v == Verdict::certified ? 'c' : 'x',
                          p.work, p.volume, p.stats, {}, -1, {}};
    if (v != Verdict::empty) r.box = p.node.box;
    if (v == Verdict::split) r.dim = p.dim, r.backoff = p.node.backoff;
    records.push_back(std::move(r));
  }
  work += p.work;
  stats += p.stats;
  volume_pending -= p.volume;
  if (v != Verdict::split) volume_done += p.volume;
  if (v == Verdict::solution || v == Verdict::certified) {
    solutions.push_back({std::move(p.node.path), std::move(p.node.box), v == Verdict::certified});
  } else if (v == Verdict::split) {
    volume_pending += volume_ratio(start, p.halves.first.box, split_dims) + volume_ratio(start, p.halves.second.box, split_dims);
    // Depth-first: the lower half on top. Breadth-first: lower half first in line.
    if (params.order == Order::depth_first) {
      pending.push_back(std::move(p.halves.second));
      pending.push_back(std::move(p.halves.first));
    } else {
      pending.push_back(std::move(p.halves.first));
      pending.push_back(std::move(p.halves.second));
    }
  }
  if (tally_pending) tally_pending->store(static_cast<long>(pending.size()), std::memory_order_relaxed);
  if (tally_done) tally_done->store(1 - volume_pending, std::memory_order_relaxed);
}

bool Search::run(int threads, double work_limit) {
  const auto t0 = std::chrono::steady_clock::now();
  State& st = *s_;
  st.paused = false;
  // A run to a work limit stops where one thread stops it: depth-first with the threads in
  // look-ahead mode, breadth-first (where committing in order would serialise) on one thread.
  if ((threads > 1 || st.lent) && work_limit > 0 && st.params.order == Order::depth_first) {
    st.run_ahead(threads, work_limit);
    st.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return done();
  }
  if (work_limit > 0) threads = 1;
  const Params& params = st.params;
  std::mutex m;
  std::condition_variable cv;
  int busy = 0;
  bool paused = false;

  auto worker = [&](prune::Sequence& c, Certifier* certify) {
    // Contractors ask between LPs: a limit or an interrupt then cuts the box being shrunk
    // short, and it goes back to the list as it was taken, its work undone in the counts.
    bool cut = false;
    const std::function<bool()> stop = [&] { return cut = st.budget.stop_now(); };
    c.stop_when(&stop);
    std::unique_lock lock(m);
    while (true) {
      cv.wait(lock, [&] { return st.stopped || paused || !st.pending.empty() || busy == 0; });
      if (st.stopped || paused || st.pending.empty()) break;
      if (work_limit > 0 && st.work >= work_limit) {
        paused = true;
        break;
      }
      if (st.pause_request && st.pause_request()) {
        paused = st.paused = true;
        break;
      }
      if (!st.budget.take_box()) {
        st.stopped = true;
        break;
      }
      // Depth-first takes the newest box, breadth-first the oldest.
      Node node = std::move(params.order == Order::depth_first ? st.pending.back() : st.pending.front());
      params.order == Order::depth_first ? st.pending.pop_back() : st.pending.pop_front();
      ++busy;
      lock.unlock();
      Processed p = st.process(c, certify, std::move(node), cut, stop);
      lock.lock();
      --busy;
      if (p.verdict == Verdict::stopped) {
        st.stopped = true;
        st.pending.push_back(std::move(p.node));
        cv.notify_all();
        break;
      }
      st.commit(std::move(p));
      cv.notify_all();
    }
    cv.notify_all();
    c.stop_when(nullptr);
  };

  st.on_threads(threads, worker);
  st.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return done();
}

// Look-ahead mode, for a run cut at a work limit with several threads (a race's turn). The
// search advances exactly as with one thread: boxes are committed (counted, their halves
// listed, their solutions kept) one at a time in depth-first order, so it stops at the same
// box with the same state. Every thread shrinks the first box in that order that nobody holds,
// the list's top or, while another thread has the top, a box after it (a listed one, or a
// half of a box shrunk ahead), and keeps the result until the top reaches it. What a box
// becomes does not depend on who shrinks it or when, so the tree is the one-thread tree. The
// threads shrink ahead only while the work committed and held stays below the limit: a turn
// leaves at most one box per thread ahead of its end, the waste when a raced candidate loses.
void Search::State::run_ahead(int threads, double work_limit) {
  bool over = false;

  auto worker = [&](prune::Sequence& c, Certifier* certify) {
    bool cut = false;
    const std::function<bool()> stop = [&] { return cut = budget.stop_now(); };
    c.stop_when(&stop);
    std::unique_lock lock(m);
    while (true) {
      // Commit the done boxes at the top, in depth-first order.
      while (!over && !stopped && !pending.empty() && work < work_limit) {
        const auto it = ahead.find(pending.back().path);
        if (it == ahead.end() || it->second.mark != Ahead::Mark::done) break;
        if (pause_request && pause_request()) {
          paused = true;
          break;
        }
        pending.pop_back();
        if (!it->second.delivered) ahead_work -= it->second.done.work;
        Processed p = std::move(it->second.done);
        ahead.erase(it);
        commit(std::move(p));
      }
      if (paused || stopped || pending.empty() || work >= work_limit) over = true;
      if (over) break;
      if (pause_request && pause_request()) {
        paused = over = true;
        break;
      }
      // The top was lent and its record is not back: wait, but not past a limit.
      const auto top = ahead.find(pending.back().path);
      if (top != ahead.end() && top->second.mark == Ahead::Mark::remote) {
        if (budget.exhausted() || budget.stop_now()) {
          stopped = over = true;
          break;
        }
        cv.wait_for(lock, std::chrono::milliseconds(20));
        continue;
      }
      // The first box in depth-first order that nobody holds.
      const Node* listed = nullptr;
      for (auto k = pending.rbegin(); k != pending.rend() && !listed; ++k)
        if (!ahead.count(k->path)) listed = &*k;
      const std::string* open = open_paths.empty() ? nullptr : &*open_paths.begin();
      if (!listed && !open) {
        cv.wait(lock);
        continue;
      }
      const bool from_list = !open || (listed && listed->path < *open);
      const std::string path = from_list ? listed->path : *open;
      if (path != pending.back().path && work + ahead_work >= work_limit) {
        cv.wait(lock);
        continue;
      }
      if (!budget.take_box()) {
        stopped = over = true;
        break;
      }
      Ahead& a = ahead[path];  // std::map: the reference survives other insertions and erasures
      Node node = from_list ? *listed : std::move(a.node);
      if (!from_list) open_paths.erase(path);
      a.mark = Ahead::Mark::busy;
      lock.unlock();
      Processed p = process(c, certify, std::move(node), cut, stop);
      lock.lock();
      if (p.verdict == Verdict::stopped) {
        // As if never taken: a listed box is still in the list; a half goes back to open.
        stopped = over = true;
        if (from_list) {
          ahead.erase(path);
        } else {
          a = Ahead{Ahead::Mark::open, std::move(p.node), {}};
          open_paths.insert(path);
        }
        break;
      }
      if (p.verdict == Verdict::split)
        for (const Node* half : {&p.halves.first, &p.halves.second})
          if (!ahead.count(half->path)) {
            ahead[half->path] = Ahead{Ahead::Mark::open, *half, {}};
            open_paths.insert(half->path);
          }
      a.mark = Ahead::Mark::done;
      ahead_work += p.work;
      a.done = std::move(p);
      cv.notify_all();
    }
    cv.notify_all();
    c.stop_when(nullptr);
  };

  on_threads(threads, worker);
}

void Search::State::on_threads(int threads, const std::function<void(prune::Sequence&, Certifier*)>& worker) {
  // The helpers' contractors are kept across runs (a race has many short turns, and a clone
  // of an LP strategy is not free); their counters are handed over after each run.
  while (static_cast<int>(helpers.size()) < threads - 1) {
    helpers.push_back(contractor.clone_sequence());
    helper_certifiers.push_back(certifier ? certifier->clone() : nullptr);
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads - 1; ++t)
    pool.emplace_back([&, t] {
      worker(*helpers[t], helper_certifiers[t].get());
      rigorous::release_thread_caches();
    });
  worker(contractor, certifier);
  for (auto& t : pool) t.join();
  for (int t = 0; t < threads - 1; ++t) {
    contractor.add_counters(*helpers[t]);
    helpers[t]->set_counters(std::vector<prune::Counters>(helpers[t]->counters().size()));
  }
}

Result Search::result() {
  State& st = *s_;
  Result r;
  std::sort(st.solutions.begin(), st.solutions.end(), [](auto& a, auto& b) { return a.path < b.path; });
  for (auto& f : st.solutions) {
    r.solutions.push_back(std::move(f.box));
    r.certified.push_back(f.certified);
  }
  st.solutions.clear();
  r.stats = st.stats;
  r.complete = st.pending.empty();
  r.volume_left = 0;
  for (auto& n : st.pending) {
    r.volume_left += volume_ratio(st.start, n.box, st.split_dims);
    r.pending.push_back(std::move(n.box));
  }
  st.pending.clear();
  r.stats.seconds = st.seconds;
  return r;
}

}  // namespace linkbox::solve
