#!/usr/bin/env python3
"""Bicyclohexane (decalin) by many-start Newton in Cartesian coordinates: an independent,
non-interval cross-check of linkbox's candidates and of the paper's Fig. 8 ("two
one-dimensional components and fifteen isolated solutions").

    python3 papers/porta-iterated-lp/bicyclohexane_newton.py [--starts 4000] [--seed 1]
            [--linkbox OUT.json]

Model (nothing shared with linkbox's: no DH chains, torsions or quaternions, only the case's
numbers): ten carbons; c1 at the origin, c2 on the +x axis, c3 in the xy plane with y > 0
(23 unknowns). 24 equations: the ten other bond lengths (1.526) and the fourteen bond angles
as dot products, pi - 1.23 at every atom of each ring and 1.91 between the bridgeheads' third
bonds (c3-c2-c7 and c6-c1-c10). Each start builds the two rings as open chains with random
torsions and lets Levenberg-Marquardt close them; a point counts when every residual is below
1e-10. Its Jacobian (24 x 23) gives the local dimension: full column rank (smallest singular
value above 1e-6) is an isolated solution, rank 22 a point of a curve. Isolated solutions are
merged by their coordinates (the gauge is fixed), paired by the mirror z -> -z, and matched
one to one to linkbox's candidates by their twelve torsions; curve points are joined by tracing each curve (pseudo-arclength
predictor-corrector), and each traced curve's smallest second singular value shows where it
nearly meets another.
"""
import argparse
import json
import math
import sys

import numpy as np
from scipy.optimize import least_squares, linear_sum_assignment

L = 1.526
RING = math.pi - 1.23
BRIDGE = 1.91
# Atoms c1..c10 as 0..9.
BONDS = [(1, 2), (2, 3), (3, 4), (4, 5), (5, 0), (1, 6), (6, 7), (7, 8), (8, 9), (9, 0)]
ANGLES = [(0, 1, 2, RING), (1, 2, 3, RING), (2, 3, 4, RING), (3, 4, 5, RING), (4, 5, 0, RING), (5, 0, 1, RING),
          (0, 1, 6, RING), (1, 6, 7, RING), (6, 7, 8, RING), (7, 8, 9, RING), (8, 9, 0, RING), (9, 0, 1, RING),
          (2, 1, 6, BRIDGE), (5, 0, 9, BRIDGE)]
# Torsions in linkbox's output order: the bond (b, c) and the atoms (a, b, c, d) around it.
TORSIONS = [("c1-c2", (5, 0, 1, 2)), ("c2-c3", (0, 1, 2, 3)), ("c3-c4", (1, 2, 3, 4)), ("c4-c5", (2, 3, 4, 5)),
            ("c5-c6", (3, 4, 5, 0)), ("c6-c1", (4, 5, 0, 1)), ("c1-c2@ring2", (9, 0, 1, 6)),
            ("c2-c7", (0, 1, 6, 7)), ("c7-c8", (1, 6, 7, 8)), ("c8-c9", (6, 7, 8, 9)), ("c9-c10", (7, 8, 9, 0)),
            ("c10-c1", (8, 9, 0, 1))]


def atoms(x):
    p = np.zeros((10, 3))
    p[1] = (L, 0, 0)
    p[2] = (x[0], x[1], 0)
    p[3:] = x[2:].reshape(7, 3)
    return p


def unknowns(p):
    return np.concatenate([p[2, :2], p[3:].ravel()])


def residual(x):
    p = atoms(x)
    r = [np.dot(p[a] - p[b], p[a] - p[b]) - L * L for a, b in BONDS]
    r += [np.dot(p[a] - p[b], p[c] - p[b]) - L * L * math.cos(t) for a, b, c, t in ANGLES]
    return np.array(r)


def jacobian(x):
    p = atoms(x)
    j = np.zeros((24, 10, 3))
    for k, (a, b) in enumerate(BONDS):
        j[k, a] += 2 * (p[a] - p[b])
        j[k, b] -= 2 * (p[a] - p[b])
    for k, (a, b, c, _) in enumerate(ANGLES, start=len(BONDS)):
        j[k, a] += p[c] - p[b]
        j[k, c] += p[a] - p[b]
        j[k, b] -= p[a] + p[c] - 2 * p[b]
    return np.concatenate([j[:, 2, :2], j[:, 3:].reshape(24, 21)], axis=1)


def place(a, b, c, angle, torsion):
    """The atom d with |cd| = L, angle bcd, and dihedral abcd (the NeRF construction)."""
    bc = (c - b) / np.linalg.norm(c - b)
    n = np.cross(b - a, bc)
    n /= np.linalg.norm(n)
    m = np.cross(n, bc)
    d = np.array([-L * math.cos(angle), L * math.sin(angle) * math.cos(torsion), L * math.sin(angle) * math.sin(torsion)])
    return c + d[0] * bc + d[1] * m + d[2] * n


