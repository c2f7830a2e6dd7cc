#include "cli/settings.hpp"

#include "input/input_error.hpp"

namespace linkbox::cli {

nlohmann::json search_settings(const solve::RunOptions& o) {
  return {{"sigma", o.params.sigma},
          {"rho", o.params.rho},
          {"order", o.params.order == solve::Order::depth_first ? "dfs" : "bfs"},
          {"prune", o.strategy.prune.text()},
          {"bisect", solve::to_string(o.bisect)},
          {"lp", prune::lp::to_string(o.strategy.lp)},
          {"lp_order", prune::lp::to_string(o.strategy.lp_order)},
          {"arith", to_string(o.strategy.arith)}};
}

void resolve_settings(SolveCommand& cmd, const input::SolveSettings& s, const std::string& file) {
  solve::RunOptions& o = cmd.options;
  auto from_case = [&](const char* flag, const char* name, const auto& value, auto apply) {
    if (cmd.given(flag)) {
      o.setting_source[name] = "flag";
    } else if (value) {
      try {
        apply(*value);
      } catch (const std::invalid_argument& e) {
        throw input::InputError(file, s.line, std::string("[solve] ") + name + ": " + e.what());
      }
      o.setting_source[name] = "case file";
    }
  };
  from_case("--sigma", "sigma", s.sigma, [&](double x) { o.params.sigma = x; });
  from_case("--rho", "rho", s.rho, [&](double x) { o.params.rho = x; });
  from_case("--time-limit", "time_limit", s.time_limit, [&](double x) { o.params.time_limit = x; });
  from_case("--prune", "prune", s.prune, [&](const std::string& x) { o.strategy.prune = solve::Strategy::parse(x); });
  from_case("--bisect", "bisect", s.bisect, [&](const std::string& x) { o.bisect = solve::parse_bisect(x); });
}

void resume_settings(SolveCommand& cmd, const nlohmann::json& saved) {
  solve::RunOptions& o = cmd.options;
  const nlohmann::json asked = search_settings(o);
  auto take = [&](const char* flag, const char* name, auto apply) {
    if (cmd.given(flag) && asked.at(name) != saved.at(name))
      throw std::invalid_argument("the checkpoint was made with " + std::string(name) + " " + saved.at(name).dump() +
                                  ", not " + asked.at(name).dump() + ": resume it with the same settings, or start afresh");
    apply(saved.at(name));
  };
  take("--sigma", "sigma", [&](const nlohmann::json& v) { o.params.sigma = v; });
  take("--rho", "rho", [&](const nlohmann::json& v) { o.params.rho = v; });
  take("--order", "order", [&](const nlohmann::json& v) {
    o.params.order = v == "bfs" ? solve::Order::breadth_first : solve::Order::depth_first;
  });
  take("--prune", "prune", [&](const nlohmann::json& v) { o.strategy.prune = solve::Strategy::parse(v.get<std::string>()); });
  take("--bisect", "bisect", [&](const nlohmann::json& v) { o.bisect = solve::parse_bisect(v); });
  take("--lp", "lp", [&](const nlohmann::json& v) {
    o.strategy.lp = v == "exact" ? prune::lp::LpBackend::exact : prune::lp::LpBackend::safe;
  });
  take("--lp-order", "lp_order", [&](const nlohmann::json& v) {
    o.strategy.lp_order = v == "given" ? prune::lp::Order::given : prune::lp::Order::nearest_bound;
  });
  take("--arith", "arith", [&](const nlohmann::json& v) {
    o.strategy.arith = v == "verified" ? Arith::verified : Arith::float_unverified;
  });
  for (auto& [name, value] : saved.items()) o.setting_source[name] = "checkpoint";
  if (search_settings(o) != saved)
    throw std::invalid_argument("the checkpoint's settings " + saved.dump() + " are not understood by this linkbox");
}

}  // namespace linkbox::cli
