#!/usr/bin/env python3
"""rings-6-7 by many-start Newton, loop by loop: an independent, non-interval count of the
case's roots, to set beside linkbox's certified ones.

    python3 papers/porta-iterated-lp/rings_newton.py [--starts 20000] [--seed 1]
            [--linkbox OUT.json]

Model (nothing shared with linkbox's: no vector model, no half-angle tangents, only the
case's numbers, read from cases/linkages/rings-6-7.toml): 4x4 DH matrices,
prod_i Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i) = I around each ring, each ring in its own
frame (z the shared joint j0, x the normal of link A); ring2's frame is ring1's turned about
j0 by the turn. The system is block triangular, and each block is solved by itself:
  1. ring1's closure: 6 equations in its 6 angles (a 6R loop, at most 16 roots);
  2. "in-joints of A": the axes of p5 (ring1) and q6 (ring2) both sit on link A, so their
     angle depends on the turn alone, a*cos(turn) + b*sin(turn) = c: closed form;
  3. for each turn, ring2's closure and "out-joints of B" (p1's axis depends on ring1's j0
     angle): 7 equations in ring2's 7 angles.
Each block starts Levenberg-Marquardt from uniform random angles; a point counts when every
residual is below 1e-11. Roots are merged by their angles modulo 2 pi; the smallest singular
value of each block's Jacobian shows that each is regular.
"""
import argparse
import itertools
import json
import math
import pathlib
import tomllib

import numpy as np
from scipy.optimize import least_squares

CASE = pathlib.Path(__file__).resolve().parents[2] / "cases" / "linkages" / "rings-6-7.toml"


def dh(theta, d, a, alpha):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def frames(links, angles):
    """The frames after each joint's step, in the ring's own frame."""
    out, t = [], np.eye(4)
    for link, theta in zip(links, angles):
        t = t @ dh(theta, link["d"], link["a"], link["alpha"])
        out.append(t)
    return out


def closure(links, angles):
    return (frames(links, angles)[-1] - np.eye(4))[:3].ravel()


def rz(turn):
    c, s = math.cos(turn), math.sin(turn)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def axis(links, angles, k):
    """Joint k's axis (k >= 1: the z axis of the frame after k steps; k = 0: j0, the z axis)."""
    return np.array([0.0, 0.0, 1.0]) if k == 0 else frames(links, angles)[k - 1][:3, 2]


def last_axis(links):
    """The axis of the joint before link A, fixed in the ring's frame: the closed loop makes the
    frame before the last step dh(last)^-1, whose z axis is Rx(-alpha) z whatever theta."""
    alpha = links[-1]["alpha"]
    return np.array([0.0, math.sin(alpha), math.cos(alpha)])


def wrap(x):
    return (np.asarray(x) + math.pi) % (2 * math.pi) - math.pi


def solve_block(residual, n, starts, rng):
    """Distinct roots (modulo 2 pi) of a block from random starts, and each root's smallest
    singular value of the Jacobian."""
    roots = []
    for _ in range(starts):
        sol = least_squares(residual, rng.uniform(-math.pi, math.pi, n), method="lm", xtol=1e-15, ftol=1e-15,
                            gtol=1e-15, max_nfev=200 * n)
        if np.max(np.abs(residual(sol.x))) > 1e-11:
            continue
        x = wrap(sol.x)
        if all(np.max(np.abs(wrap(x - y))) > 1e-7 for y, _ in roots):
            s = np.linalg.svd(sol.jac, compute_uv=False)[-1]
            roots.append((x, s))
    return roots


def turns(ring1, ring2, cos_a):
    """The turns solving "in-joints of A": u . Rz(t) v = cos_a, u and v fixed on link A."""
    u, v = last_axis(ring1), last_axis(ring2)
    # u . Rz(t) v = u_z v_z + cos t (u_x v_x + u_y v_y) + sin t (u_y v_x - u_x v_y)
    a, b, c = u[0] * v[0] + u[1] * v[1], u[1] * v[0] - u[0] * v[1], cos_a - u[2] * v[2]
    r = math.hypot(a, b)
    if abs(c) > r:
        return []
    phi, delta = math.atan2(b, a), math.acos(c / r)
    return sorted({float(wrap(phi + delta)), float(wrap(phi - delta))})


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--starts", type=int, default=20000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--linkbox", help="linkbox's JSON output for rings-6-7, to match root by root")
    args = ap.parse_args()
    case = tomllib.loads(CASE.read_text())
    ring1, ring2 = (loop["links"] for loop in case["loops"])
    cons = {tuple(c["joints"]): math.cos(c["angle"]) for c in case["angle_constraints"]}
    rng = np.random.default_rng(args.seed)

    roots1 = solve_block(lambda x: closure(ring1, x), 6, args.starts, rng)
    print(f"ring1 (6 equations, 6 angles): {len(roots1)} roots from {args.starts} starts; smallest singular "
          f"values {', '.join(f'{s:.2e}' for _, s in roots1)}")
    roots = []
    for x1, _ in roots1:
        for t in turns(ring1, ring2, cons[("p5", "q6")]):
            p1 = axis(ring1, x1, 1)

            def block(x2, t=t, p1=p1):
                b = p1 @ (rz(t) @ axis(ring2, x2, 1)) - cons[("p1", "q1")]
                return np.concatenate([closure(ring2, x2), [b]])

            found = solve_block(block, 7, args.starts // 4, rng)
            print(f"  ring1 j0 {x1[0]:+.6f}, turn {t:+.6f}: {len(found)} ring2 roots (7 equations, 7 angles); "
                  f"smallest singular values {', '.join(f'{s:.2e}' for _, s in found) or '-'}")
            roots += [np.concatenate([x1, x2[1:], [x2[0], t]]) for x2, _ in found]
    print(f"total: {len(roots)} roots")
    if args.linkbox:
        match(roots, args.linkbox)


def match(roots, path):
    """Pairs each many-start root with a linkbox certified root (same variable order: j0, p1..p5,
    q1..q6, j0@ring2, turn)."""
    out = json.load(open(path))
    names = out["variables"]
    boxes = [np.array(r["midpoint"]) for r in out["roots"]]
    assert len(names) == 14 and all(len(b) == 14 for b in boxes), "not a rings-6-7 result"
    pairs = [(i, j, np.max(np.abs(wrap(x - y)))) for (i, x), (j, y) in itertools.product(enumerate(roots), enumerate(boxes))]
    close_pairs = [(i, j, e) for i, j, e in pairs if e < 1e-8]
    matched_roots = {i for i, _, _ in close_pairs}
    matched_boxes = {j for _, j, _ in close_pairs}
    worst = max((e for _, _, e in close_pairs), default=float("nan"))
    print(f"linkbox: {len(boxes)} certified roots; {len(matched_boxes)} matched to {len(matched_roots)} many-start "
          f"roots (largest angle difference {worst:.1e}); unmatched: {len(roots) - len(matched_roots)} many-start, "
          f"{len(boxes) - len(matched_boxes)} linkbox")


if __name__ == "__main__":
    main()
