#pragma once
// 3BCID shaving (Trombettoni & Chabert, CP 2007), the "ACID" contractor of IbexSolve's default
// solver: for each variable, cut its interval into slices and run a cheap contractor on the
// outermost ones; slices it proves empty are shaved off, and the box becomes the hull of what
// remains of the left slice, the middle and the right slice after contraction (the CID part,
// which narrows the other variables too). Sound because the slices cover the box and each is
// contracted soundly.
//
// Propagation alone is local: it cannot see that a slice at the edge of a wide box is empty
// when that takes several equations at once. Shaving turns such global information into
// removed volume, and so cuts the boxes the search must bisect (Eco9: see papers/benchmarks).
#include "prune/contractor.hpp"

#include <memory>
#include <vector>

namespace linkbox::prune {

class Acid final : public Contractor {
 public:
  // `inner` contracts one slice (HC4); `dims` are the variables shaved, in order.
  Acid(std::unique_ptr<Contractor> inner, std::vector<int> dims, int slices = 10);
  Acid(const Acid& other);
  std::string name() const override { return "acid"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<Acid>(*this); }

 private:
  // The first slice from the left (step +1) or the right (step -1), starting at `first` and
  // not past `last`, that `inner_` does not prove empty, contracted into `out`; -1 if none.
  int shave(const Box& box, int var, int first, int last, int step, Box& out);
  Interval slice(const Interval& x, int from, int to) const;  // slices [from, to], inclusive

  std::unique_ptr<Contractor> inner_;
  std::vector<int> dims_;
  int slices_;
};

}  // namespace linkbox::prune
