#include "solve/race.hpp"

#include "solve/lead.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace linkbox::solve {

namespace {

// After the first turn, the leader's share of a turn is 1, every other candidate's this.
constexpr double kRaceShare = 0.125;
constexpr double kFirstTurn = 4000;
// In the first round a box may cost at most this: a candidate whose first box costs a hundred
// times the others' whole share (an LP over a large lifted system) would otherwise spend it
// before any candidate is compared. The cap holds within a pass too (between its LPs), so one
// pass over a large relaxation cannot overrun it. A capped box goes back to the candidate's
// list as far as its passes shrank it, their work counted, and next round it is shrunk on,
// uncapped. Caps only ever grow (first round, then none), so a box is capped in a look-ahead
// exactly when one thread would cap it.
constexpr double kFirstRoundBoxCap = kFirstTurn;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

Standing standing(const Search& s) { return {s.work(), s.tree_done()}; }

std::string describe(const Search& s) {
  return "work " + number(s.work()) + ", " + number(s.tree_done()) + " of the tree, projected " +
         number(projected(standing(s)));
}

}  // namespace

std::unique_ptr<Racer> make_racer(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                                  const Strategy& strategy, const StrategyOptions& options) {
  return std::unique_ptr<Racer>(
      new Racer{make_pruning(strategy, options, sub), NaturalCertifier(formulation, i), nullptr});
}

namespace {

bool extends(const Strategy& longer, const Strategy& shorter) {
  const auto& a = longer.stages();
  const auto& b = shorter.stages();
  return a.size() > b.size() && std::equal(b.begin(), b.end(), a.begin());
}

}  // namespace

Race::Race(std::vector<std::unique_ptr<Racer>> racers, Sharing* lending, bool twins)
    : racers_(std::move(racers)),
      extends_(racers_.size(), -1),
      at_{kFirstTurn, 0, 0, -1, -1, {}, {}},
      lending_(lending) {
  if (!twins || lending_) return;
  for (size_t k = 0; k < racers_.size(); ++k)
    for (size_t j = 0; j < racers_.size(); ++j)
      if (extends_[k] < 0 && extends(racers_[k]->pruning.strategy, racers_[j]->pruning.strategy))
        extends_[k] = static_cast<int>(j);
}

Race::~Race() {
  if (lending_) lending_->end_lending();
}

void Race::resume(size_t i, const SubCheckpoint& saved) {
  if (saved.searches.size() != racers_.size())
    throw std::invalid_argument("the checkpoint's sub-problem " + std::to_string(i) + " ran " +
                                std::to_string(saved.searches.size()) + " strategies, this run " +
                                std::to_string(racers_.size()));
  for (size_t k = 0; k < racers_.size(); ++k) {
    racers_[k]->search->set_state(saved.searches[k]);
    racers_[k]->pruning.sequence->set_counters(saved.counters[k]);
  }
  at_ = saved.race;
}

SubCheckpoint Race::checkpoint() const {
  SubCheckpoint c;
  c.phase = SubCheckpoint::Phase::searching;
  for (auto& r : racers_) {
    c.searches.push_back(r->search->state());
    c.counters.push_back(r->pruning.sequence->counters());
  }
  c.race = at_;
  return c;
}

Search& Race::run_turn(int threads) {
  if (racers_.size() > 1 && at_.target < 0) {
    start_turn();
    if (copied_twin(running())) return *racers_[running()]->search;
    const size_t k = running();
    if (std::find(extends_.begin(), extends_.end(), static_cast<int>(k)) != extends_.end())
      twin_turn_ = {static_cast<int>(k), racers_[k]->search->work(), at_.target, racers_[k]->pruning.sequence->stalls()};
  }
  Search& search = *racers_[running()]->search;
  if (racers_.size() == 1) {
    search.run(threads);
  } else {
    // Every thread on this candidate's turn: the turn still ends where one thread ends it
    // (look-ahead mode, lookahead.hpp), so the race and its winner do not depend on
    // the thread count.
    search.run(threads, at_.target, at_.turn == kFirstTurn ? kFirstRoundBoxCap : 0);
    if (search.capped()) note_capped(running());
  }
  if (search.complete() && at_.winner < 0 && racers_.size() > 1)
    at_.choices.push_back(name_of(running()) + " finished its search first (" + describe(search) + "): its boxes are the result");
  if (search.complete()) at_.winner = static_cast<int>(running());
  return search;
}

void Race::start_turn() {
  if (at_.next == 0 && at_.turn > kFirstTurn) pick_lead();
  if (lender_ >= 0 && at_.lead != static_cast<size_t>(lender_)) {
    // The lender lost the lead: its lent boxes' searches would serve a likely loser. It
    // takes them back (it may never need them); the new leader lends from now on.
    lending_->recall();
    racers_[lender_]->search->unlend();
    lender_ = -1;
  }
  at_.target = target_of(running());
}

