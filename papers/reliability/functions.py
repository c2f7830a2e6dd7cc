#!/usr/bin/env python3
"""Planted roots of elementary-function systems, linkbox beside IbexSolve.

Each seed gives a Minibex system in 1-4 unknowns on [-1, 1]^n: a diagonally dominant
integer linear part plus one or two terms c f(arg) or c f(arg) g(arg') per equation (f, g
among exp, ln, sqrt, sin, cos, tan, atan, sinh, cosh, tanh, asin, acos, sqr, with arguments
kept inside their domains), shifted so that a random point r is a root up to the rounding of
the constant (its digits are printed to 17 places, so the root of the file is within about
1e-15 of r). The system is a pure function of the seed.

A run is checked on three counts: r lies in a solution box (1e-6 slack for the rounded
constant); IbexSolve (an independent solver) finds the same number of solution boxes where
both finish; linkbox's "exactly N" is at least 1.

  python3 functions.py run --linkbox build/linkbox --ibexsolve ../shared/peers/ibex/ibexsolve \
      --seeds 0:400 --out functions.csv
  python3 functions.py render functions.csv > functions.md
  python3 functions.py case SEED      # the system as a .bch file
"""
import argparse
import csv
import json
import math
import os
import random
import re
import resource
import subprocess
import sys
import tempfile

# name in Minibex, float function, argument maker (returns text and value from x).
FUNCTIONS = {
    "exp": math.exp, "ln": math.log, "sqrt": math.sqrt, "sin": math.sin, "cos": math.cos,
    "tan": math.tan, "atan": math.atan, "sinh": math.sinh, "cosh": math.cosh, "tanh": math.tanh,
    "asin": math.asin, "acos": math.acos, "sqr": lambda v: v * v,
}


def argument(name, rnd, r):
    """An argument inside the function's domain over the whole box: text and value at r."""
    n = len(r)
    j, k = rnd.randrange(n), rnd.randrange(n)
    if name in ("ln", "sqrt"):
        return "(x%d^2 + 1)" % j, r[j] ** 2 + 1
    if name in ("asin", "acos"):
        return "(0.5*x%d)" % j, 0.5 * r[j]
    if name == "tan":  # |arg| <= 1 < pi/2: no pole in the box
        return "(0.5*x%d)" % j, 0.5 * r[j]
    if j != k:
        return "(x%d - x%d)" % (j, k), r[j] - r[k]
    return "(x%d)" % j, r[j]


def system(seed):
    """(Minibex text, planted root)."""
    rnd = random.Random(seed)
    n = rnd.randint(1, 4)
    r = [rnd.randint(-60, 60) / 64 for _ in range(n)]
    lines = []
    for i in range(n):
        terms, value = [], 0.0
        for j in range(n):
            a = rnd.choice([-3, -2, -1, 1, 2, 3]) + (5 if i == j else 0)
            terms.append("%d*x%d" % (a, j))
            value += a * r[j]
        for _ in range(rnd.randint(1, 2)):
            c = rnd.choice([-1, 1]) * rnd.choice([0.5, 1, 2, 4])
            f = rnd.choice(sorted(FUNCTIONS))
            text, v = argument(f, rnd, r)
            term, tv = "%s%s" % (f, text), FUNCTIONS[f](v)
            if rnd.random() < 0.3:
                g = rnd.choice(sorted(FUNCTIONS))
                text, v = argument(g, rnd, r)
                term, tv = "%s*%s" % (term, "%s%s" % (g, text)), tv * FUNCTIONS[g](v)
            terms.append("%g*%s" % (c, term))
            value += c * tv
        lines.append(" + ".join(terms) + " = %.17g;" % value)
    text = "Variables\n" + "".join("x%d in [-1, 1];\n" % j for j in range(n))
    text += "Constraints\n" + "\n".join(lines) + "\nend\n"
    return text, r


