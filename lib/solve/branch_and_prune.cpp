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
};

enum class Verdict { empty, solution, split };

// Shrinks until empty, small, or no longer shrinking by more than rho.
Verdict shrink(Box& box, prune::Contractor& contractor, std::span<const int> dims, const Params& params, Stats& stats) {
  while (true) {
    Box before = box;
    stats.shrinks++;
    if (contractor.contract(box) == prune::Outcome::empty) return Verdict::empty;
    const double size = max_width(box, dims);
    if (size <= params.sigma) return Verdict::solution;
    if (volume_ratio(before, box, dims) > params.rho) return Verdict::split;
  }
}

}  // namespace

Result branch_and_prune(const Box& start, prune::Sequence& contractor, std::span<const int> split_dims,
                        const Params& params, Budget& budget, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  std::deque<Node> pending{{start, ""}};
  std::vector<std::pair<std::string, Box>> solutions;
  std::mutex m;
  std::condition_variable cv;
  int busy = 0;
  bool stopped = false;

  auto worker = [&](prune::Contractor& c) {
    Stats stats;
    std::vector<std::pair<std::string, Box>> found;
    std::unique_lock lock(m);
    while (true) {
      cv.wait(lock, [&] { return stopped || !pending.empty() || busy == 0; });
      if (stopped || pending.empty()) break;
      if (!budget.take_box()) {
        stopped = true;
        break;
      }
      // Depth-first takes the newest box, breadth-first the oldest.
      Node node = std::move(params.order == Order::depth_first ? pending.back() : pending.front());
      params.order == Order::depth_first ? pending.pop_back() : pending.pop_front();
      ++busy;
      lock.unlock();

      stats.processed++;
      const Verdict v = shrink(node.box, c, split_dims, params, stats);
      std::pair<Node, Node> halves;
      if (v == Verdict::empty) {
        stats.empty++;
      } else if (v == Verdict::solution) {
        stats.solution++;
        found.emplace_back(std::move(node.path), std::move(node.box));
      } else {
        stats.split++;
        auto [a, b] = bisect(node.box, widest_dimension(node.box, split_dims));
        halves = {{std::move(a), node.path + '0'}, {std::move(b), node.path + '1'}};
      }

      lock.lock();
      --busy;
      if (v == Verdict::split) {
        // Depth-first: the lower half on top. Breadth-first: lower half first in line.
        if (params.order == Order::depth_first) {
          pending.push_back(std::move(halves.second));
          pending.push_back(std::move(halves.first));
        } else {
          pending.push_back(std::move(halves.first));
          pending.push_back(std::move(halves.second));
        }
      }
      cv.notify_all();
    }
    cv.notify_all();
    r.stats += stats;
    for (auto& f : found) solutions.push_back(std::move(f));
  };

  std::vector<std::unique_ptr<prune::Contractor>> clones;
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    clones.push_back(contractor.clone());
    pool.emplace_back(worker, std::ref(*clones.back()));
  }
  worker(contractor);
  for (auto& t : pool) t.join();
  for (auto& c : clones) contractor.add_counters(static_cast<const prune::Sequence&>(*c));

  std::sort(solutions.begin(), solutions.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& s : solutions) r.solutions.push_back(std::move(s.second));
  r.complete = !stopped;
  if (stopped)
    for (auto& n : pending) r.pending.push_back(std::move(n.box));
  r.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace linkbox::solve
