#include "solve/branch_and_prune.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

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
};

Search::Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
               Budget& budget, Certifier* certifier, const Bisector* bisector)
    : s_(new State(contractor, std::move(split_dims), params, budget, certifier, bisector)) {
  s_->start = start;
  s_->params.rho = rho_for(params.rho, true);  // direct users: the papers' rule unless given
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
  s_->volume_pending = 0;
  for (auto& n : s_->pending) s_->volume_pending += volume_ratio(s_->start, n.box, s_->split_dims);
  s_->stopped = false;
}

bool Search::run(int threads, double work_limit) {
  const auto t0 = std::chrono::steady_clock::now();
  State& st = *s_;
  const Params& params = st.params;
  std::mutex m;
  std::condition_variable cv;
  int busy = 0;
  bool paused = false;
  st.paused = false;

  auto worker = [&](prune::Sequence& c, Certifier* certify) {
    Stats stats;
    std::vector<Found> found;
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

      const Stats stats_before = stats;
      const std::vector<prune::Counters> counters_before = c.counters();
      Node taken = node;
      stats.processed++;
      const double volume = volume_ratio(st.start, node.box, st.split_dims);
      const long lps = lps_of(c);
      const auto shrink_start = st.log ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
      const Verdict v = shrink(node.box, node.backoff, c, certify, st.split_dims, params, cut, stop, stats);
      if (st.log && v != Verdict::stopped)
        st.log->add({st.log_subproblem, st.log_candidate, node.path,
                     v == Verdict::empty ? 'e' : v == Verdict::split ? 'x' : 's',
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - shrink_start).count()});
      const double work = 1 + kLpWork * static_cast<double>(lps_of(c) - lps) + (v == Verdict::solution ? kSolutionWork : 0);
      std::pair<Node, Node> halves;
      if (v == Verdict::stopped) {
        stats = stats_before;
        c.set_counters(counters_before);
      } else if (v == Verdict::empty) {
        stats.empty++;
      } else if (v == Verdict::solution || v == Verdict::certified) {
        stats.solution++;
        stats.certified += v == Verdict::certified;
        found.push_back({std::move(node.path), std::move(node.box), v == Verdict::certified});
      } else {
        stats.split++;
        const int depth = static_cast<int>(node.path.size());
        const int dim = st.bisector ? st.bisector->choose(node.box, depth) : widest_dimension(node.box, st.split_dims);
        auto [a, b] = bisect(node.box, dim);
        halves = {{std::move(a), node.path + '0', node.backoff.child()}, {std::move(b), node.path + '1', node.backoff.child()}};
      }

      lock.lock();
      --busy;
      st.volume_pending -= volume;
      if (v == Verdict::stopped) {
        st.volume_pending += volume;
        st.stopped = true;
        st.pending.push_back(std::move(taken));
        cv.notify_all();
        break;
      }
      st.work += work;
      if (v != Verdict::split) st.volume_done += volume;
      if (v == Verdict::split) {
        st.volume_pending += volume_ratio(st.start, halves.first.box, st.split_dims) +
                             volume_ratio(st.start, halves.second.box, st.split_dims);
        // Depth-first: the lower half on top. Breadth-first: lower half first in line.
        if (params.order == Order::depth_first) {
          st.pending.push_back(std::move(halves.second));
          st.pending.push_back(std::move(halves.first));
        } else {
          st.pending.push_back(std::move(halves.first));
          st.pending.push_back(std::move(halves.second));
        }
      }
      if (st.tally_pending) st.tally_pending->store(static_cast<long>(st.pending.size()), std::memory_order_relaxed);
      if (st.tally_done) st.tally_done->store(1 - st.volume_pending, std::memory_order_relaxed);
      cv.notify_all();
    }
    cv.notify_all();
    c.stop_when(nullptr);
    st.stats += stats;
    for (auto& f : found) st.solutions.push_back(std::move(f));
  };

  std::vector<std::unique_ptr<prune::Sequence>> clones;
  std::vector<std::unique_ptr<Certifier>> certifiers;
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    clones.push_back(st.contractor.clone_sequence());
    certifiers.push_back(st.certifier ? st.certifier->clone() : nullptr);
    pool.emplace_back([&, c = clones.back().get(), certify = certifiers.back().get()] {
      worker(*c, certify);
      rigorous::release_thread_caches();
    });
  }
  worker(st.contractor, st.certifier);
  for (auto& t : pool) t.join();
  for (auto& c : clones) st.contractor.add_counters(*c);
  st.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return done();
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
