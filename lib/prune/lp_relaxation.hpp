#pragma once
// The iterated-LP contractor (Porta, Ros, Thomas; Algorithm 2, SHRINK-BOX): tighten the
// dummy ranges by interval propagation, build the outward-rounded LP relaxation of the
// L/P/H system over the box, then minimise and maximise every primary variable.
// The box is declared empty only on proof: an interval check, a checked Farkas certificate,
// a rigorous bound beyond the box, or the exact solver's verdict.
#include "model/lph.hpp"
#include "prune/contractor.hpp"
#include "prune/lp/lp_solver.hpp"
#include "prune/lp/tighten.hpp"

#include <memory>

namespace linkbox::prune {

// Interval propagation through q = x^2 and b = x*y: q within x^2 and x within +-sqrt(q);
// b within x*y, and x within b/y (y within b/x) when the divisor excludes zero. Repeats a
// few passes while something moves. Returns false when it proves the box holds no point of
// the product surfaces; `box` is then unspecified.
bool propagate_products(const model::LphSystem& system, Box& box);

// False when some linear equation provably has no solution in the box (interval check).
bool linear_equations_possible(const model::LphSystem& system, const Box& box);

class LpRelaxation final : public Contractor {
 public:
  // `order`: which bound each pass tightens next (lp/tighten.hpp); `given` is the paper's.
  explicit LpRelaxation(const model::LphSystem& system, lp::LpBackend backend = lp::LpBackend::safe,
                        lp::Order order = lp::Order::nearest_bound);
  std::string name() const override;  // "lp-safe" or "lp-exact"
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;

  void stop_when(const std::function<bool()>* request) override { stop_ = request; }
  void add_work(Counters& counters) const override;
  long lps_solved() const { return lps_solved_; }  // a min or a max each

 private:
  LpRelaxation(std::shared_ptr<const model::LphSystem> system, lp::LpBackend backend, lp::Order order);

  std::shared_ptr<const model::LphSystem> system_;  // shared read-only by clones
  lp::LpBackend backend_;
  lp::Order order_;
  std::unique_ptr<lp::LpSolver> solver_;  // per instance: holds warm-start state
  long lps_solved_ = 0;
  const std::function<bool()>* stop_ = nullptr;
};

}  // namespace linkbox::prune
