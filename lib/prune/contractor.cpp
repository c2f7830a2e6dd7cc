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

Counters& Counters::operator+=(const Counters& o) {
  calls += o.calls;
  emptied += o.emptied;
  seconds += o.seconds;
  volume_removed += o.volume_removed;
  lps_solved += o.lps_solved;
  lp_iterations += o.lp_iterations;
  return *this;
}

Outcome Sequence::contract(Box& box) {
  Outcome total = Outcome::unchanged;
  for (size_t i = 0; i < members_.size(); ++i) {
    auto t0 = std::chrono::steady_clock::now();
    Box before = box;
    Contractor& member = *members_[i];
    const long lps = member.lps_solved(), iterations = member.lp_iterations();
    Outcome o = member.contract(box);
    Counters& c = counters_[i];
    c.calls++;
    c.lps_solved += member.lps_solved() - lps;
    c.lp_iterations += member.lp_iterations() - iterations;
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
  for (size_t i = 0; i < counters_.size() && i < other.counters_.size(); ++i) counters_[i] += other.counters_[i];
}

std::unique_ptr<Contractor> Sequence::clone() const {
  std::vector<std::unique_ptr<Contractor>> m;
  for (auto& c : members_) m.push_back(c->clone());
  return std::make_unique<Sequence>(std::move(m), dims_);
}

}  // namespace linkbox::prune
