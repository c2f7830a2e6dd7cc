#pragma once
// `linkbox check` on a curve cluster's map: everything re-proved from the file and the case.
#include "formulate/formulation.hpp"
#include "verify/curve_map.hpp"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <string>
#include <vector>

namespace linkbox::verify {

struct MapCheck {
  std::vector<std::string> failures;
  bool proved = false;  // the map holds and proves the cluster's solution set
  int closed = 0, open = 0;  // its components, when proved
  int branches = 0, singular = 0;  // components ending in singular points' boxes; those points
  int arcs = 0;         // arc certificates re-proved
  CurveMap map;         // as re-proved: arcs, images and ends recomputed, joined anew
};

// Each arc re-proved from its box, parameter and preconditioner; each member's natural box
// walked as the map walks it (walk_pieces), so that arcs, exclusions and the listed unresolved
// pieces cover it; the arcs joined anew. The components, their closedness and "proved" must be
// what the file says. `members` are the cluster's solution boxes (output variables);
// `chart_exists` says which charts the case has.
MapCheck check_map(const nlohmann::json& map, const formulate::Formulation& f, const std::vector<Box>& members,
                   const std::function<bool(std::uint64_t)>& chart_exists);

// Whether the members provably hold no solution through a symmetric loop's map (recomputed).
bool symmetric_empty(const formulate::Formulation& f, const std::vector<Box>& members);

}  // namespace linkbox::verify
