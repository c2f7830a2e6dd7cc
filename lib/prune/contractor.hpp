#pragma once
// One small interface for every pruning strategy: shrink a box without losing any root.
// A contractor may only answer `empty` when it has *proved* the box holds no root.
// Contractors combine as in IBEX: in order (composition.hpp), in stages that run only when the
// earlier ones stall (staged.hpp), and counted (counted.hpp); sequence.hpp puts the three
// together for the search.
#include "interval/box.hpp"
#include "prune/counters.hpp"

#include <functional>
#include <memory>
#include <string>

namespace linkbox::prune {

enum class Outcome { empty, shrunk, unchanged };

class Contractor {
 public:
  virtual ~Contractor() = default;
  virtual std::string name() const = 0;
  // Shrinks `box` in place. On `empty`, the contents of `box` are unspecified.
  virtual Outcome contract(Box& box) = 0;
  // A fresh contractor of the same kind and settings with its own scratch state, for
  // another thread.
  virtual std::unique_ptr<Contractor> clone() const = 0;
  // Whether the last contract() proved that the box it returned holds at most one root (see
  // IntervalNewton). A hint for the search to try a certificate; never a proof of existence.
  virtual bool at_most_one_root() const { return false; }
  // Asked between the costly steps of one contract() (the LPs of a relaxation): when it
  // returns true, the contractor returns what it has proved so far, so a time limit or an
  // interrupt is honoured within one step. The function must outlive its use.
  virtual void stop_when(const std::function<bool()>* request) { (void)request; }
  // Adds the work done so far that only the contractor itself can count (its operations; an
  // LP-based one: LPs solved, simplex iterations, the exact backend's paths) to `counters`;
  // none by default.
  virtual void add_work(Counters& counters) const { (void)counters; }
};

}  // namespace linkbox::prune
