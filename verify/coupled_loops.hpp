#pragma once
// Isolated poses of a linkage of several loops whose natural system has more equations than
// unknowns because a loop is mobile on its own (bicyclohexane: two six-joint rings, each
// with a closed curve of boat poses, tied by two angle constraints at the bridgeheads). At
// such a pose a square subsystem has a unique root, but nothing proves that the equation
// left out vanishes there. What does, in a box X of natural unknowns:
//  - a loop rigid in X: interval Newton on its own closure (as many equations as its
//    unknowns, which no other loop has) proves one root of it there;
//  - every other loop is a symmetric six-joint loop (verify/symmetric_loop.hpp): at v = 0 its
//    closure holds wherever R(u) = 0 (a half-turn T(u) whose axis is orthogonal to its
//    translation has T(u)^2 = I), two equations in its three u;
//  - the curve loops' u and the unknowns of no loop (turns), with the rigid loops' roots as
//    interval parameters, must satisfy R = 0 for each curve loop and every equation of no
//    loop (angle constraints), less one that another implies at two rigid loops' common
//    root (verify/twin_loops.hpp): when that system is square, a Krawczyk image strictly
//    inside Y proves one root of it in Y for every value of the parameters.
// The point made of those roots satisfies every natural equation, so the whole system has a
// root in the box they span. Uniqueness is the caller's: a square subsystem whose root is
// unique in the cluster bounds the whole system's roots there to that one.
#include "formulate/formulation.hpp"
#include "newton/certify.hpp"

#include <cstdint>
#include <string>

namespace linkbox::verify {

struct CoupledLoops {
  bool proved = false;
  Box box;          // natural unknowns: holds a root of every natural equation, inside `within`
  std::string how;  // what each loop contributed, or why no root was proved
  // The system left once rigid loops are fixed and the others are on their curves (0 when
  // the argument stopped before it): a curve of the coupled loops when one more unknown.
  int equations = 0, unknowns = 0;
};

// The argument above from the box `x` (natural unknowns of chart `chart`), each part's box
// grown as its Newton test needs but kept inside `within`.
CoupledLoops coupled_loops_root(const formulate::Formulation& f, std::uint64_t chart, const Box& x,
                                const Box& within);

// Where the argument may place its parts for a cluster of natural box `start` whose square
// subsystem `f` was certified by `c`: the cluster and the certified box grown by a thousand
// times its width (each part's Newton test needs some room around the root, which a cluster
// of one tiny box does not give), when the subsystem's root is proved unique there; else the
// grown certified box alone, when it is there.
struct CoupledRoom {
  Box box;
  bool unique = false;   // the subsystem's root is proved unique in `box`
  bool cluster = false;  // `box` holds the cluster
};
CoupledRoom coupled_room(const std::vector<model::Polynomial>& f, const Box& start, const newton::Certificate& c);

}  // namespace linkbox::verify
