#include "prune/staged.hpp"

#include <algorithm>

namespace linkbox::prune {

namespace {
// A later stage succeeds when it proves the box empty or removes a tenth of its volume; the
// search iterates it, so a tenth per call adds up (the choice: papers/decisions/contractors.md).
constexpr double kWorthIt = 0.9;
constexpr int kMaxLevel = 10;
}  // namespace

Staged::Staged(std::vector<std::unique_ptr<Contractor>> stages, std::vector<int> measured_dims, double stall)
    : stages_(std::move(stages)), dims_(std::move(measured_dims)), stall_(stall) {}

std::string Staged::name() const {
  std::string n;
  for (auto& s : stages_) n += (n.empty() ? "" : ",") + s->name();
  return n;
}

Outcome Staged::contract(Box& box) {
  Backoff never;
  return contract(box, never);
}

Outcome Staged::contract(Box& box, Backoff& backoff) {
  Outcome total = Outcome::unchanged;
  at_most_one_ = false;
  Box stage_start;
  bool gated = false;  // inside a later stage
  auto judge = [&](bool emptied) {
    if (!gated) return;
    if (emptied || volume_ratio(stage_start, box, dims_) <= kWorthIt) {
      backoff.level = 0;
    } else {
      backoff.level = std::min(backoff.level + 1, kMaxLevel);
      backoff.skip = (1 << backoff.level) - 1;
    }
  };
  for (size_t i = 0; i < stages_.size(); ++i) {
    if (i > 0) {
      judge(false);
      // The earlier stages made progress: the stronger (costlier) ones wait for a stall,
      // and for the backoff.
      if (volume_ratio(stage_start, box, dims_) <= stall_ || backoff.skip > 0) return total;
      gated = true;
    }
    stage_start = box;
    Contractor& stage = *stages_[i];
    const Outcome o = stage.contract(box);
    if (o == Outcome::empty) {
      judge(true);
      return Outcome::empty;
    }
    if (o == Outcome::shrunk) total = Outcome::shrunk;
    at_most_one_ = at_most_one_ || stage.at_most_one_root();
  }
  judge(false);
  if (backoff.skip == 0 && volume_ratio(stage_start, box, dims_) > stall_) ++stalls_;
  return total;
}

std::unique_ptr<Contractor> Staged::clone() const {
  std::vector<std::unique_ptr<Contractor>> s;
  for (auto& c : stages_) s.push_back(c->clone());
  return std::make_unique<Staged>(std::move(s), dims_, stall_);
}

void Staged::stop_when(const std::function<bool()>* request) {
  for (auto& s : stages_) s->stop_when(request);
}

void Staged::add_work(Counters& counters) const {
  for (auto& s : stages_) s->add_work(counters);
}

}  // namespace linkbox::prune
