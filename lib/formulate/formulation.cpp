#include "formulate/formulation.hpp"

namespace linkbox::formulate {

SubProblem PolynomialFormulation::subproblem(size_t) const {
  SubProblem s{"all", system_, {}, nullptr};
  for (size_t i = 0; i < system_.variables.size(); ++i) s.split_dims.push_back(static_cast<int>(i));
  return s;
}

}  // namespace linkbox::formulate
