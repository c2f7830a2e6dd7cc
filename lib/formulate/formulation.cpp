#include "formulate/formulation.hpp"

namespace linkbox::formulate {

SubProblem PolynomialFormulation::subproblem(size_t) const {
  SubProblem s{"all", system_, {}, nullptr, nullptr, false};
  for (size_t i = 0; i < system_.variables.size(); ++i) s.split_dims.push_back(static_cast<int>(i));
  return s;
}

const NaturalSystem& Formulation::natural(std::uint64_t chart) const {
  std::lock_guard lock(natural_mutex_);
  auto& slot = natural_[chart];
  if (!slot) {
    auto sys = std::make_unique<NaturalSystem>(natural_system(chart));
    if (!sys->unknowns.empty() && sys->equations.size() == sys->unknowns.size())
      sys->compiled = std::make_shared<const model::CompiledSystem>(sys->equations, sys->unknowns.size());
    slot = std::move(sys);
  }
  return *slot;
}

NaturalSystem PolynomialFormulation::natural_system(std::uint64_t) const {
  return {system_.equations, system_.names(), system_.domain(), {}, nullptr};
}

}  // namespace linkbox::formulate
