#include "solve/strategy.hpp"

#include "formulate/to_lph.hpp"
#include "model/lifting.hpp"
#include "prune/acid.hpp"
#include "prune/hc4.hpp"
#include "prune/lifted.hpp"
#include "prune/links.hpp"
#include "prune/lp_relaxation.hpp"
#include "prune/newton_contractor.hpp"
#include "prune/taylor.hpp"
#include "prune/trapezoid.hpp"
#include "solve/pruning.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace linkbox::solve {

namespace {

using prune::Contractor;
using Make = std::unique_ptr<Contractor> (*)(const StrategyOptions&, const formulate::SubProblem&);

std::unique_ptr<Contractor> make_trapezoid(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  if (!pruned.is_multi_affine())
    throw std::invalid_argument("--prune trapezoid needs a multi-affine system; this one is not");
  return std::make_unique<prune::Trapezoid>(pruned.equations, options.arith);
}

std::unique_ptr<Contractor> make_lp(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const auto backend = options.arith != Arith::verified ? prune::lp::LpBackend::float_trusted : options.lp;
  if (sub.lph) return std::make_unique<prune::LpRelaxation>(*sub.lph, backend, options.lp_order);
  // Any polynomial system, lifted to L/P/H form around the search's own variables. Links
  // (y = f(a)) are left out: a relaxation of fewer constraints holds every root still, and
  // the Links contractor that runs first with it (make_pruning) prunes by them.
  model::LphSystem lph = formulate::to_lph(sub.system);
  auto inner = std::make_unique<prune::LpRelaxation>(lph, backend, options.lp_order);
  return std::make_unique<prune::Lifted>(std::move(lph), sub.system.variables.size(), std::move(inner));
}

std::unique_ptr<Contractor> make_hc4(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  return std::make_unique<prune::Hc4>(pruned.equations, options.arith, pruned.inequalities, pruned.links);
}

std::unique_ptr<Contractor> make_acid(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  std::vector<int> dims;
  for (int d : sub.split_dims)
    if (d < static_cast<int>(pruned.variables.size())) dims.push_back(d);
  return std::make_unique<prune::Acid>(make_hc4(options, sub), dims);
}

// The unknowns that stand for a sum raised to a power (model/lifter.cpp): they are there for
// propagation's sake, and Newton substitutes them out.
std::vector<int> lifted_sums(const model::System& system) {
  std::vector<int> r;
  if (!system.lifting) return r;
  const model::Lifting& lifting = *system.lifting;
  for (size_t v = 0; v < lifting.sources.size() && v < system.variables.size(); ++v) {
    const auto& source = lifting.sources[v];
    if (source.kind == model::Lifting::Source::Kind::application &&
        lifting.applications[source.index].function == model::Application::Function::base)
      r.push_back(static_cast<int>(v));
  }
  return r;
}

std::unique_ptr<Contractor> make_newton(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  return std::make_unique<prune::IntervalNewton>(pruned.equations, pruned.variables.size(), options.arith,
                                                 pruned.links, lifted_sums(pruned));
}

// One pass of HC4 and Newton over a box, whatever the strategy: every candidate of a race is
// priced in this one unit. Counted from the system's shape: building the contractors only to
// price a box was a quarter of a run of many sub-problems. Newton is built where it may
// substitute lifted sums (which ones depends on the coefficients).
double box_operations(const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  const size_t n = pruned.variables.size();
  const std::vector<int> sums = lifted_sums(pruned);
  const double newton =
      sums.empty() ? prune::IntervalNewton::step_operations_of(pruned.equations, n, pruned.links)
                   : prune::IntervalNewton(pruned.equations, n, Arith::verified, pruned.links, sums).step_operations();
  return std::max(1.0, prune::Hc4::call_operations_of(pruned.equations, pruned.inequalities, pruned.links.size()) +
                           newton);
}

std::unique_ptr<Contractor> make_taylor(const StrategyOptions& options, const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  const auto backend = options.arith != Arith::verified ? prune::lp::LpBackend::float_trusted : options.lp;
  return std::make_unique<prune::TaylorRelaxation>(pruned.equations, pruned.variables.size(), backend, options.arith,
                                                   pruned.links);
}

struct Row {
  ContractorKind kind;
  const char* name;
  Make make;
};

// Every contractor a strategy can name, in the order the help text and messages list them.
constexpr Row kContractors[] = {
    {ContractorKind::trapezoid, "trapezoid", make_trapezoid},
    {ContractorKind::lp, "lp", make_lp},
    {ContractorKind::hc4, "hc4", make_hc4},
    {ContractorKind::acid, "acid", make_acid},
    {ContractorKind::newton, "newton", make_newton},
    {ContractorKind::taylor, "taylor", make_taylor},
};

const Row& row_of(ContractorKind kind) {
  return *std::find_if(std::begin(kContractors), std::end(kContractors), [&](const Row& r) { return r.kind == kind; });
}

constexpr const char* kAuto = "auto";

// The text's names in order, "/" for each stage boundary; spaces dropped.
std::vector<std::string> tokens_of(const std::string& text) {
  std::vector<std::string> r;
  std::string item;
  auto flush = [&] {
    if (!item.empty()) r.push_back(item);
    item.clear();
  };
  for (char c : text) {
    if (c == ',' || c == '/') {
      flush();
      if (c == '/') r.push_back("/");
    } else if (c != ' ') {
      item += c;
    }
  }
  flush();
  return r;
}

const Row* find_row(const std::string& name) {
  for (const Row& r : kContractors)
    if (name == r.name) return &r;
  return nullptr;
}

}  // namespace

