#!/usr/bin/env python3
"""What the certified curve maps cost: each bundled curve case and symmetric loop solved with
no flags (N runs, medians), beside the same run with the map's narrowing off (`--narrow 0`,
the search alone, which reads "unresolved" on a symmetric loop), and the symmetric loops under
other strategies and sigmas (one run each): the same map must come out.

    python3 papers/benchmarks/curve_maps.py [--runs 3] [--linkbox build/linkbox]

Prints a Markdown table: CPU seconds of the whole process (user + system, search and
verification), the verification's wall seconds, solution boxes, arcs and the headline's map.
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

CURVES = ["cases/curves/%s.toml" % c for c in
          ("fourbar-grashof", "fourbar-nongrashof", "fourbar-half-domain", "circle-3d", "fourbar-parallelogram",
           "circle-on-plane", "viviani")] + ["cases/hard/gimbal-lock.toml"]
LOOPS = ["cases/linkages/6r-mobile.toml", "cases/linkages/cyclohexane.toml"]
VARIANTS = [["--prune", "hc4,newton"], ["--prune", "lp"], ["--sigma", "0.03"], ["--sigma", "0.01"]]


def run_once(linkbox, case, flags):
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as t:
        out = t.name
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run([linkbox, "solve", os.path.join(ROOT, case), "--quiet", "--json", out] + flags,
                       capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    if p.returncode not in (0, 4, 5):
        raise SystemExit("%s %s: exit %d\n%s" % (case, " ".join(flags), p.returncode, p.stderr[-400:]))
    with open(out) as f:
        r = json.load(f)
    os.unlink(out)
    return cpu, r


def row(linkbox, case, flags, runs):
    cpus, last = [], None
    for _ in range(runs):
        cpu, last = run_once(linkbox, case, flags)
        cpus.append(cpu)
    arcs = sum(len((c.get("map") or {}).get("arcs", [])) for c in last.get("clusters", []))
    headline = last.get("headline", "").split(" (")[0]
    return "| %s | %s | %d | %.2f | %.2f | %d | %s | %s |" % (
        os.path.basename(case)[:-5], " ".join(flags) or "none", runs, statistics.median(cpus),
        last["verification"]["seconds"], last["stats"]["solution_boxes"], arcs or "", headline)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--linkbox", default=os.path.join(ROOT, "build", "linkbox"))
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    print("| case | flags | runs | CPU s | verification s | solution boxes | arcs | headline |")
    print("|---|---|---|---|---|---|---|---|")
    for case in CURVES:
        print(row(a.linkbox, case, [], a.runs), flush=True)
    for case in LOOPS:
        print(row(a.linkbox, case, [], a.runs), flush=True)
        print(row(a.linkbox, case, ["--narrow", "0"], a.runs), flush=True)
        for v in VARIANTS:
            print(row(a.linkbox, case, v, 1), flush=True)


if __name__ == "__main__":
    main()
