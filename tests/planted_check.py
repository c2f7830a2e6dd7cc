#!/usr/bin/env python3
"""Planted-root systems through the CLI: no strategy loses a planted root, and the default
settings certify "exactly N" even where roots come in close pairs.

  planted_check.py LINKBOX [--count N] [--first-seed S]

Shapes: square systems of 2-4 unknowns (some with a close pair of roots 2^-10 apart) run
with the defaults (prune auto); systems with one or two redundant equations (more equations
than unknowns) run with Newton on square subsystems (newton, hc4,newton). A root is found
when a solution box contains it (the planted roots are exact rationals; the check allows
1e-9 for their conversion to double)."""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import planted  # noqa: E402

SHAPES = [  # unknowns, degrees, close pair, extra equations, strategies
    (2, [2, 3], None, 0, ["auto"]),
    (3, [2, 2, 2], 10, 0, ["auto"]),
    (3, [2, 2, 3], None, 0, ["auto"]),
    (4, [2, 2, 2, 2], None, 0, ["auto"]),
    (2, [2, 2], None, 1, ["newton", "hc4,newton", "auto"]),
    (3, [2, 2, 2], None, 2, ["newton", "hc4,newton"]),
]


def inside(root, box, tol=1e-9):
    return all(lo - tol <= float(v) <= hi + tol for v, (lo, hi) in zip(root, box))


inexact = []


def run(linkbox, seed, shape, workdir):
    n, degrees, gap, extra, strategies = shape
    eqs, roots = planted.generate(seed, n, degrees, gap, extra)
    path = os.path.join(workdir, f"planted-{seed}.toml")
    with open(path, "w") as f:
        f.write(planted.to_toml(seed, n, degrees, eqs, roots, gap, extra, 1))
    failures = []
    for prune in strategies:
        out = os.path.join(workdir, "out.json")
        args = [linkbox, "solve", path, "--quiet", "--json", out, "--prune", prune, "--time-limit", "60"]
        p = subprocess.run(args, capture_output=True, text=True)
        if p.returncode not in (0, 4, 5):  # a result was written (exact, unresolved, incomplete)
            failures.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()[:300]}")
            continue
        r = json.load(open(out))
        boxes = [s["box"] for s in r["solutions"]]
        lost = [root for root in roots if not any(inside(root, b) for b in boxes)]
        if lost:
            failures.append(f"{path} --prune {prune}: {len(lost)} of {len(roots)} planted roots lost (complete={r['complete']})")
        # Never a wrong count.
        if r["headline"].startswith("exactly") and not r["headline"].startswith(f"exactly {len(roots)} root"):
            failures.append(f"{path} --prune {prune}: WRONG COUNT '{r['headline']}', {len(roots)} planted")
        # Square systems at the default settings: every root certified and counted.
        if prune == "auto" and extra == 0 and r["complete"]:
            if not r["headline"].startswith(f"exactly {len(roots)} root"):
                inexact.append(f"{path}: headline '{r['headline']}', {len(roots)} planted")
    return len(roots), failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("linkbox")
    ap.add_argument("--count", type=int, default=12)
    ap.add_argument("--first-seed", type=int, default=100)
    a = ap.parse_args()
    failures, systems, planted_roots = [], 0, 0
    with tempfile.TemporaryDirectory() as work:
        for k in range(a.count):
            seed = a.first_seed + k
            shape = SHAPES[k % len(SHAPES)]
            roots, f = run(a.linkbox, seed, shape, work)
            systems += 1
            planted_roots += roots
            failures += f
    # Reported, not failed (issue 9 keeps it open): a sigma-sized box left beside a certified
    # box whose Newton iterate leaves it ("root outside the hull") keeps the count open.
    squares = sum(1 for k in range(a.count) if SHAPES[k % len(SHAPES)][3] == 0)
    for f in failures:
        print("FAIL", f)
    for x in inexact:
        print("not exact:", x)
    print(f"{systems} planted systems, {planted_roots} planted roots, {len(failures)} failure(s), "
          f"{len(inexact)} of {squares} square systems without an exact count")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
