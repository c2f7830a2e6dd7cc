#include "solve/search.hpp"

#include "interval/rigorous.hpp"
#include "solve/lookahead.hpp"
#include "solve/search_core.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
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

namespace detail {

void SearchCore::commit(Processed&& p) {
  const Verdict v = p.verdict;
  if (records.on) records.list.push_back(record_of(p));
  Committed& c = committed;
  c.work += p.work;
  c.stats += p.stats;
  c.volume_pending -= p.volume;
  if (v != Verdict::split) c.volume_done += p.volume;
  if (v == Verdict::solution || v == Verdict::certified) {
    c.solutions.push_back({std::move(p.node.path), std::move(p.node.box), v == Verdict::certified});
  } else if (v == Verdict::split) {
    c.volume_pending += volume_ratio(setup.start, p.halves.first.box, setup.split_dims) +
                        volume_ratio(setup.start, p.halves.second.box, setup.split_dims);
    // Depth-first: the lower half on top. Breadth-first: lower half first in line.
    if (setup.params.order == Order::depth_first) {
      c.pending.push_back(std::move(p.halves.second));
      c.pending.push_back(std::move(p.halves.first));
    } else {
      c.pending.push_back(std::move(p.halves.first));
      c.pending.push_back(std::move(p.halves.second));
    }
  }
  if (tallies.pending) tallies.pending->store(static_cast<long>(c.pending.size()), std::memory_order_relaxed);
  publish_volume();
}

void SearchCore::publish_volume() {
  if (tallies.volume_outside) tallies.volume_outside->store(1 - committed.volume_pending, std::memory_order_relaxed);
}

void SearchCore::keep_capped(const Processed& p) {
  Committed& c = committed;
  c.work += p.work;
  c.volume_pending += volume_ratio(setup.start, p.node.box, setup.split_dims) - p.volume;
  publish_volume();
}

void SearchCore::run(int threads, double work_limit, double box_cap) {
  const Params& params = setup.params;
  std::mutex m;
  std::condition_variable cv;
  int busy = 0;
  bool paused = false;

  auto worker = [&](prune::Sequence& c, Certifier* certify) {
    // Contractors ask between LPs: a limit or an interrupt then cuts the box being shrunk
    // short, and it goes back to the list as it was taken, its work undone in the counts.
    bool cut = false;
    const std::function<bool()> stop = [&] { return cut = setup.budget.stop_now(); };
    c.stop_when(&stop);
    std::unique_lock lock(m);
    while (true) {
      cv.wait(lock, [&] { return control.stopped || paused || !committed.pending.empty() || busy == 0; });
      if (control.stopped || paused || committed.pending.empty()) break;
      if (work_limit > 0 && committed.work >= work_limit) {
        paused = true;
        break;
      }
      if (control.pause_request && control.pause_request()) {
        paused = control.paused = true;
        break;
      }
      if (!setup.budget.take_box()) {
        control.stopped = true;
        break;
      }
      // Depth-first takes the newest box, breadth-first the oldest.
      std::deque<Node>& pending = committed.pending;
      Node node = std::move(params.order == Order::depth_first ? pending.back() : pending.front());
      params.order == Order::depth_first ? pending.pop_back() : pending.pop_front();
      ++busy;
      lock.unlock();
      Processed p = process(c, certify, std::move(node), cut, stop, box_cap);
      lock.lock();
      --busy;
      if (p.verdict == Verdict::capped || p.verdict == Verdict::stopped) {
        // Back where it was taken from, so the next run takes it first.
        if (p.verdict == Verdict::capped) {
          control.capped = paused = true;
          keep_capped(p);
        } else {
          control.stopped = true;
        }
        if (params.order == Order::depth_first)
          pending.push_back(std::move(p.node));
        else
          pending.push_front(std::move(p.node));
        cv.notify_all();
        break;
      }
      commit(std::move(p));
      cv.notify_all();
    }
    cv.notify_all();
    c.stop_when(nullptr);
  };

  on_threads(threads, worker);
}

void SearchCore::on_threads(int threads, const std::function<void(prune::Sequence&, Certifier*)>& worker) {
  while (static_cast<int>(crew.contractors.size()) < threads - 1) {
    crew.contractors.push_back(setup.contractor.clone_sequence());
    crew.certifiers.push_back(setup.certifier ? setup.certifier->clone() : nullptr);
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads - 1; ++t)
    pool.emplace_back([&, t] {
      worker(*crew.contractors[t], crew.certifiers[t].get());
      rigorous::release_thread_caches();
    });
  worker(setup.contractor, setup.certifier);
  for (auto& t : pool) t.join();
  for (int t = 0; t < threads - 1; ++t) setup.contractor.take_counters(*crew.contractors[t]);
}

}  // namespace detail

struct Search::State {
  explicit State(detail::Setup setup) : core{std::move(setup), {}, {}, {}, {}, {}, {}} {}
  detail::SearchCore core;
  detail::Lookahead lookahead;
};

