#pragma once
// A case solved, verified and serialised as `linkbox solve` does it, for tests that look at
// every stage: the search result, the verification report, the JSON and the distinct
// certified roots.
#include "formulate/load.hpp"
#include "report/json.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace linkbox::test {

struct SolvedCase {
  formulate::LoadedCase c;
  solve::CaseResult r;
  verify::VerifyReport v;
  nlohmann::json j;
  std::vector<Box> roots;  // certified, distinct, in the case's output variables
};

inline SolvedCase solve_loaded(formulate::LoadedCase c, const std::string& prune, double sigma) {
  SolvedCase run{std::move(c), {}, {}, {}, {}};
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse(prune);
  o.params.sigma = sigma;
  run.r = solve::solve_case(*run.c.formulation, o);
  REQUIRE(run.r.complete);
  run.v = verify::verify_case(*run.c.formulation, run.r);
  run.j = report::result_json(run.c.name, run.c.file, *run.c.formulation, o, run.r);
  report::add_verification(run.j, *run.c.formulation, run.v);
  for (auto& cl : run.v.clusters)
    if (cl.status == verify::ClusterStatus::certified && cl.duplicate_of < 0) run.roots.push_back(cl.root);
  return run;
}

inline SolvedCase solve_text(const std::string& toml, const std::string& prune = "hc4,newton",
                             double sigma = 1e-6) {
  return solve_loaded(formulate::load_case_text(toml, "inline.toml"), prune, sigma);
}

}  // namespace linkbox::test
