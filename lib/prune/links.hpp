#pragma once
// The links of a system (model/link.hpp, y = f(a) for an elementary f) as a contractor:
// y := y ∩ f(a), a := a ∩ f^-1(y) where f is monotone (cosh: on each branch), a := a ∩ f's
// domain, each through MPFI, repeated while the box shrinks (links may feed each other, as in
// exp(exp(x))). No other contractor reads links, except HC4 and Newton which take them too,
// so the strategy runs this one first, always, for a system with links.
#include "model/link.hpp"
#include "prune/contractor.hpp"

#include <vector>

namespace linkbox::prune {

class Links final : public Contractor {
 public:
  explicit Links(std::vector<model::Link> links) : links_(std::move(links)) {}
  std::string name() const override { return "links"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<Links>(links_); }
  void add_work(Counters& counters) const override { counters.operations += operations_; }

 private:
  std::vector<model::Link> links_;
  double operations_ = 0;
};

// One pass of model::narrow over `links`: false when one proves the box empty; `shrunk` is set
// when a side moved.
bool narrow_links(const std::vector<model::Link>& links, Box& box, bool& shrunk);

}  // namespace linkbox::prune
