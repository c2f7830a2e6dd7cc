#include "formulate/formulation.hpp"

#include "model/lifting.hpp"

namespace linkbox::formulate {

// With links, the unknowns that stand for functions of the declared variables (a link's y
// and argument, a quotient, a square root, cos and sin of an atan2) are not split: propagation
// narrows them from the declared ones, and splitting them too multiplies the boxes (a link's
// y often spans many orders of magnitude). Without links every unknown is split, except a
// power's base (a sum of split unknowns, so splitting it would only split them again, along a
// diagonal). An atan2's own unknown is split: its links to cos and sin give propagation
// nothing to narrow it by, and unsplit it spans both angles that a direction (c, s) and its
// opposite give, over boxes along a whole curve of X s = Y c.
SubProblem PolynomialFormulation::subproblem(size_t) const {
  SubProblem s{"all", system_, {}, nullptr, nullptr, false};
  using Kind = model::Lifting::Source::Kind;
  using Function = model::Application::Function;
  for (size_t i = 0; i < system_.variables.size(); ++i) {
    const auto& source = system_.lifting ? system_.lifting->sources[i] : model::Lifting::Source{Kind::declared, 0};
    const auto function = [&] { return system_.lifting->applications[source.index].function; };
    const bool base = source.kind == Kind::application && function() == Function::base;
    const bool angle = source.kind == Kind::application && function() == Function::atan2;
    const bool of_declared = source.kind == Kind::application || source.kind == Kind::argument ||
                             source.kind == Kind::angle_cos || source.kind == Kind::angle_sin;
    const bool dependent = !angle && (base || (!system_.links.empty() && of_declared));
    if (!dependent) s.split_dims.push_back(static_cast<int>(i));
  }
  return s;
}

const NaturalSystem& Formulation::natural(std::uint64_t chart) const {
  std::lock_guard lock(natural_mutex_);
  auto& slot = natural_[chart];
  if (!slot) {
    auto sys = std::make_unique<NaturalSystem>(natural_system(chart));
    if (!sys->unknowns.empty() && sys->equations.size() + sys->links.size() == sys->unknowns.size())
      sys->compiled = std::make_shared<const model::CompiledSystem>(sys->equations, sys->links, sys->unknowns.size());
    slot = std::move(sys);
  }
  return *slot;
}

NaturalSystem PolynomialFormulation::natural_system(std::uint64_t) const {
  return {system_.equations, system_.names(), system_.domain(), system_.inequalities, {}, nullptr,
          system_.interval_constants, system_.links, system_.assumed_bounds, {}};
}

std::vector<std::string> PolynomialFormulation::output_names() const {
  if (!system_.lifting) return system_.names();
  std::vector<std::string> names;
  for (auto& v : system_.lifting->declared) names.push_back(v.name);
  return names;
}

Box PolynomialFormulation::to_output(size_t, const Box& box) const {
  return system_.lifting ? system_.lifting->to_declared(box) : box;
}

Box PolynomialFormulation::output_to_natural(std::uint64_t, const Box& output) const {
  return system_.lifting ? system_.lifting->to_lifted(output) : output;
}

std::vector<std::string> PolynomialFormulation::model_notes() const {
  std::vector<std::string> notes;
  if (system_.lifting) {
    const size_t declared = system_.lifting->declared.size(), unknowns = system_.variables.size();
    const size_t links = system_.links.size(), equations = system_.equations.size() + links;
    notes.push_back("lifted: " + std::to_string(declared) + " declared variables -> " + std::to_string(unknowns) +
                    " unknowns, " + std::to_string(equations) + " equations" +
                    (links ? " (" + std::to_string(links) + (links == 1 ? " link" : " links") + " y = f(a) among them)"
                           : std::string()));
    for (auto& n : system_.lifting->notes) notes.push_back("  " + n);
  }
  if (!system_.interval_constants.empty()) {
    std::string list;
    for (auto& c : system_.interval_constants) list += (list.empty() ? "" : ", ") + c;
    notes.push_back("interval constants " + list + ": each use is an interval coefficient, and roots are claimed "
                    "for every value of them");
  }
  if (!system_.assumed_bounds.empty()) {
    std::string list;
    for (auto& b : system_.assumed_bounds) list += (list.empty() ? "" : ", ") + b;
    notes.push_back("unbounded in the file, searched within a default bound: " + list +
                    " (roots beyond it are not reported)");
  }
  if (!system_.inequalities.empty()) {
    std::string list;
    for (auto& c : system_.inequalities) list += (list.empty() ? "" : "; ") + c.name;
    notes.push_back(std::to_string(system_.inequalities.size()) + " inequalit" +
                    (system_.inequalities.size() == 1 ? "y" : "ies") + ": " + list);
  }
  return notes;
}

}  // namespace linkbox::formulate
