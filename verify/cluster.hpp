#pragma once
// Clustering of solution boxes: boxes whose closures touch or overlap belong together, so a
// root on a shared face is counted once. Connected components of the touch relation, found
// by sort-and-sweep plus union-find (no all-pairs loop).
#include "interval/box.hpp"

#include <vector>

namespace linkbox::verify {

// Rigorous enclosure of 2*pi, the period of angle dimensions.
Interval two_pi();

// `b` with each angle side shifted by the whole turns that bring it nearest `ref` (an exact
// translation, enclosed with two_pi()), as a cluster's boxes are unwrapped; `b` itself when
// the sides are not angles or the sizes differ.
Box unwrap(const Box& b, const Box& ref, bool angles);

// Whether the closures of `a` and `b` touch or overlap. In a dimension flagged periodic
// (empty `periodic` = none) the test is modulo 2*pi, so a box ending at +pi touches one
// starting at -pi. Conservative there: the boxes are said to touch unless they are apart
// for every period in the enclosure two_pi() (merging too much is safe, splitting a root's
// boxes apart is not). Boxes with a NaN bound touch nothing.
bool boxes_touch(const Box& a, const Box& b, const std::vector<bool>& periodic = {});

// Upper bound on the largest max-norm distance from a point of `a` to a point of `b`
// (outward rounded). In a periodic dimension `b` is first shifted by the whole turns that
// bring its centre nearest `a`'s, an exact translation; the distance modulo 2*pi is at most
// the distance to that copy.
double farthest_distance(const Box& a, const Box& b, const std::vector<bool>& periodic = {});

// Connected components of boxes_touch over `boxes` (all of one dimension; throws
// std::invalid_argument otherwise). Each cluster lists box indices ascending; clusters are
// ordered by their smallest index.
std::vector<std::vector<int>> cluster_boxes(const std::vector<Box>& boxes,
                                            const std::vector<bool>& periodic = {});

}  // namespace linkbox::verify
