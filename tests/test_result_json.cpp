// `check_certificates` on a curve that winds around a whole turn (gimbal lock), whose
// crossings are each in their own chart.
#include "io/case_file.hpp"
#include "io/result_json.hpp"
#include "io/verify_json.hpp"
#include "prune/strategy.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>

using namespace linkbox;
using nlohmann::json;

namespace {

struct Written {
  io::LoadedCase c;
  verify::VerifyReport v;
  json j;
};

Written solve_and_write(const std::string& path, double sigma) {
  Written w{io::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + path), {}, {}};
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = sigma;
  o.strategy.contractors = prune::parse_strategy_list("trapezoid");
  const solve::CaseResult r = solve::solve_case(*w.c.formulation, o);
  w.v = verify::verify_case(*w.c.formulation, r);
  w.j = io::result_json(w.c.name, w.c.file, *w.c.formulation, o, r);
  io::add_verification(w.j, *w.c.formulation, w.v);
  return w;
}

}  // namespace

TEST_CASE("json: check re-runs every gimbal-lock crossing, each in its own chart", "[json][hard]") {
  Written w = solve_and_write("cases/hard/gimbal-lock.toml", 1e-2);
  REQUIRE(w.v.curves == 1);
  const auto& curve = *std::find_if(w.j["clusters"].begin(), w.j["clusters"].end(),
                                    [](const json& c) { return c["status"] == "curve"; });
  std::set<std::uint64_t> charts;
  for (auto& x : curve["crossings"]) charts.insert(x["chart"].get<std::uint64_t>());
  CHECK(charts.size() >= 2);  // the curve winds around a whole turn
  const io::CheckOutcome ok = io::check_certificates(w.j, *w.c.formulation);
  CHECK(ok.failures.empty());
  CHECK(ok.checked == curve["crossings_certified"].get<int>());
  CHECK(ok.checked > 0);
}