def cpu_of(cmd, timeout):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        out, code = p.stdout + p.stderr, p.returncode
    except subprocess.TimeoutExpired:
        out, code = "", -1
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return out, code, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def run_linkbox(linkbox, path, r):
    out_json = path + ".json"
    _, code, cpu = cpu_of([linkbox, "solve", path, "--threads", "1", "--cpu-limit", "20", "--json", out_json], 60)
    d = json.load(open(out_json))
    exact = re.match(r"exactly (\d+) root", d["headline"])
    boxes = [c["box"] for c in d["roots"]] + [s["box"] for s in d.get("solutions", []) if "box" in s]
    found = any(all(lo - 1e-6 <= r[j] <= hi + 1e-6 for j, (lo, hi) in enumerate(b)) for b in boxes)
    return {"linkbox_exit": code, "linkbox_exact": exact.group(1) if exact else "",
            "linkbox_complete": d["complete"], "planted_found": found, "linkbox_cpu": round(cpu, 3),
            "headline": d["headline"][:120]}


def run_ibex(ibexsolve, path):
    out, _, cpu = cpu_of([ibexsolve, path, "--timeout=20", "--eps-min=1e-8", "--output=" + path + ".cov"], 60)
    done = "solving successful" in out
    count = re.search(r"number of solution boxes:\s*(\d+)", out)
    return {"ibex_complete": done, "ibex_boxes": count.group(1) if count else "", "ibex_cpu": round(cpu, 3)}


def run(args):
    first, last = (int(x) for x in args.seeds.split(":"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(first, last):
            text, r = system(seed)
            path = os.path.join(tmp, "f%d.bch" % seed)
            open(path, "w").write(text)
            row = {"seed": seed, "unknowns": len(r)}
            row.update(run_linkbox(args.linkbox, path, r))
            row.update(run_ibex(args.ibexsolve, path))
            rows.append(row)
            print(seed, row["headline"], "| ibex", row["ibex_boxes"], file=sys.stderr, flush=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def median(xs):
    xs = sorted(xs)
    return xs[len(xs) // 2] if xs else float("nan")


def render(args):
    rows = list(csv.DictReader(open(args.csv)))
    yes = lambda v: v == "True"
    lost = [r for r in rows if not yes(r["planted_found"])]
    exact = [r for r in rows if r["linkbox_exact"]]
    both = [r for r in rows if r["linkbox_exact"] and yes(r["ibex_complete"])]
    differ = [r for r in both if r["linkbox_exact"] != r["ibex_boxes"]]
    print("# Planted roots of elementary-function systems, beside IbexSolve\n")
    print("`python3 papers/reliability/functions.py run` (see its docstring); %d systems, seeds %s..%s.\n"
          % (len(rows), rows[0]["seed"], rows[-1]["seed"]))
    print("| | systems |\n|---|--:|")
    print("| planted root lost by linkbox | %d |" % len(lost))
    print("| linkbox: exactly N, certified | %d |" % len(exact))
    print("| linkbox complete | %d |" % sum(yes(r["linkbox_complete"]) for r in rows))
    print("| IbexSolve complete | %d |" % sum(yes(r["ibex_complete"]) for r in rows))
    print("| both: linkbox's exact N and IbexSolve's solution boxes | %d |" % len(both))
    print("| of which the counts differ | %d |" % len(differ))
    print("\nCPU s, median over the systems: linkbox %.3f, IbexSolve %.3f.\n"
          % (median([float(r["linkbox_cpu"]) for r in rows]), median([float(r["ibex_cpu"]) for r in rows])))
    rest = [r for r in rows if not r["linkbox_exact"]]
    if rest:
        print("Runs without an exact count:\n")
        print("| seed | linkbox | IbexSolve boxes |\n|---|---|--:|")
        for r in rest:
            print("| %s | %s | %s |" % (r["seed"], r["headline"], r["ibex_boxes"]))
    for r in lost + differ:
        print("\nseed %s: %s; IbexSolve %s" % (r["seed"], r["headline"], r["ibex_boxes"]))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("--linkbox", default="build/linkbox")
    r.add_argument("--ibexsolve", default="../shared/peers/ibex/ibexsolve")
    r.add_argument("--seeds", default="0:400")
    r.add_argument("--out", default="papers/reliability/functions.csv")
    g = sub.add_parser("render")
    g.add_argument("csv")
    c = sub.add_parser("case")
    c.add_argument("seed", type=int)
    a = p.parse_args()
    if a.command == "run":
        run(a)
    elif a.command == "render":
        render(a)
    else:
        print(system(a.seed)[0], end="")


if __name__ == "__main__":
    main()
