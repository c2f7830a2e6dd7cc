#pragma once
// A solution box that the certifier did not settle (too wide for Newton near a close pair of
// roots, or beside a certified box) is searched again with a smaller sigma, round by round, down
// to a floor: the certified answer should not depend on the user's sigma. What the refinement
// proves empty is dropped, what it certifies replaces the box, what is left stays.
#include "formulate/formulation.hpp"
#include "prune/sequence.hpp"
#include "solve/bisector.hpp"
#include "solve/search.hpp"
#include "solve/certifier.hpp"

namespace linkbox::solve {

// `r` is a complete search's result, which took `search_work`; its solutions, certificates and
// counts are updated in place. Returns how many boxes due for a refinement a limit of `budget`
// left as they were.
long refine(Result& r, double search_work, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, Certifier& certifier, const Bisector& bisector);

}  // namespace linkbox::solve
