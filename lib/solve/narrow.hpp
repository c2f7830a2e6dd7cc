#pragma once
// A curve's solution boxes are as wide as sigma, and a certified map of the curve
// (verify/symmetric_map.hpp) needs pieces much narrower than the case's sigma: where a piece
// is wide, its interval tests neither exclude nor certify. So each uncertified solution box is
// searched again with sigma = `narrow` by `contractor` (subproblem.cpp picks it), and its
// solution boxes replace it. Only what the contractors prove empty is dropped (as in the
// search), so the boxes still cover every solution the original box held.
#include "formulate/formulation.hpp"
#include "prune/sequence.hpp"
#include "solve/bisector.hpp"
#include "solve/search.hpp"

namespace linkbox::solve {

// `r` is a complete search's result; its uncertified solutions wider than params.narrow are
// replaced by their narrowed pieces (a box whose search a limit cut short is kept as it was).
// Returns how many boxes due for narrowing a limit left as they were.
long narrow(Result& r, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, const Bisector& bisector);

}  // namespace linkbox::solve
