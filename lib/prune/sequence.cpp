#include "prune/sequence.hpp"

#include "prune/composition.hpp"

namespace linkbox::prune {

namespace {

std::vector<std::unique_ptr<Counted>> counted(std::vector<std::unique_ptr<Contractor>> members,
                                              const std::vector<int>& dims) {
  std::vector<std::unique_ptr<Counted>> c;
  for (auto& m : members) c.push_back(std::make_unique<Counted>(std::move(m), dims));
  return c;
}

}  // namespace

Sequence::Sequence(std::vector<std::unique_ptr<Contractor>> members, std::vector<int> measured_dims,
                   std::vector<int> stages, double stall)
    : Sequence(counted(std::move(members), measured_dims), measured_dims, std::move(stages), stall) {}

Sequence::Sequence(std::vector<std::unique_ptr<Counted>> members, std::vector<int> measured_dims,
                   std::vector<int> stages, double stall)
    : dims_(std::move(measured_dims)), stages_(std::move(stages)), stall_(stall) {
  stages_.resize(members.size(), stages_.empty() ? 0 : stages_.back());
  std::vector<std::unique_ptr<Contractor>> composed, stage;
  for (size_t i = 0; i < members.size(); ++i) {
    if (i > 0 && stages_[i] != stages_[i - 1])
      composed.push_back(std::make_unique<Composition>(std::move(stage))), stage.clear();
    members_.push_back(members[i].get());
    stage.push_back(std::move(members[i]));
  }
  if (!stage.empty()) composed.push_back(std::make_unique<Composition>(std::move(stage)));
  staged_ = std::make_unique<Staged>(std::move(composed), dims_, stall_);
}

std::unique_ptr<Sequence> Sequence::clone_sequence() const {
  std::vector<std::unique_ptr<Counted>> m;
  for (const Counted* c : members_) m.push_back(c->clone_counted());
  std::unique_ptr<Sequence> s(new Sequence(std::move(m), dims_, stages_, stall_));
  s->operations_per_box_ = operations_per_box_;
  return s;
}

double Sequence::operations() const {
  double n = 0;
  for (const Counted* m : members_) n += m->counters().operations;
  return n;
}

double Sequence::live_operations() const {
  double n = 0;
  for (const Counted* m : members_) n += m->live_operations();
  return n;
}

std::vector<Counters> Sequence::counters() const {
  std::vector<Counters> c;
  for (const Counted* m : members_) c.push_back(m->counters());
  return c;
}

bool Sequence::ran_later_stages() const {
  for (size_t i = 0; i < members_.size(); ++i)
    if (stages_[i] > stages_.front() && members_[i]->counters().calls > 0) return true;
  return false;
}

void Sequence::add_counters(const Sequence& other) {
  for (size_t i = 0; i < members_.size() && i < other.members_.size(); ++i) {
    Counters sum = members_[i]->counters();
    sum += other.members_[i]->counters();
    members_[i]->set_counters(sum);
  }
}

void Sequence::take_counters(Sequence& other) {
  add_counters(other);
  other.set_counters(std::vector<Counters>(other.members_.size()));
  staged_->set_stalls(staged_->stalls() + other.stalls());
  other.staged_->set_stalls(0);
}

void Sequence::set_counters(const std::vector<Counters>& counters) {
  for (size_t i = 0; i < members_.size(); ++i) members_[i]->set_counters(i < counters.size() ? counters[i] : Counters{});
}

}  // namespace linkbox::prune