def gauge(p):
    """Moves p so that c1 is at the origin, c2 on +x, c3 in the xy plane with y > 0."""
    p = p - p[0]
    ex = p[1] / np.linalg.norm(p[1])
    ey = p[2] - np.dot(p[2], ex) * ex
    ey /= np.linalg.norm(ey)
    return p @ np.array([ex, ey, np.cross(ex, ey)]).T


def chain_start(rng):
    """Both rings as open chains from c1-c2 with random torsions (their closures left open)."""
    p = np.zeros((10, 3))
    p[1] = (L, 0, 0)
    p[2] = p[1] + L * np.array([-math.cos(RING), math.sin(RING), 0])
    t = rng.uniform(-math.pi, math.pi, size=8)
    p[3] = place(p[0], p[1], p[2], RING, t[0])
    p[4] = place(p[1], p[2], p[3], RING, t[1])
    p[5] = place(p[2], p[3], p[4], RING, t[2])
    p[6] = place(p[5], p[0], p[1], RING, t[3])  # c7 about c1-c2
    p[7] = place(p[0], p[1], p[6], RING, t[4])
    p[8] = place(p[1], p[6], p[7], RING, t[5])
    p[9] = place(p[6], p[7], p[8], RING, t[6])
    return gauge(p)


def polish(x):
    y = corrected(x)
    return x if y is None else y


def dihedral(p, a, b, c, d):
    b0, b1, b2 = p[a] - p[b], p[c] - p[b], p[d] - p[c]
    b1 /= np.linalg.norm(b1)
    v, w = b0 - np.dot(b0, b1) * b1, b2 - np.dot(b2, b1) * b1
    return math.atan2(np.dot(np.cross(b1, v), w), np.dot(v, w))


def solve(starts, seed):
    rng = np.random.default_rng(seed)
    isolated, curve = [], []
    for _ in range(starts):
        x0 = unknowns(chain_start(rng))
        sol = least_squares(residual, x0, jac=jacobian, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=400)
        x = polish(sol.x)
        if np.max(np.abs(residual(x))) > 1e-10 or x[1] <= 0:
            continue
        s = np.linalg.svd(jacobian(x), compute_uv=False)
        (isolated if s[-1] > 1e-6 else curve).append((x, s[-1], s[-2]))
    return isolated, curve


def distinct(points, tol=1e-6):
    out = []
    for x, s1, s2 in points:
        if all(np.max(np.abs(x - y)) > tol for y, _, _ in out):
            out.append((x, s1, s2))
    return out


def mirror(x):
    p = atoms(x)
    p[:, 2] *= -1
    return unknowns(p)


def corrected(x):
    """Gauss-Newton back onto the solution set; None when it does not settle."""
    for _ in range(12):
        r = residual(x)
        if np.max(np.abs(r)) < 1e-12:
            return x
        x = x - np.linalg.lstsq(jacobian(x), r, rcond=None)[0]
    return x if np.max(np.abs(residual(x))) < 1e-12 else None


def on_plane(x, t, h):
    """The solution on the hyperplane t . (y - x) = h (pseudo-arclength); None if none found."""
    y = x + h * t
    for _ in range(12):
        f = np.concatenate([residual(y), [np.dot(t, y - x) - h]])
        if np.max(np.abs(f)) < 1e-12:
            return y
        y = y - np.linalg.lstsq(np.vstack([jacobian(y), t]), f, rcond=None)[0]
    return None


def trace(x, step=0.02, limit=5000):
    """Follows the curve through x (predictor along the Jacobian's null vector, pseudo-arclength
    corrector, the step halved where the corrector fails) until it comes back to x; the
    polyline and whether it closed."""
    path, tangent, length = [x], np.linalg.svd(jacobian(x))[2][-1], 0.0
    while len(path) < limit:
        t = np.linalg.svd(jacobian(path[-1]))[2][-1]
        t = t if np.dot(t, tangent) > 0 else -t
        h = step
        while h > step / 64:
            y = on_plane(path[-1], t, h)
            if y is not None and np.linalg.norm(y - path[-1]) < 2 * h:
                break
            h /= 2
        else:
            return np.array(path), False
        tangent, length = t, length + np.linalg.norm(y - path[-1])
        path.append(y)
        if length > 20 * step and np.linalg.norm(y - x) < 1.5 * step:
            return np.array(path), True
    return np.array(path), False


def torsions(p):
    return np.array([dihedral(p, *four) for _, four in TORSIONS])