const char* name_of(ContractorKind kind) { return row_of(kind).name; }

std::string contractor_names() {
  std::string r;
  for (const Row& row : kContractors) r += (r.empty() ? "" : ", ") + std::string(row.name);
  return r;
}

Strategy Strategy::automatic() {
  Strategy s;
  s.auto_ = true;
  return s;
}

Strategy Strategy::parse(const std::string& text) {
  const std::vector<std::string> tokens = tokens_of(text);
  // Checked here so a misspelt name fails before any work, wherever it was written.
  for (auto& name : tokens)
    if (name != "/" && name != kAuto && !find_row(name))
      throw std::invalid_argument("unknown pruning strategy '" + name + "' (known: " + kAuto + ", " +
                                  contractor_names() + ")");
  if (std::count(tokens.begin(), tokens.end(), "/") == static_cast<long>(tokens.size()))
    throw std::invalid_argument("no pruning strategy given");
  if (tokens == std::vector<std::string>{kAuto}) return automatic();
  if (std::count(tokens.begin(), tokens.end(), kAuto) > 0)
    throw std::invalid_argument(std::string("'") + kAuto + "' chooses the whole strategy; it is not combined with contractors");
  std::vector<Stage> stages(1);
  for (auto& name : tokens) {
    if (name == "/") stages.emplace_back();
    else stages.back().push_back(find_row(name)->kind);
  }
  return Strategy(std::move(stages));
}

bool Strategy::empty() const { return !auto_ && stages_.empty(); }

bool Strategy::uses(ContractorKind kind) const {
  for (auto& stage : stages_)
    if (std::find(stage.begin(), stage.end(), kind) != stage.end()) return true;
  return false;
}

std::string Strategy::text() const {
  if (auto_) return kAuto;
  std::string t;
  for (size_t k = 0; k < stages_.size(); ++k) {
    if (k > 0) t += '/';
    for (size_t j = 0; j < stages_[k].size(); ++j) t += (j > 0 ? "," : "") + std::string(name_of(stages_[k][j]));
  }
  return t;
}

Strategy narrowing_strategy() {
  using K = ContractorKind;
  return Strategy({{K::hc4, K::newton, K::taylor}});
}

std::vector<Strategy> candidates(const Strategy& strategy, const formulate::SubProblem& sub) {
  if (!strategy.is_auto()) return {strategy};
  using K = ContractorKind;
  if (sub.clipping && sub.pruned().is_multi_affine()) return {Strategy({{K::trapezoid}})};
  return {Strategy({{K::hc4, K::newton}}), Strategy({{K::hc4, K::newton}, {K::lp}}),
          Strategy({{K::hc4, K::newton, K::taylor}})};
}

Pruning make_pruning(const Strategy& strategy, const StrategyOptions& options, const formulate::SubProblem& sub) {
  if (strategy.is_auto()) throw std::logic_error("make_pruning: \"auto\" is resolved by candidates() first");
  std::vector<std::unique_ptr<Contractor>> members;
  std::vector<int> stages;
  // Links (y = f(a)) are read by HC4 and Newton only: their own contractor runs first in
  // every pass, whatever the strategy, so no member's strategy can leave them unchecked.
  if (!sub.pruned().links.empty()) {
    members.push_back(std::make_unique<prune::Links>(sub.pruned().links));
    stages.push_back(0);
  }
  const size_t links = members.size();
  int stage = 0;  // empty stages take no number
  for (auto& contractors : strategy.stages()) {
    for (ContractorKind kind : contractors) {
      members.push_back(row_of(kind).make(options, sub));
      stages.push_back(stage);
    }
    stage += !contractors.empty();
  }
  if (members.size() == links) throw std::invalid_argument("no pruning strategy given");
  auto sequence = std::make_unique<prune::Sequence>(std::move(members), sub.split_dims, std::move(stages), options.stall);
  sequence->set_operations_per_box(box_operations(sub));
  return {strategy, std::move(sequence)};
}

}  // namespace linkbox::solve
