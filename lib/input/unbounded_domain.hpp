#pragma once
// A domain end that a case file leaves infinite (no domain in Minibex, "oo", "INF" or "inf")
// is kDefaultBound in magnitude: linkbox encloses roots in a bounded box, and mapping an
// unbounded domain onto a bounded one would make the certificates speak of another system.
// The bound is stated, not hidden: the model notes and every headline repeat it (System::
// assumed_bounds), so "exactly N roots" reads as N roots within it. 1e8 is what IbexSolve's
// benchmark files write for an unbounded variable.
#include <string>

namespace linkbox::input {

inline constexpr double kDefaultBound = 1e8;
inline constexpr const char* kDefaultBoundText = "1e8";  // as written in messages and models

// "x in [-1e8, 1e8]" for the variable `name` whose ends `lower`, `upper` (as written; empty
// when infinite) were completed by the default bound.
std::string assumed_bound(const std::string& name, const std::string& lower, const std::string& upper);

}  // namespace linkbox::input
