#pragma once
// exp and log of an interval in double arithmetic: the ends are reduced by a power of two
// (exactly) and a two-part enclosure of ln 2, and evaluated by Taylor series whose remainder
// is bounded, all outward rounded. An enclosure of the range like rigorous::exp/log (MPFI),
// a few ulps wider, without libm and without multi-precision, for hot loops.
#include "interval/interval.hpp"

namespace linkbox::fast_exp {

// Each requires a live RoundingGuard (FastInterval arithmetic) and returns false, leaving
// `out` untouched, where it does not answer (for exp: an upper end above 700, in [-746, -700)
// or not finite; for log: an end not positive or not finite): the caller goes to rigorous::
// then. exp's lower end below -700 (-inf too) gives the lower bound 0.
bool exp(const FastInterval& x, FastInterval& out);
bool log(const FastInterval& x, FastInterval& out);

}  // namespace linkbox::fast_exp
