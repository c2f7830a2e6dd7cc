#pragma once
// Whether two searches stand at the same place: the same work, boxes processed, pending paths
// and solutions (bit for bit). For tests that compare ways of running one search.
#include "solve/search_state.hpp"

#include <catch2/catch.hpp>

namespace linkbox::test {

inline void check_same_state(const solve::SearchState& a, const solve::SearchState& b) {
  CHECK(a.work == b.work);
  CHECK(a.stats.processed == b.stats.processed);
  REQUIRE(a.pending.size() == b.pending.size());
  for (size_t j = 0; j < a.pending.size(); ++j) CHECK(a.pending[j].path == b.pending[j].path);
  REQUIRE(a.solutions.size() == b.solutions.size());
  for (size_t j = 0; j < a.solutions.size(); ++j) {
    CHECK(a.solutions[j].path == b.solutions[j].path);
    for (size_t d = 0; d < a.solutions[j].box.size(); ++d) {
      CHECK(a.solutions[j].box[d].lower() == b.solutions[j].box[d].lower());
      CHECK(a.solutions[j].box[d].upper() == b.solutions[j].box[d].upper());
    }
  }
}

}  // namespace linkbox::test
