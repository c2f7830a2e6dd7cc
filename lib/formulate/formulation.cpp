#include "formulate/formulation.hpp"

namespace linkbox::formulate {

SubProblem PolynomialFormulation::subproblem(size_t) const {
  SubProblem s{"all", system_, {}, nullptr};
  for (size_t i = 0; i < system_.variables.size(); ++i) s.split_dims.push_back(static_cast<int>(i));
  return s;
}

NaturalSystem PolynomialFormulation::natural_system(std::uint64_t) const {
  return {system_.equations, system_.names(), system_.domain(), {}};
}

}  // namespace linkbox::formulate
