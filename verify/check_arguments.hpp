#pragma once
// Certified clusters of an overdetermined natural system (`argument` in docs/json.md): what
// makes the root of a square subsystem a root of every natural equation, re-run from the
// cluster's JSON and the case. Each returns the subsystem's proved Newton image (it holds the
// root) when the argument holds, and nothing otherwise.
#include "formulate/formulation.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <optional>

namespace linkbox::verify {

// "exact root": the stated rational point lies in the image and zeroes every equation exactly;
// when the cluster claims no other root in its hull, the subsystem's uniqueness over `start`
// (the hull in natural unknowns) is proved again.
std::optional<Box> recheck_exact_root(const formulate::NaturalSystem& sys, const nlohmann::json& cluster,
                                      const Box& start);
// "coupled loops" (verify/coupled_loops.hpp), in chart `chart` of `f`.
std::optional<Box> recheck_coupled_loops(const formulate::Formulation& f, std::uint64_t chart,
                                         const nlohmann::json& cluster, const Box& start);

}  // namespace linkbox::verify