Search::Search(const Box& start, prune::Sequence& contractor, std::vector<int> split_dims, const Params& params,
               Budget& budget, Certifier* certifier, const Bisector* bisector)
    : s_(new State({contractor, certifier, bisector, start, std::move(split_dims), params, budget})) {
  s_->core.committed.pending.push_back({start, "", {}});
}

Search::~Search() = default;

bool Search::run(int threads, double work_limit, double box_cap) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::SearchCore& core = s_->core;
  core.control.paused = core.control.capped = false;
  // A run to a work limit stops where one thread stops it: depth-first with the threads in
  // look-ahead mode, breadth-first (where committing in order would serialise) on one thread.
  if ((threads > 1 || s_->lookahead.lent()) && work_limit > 0 && core.setup.params.order == Order::depth_first)
    s_->lookahead.run(core, threads, work_limit, box_cap);
  else
    core.run(work_limit > 0 ? 1 : threads, work_limit, work_limit > 0 ? box_cap : 0);
  core.committed.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return core.control.stopped || complete();
}

bool Search::complete() const { return s_->core.committed.pending.empty(); }
double Search::work() const { return s_->core.committed.work; }
double Search::volume_done() const { return s_->core.committed.volume_done; }
double Search::tree_done() const {
  double pending = 0;
  for (auto& n : s_->core.committed.pending) pending += std::ldexp(1.0, -static_cast<int>(n.path.size()));
  return 1 - pending;
}
bool Search::paused() const { return s_->core.control.paused; }
bool Search::capped() const { return s_->core.control.capped; }
void Search::pause_when(std::function<bool()> request) { s_->core.control.pause_request = std::move(request); }

void Search::report_to(std::atomic<long>* pending, std::atomic<double>* volume_outside) {
  s_->core.tallies = {pending, volume_outside};
}

void Search::log_to(BoxLog* log, size_t subproblem, int candidate) { s_->core.log = {log, subproblem, candidate}; }

SearchState Search::state() const {
  const detail::SearchCore& core = s_->core;
  SearchState r;
  r.pending.assign(core.committed.pending.begin(), core.committed.pending.end());
  r.solutions = core.committed.solutions;
  r.stats = core.committed.stats;
  r.stats.seconds = core.committed.seconds;
  r.work = core.committed.work;
  r.volume_done = core.committed.volume_done;
  r.records = core.records.list;
  return r;
}

void Search::set_state(SearchState state) {
  detail::SearchCore& core = s_->core;
  detail::Committed& c = core.committed;
  c.pending.assign(std::make_move_iterator(state.pending.begin()), std::make_move_iterator(state.pending.end()));
  c.solutions = std::move(state.solutions);
  c.stats = state.stats;
  c.seconds = state.stats.seconds;
  c.stats.seconds = 0;
  c.work = state.work;
  c.volume_done = state.volume_done;
  core.records.list = std::move(state.records);
  c.volume_pending = 0;
  for (auto& n : c.pending) c.volume_pending += volume_ratio(core.setup.start, n.box, core.setup.split_dims);
  core.control.stopped = false;
  s_->lookahead.clear();
}

Result Search::result() {
  detail::SearchCore& core = s_->core;
  detail::Committed& c = core.committed;
  Result r;
  std::sort(c.solutions.begin(), c.solutions.end(), [](auto& a, auto& b) { return a.path < b.path; });
  for (auto& f : c.solutions) {
    r.solutions.push_back(std::move(f.box));
    r.certified.push_back(f.certified);
  }
  c.solutions.clear();
  r.stats = c.stats;
  r.complete = c.pending.empty();
  r.volume_left = 0;
  for (auto& n : c.pending) {
    r.volume_left += volume_ratio(core.setup.start, n.box, core.setup.split_dims);
    r.pending.push_back(std::move(n.box));
  }
  c.pending.clear();
  r.stats.seconds = c.seconds;
  return r;
}

std::optional<SearchState::Node> Search::give() {
  if (s_->core.committed.pending.size() < 2) return std::nullopt;
  SearchState st = state();
  SearchState::Node node = std::move(st.pending.front());
  st.pending.erase(st.pending.begin());
  set_state(std::move(st));
  return node;
}

std::optional<SearchState::Node> Search::lend() { return s_->lookahead.lend(s_->core.committed.pending); }

void Search::deliver(std::vector<SearchState::Record> records, const std::vector<prune::Counters>& counters) {
  s_->lookahead.deliver(std::move(records), counters);
}

void Search::unlend() { s_->lookahead.unlend(); }
std::vector<prune::Counters> Search::delivered_counters() const { return s_->lookahead.delivered_counters(); }
void Search::record_boxes() { s_->core.records.on = true; }
size_t Search::recorded() const { return s_->core.records.list.size(); }
std::vector<SearchState::Record> Search::take_records() { return std::exchange(s_->core.records.list, {}); }

}  // namespace linkbox::solve