def linkbox_candidates(path):
    """(reason, torsions at the hull's midpoint) of each cluster not proved empty."""
    with open(path) as f:
        r = json.load(f)
    names = r["variables"]
    out = []
    for c in r.get("clusters", []):
        if c.get("status") == "empty":
            continue
        mid = {n: (lo + hi) / 2 for n, (lo, hi) in zip(names, c["hull"])}
        out.append((c.get("reason", ""), np.array([mid[n] for n, _ in TORSIONS])))
    return out


def solution_boxes(path):
    """linkbox's solution boxes over the twelve torsions."""
    with open(path) as f:
        r = json.load(f)
    names = r["variables"]
    return np.array([[dict(zip(names, s["box"]))[n] for n, _ in TORSIONS] for s in r["solutions"]])


def in_boxes(theta, boxes):
    """Whether theta (mod 2 pi) lies in one of the boxes (N x 12 x 2), within 1e-9."""
    d = np.angle(np.exp(1j * (theta[None, :] - boxes.mean(axis=2))))
    return bool(np.any(np.all(np.abs(d) <= (boxes[:, :, 1] - boxes[:, :, 0]) / 2 + 1e-9, axis=1)))


def match(candidates, solutions, tol=0.1):
    """One-to-one: per candidate, the solution whose twelve torsions are within tol (as angles),
    under the convention theta = s phi + c (s = +-1, c = 0 or pi, the same for every bond)
    that matches the most; -1 where none is. Solutions come in pairs with equal torsions (ring
    2 turned either way about c1-c2), so the pairing is an assignment, not a nearest search;
    the turn itself is not compared."""
    best = None
    for sign in (1, -1):
        for shift in (0.0, math.pi):
            cost = np.array([[np.max(np.abs(np.angle(np.exp(1j * (theta - sign * phi - shift))))) for phi in solutions]
                             for _, theta in candidates])
            rows, cols = linear_sum_assignment(cost)
            got = [-1] * len(candidates)
            for r, c in zip(rows, cols):
                if cost[r, c] < tol:
                    got[r] = int(c)
            if best is None or sum(k >= 0 for k in got) > sum(k >= 0 for k in best[0]):
                best = (got, sign, shift)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--starts", type=int, default=4000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--linkbox", help="a linkbox result of cases/linkages/bicyclohexane.toml to match")
    args = ap.parse_args()
    isolated, curve = solve(args.starts, args.seed)
    iso = distinct(isolated)
    print("starts %d: %d converged isolated (%d distinct), %d converged on curves"
          % (args.starts, len(isolated), len(iso), len(curve)))
    achiral = sum(1 for x, _, _ in iso if np.max(np.abs(mirror(x) - x)) < 1e-6)
    print("isolated: %d, of which %d are their own mirror image: %d classes up to the mirror"
          % (len(iso), achiral, achiral + (len(iso) - achiral) // 2))
    print("smallest singular value at the isolated ones: %.3g .. %.3g"
          % (min(s for _, s, _ in iso), max(s for _, s, _ in iso)) if iso else "")
    components = []
    for x, _, _ in curve:
        if any(np.min(np.linalg.norm(path - x, axis=1)) < 0.05 for path in components):
            continue
        path, closed = trace(x)
        components.append(path)
        print("curve component %d: %d steps of at most 0.02, %s; smallest second singular value %.3g"
              % (len(components), len(path), "closed" if closed else "NOT closed", np.min(
                  [np.linalg.svd(jacobian(y), compute_uv=False)[-2] for y in path[::50]])))
    print("curve components: %d (from %d curve points)" % (len(components), len(curve)))
    for a in range(len(components)):
        for b in range(a + 1, len(components)):
            gap = min(np.min(np.linalg.norm(components[b] - y, axis=1)) for y in components[a])
            if gap < 0.05:
                print("  components %d and %d come within %.4f of each other (a crossing, if they meet)" % (a + 1, b + 1, gap))
    if args.linkbox:
        cands = linkbox_candidates(args.linkbox)
        got, sign, shift = match(cands, [torsions(atoms(x)) for x, _, _ in iso])
        print("linkbox clusters (not proved empty): %d; convention theta = %+d phi + %g" % (len(cands), sign, shift))
        print("  within 0.1 rad in every torsion of an isolated solution: %d, on %d distinct solutions of %d"
              % (sum(k >= 0 for k in got), len({k for k in got if k >= 0}), len(iso)))
        for reason, _ in (c for c, k in zip(cands, got) if k < 0):
            print("  not an isolated solution: %s" % reason[:70])
        boxes = solution_boxes(args.linkbox)
        for n, path in enumerate(components, start=1):
            inside = sum(in_boxes(sign * torsions(atoms(y)) + shift, boxes) for y in path)
            print("  curve component %d: %d of its %d traced points lie in linkbox's solution boxes (torsions)"
                  % (n, inside, len(path)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
