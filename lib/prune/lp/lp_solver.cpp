#include "prune/lp/lp_solver.hpp"

#include "prune/lp/cgal_lp.hpp"
#include "prune/lp/exact_lp.hpp"
#include "prune/lp/lp_record.hpp"
#include "prune/lp/safe_lp.hpp"

namespace linkbox::prune::lp {

std::unique_ptr<LpSolver> make_lp_solver(LpBackend backend) {
  std::unique_ptr<LpSolver> solver;
  switch (backend) {
    case LpBackend::exact: solver = std::make_unique<ExactLp>(); break;
    case LpBackend::cgal: solver = std::make_unique<CgalLp>(); break;
    case LpBackend::safe:
    case LpBackend::float_trusted: solver = std::make_unique<SafeLp>(backend == LpBackend::float_trusted); break;
  }
  return record_if_asked(std::move(solver));
}

std::string to_string(LpBackend backend) {
  switch (backend) {
    case LpBackend::safe: return "safe";
    case LpBackend::exact: return "exact";
    case LpBackend::cgal: return "cgal";
    case LpBackend::float_trusted: return "float";
  }
  return "?";
}

}  // namespace linkbox::prune::lp