// Candidate k's turn is the last turn of the candidate it extends, box for box, when it has not
// yet run its own later stages, starts where that turn started, runs to the same target, and
// that turn had no stall: then k takes that candidate's state, and its counters for the
// members they share (the first ones, make_pruning).
bool Race::copied_twin(size_t k) {
  const int j = extends_[k];
  if (j < 0 || twin_turn_.candidate != j) return false;
  Racer& me = *racers_[k];
  const Racer& twin = *racers_[j];
  if (me.pruning.sequence->ran_later_stages() || me.search->work() != twin_turn_.work ||
      at_.target != twin_turn_.target || twin.pruning.sequence->stalls() != twin_turn_.stalls)
    return false;
  me.search->set_state(twin.search->state());
  auto counters = me.pruning.sequence->counters();
  const auto shared = twin.pruning.sequence->counters();
  std::copy(shared.begin(), shared.end(), counters.begin());
  me.pruning.sequence->set_counters(counters);
  if (twin.search->capped()) note_capped(k);
  ++twin_turns_;
  return true;
}

void Race::note_capped(size_t k) {
  at_.choices.push_back("turn " + number(at_.turn) + ": " + name_of(k) + " stopped at a box costing over " +
                        number(kFirstRoundBoxCap) + " (the first round's cap; " + describe(*racers_[k]->search) +
                        "): it shrinks that box on next round");
}

// The lead runs first in each round: when it finishes in its turn, the others' shares of that
// round (a quarter of the lead's turn with three candidates) are never spent.
size_t Race::running() const {
  if (at_.next == 0) return at_.lead;
  return at_.next <= at_.lead ? at_.next - 1 : at_.next;
}

void Race::next_turn() {
  at_.target = -1;
  if (++at_.next == racers_.size()) {
    at_.next = 0;
    at_.turn *= 2;
  }
}

void Race::pick_lead() {
  const size_t held = at_.lead;
  std::vector<Standing> now;
  for (auto& r : racers_) now.push_back(standing(*r->search));
  if (at_.progress.size() != racers_.size()) at_.progress.assign(racers_.size(), {});
  for (size_t k = 0; k < now.size(); ++k) at_.progress[k].push_back({now[k].work, now[k].tree});
  at_.lead = choose_lead(held, now, at_.progress[held]);
  std::string why;
  for (size_t k = 0; k < racers_.size(); ++k) {
    if (k == held) continue;
    why += "; " + name_of(k) + " " + describe(*racers_[k]->search) +
           (now[k].work <= 0                           ? ", no work counted yet"
            : ahead_of(at_.progress[held], now[k]) < 0 ? ", behind on the tree at equal work"
            : cheaper(now[held], now[k])             ? ", 2x cheaper"
                                                     : ", not 2x cheaper");
  }
  at_.choices.push_back("turn " + number(at_.turn) + ": " + name_of(at_.lead) +
                        (at_.lead == held ? " keeps the lead (" : " takes the lead from " + name_of(held) + " (") +
                        name_of(held) + " " + describe(*racers_[held]->search) + why + ")");
}

std::string Race::name_of(size_t k) const { return racers_[k]->pruning.strategy.text(); }

// First turn: every candidate gets the share (a costly first box of one should not delay
// another that finishes at once: the rigid 6R's LP candidate).
double Race::target_of(size_t k) const {
  const double share = k == at_.lead && at_.turn > kFirstTurn ? 1 : kRaceShare;
  return racers_[k]->search->work() + at_.turn * share;
}

bool Race::lend_asked(size_t k) {
  const bool may_lend = lender_ < 0 ? k == at_.lead && at_.turn > kFirstTurn : static_cast<int>(k) == lender_;
  return lending_ && may_lend && lending_->asked();
}

void Race::lend(size_t subproblem) {
  Racer& r = *racers_[running()];
  if (lending_ && lending_->asked() && lending_->lend(subproblem, r.pruning.strategy, *r.search))
    lender_ = static_cast<int>(running());
}

void Race::end_lending() {
  if (lending_) lending_->end_lending();
  if (lender_ < 0 || at_.winner != lender_) return;
  Racer& r = *racers_[lender_];
  auto counters = r.pruning.sequence->counters();
  const auto delivered = r.search->delivered_counters();
  for (size_t k = 0; k < counters.size() && k < delivered.size(); ++k) counters[k] += delivered[k];
  r.pruning.sequence->set_counters(std::move(counters));
}

Racer& Race::best() {
  if (over()) return *racers_[at_.winner];
  size_t best = 0;
  for (size_t k = 1; k < racers_.size(); ++k)
    if (racers_[k]->search->volume_done() > racers_[best]->search->volume_done()) best = k;
  return *racers_[best];
}

std::vector<std::pair<std::string, double>> Race::record() {
  std::vector<std::pair<std::string, double>> r;
  if (!over()) return r;
  const Racer& winner = best();
  for (auto& c : racers_)
    if (c.get() != &winner) r.push_back({c->pruning.strategy.text(), c->search->work()});
  if (racers_.size() > 1) r.push_back({winner.pruning.strategy.text(), winner.search->work()});
  return r;
}

}  // namespace linkbox::solve
