#pragma once
// Curve clusters: an unresolved cluster whose boxes follow a solution curve (a mobile
// mechanism, gimbal lock) is recognised and its crossings certified box by box.
#include "verify/cluster_report.hpp"

namespace linkbox::verify {

// Reclassifies an unverified cluster `c` as a curve when it is long, the Jacobian is rank
// deficient near its boxes, and certified crossings of the curve cover at least half of
// them. `member` are its boxes in the output variables; `chart_holds_cluster` is false when
// no single chart holds the cluster (each box is then analysed in its own). Returns whether
// the cluster looks like a curve (long, rank deficient near its boxes), certified or not.
bool classify_curve(const formulate::Formulation& f, const std::vector<Box>& member,
                    bool chart_holds_cluster, ClusterReport& c, const newton::NewtonOptions& options);

}  // namespace linkbox::verify
