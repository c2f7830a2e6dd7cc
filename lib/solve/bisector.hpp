#pragma once
// Which side of a box to split. Any choice is sound (both halves are searched); it only
// decides how fast propagation and Newton get a grip.
//   widest       the longest split side (the papers' rule)
//   round-robin  split sides in turn, by depth in the search tree
//   smear        the side whose variation moves the equations most: for each equation, the
//                share |df/dx_j| * width_j of its total, summed over equations (IbexSolve's
//                "smearsumrel"); sides already <= sigma are never chosen. On a system that
//                separates into blocks, only among those of the first one still open
//   auto         widest on the spherical paper's formulation (its method and tables),
//                smear otherwise
#include "formulate/formulation.hpp"
#include "model/compiled.hpp"

#include <memory>
#include <string>
#include <vector>

namespace linkbox::solve {

enum class Bisect { automatic, widest, round_robin, smear };

std::string to_string(Bisect b);
Bisect parse_bisect(const std::string& name);  // throws std::invalid_argument naming the known rules

class Bisector {
 public:
  // Smear reads the system propagation works on (sub.pruned(): its variables are the first
  // ones of the box).
  Bisector(Bisect rule, const formulate::SubProblem& sub, double sigma);
  Bisect rule() const { return rule_; }  // "automatic" resolved
  // Thread-safe. `depth` is the box's depth in the search tree.
  int choose(const Box& box, int depth) const;

 private:
  int smear(const Box& box) const;
  int first_open_block(const Box& box) const;
  Bisect rule_;
  std::vector<int> dims_;
  double sigma_;
  std::shared_ptr<const model::CompiledSystem> compiled_;  // smear only
  // Smear only: per variable, its block (model/block_triangular.hpp); empty for one block.
  std::vector<int> block_;
};

}  // namespace linkbox::solve
