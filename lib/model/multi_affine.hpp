#pragma once
// Dense form of a multi-affine polynomial: one coefficient per subset of its k variables
// (bit j of the index = variable vars[j] present). Corner evaluation is then a butterfly
// of k * 2^k operations.
#include "model/polynomial.hpp"

namespace linkbox::model {

struct MultiAffine {
  std::vector<int> vars;      // system variable indices, sorted
  std::vector<Interval> coef;  // size 2^vars.size()

  // Throws std::invalid_argument if `p` is not multi-affine.
  static MultiAffine from(const Polynomial& p);
  Polynomial to_polynomial() const;
};

}  // namespace linkbox::model
