// Solves a case through the installed library and certifies its roots; exits 1 unless the
// count is exact and matches what the case says.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  using namespace linkbox;
  const formulate::LoadedCase c = formulate::load_case(argv[1]);
  solve::RunOptions options;
  options.progress = false;
  const solve::CaseResult r = solve::solve_case(*c.formulation, options);
  const verify::VerifyReport v = verify::verify_case(*c.formulation, r);
  std::printf("%s: %s\n", c.name.c_str(), v.headline.c_str());
  return v.exact && v.certified_roots == 2 ? 0 : 1;
}
