#include "prune/composition.hpp"

namespace linkbox::prune {

Composition::Composition(std::vector<std::unique_ptr<Contractor>> members) : members_(std::move(members)) {}

std::string Composition::name() const {
  std::string n;
  for (auto& m : members_) n += (n.empty() ? "" : ",") + m->name();
  return n;
}

Outcome Composition::contract(Box& box) {
  Outcome total = Outcome::unchanged;
  at_most_one_ = false;
  for (auto& member : members_) {
    const Outcome o = member->contract(box);
    if (o == Outcome::empty) return Outcome::empty;
    if (o == Outcome::shrunk) total = Outcome::shrunk;
    at_most_one_ = at_most_one_ || member->at_most_one_root();
  }
  return total;
}

std::unique_ptr<Contractor> Composition::clone() const {
  std::vector<std::unique_ptr<Contractor>> m;
  for (auto& c : members_) m.push_back(c->clone());
  return std::make_unique<Composition>(std::move(m));
}

void Composition::stop_when(const std::function<bool()>* request) {
  for (auto& m : members_) m->stop_when(request);
}

void Composition::add_work(Counters& counters) const {
  for (auto& m : members_) m->add_work(counters);
}

}  // namespace linkbox::prune
