#!/usr/bin/env python3
"""Builds cases/linkages/rings-6-7.toml from a known configuration (run from anywhere:
python3 cases/linkages/make_rings.py > cases/linkages/rings-6-7.toml).

Two loops share the joint j0 and the links A (before it) and B (after it), like the
bridgehead bond of bicyclohexane: ring1 is a 6R loop, ring2 a 7R loop. Each ring is built
as in cases/hard/make_linkages.py: DH steps chosen for all links but the last, whose
parameters (and the angles of the joints next to it) are measured from the axes, so each
ring closes at the planted angles. Ring2 starts from ring1's frame at A turned by `turn`
about j0 (link A's two normals make that angle). Two angle constraints fix the angle between
the in-joints of A in the two rings and between the out-joints of B, to their planted
values. Natural system: 6 + 7 joint angles, j0 seen in ring2, and the turn = 14 unknowns;
6 + 6 closure equations and 2 constraints = 14 equations: square, with isolated roots.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "hard"))
from make_linkages import chain, close, closure_error, cross, dot, unit  # noqa: E402

# (theta, d, a, alpha) of entries 1..n-1; alpha in (0, pi) so that the measured normals
# are the chain's.
RING1 = [(0.7, 0.2, 0.9, 1.1), (-1.2, 0.4, 0.6, 0.8), (0.5, -0.3, 1.1, 1.4), (1.9, 0.1, 0.7, 0.9),
         (-0.6, 0.5, 0.8, 1.2)]
RING2 = [(-0.4, 0.3, 0.7, 1.3), (1.1, -0.2, 0.9, 0.6), (-0.8, 0.4, 0.5, 1.0), (0.3, 0.2, 1.2, 1.5),
         (1.4, -0.1, 0.6, 0.7), (-1.0, 0.3, 0.8, 1.1)]
START = 1.3  # ring2's chain starts from ring1's first normal turned by this about j0


def ring(steps, turn):
    lines = chain([math.cos(turn), math.sin(turn), 0.0], steps)
    return lines, close(steps, lines)


def closing_normal(lines):
    """The normal of the last link, from the last joint to the first (as measured)."""
    return unit(cross(lines[-1][1], lines[0][1]))


def angle(u, v):
    return math.acos(max(-1.0, min(1.0, dot(u, v))))


def main():
    lines1, ring1 = ring(RING1, 0.0)
    lines2, ring2 = ring(RING2, START)
    assert closure_error(ring1) < 1e-12 and closure_error(ring2) < 1e-12
    n1, n2, axis = closing_normal(lines1), closing_normal(lines2), lines1[0][1]
    turn = math.atan2(dot(cross(n1, n2), axis), dot(n1, n2))
    # Ring1's in-joint of A is its joint 6 (line 5), ring2's is joint 7 (line 6); the
    # out-joints of B are the joints 2 (line 1).
    bridge_a = angle(lines1[5][1], lines2[6][1])
    bridge_b = angle(lines1[1][1], lines2[1][1])
    names1 = [("j0", "B")] + [("p%d" % i, "r%d" % i) for i in range(1, 5)] + [("p5", "A")]
    names2 = [("j0", "B")] + [("q%d" % i, "s%d" % i) for i in range(1, 6)] + [("q6", "A")]
    out = []
    w = out.append
    w("# Two rings sharing the joint j0 and the links A and B (like the bridgehead bond of")
    w("# bicyclohexane): a 6R ring and a 7R ring tied by two angle constraints, so that the")
    w("# natural system is square: 14 unknowns (6 + 7 joint angles, j0@ring2, the turn")
    w("# turn[A@ring2] of ring2 about j0) and 14 equations (two DH closures, two constraints).")
    w("# Built by cases/linkages/make_rings.py from a planted configuration (both closures to")
    w("# %.0e in double precision):" % max(closure_error(ring1), closure_error(ring2)))
    w("#   ring1 theta = (%s)" % ", ".join("%r" % e["theta"] for e in ring1))
    w("#   ring2 theta = (%s)" % ", ".join("%r" % e["theta"] for e in ring2))
    w("#   turn[A@ring2] = %r" % turn)
    w("# EXPECTED: exactly 10 isolated roots, each certified, no curve; the planted configuration")
    w("# is one (tests/unit/formulate/test_linkage.cpp certifies it from a box around it). Ring1")
    w("# has 2 poses, the turn 1, and ring2 then 6 and 4; the independent many-start count is in")
    w("# papers/porta-iterated-lp/rings-6-7.md. A full search takes minutes, so no test runs it.")
    w('kind = "linkage"')
    w('name = "rings-6-7"')
    w('ground = "A"')
    for name, entries, names in (("ring1", ring1, names1), ("ring2", ring2, names2)):
        w("")
        w("[[loops]]")
        w('name = "%s"' % name)
        w("links = [")
        for (joint, link), e in zip(names, entries):
            w('  { joint = "%s", link = "%s", a = %r, d = %r, alpha = %r },' % (joint, link, e["a"], e["d"], e["alpha"]))
        w("]")
    for name, (j1, j2), value in (("in-joints of A", ("p5", "q6"), bridge_a), ("out-joints of B", ("p1", "q1"), bridge_b)):
        w("")
        w("[[angle_constraints]]")
        w('name = "%s"' % name)
        w('joints = ["%s", "%s"]' % (j1, j2))
        w("angle = %r" % value)
    print("\n".join(out))


if __name__ == "__main__":
    main()
