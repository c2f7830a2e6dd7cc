#include "solve/branch_and_prune.hpp"

#include <algorithm>
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
    : start_(std::chrono::steady_clock::now()), time_limit_(p.time_limit), max_boxes_(p.max_boxes) {}

double Budget::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Budget::take_box() {
  if (exhausted()) return false;
  long n = taken_.fetch_add(1) + 1;
  const char* why = nullptr;
  if (max_boxes_ > 0 && n > max_boxes_) why = "box limit reached";
  // Reading the clock every box is cheap next to a shrink, but not free: every 16th.
  else if (time_limit_ > 0 && (n & 15) == 0 && elapsed() > time_limit_) why = "time limit reached";
  if (!why) return true;
  static std::mutex m;
  std::lock_guard lock(m);
  if (!exhausted()) {
    reason_ = why;
    exhausted_.store(true);
  }
  return false;
}

namespace {

// A box with its place in the search tree: '0' = lower half, '1' = upper half.
struct Node {
  Box box;
  std::string path;
  prune::Sequence::Backoff backoff;  // inherited from the parent (see Sequence)
};

enum class Verdict { empty, certified, solution, split };

// Shrinks until empty, certified, small, or no longer shrinking by more than rho.
Verdict shrink(Box& box, prune::Sequence::Backoff& backoff, prune::Sequence& contractor, Certifier* certifier,
               std::span<const int> dims, const Params& params, Stats& stats) {
  while (true) {
    Box before = box;
    stats.shrinks++;
    if (contractor.contract(box, backoff) == prune::Outcome::empty) return Verdict::empty;
    if (certifier && contractor.at_most_one_root()) {
      stats.certify_calls++;
      if (certifier->certify(box)) return Verdict::certified;
    }
    const double size = max_width(box, dims);
    if (size <= params.sigma) return Verdict::solution;
    if (volume_ratio(before, box, dims) > params.rho) return Verdict::split;
  }
}


struct Found {
  std::string path;
  Box box;
  bool certified;
};

long lps_of(const prune::Sequence& c) {
  long n = 0;
  for (auto& k : c.counters()) n += k.lps_solved;
  return n;
}

}  // namespace

struct Search::State {
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
  Box start;
  bool stopped = false;  // by the budget
  double seconds = 0;
};

Search::Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
               Budget& budget, Certifier* certifier, const Bisector* bisector)
    : s_(new State{contractor, std::move(split_dims), params, budget, certifier, bisector, {}, {}, {}, 0, 0, start, false, 0}) {
  s_->pending.push_back({start, "", {}});
}

Search::~Search() = default;

double Search::work() const { return s_->work; }
double Search::fraction_done() const { return s_->volume_done; }
bool Search::done() const { return s_->stopped || s_->pending.empty(); }

bool Search::run(int threads, double work_limit) {
  const auto t0 = std::chrono::steady_clock::now();
  State& st = *s_;
  const Params& params = st.params;
  std::mutex m;
  std::condition_variable cv;
  int busy = 0;
  bool paused = false;

  auto worker = [&](prune::Sequence& c, Certifier* certify) {
    Stats stats;
    std::vector<Found> found;
    std::unique_lock lock(m);
    while (true) {
      cv.wait(lock, [&] { return st.stopped || paused || !st.pending.empty() || busy == 0; });
      if (st.stopped || paused || st.pending.empty()) break;
      if (work_limit > 0 && st.work >= work_limit) {
        paused = true;
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

      stats.processed++;
      const double volume = volume_ratio(st.start, node.box, st.split_dims);
      const long lps = lps_of(c);
      const Verdict v = shrink(node.box, node.backoff, c, certify, st.split_dims, params, stats);
      const double work = 1 + kLpWork * static_cast<double>(lps_of(c) - lps);
      std::pair<Node, Node> halves;
      if (v == Verdict::empty) {
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
      st.work += work;
      if (v != Verdict::split) st.volume_done += volume;
      if (v == Verdict::split) {
        // Depth-first: the lower half on top. Breadth-first: lower half first in line.
        if (params.order == Order::depth_first) {
          st.pending.push_back(std::move(halves.second));
          st.pending.push_back(std::move(halves.first));
        } else {
          st.pending.push_back(std::move(halves.first));
          st.pending.push_back(std::move(halves.second));
        }
      }
      cv.notify_all();
    }
    cv.notify_all();
    st.stats += stats;
    for (auto& f : found) st.solutions.push_back(std::move(f));
  };

  std::vector<std::unique_ptr<prune::Sequence>> clones;
  std::vector<std::unique_ptr<Certifier>> certifiers;
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    clones.push_back(st.contractor.clone_sequence());
    certifiers.push_back(st.certifier ? st.certifier->clone() : nullptr);
    pool.emplace_back(worker, std::ref(*clones.back()), certifiers.back().get());
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
  for (auto& n : st.pending) r.pending.push_back(std::move(n.box));
  st.pending.clear();
  r.stats.seconds = st.seconds;
  return r;
}

}  // namespace linkbox::solve
