#include "prune/lp/lp_solver.hpp"

#include "prune/lp/exact_lp.hpp"
#include "prune/lp/safe_lp.hpp"

namespace linkbox::prune::lp {

std::unique_ptr<LpSolver> make_lp_solver(LpBackend backend) {
  if (backend == LpBackend::exact) return std::make_unique<ExactLp>();
  return std::make_unique<SafeLp>(backend == LpBackend::float_trusted);
}

std::string to_string(LpBackend backend) { return backend == LpBackend::exact ? "exact" : backend == LpBackend::safe ? "safe" : "float"; }

}  // namespace linkbox::prune::lp
