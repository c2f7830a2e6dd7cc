#include "prune/contractor.hpp"

#include <chrono>

namespace linkbox::prune {

Sequence::Sequence(std::vector<std::unique_ptr<Contractor>> members, std::vector<int> measured_dims)
    : members_(std::move(members)), counters_(members_.size()), dims_(std::move(measured_dims)) {}

std::string Sequence::name() const {
  std::string n;
  for (auto& m : members_) n += (n.empty() ? "" : ",") + m->name();
  return n;
}

Outcome Sequence::contract(Box& box) {
  Outcome total = Outcome::unchanged;
  for (size_t i = 0; i < members_.size(); ++i) {
    auto t0 = std::chrono::steady_clock::now();
    Box before = box;
    Outcome o = members_[i]->contract(box);
    Counters& c = counters_[i];
    c.calls++;
    c.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (o == Outcome::empty) {
      c.emptied++;
      c.volume_removed += 1;
      return Outcome::empty;
    }
    if (o == Outcome::shrunk) {
      c.volume_removed += 1 - volume_ratio(before, box, dims_);
      total = Outcome::shrunk;
    }
  }
  return total;
}

void Sequence::add_counters(const Sequence& other) {
  for (size_t i = 0; i < counters_.size() && i < other.counters_.size(); ++i) {
    counters_[i].calls += other.counters_[i].calls;
    counters_[i].emptied += other.counters_[i].emptied;
    counters_[i].seconds += other.counters_[i].seconds;
    counters_[i].volume_removed += other.counters_[i].volume_removed;
  }
}

std::unique_ptr<Contractor> Sequence::clone() const {
  std::vector<std::unique_ptr<Contractor>> m;
  for (auto& c : members_) m.push_back(c->clone());
  return std::make_unique<Sequence>(std::move(m), dims_);
}

}  // namespace linkbox::prune
