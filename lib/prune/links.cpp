#include "prune/links.hpp"

namespace linkbox::prune {

namespace {

// Passes over the links at most: each pass after the first only follows what the one before
// moved, and a chain of links longer than this is rare.
constexpr int kMaxPasses = 4;

}  // namespace

bool narrow_links(const std::vector<model::Link>& links, Box& box, bool& shrunk) {
  for (const model::Link& l : links) {
    const Interval y = box[l.y], a = box[l.a];
    if (!model::narrow(l, box)) return false;
    const auto moved = [](const Interval& before, const Interval& after) {
      return before.lower() != after.lower() || before.upper() != after.upper();
    };
    shrunk = shrunk || moved(y, box[l.y]) || moved(a, box[l.a]);
  }
  return true;
}

Outcome Links::contract(Box& box) {
  bool any = false;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool shrunk = false;
    operations_ += model::kLinkOperations * static_cast<double>(links_.size());
    if (!narrow_links(links_, box, shrunk)) return Outcome::empty;
    any = any || shrunk;
    if (!shrunk) break;
  }
  return any ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
