#pragma once
// What a case becomes: one or more sub-problems (systems with a start box) plus the map
// from a search box back to the user's output variables (joint angles for mechanisms).
#include "model/compiled.hpp"
#include "model/lph.hpp"
#include "model/polynomial.hpp"

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>

#include <string>
#include <utility>
#include <vector>

namespace linkbox::formulate {

struct SubProblem {
  std::string label;    // e.g. "shift 010" for a half-turn-shifted spherical sub-problem
  model::System system;
  std::vector<int> split_dims;  // variables that are split and measured (primary variables)
  // The same system in L/P/H form when the formulation builds one (linkages); the LP
  // strategy derives it from `system` otherwise. Variable indices agree with `system`.
  std::shared_ptr<const model::LphSystem> lph;
  // When `system` is that L/P/H form: the equations before lifting, over its first (primary)
  // variables. Their roots are the projections of the lifted roots, so contractors may work
  // on them instead, and propagation and Newton are far cheaper there.
  std::shared_ptr<const model::System> unlifted;
  // The spherical paper's formulation: trapezoid clipping and widest-side bisection are its
  // method, and what "auto" runs on it.
  bool clipping = false;

  // What propagation, Newton and clipping work on.
  const model::System& pruned() const { return unlifted ? *unlifted : system; }
};

// A declared output evaluated on a box, e.g. a platform rotation matrix (row-major).
struct MatrixOutput {
  std::string name;
  std::vector<std::vector<Interval>> rows;
};

// The system in which roots are certified, in the case's natural unknowns (e.g. half-angle
// tangents of the joints in one chart of half-turn shifts), never in dummy or redundant
// variables. Certification needs it square; verify says so when it is not (a mobile
// linkage has fewer equations than unknowns, one closing by symmetry more).
struct NaturalSystem {
  std::vector<model::Polynomial> equations;
  std::vector<std::string> unknowns;
  Box domain;  // where roots count; empty = unbounded (angles: every chart covers the circle)
  // Over `unknowns`: a certified root counts only where every one provably holds (verify
  // classifies it, see verify/isolated.hpp); Newton ignores them.
  std::vector<model::Inequality> inequalities;
  std::string missing;  // no equations: why the formulation has none (empty: not given)
  // When square (equations and links as many as the unknowns): both compiled for interval
  // Newton, over `unknowns`.
  std::shared_ptr<const model::CompiledSystem> compiled;
  // The genuine interval constants of the coefficients (model::System): a certified root is
  // then one for every value of them.
  std::vector<std::string> interval_constants;
  // Non-polynomial equations y = f(a) (model/link.hpp): each counts as an equation (rows
  // after `equations` in `compiled`), and a certified root satisfies them too.
  std::vector<model::Link> links;
  // Domains the case left unbounded, bounded by default (model::System::assumed_bounds).
  std::vector<std::string> assumed_bounds;
  // Linkages: the rows [first, second) of `equations` that close each loop, in case order.
  std::vector<std::pair<int, int>> loop_rows;
};

class Formulation {
 public:
  virtual ~Formulation() = default;
  virtual std::string kind() const = 0;
  virtual size_t subproblem_count() const = 0;
  virtual SubProblem subproblem(size_t index) const = 0;
  // Names of the output variables (joint angles in radians for mechanisms).
  virtual std::vector<std::string> output_names() const = 0;
  // Rigorous enclosure of the output variables over a box of sub-problem `index`.
  virtual Box to_output(size_t index, const Box& box) const = 0;
  // Declared outputs (e.g. rotation matrices), rigorous over the box.
  virtual std::vector<MatrixOutput> declared_outputs(size_t, const Box&) const { return {}; }
  // What the model adds to the case as written, one line each (e.g. functions of variables
  // lifted to new unknowns, inequalities), for the model-size print. Empty: nothing.
  virtual std::vector<std::string> model_notes() const { return {}; }
  // True when output variables are angles (compared modulo 2*pi).
  virtual bool outputs_are_angles() const { return false; }

  // Certification (verify/). A chart is a parametrisation of the natural unknowns, chosen
  // from a box of output variables so the cluster is well inside it; its number is stored
  // with each certificate so `linkbox check` can rebuild the same system.
  virtual std::uint64_t chart_for(const Box& /*output_hull*/) const { return 0; }
  // Defaults: no natural system (nothing can be certified; verify says so).
  virtual NaturalSystem natural_system(std::uint64_t) const { return {}; }
  virtual Box output_to_natural(std::uint64_t, const Box& output) const { return output; }
  virtual Box natural_to_output(std::uint64_t, const Box& natural) const { return natural; }
  virtual std::vector<MatrixOutput> natural_outputs(std::uint64_t, const Box&) const { return {}; }

  // natural_system(chart), built and compiled once and shared by every thread: the search's
  // certifier, verification and the report ask for the same charts many times (a linkage's
  // natural system is a symbolic product of loop transforms).
  const NaturalSystem& natural(std::uint64_t chart) const;

 private:
  mutable std::mutex natural_mutex_;
  mutable std::map<std::uint64_t, std::unique_ptr<const NaturalSystem>> natural_;
};

// A polynomial system as typed by a user: one sub-problem, outputs are its variables. When
// functions of variables were lifted (system.lifting), the search and certification work on
// the lifted unknowns and outputs are the variables the user declared, mapped back one to
// one (model/lifting.hpp).
class PolynomialFormulation final : public Formulation {
 public:
  explicit PolynomialFormulation(model::System system) : system_(std::move(system)) {}
  std::string kind() const override { return "polynomial"; }
  size_t subproblem_count() const override { return 1; }
  SubProblem subproblem(size_t) const override;
  std::vector<std::string> output_names() const override;
  Box to_output(size_t, const Box& box) const override;
  std::vector<std::string> model_notes() const override;
  NaturalSystem natural_system(std::uint64_t) const override;
  Box output_to_natural(std::uint64_t, const Box& output) const override;
  Box natural_to_output(std::uint64_t, const Box& natural) const override { return to_output(0, natural); }

 private:
  model::System system_;
};

}  // namespace linkbox::formulate
