#pragma once
// Real e-th roots of an interval: each end from a double guess, then moved ulp by ulp until
// its e-th power, enclosed outward, proves it a lower (upper) bound. The same enclosure as
// Boost's nth_root (an interval Newton iteration that switches to round-to-nearest for every
// midpoint) within a few ulps, for HC4's backward projection of powers.
#include "interval/interval.hpp"

namespace linkbox::root {

// {v : v^e in p} for odd e (one increasing branch), or its non-negative part for even e
// (p.lower() >= 0 required), e >= 1. p finite. Requires a live RoundingGuard.
FastInterval nth_root(const FastInterval& p, int e);

}  // namespace linkbox::root
