#pragma once
// Every box the searches of a run process, to replay the run (papers/benchmarks/scaling.py
// models distributed runs from it: the tree, and what each box cost). Costs two clock reads per
// box when a search logs to one.
#include <cstddef>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace linkbox::solve {

class BoxLog {
 public:
  struct Entry {
    size_t subproblem;
    int candidate;     // which raced strategy (0 when one ran)
    std::string path;  // the box's place in the search tree
    char outcome;      // 'e' empty, 's' solution, 'x' split
    double seconds;
  };
  void add(Entry e) {
    std::lock_guard lock(m_);
    entries_.push_back(std::move(e));
  }
  std::vector<Entry> take() {
    std::lock_guard lock(m_);
    return std::move(entries_);
  }

 private:
  std::mutex m_;
  std::vector<Entry> entries_;
};

}  // namespace linkbox::solve
