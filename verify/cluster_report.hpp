#pragma once
// What verification says about each cluster of solution boxes, and about the run.
#include "newton/certify.hpp"
#include "formulate/formulation.hpp"
#include "verify/curve_map.hpp"

#include <string>
#include <vector>

namespace linkbox::verify {

// empty: proved to hold no root (a spurious cluster of the search). infeasible: proved to
// hold no root where the inequalities hold (its only root violates one, or one fails on all
// of it). A certified root is certified only when it provably satisfies every inequality; one
// that sits on an inequality's boundary (the enclosure cannot tell) is unverified.
enum class ClusterStatus { certified, unverified, curve, empty, infeasible };
const char* to_string(ClusterStatus s);

struct CurveCrossing {
  size_t box = 0;  // index into ClusterReport::boxes
  // The chart the certificate is in: the cluster's, or the member box's own when no single
  // chart holds the whole cluster (a curve winding around a whole turn).
  std::uint64_t chart = 0;
  newton::Certificate certificate;
  // The natural equations left out of the crossing's system (one fewer kept than unknowns);
  // each must contain 0 on the crossing box.
  std::vector<int> dropped_equations;
};

struct ClusterReport {
  ClusterStatus status = ClusterStatus::unverified;
  std::string reason;                           // unverified: why; certified: notes
  std::vector<std::pair<size_t, size_t>> boxes;  // (sub-problem, solution index)
  Box hull;                                     // output variables (angles unwrapped)
  std::uint64_t chart = 0;
  newton::Certificate certificate;                      // in the chart's natural unknowns
  // Natural systems that are not square: the equations `certificate` is about (a square
  // subsystem; empty = all), or the one whose range over certificate.box misses 0.
  std::vector<int> subsystem;
  int excluding_equation = -1;
  // Certified with a square subsystem: what proves the other equations vanish at its root
  // ("coupled loops": verify/coupled_loops.hpp); empty otherwise.
  std::string argument;
  Box root;                                     // certified box in the output variables
  std::vector<formulate::MatrixOutput> outputs;  // declared outputs over the certified box
  std::vector<CurveCrossing> crossings;         // curve clusters
  int crossings_certified = 0;
  // Curve clusters: the certified map of the solution set in the cluster's boxes, when the
  // arcs cover enough of them to state one.
  std::optional<CurveMap> map;
  int duplicate_of = -1;  // certified, but the same root as that cluster's
  // Inequalities of the natural system: the one a root violates (infeasible) or sits on the
  // boundary of (unverified), -1 if none; and those whose sign the enclosure of the cluster
  // (its certified root when certified, else its hull) leaves undecided.
  int inequality = -1;
  std::vector<int> straddled;
  // Certified: the root as an exact rational point (verify/exact_point.hpp), when the
  // certified box holds one that every equation vanishes at; the domain and the inequalities
  // its enclosure leaves undecided are decided there.
  std::vector<std::string> exact_root;
  // Upper bounds: the largest rigorous residual max_i |f_i(midpoint)| of a member box in its
  // sub-problem's system; for a certified cluster, per member (same order as `boxes`) the
  // farthest distance (max norm, output variables, angles modulo 2 pi) from a point of the
  // member to a point of `root`, and the largest of those.
  double max_residual = 0;
  std::vector<double> distances;
  double max_distance = 0;
};

struct VerifyReport {
  std::vector<ClusterReport> clusters;
  int certified_roots = 0;
  int unverified = 0;
  int curves = 0;
  // Components of the curve clusters' maps, and whether every curve cluster's map is proved.
  int closed_curves = 0;
  int open_arcs = 0;
  // Arcs that end in proved singular points' boxes, and those points.
  int branches = 0;
  int singular_points = 0;
  bool maps_proved = false;
  int empty = 0;
  int infeasible = 0;
  int inequalities = 0;  // of the natural system: the count is of roots where they all hold
  // The natural system's genuine interval constants: every claim holds for every value of them.
  std::vector<std::string> interval_constants;
  // Domains the case left unbounded, bounded by default: every claim is within them.
  std::vector<std::string> assumed_bounds;
  bool exact = false;  // "exactly N roots in the domain" holds
  bool timed_out = false;  // some cluster was skipped at VerifyOptions::time_limit
  std::string headline;
  double seconds = 0;
};

}  // namespace linkbox::verify
