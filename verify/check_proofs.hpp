#pragma once
// The proofs `linkbox check` re-derives from a stored certificate and the case's equations.
#include "formulate/formulation.hpp"
#include "newton/certify.hpp"

#include <optional>
#include <vector>

namespace linkbox::verify {

// Box inclusion that fails on a size mismatch (contains() of box.hpp reads `inner` by
// `outer`'s size): every box here comes from the file.
bool encloses(const Box& outer, const Box& inner);

// The Newton image of a certificate's box under its preconditioner, computed as
// newton::recheck computes it (a curve crossing: the variable fixed_variable held at its
// degenerate side). Empty when the test does not hold: the image is not strictly inside the
// box, or the sizes do not fit the equations.
std::optional<Box> proved_image(const std::vector<model::Polynomial>& f, const newton::Certificate& c);
// The same in a natural system, links included (a system with links: a root certificate only,
// in the compiled square system; a curve crossing never holds there).
std::optional<Box> proved_image(const formulate::NaturalSystem& sys, const newton::Certificate& c);

// newton::certify_root in a natural system, links included (not square: not_square).
newton::Certificate certify_natural(const formulate::NaturalSystem& sys, const Box& hull,
                                    const newton::NewtonOptions& options = {});

// unique_in_hull re-proved as newton::certify_root proves it: no root in hull(start, box)
// other than the certificate's. Either the box covers the start, or the Newton test with the
// certificate's C holds on the union itself (when certify_root certified its start whole and
// then tightened), or ||I - C F'|| < 1 over the union (F injective there) with that C or, as
// certify_root tries next, the inverse of the union's midpoint Jacobian (float, only chosen:
// any C makes either test a proof).
bool unique_over(const formulate::NaturalSystem& sys, const Box& start, const newton::Certificate& c);
// The same for a square subsystem `f` of the natural equations.
bool unique_over(const std::vector<model::Polynomial>& f, const Box& start, const newton::Certificate& c);

}  // namespace linkbox::verify
