#pragma once
// The root a cluster should hold, certified by interval Newton in the natural system of the
// cluster's chart (`start` = the cluster's hull there). A natural system that is not square
// certifies nothing but can still prove the cluster empty, or (overdetermined) find a
// consistent candidate; `c` says which.
#include "verify/cluster_report.hpp"

namespace linkbox::verify {

// `members` are the cluster's boxes in the output variables (for the distances to a
// certified root); `periodic` flags the angle dimensions.
// Marks the cluster certified at its certificate's box (root, outputs, distances).
void accept_root(const formulate::Formulation& f, const std::vector<Box>& members, const std::vector<bool>& periodic,
                 ClusterReport& c);
// An overdetermined cluster whose square subsystem's root is unique in `start`: certified
// when its loops prove a root of every equation in `start` (verify/coupled_loops.hpp), which
// can then only be that root.
void certify_coupled(const formulate::Formulation& f, const Box& start, const std::vector<Box>& members,
                     const std::vector<bool>& periodic, ClusterReport& c);
void certify_isolated(const formulate::Formulation& f, const formulate::NaturalSystem& sys, const Box& start,
                      const std::vector<Box>& members, const std::vector<bool>& periodic, ClusterReport& c,
                      const newton::NewtonOptions& options);

// Whether natural equation `e` provably holds nowhere in `box`: its range misses 0 (a
// polynomial, e < equations.size()) or link e - equations.size() cannot hold there.
bool excludes(const formulate::NaturalSystem& sys, int e, const Box& box);

// After certification, against the natural system's inequalities (`start`: the cluster's
// hull in the natural unknowns). A certified root stays certified only when every
// inequality provably holds on its certified box; one violated there makes the cluster
// infeasible (its hull holds no other root) or unverified (it might), one undecided makes it
// unverified "on the boundary". A cluster not certified on which an inequality fails
// throughout is infeasible; the inequalities it straddles are listed.
void classify_inequalities(const formulate::NaturalSystem& sys, const Box& start, ClusterReport& c);

}  // namespace linkbox::verify
