#include "prune/lifted.hpp"

#include "model/lph.hpp"

namespace linkbox::prune {

Lifted::Lifted(model::LphSystem lph, size_t n, std::unique_ptr<Contractor> inner)
    : lph_(std::move(lph)), n_(n), inner_(std::move(inner)) {}

Outcome Lifted::contract(Box& box) {
  Box lifted = model::lift(lph_, Box(box.begin(), box.begin() + n_));
  const Outcome o = inner_->contract(lifted);
  if (o != Outcome::shrunk) return o;
  bool changed = false;
  for (size_t i = 0; i < n_; ++i) {
    changed = changed || lifted[i].lower() != box[i].lower() || lifted[i].upper() != box[i].upper();
    box[i] = lifted[i];
  }
  return changed ? Outcome::shrunk : Outcome::unchanged;
}

std::unique_ptr<Contractor> Lifted::clone() const {
  return std::make_unique<Lifted>(lph_, n_, inner_->clone());
}

}  // namespace linkbox::prune
