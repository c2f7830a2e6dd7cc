#pragma once
// One small interface for every pruning strategy: shrink a box without losing any root.
// A contractor may only answer `empty` when it has *proved* the box holds no root.
#include "interval/box.hpp"
#include "prune/counters.hpp"

#include <memory>
#include <string>
#include <vector>

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
  // Work done so far by an LP-based contractor (0 for the others), for the counters.
  virtual long lps_solved() const { return 0; }
  virtual long lp_iterations() const { return 0; }
};

// Applies its members in order; stops at the first `empty`. Keeps counters per member.
class Sequence final : public Contractor {
 public:
  explicit Sequence(std::vector<std::unique_ptr<Contractor>> members, std::vector<int> measured_dims = {});
  std::string name() const override;
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;
  const std::vector<std::unique_ptr<Contractor>>& members() const { return members_; }
  const std::vector<Counters>& counters() const { return counters_; }
  void add_counters(const Sequence& other);  // same members, e.g. a clone run elsewhere

 private:
  std::vector<std::unique_ptr<Contractor>> members_;
  std::vector<Counters> counters_;
  std::vector<int> dims_;
};

}  // namespace linkbox::prune
