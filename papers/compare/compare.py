#!/usr/bin/env python3
"""Strategy comparison: every applicable pruning strategy on every bundled case, over a
sigma sweep, verified and float.

    python3 papers/compare/compare.py [--build build] [--out papers/compare] [--quick]
        [--sets spherical,polynomial,linkages,hard] [--cases NAME,...] [--strategies ...]
        [--sigmas 1e-1,1e-2,...] [--reps 3] [--time-limit 20] [--exact-time-limit 10]
        [--jobs 1] [--no-plots]

For each (case, strategy, arithmetic) the sigmas are run from the largest down; a run that
hits --time-limit (or fails, or whose search plus certification took longer than the limit:
certification is not bounded by --time-limit) stops that strategy's sweep on that case
(smaller sigmas would only be slower): the rows below it are marked "skipped". Each run is repeated --reps times
(only while a run takes under --repeat-below seconds) and the median time is kept.

Writes into --out: compare.csv (one row per run configuration), compare.md (summary:
strategy x case at --summary-sigma, winners), and with matplotlib (Agg) the plots
time_vs_error.png, boxes_vs_sigma.png and solution_boxes_vs_sigma.png.

Metrics. time: the search's wall time (JSON stats.seconds), median over repetitions;
verify_s: the certification's; processed / solution_boxes (JSON stats); clusters; certified
roots; exact (the headline is "exactly N"); lp_calls: calls of the "lp" contractor;
lps_solved: the LPs they solved (JSON contractors[].lps_solved); err_root: the largest distance
(max norm, output variables, angles modulo 2 pi) from a point of a solution box to the
certified root box of its cluster, over certified clusters (the JSON's clusters[].max_distance
is the same bound; this script recomputes it as a cross-check); rigorous_residual: the largest
of the JSON's solutions[].residual (an outward-rounded bound on max |f| at the centre of the
search box, in the sub-problem's own variables); residual: the largest residual of the
case's equations at the solution boxes' centres, evaluated here in double precision from the
case file (polynomial: the equations; spherical: |vector part| / |q| of each loop's
quaternion product; linkage, one loop of revolute joints: max |T - I| of the DH product).
"""
import argparse
import concurrent.futures
import csv
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = None

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))

# (label, --prune, --lp)
STRATEGIES = [
    ("trapezoid", "trapezoid", "safe"),
    ("hc4", "hc4", "safe"),
    ("lp", "lp", "safe"),
    ("lp-exact", "lp", "exact"),
    ("newton", "newton", "safe"),
    ("hc4,lp", "hc4,lp", "safe"),
    ("trapezoid,newton", "trapezoid,newton", "safe"),
    ("trapezoid,lp", "trapezoid,lp", "safe"),
]
ARITHS = ["verified", "float"]
DEFAULT_SIGMAS = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
SETS = {
    "spherical": ["cases/spherical/*.toml"],
    "polynomial": ["cases/polynomial/*.toml"],
    "linkages": ["cases/linkages/6r-rigid.toml"],
    "hard": ["cases/hard/*.toml"],
}
QUICK_CASES = ["wrist", "circle-line"]

CSV_FIELDS = ["case", "kind", "strategy", "prune", "lp", "arith", "sigma", "status", "reps", "time_s", "time_min_s",
              "time_max_s", "verify_s", "processed", "solution_boxes", "clusters", "certified_roots", "unverified",
              "curves", "empty", "exact", "complete", "lp_calls", "lps_solved", "err_root", "max_distance",
              "rigorous_residual", "residual", "headline"]


# ---------------------------------------------------------------------------------------
# Case files: expressions and residuals (double precision; an indicator, not a proof).

MATH = {k: getattr(math, k) for k in ("sin", "cos", "tan", "asin", "acos", "atan", "sqrt", "exp", "log")}
MATH.update(pi=math.pi, __builtins__={})


def number(x):
    if isinstance(x, (int, float)):
        return float(x)
    return float(eval(str(x).replace("^", "**"), MATH))  # case files are trusted input


def load_toml(path):
    if tomllib is None:
        return None
    with open(path, "rb") as f:
        return tomllib.load(f)


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def axis_angle(axis, angle):
    n = math.sqrt(sum(c * c for c in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


def dh(theta, d, a, alpha):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0.0, sa, ca, d], [0.0, 0.0, 0.0, 1.0]]


def matmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


class Residual:
    """Residual of a case's equations at a point of its output variables, or None."""

    def __init__(self, path):
        self.f = None
        try:
            doc = load_toml(path)
            if doc is None:
                return
            kind = doc.get("kind")
            if kind == "polynomial":
                self.f = self._polynomial(doc)
            elif kind == "spherical":
                self.f = self._spherical(doc)
            elif kind == "linkage":
                self.f = self._linkage(doc)
        except Exception:  # an unusual case file: no residual column for it
            self.f = None

    def __call__(self, point):
        return None if self.f is None else self.f(point)

    @staticmethod
    def _polynomial(doc):
        names = [v["name"] for v in doc["variables"]]
        eqs = []
        for e in doc["equations"]:
            text = e if isinstance(e, str) else e["equation"]
            eqs.append(compile(text.replace("^", "**"), "<equation>", "eval"))

        def f(p):
            env = dict(MATH)
            env.update(zip(names, p))
            return max(abs(eval(c, env)) for c in eqs)
        return f

    @staticmethod
    def _spherical(doc):
        joints = {name: i for i, name in enumerate(doc["joints"])}
        loops = []
        for loop in doc["loops"]:
            factors = []
            for fa in loop["factors"]:
                sign = -1.0 if fa.get("inverse", False) else 1.0
                if "joint" in fa:
                    factors.append(("joint", [number(c) for c in fa["axis"]], joints[fa["joint"]], sign))
                elif "quaternion" in fa:
                    q = [number(c) for c in fa["quaternion"]]
                    if sign < 0:
                        q = [q[0], -q[1], -q[2], -q[3]]
                    factors.append(("const", tuple(q), None, 1.0))
                else:
                    factors.append(("const", axis_angle([number(c) for c in fa["axis"]], sign * number(fa["angle"])),
                                    None, 1.0))
            loops.append(factors)

        def f(p):
            worst = 0.0
            for factors in loops:
                q = (1.0, 0.0, 0.0, 0.0)
                for kind, v, j, sign in factors:
                    q = qmul(q, axis_angle(v, sign * p[j]) if kind == "joint" else v)
                n = math.sqrt(sum(c * c for c in q))
                worst = max(worst, math.sqrt(q[1] ** 2 + q[2] ** 2 + q[3] ** 2) / n)
            return worst
        return f

    @staticmethod
    def _linkage(doc):
        loops = doc["loops"]
        if len(loops) != 1 or doc.get("angle_constraints"):
            return None
        links = loops[0]["links"]
        if any(e.get("type", "revolute") != "revolute" for e in links):
            return None
        params = [(number(e["d"]), number(e["a"]), number(e["alpha"])) for e in links]

        def f(p):
            T = [[float(i == j) for j in range(4)] for i in range(4)]
            for theta, (d, a, alpha) in zip(p, params):
                T = matmul(T, dh(theta, d, a, alpha))
            return max(abs(T[i][j] - float(i == j)) for i in range(3) for j in range(4))
        return f


# ---------------------------------------------------------------------------------------
# Metrics from one result JSON.

def unwrap(lo, hi, ref):
    """Shift [lo, hi] by whole turns towards ref."""
    k = round((ref - (lo + hi) / 2) / (2 * math.pi))
    return lo + 2 * math.pi * k, hi + 2 * math.pi * k


def box_to_root(box, root, angles):
    """sup over x in box of the max-norm distance from x to the box root."""
    worst = 0.0
    for (lo, hi), (rlo, rhi) in zip(box, root):
        if angles:
            lo, hi = unwrap(lo, hi, (rlo + rhi) / 2)
        worst = max(worst, hi - rhi, rlo - lo, 0.0)
    return worst


def metrics(j, residual):
    m = {}
    st = j.get("stats", {})
    m["time_s"] = st.get("seconds")
    m["processed"] = st.get("processed")
    m["solution_boxes"] = st.get("solution_boxes")
    m["complete"] = j.get("complete")
    ver = j.get("verification", {})
    m["verify_s"] = ver.get("seconds")
    m["exact"] = ver.get("exact")
    m["certified_roots"] = j.get("certified_roots")
    m["unverified"] = ver.get("unverified")
    m["curves"] = ver.get("curves")
    m["empty"] = ver.get("empty")
    m["headline"] = j.get("headline", "")
    clusters = j.get("clusters", [])
    m["clusters"] = len(clusters)
    lp = [c for c in j.get("contractors", []) if c.get("name") == "lp"]
    m["lp_calls"] = sum(c.get("calls", 0) for c in lp) if lp else None
    m["lps_solved"] = sum(c.get("lps_solved", 0) for c in lp) if lp else None
    distances = [c["max_distance"] for c in clusters if c.get("status") == "certified" and "max_distance" in c]
    m["max_distance"] = max(distances) if distances else None
    residuals = [s["residual"] for s in j.get("solutions", []) if s.get("residual") is not None]
    m["rigorous_residual"] = max(residuals) if residuals else None
    angles = j.get("variables_unit") in ("radian", "radians", "rad") or j.get("kind") in ("spherical", "linkage")
    # Solutions by (sub-problem, index within it), as cluster members name them.
    by_member, count = {}, {}
    for s in j.get("solutions", []):
        k = s.get("subproblem", 0)
        by_member[(k, count.get(k, 0))] = s["box"]
        count[k] = count.get(k, 0) + 1
    err = None
    for c in clusters:
        if c.get("status") != "certified" or not c.get("root"):
            continue
        for mem in c.get("members", []):
            box = by_member.get(tuple(mem))
            if box is not None:
                d = box_to_root(box, c["root"], angles)
                err = d if err is None else max(err, d)
    m["err_root"] = err
    res = None
    for s in j.get("solutions", []):
        try:
            r = residual([(lo + hi) / 2 for lo, hi in s["box"]])
        except Exception:
            r = None
        if r is not None:
            res = r if res is None else max(res, r)
    m["residual"] = res
    return m


# ---------------------------------------------------------------------------------------
# Running.

def find_cases(sets, names):
    import glob
    out = []
    for s in sets:
        for pattern in SETS[s]:
            for path in sorted(glob.glob(os.path.join(ROOT, pattern))):
                stem = os.path.splitext(os.path.basename(path))[0]
                if names and stem not in names:
                    continue
                if path not in [p for p, _ in out]:
                    out.append((path, s))
    return out


def case_info(path):
    doc = load_toml(path) or {}
    kind = doc.get("kind", "?")
    if kind == "spherical":
        unknowns = len(doc.get("joints", []))
    elif kind == "polynomial":
        unknowns = len(doc.get("variables", []))
    else:
        unknowns = 99
    return kind, unknowns


def applicable(kind, unknowns, strategy):
    label, prune, lp = strategy
    if "trapezoid" in prune and kind != "spherical":
        return False  # trapezoid clipping needs multi-affine systems
    if lp == "exact" and (kind == "linkage" or unknowns > 6):
        return False  # exact LP only on small cases
    return True


def solve_once(cli, path, prune, lp, arith, sigma, time_limit, tmp):
    out = os.path.join(tmp, "r-%d-%d.json" % (os.getpid(), time.monotonic_ns()))
    cmd = [cli, "solve", path, "--bisect", "widest", "--prune", prune, "--lp", lp, "--arith", arith, "--sigma", repr(sigma), "--quiet",
           "--time-limit", repr(time_limit), "--json", out]
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                           timeout=2 * time_limit + 30)
    except subprocess.TimeoutExpired:
        return "killed", None, time.monotonic() - t0, "process killed"
    wall = time.monotonic() - t0
    if p.returncode == 2 and ("needs a" in p.stderr or "square" in p.stderr or "multi-affine" in p.stderr):
        return "n/a", None, wall, p.stderr.strip()
    if p.returncode not in (0, 4, 5) or not os.path.exists(out):
        return "error", None, wall, p.stderr.strip()[-300:]
    with open(out) as f:
        j = json.load(f)
    os.remove(out)
    return "ok", j, wall, ""


def sweep(cli, path, case, kind, strategy, arith, sigmas, a, tmp, residual):
    label, prune, lp = strategy
    rows = []
    stop = None
    limit = min(a.time_limit, a.exact_time_limit) if lp == "exact" else a.time_limit
    for sigma in sigmas:
        row = dict(case=case, kind=kind, strategy=label + ("" if arith == "verified" else " float"), prune=prune,
                   lp=lp, arith=arith, sigma=sigma)
        if stop:
            row.update(status=stop, reps=0)
            rows.append(row)
            continue
        times, first = [], None
        for rep in range(a.reps):
            status, j, wall, msg = solve_once(cli, path, prune, lp, arith, sigma, limit, tmp)
            if status != "ok":
                row.update(status=status, reps=rep, headline=msg)
                break
            m = metrics(j, residual)
            if first is None:
                first = m
            times.append(m["time_s"])
            if not m["complete"] or m["time_s"] > a.repeat_below:
                break
        if first is None:
            rows.append(row)
            if row["status"] == "n/a":
                stop = "n/a"
            else:
                stop = "skipped"
            continue
        row.update(first)
        row.update(time_s=statistics.median(times), time_min_s=min(times), time_max_s=max(times), reps=len(times))
        row["status"] = "ok" if first["complete"] else "timeout"
        if not first["complete"]:
            stop = "skipped"
        elif (first["time_s"] or 0) + (first["verify_s"] or 0) > limit:
            stop = "skipped"  # search + certification already over the limit: a smaller sigma is slower
        rows.append(row)
    return rows


def run_all(a):
    cli = os.path.join(a.build, "linkbox")
    if not os.path.exists(cli):
        sys.exit("compare.py: no linkbox executable in %s (build first, or pass --build)" % a.build)
    if tomllib is None:
        print("compare.py: Python without tomllib: residuals and case sizes unavailable", file=sys.stderr)
    cases = find_cases(a.sets, a.cases)
    if not cases:
        sys.exit("compare.py: no case selected")
    strategies = [s for s in STRATEGIES if s[0] in a.strategies]
    tasks = []
    for path, _ in cases:
        kind, unknowns = case_info(path)
        case = os.path.splitext(os.path.basename(path))[0]
        residual = Residual(path)
        for s in strategies:
            if not applicable(kind, unknowns, s):
                continue
            for arith in a.ariths:
                tasks.append((path, case, kind, s, arith, residual))
    rows = []
    with tempfile.TemporaryDirectory(prefix="linkbox-compare-") as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = [pool.submit(sweep, cli, path, case, kind, s, arith, a.sigmas, a, tmp, residual)
                       for path, case, kind, s, arith, residual in tasks]
            for k, fu in enumerate(concurrent.futures.as_completed(futures)):
                r = fu.result()
                rows.extend(r)
                if not a.quiet:
                    ok = [x for x in r if x.get("status") == "ok"]
                    print("[%d/%d] %s %s: %d/%d sigmas ok" % (k + 1, len(futures), r[0]["case"], r[0]["strategy"],
                                                           len(ok), len(r)), file=sys.stderr, flush=True)
    order = {s[0]: i for i, s in enumerate(STRATEGIES)}
    rows.sort(key=lambda r: (r["case"], r["arith"] != "verified", order.get(r["strategy"].replace(" float", ""), 99),
                             -r["sigma"]))
    return rows, [os.path.splitext(os.path.basename(p))[0] for p, _ in cases]


# ---------------------------------------------------------------------------------------
# Outputs.

def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in CSV_FIELDS})


def fmt_time(t):
    if t is None:
        return "-"
    return "%.3g" % t if t >= 1e-3 else "%.1e" % t


def cell(r):
    if r is None:
        return ""
    st = r.get("status")
    if st == "n/a":
        return "n/a"
    if st in ("skipped", "timeout", "killed", "error"):
        return {"skipped": "(stopped earlier)", "timeout": "timeout", "killed": "killed", "error": "error"}[st]
    mark = "✓" if r.get("exact") else ""
    return "%s s, %s%s" % (fmt_time(r.get("time_s")), r.get("certified_roots"), mark)


def nearest_sigma(rows, want):
    sig = sorted({r["sigma"] for r in rows})
    return min(sig, key=lambda s: abs(math.log10(s) - math.log10(want))) if sig else want


def winners(rows, cases, sigma):
    """Per case: fastest verified strategy among the complete runs with the most certified
    roots (exact ones first)."""
    out = {}
    for case in cases:
        cand = [r for r in rows if r["case"] == case and r["arith"] == "verified" and r["sigma"] == sigma
                and r.get("status") == "ok"]
        if not cand:
            out[case] = None
            continue
        best_exact = any(r.get("exact") for r in cand)
        best_roots = max(r.get("certified_roots") or 0 for r in cand)
        good = [r for r in cand if (not best_exact or r.get("exact")) and (r.get("certified_roots") or 0) == best_roots]
        out[case] = min(good, key=lambda r: r["time_s"])
    return out


def write_md(rows, cases, a, path, elapsed):
    sigma = nearest_sigma(rows, a.summary_sigma)
    labels = [s[0] for s in STRATEGIES if s[0] in a.strategies]
    L = []
    L.append("# Strategy comparison")
    L.append("")
    L.append("Generated by `python3 papers/compare/compare.py %s` on %s (%s, %d CPUs), %.0f s."
             % (" ".join(a.argv), datetime.date.today().isoformat(), platform.machine(), os.cpu_count() or 0, elapsed))
    L.append("Sigmas: %s; repetitions: %d (median time; a run over %g s is not repeated); time limit %g s per run "
             "(exact LP: %g s). Full data: `compare.csv`; plots: `time_vs_error.png`, `boxes_vs_sigma.png`, "
             "`solution_boxes_vs_sigma.png`." % (", ".join("%g" % s for s in a.sigmas), a.reps, a.repeat_below,
                                                 a.time_limit, min(a.time_limit, a.exact_time_limit)))
    L.append("")
    for arith in a.ariths:
        L.append("## %s arithmetic at sigma %g: search time, certified roots (✓ = exact headline)" % (arith, sigma))
        L.append("")
        L.append("| case | " + " | ".join(labels) + " |")
        L.append("|---|" + "---|" * len(labels))
        for case in cases:
            cells = []
            for lab in labels:
                name = lab + ("" if arith == "verified" else " float")
                r = next((x for x in rows if x["case"] == case and x["strategy"] == name and x["sigma"] == sigma), None)
                cells.append(cell(r))
            L.append("| %s | %s |" % (case, " | ".join(cells)))
        L.append("")
    L.append("Empty cell: strategy not applicable (trapezoid needs a multi-affine system, i.e. a spherical case; "
             "exact LP only on cases with at most 6 unknowns and not on linkages). n/a: the library refused it "
             "(e.g. newton on a non-square system). \"(stopped earlier)\": a larger sigma already hit the time limit.")
    L.append("")
    L.append("## Which strategy wins where (verified, sigma %g)" % sigma)
    L.append("")
    L.append("Fastest complete verified run among those with the most certified roots (and an exact headline when "
             "any strategy reached one).")
    L.append("")
    L.append("| case | winner | time [s] | certified | exact | runner-up | time [s] |")
    L.append("|---|---|---|---|---|---|---|")
    win = winners(rows, cases, sigma)
    tally = {}
    for case in cases:
        w = win.get(case)
        if w is None:
            L.append("| %s | (no complete verified run) | | | | | |" % case)
            continue
        tally[w["strategy"]] = tally.get(w["strategy"], 0) + 1
        others = sorted((r for r in rows if r["case"] == case and r["arith"] == "verified" and r["sigma"] == sigma
                         and r.get("status") == "ok" and r is not w
                         and r.get("certified_roots") == w.get("certified_roots")
                         and bool(r.get("exact")) == bool(w.get("exact"))), key=lambda r: r["time_s"])
        ru = others[0] if others else None
        L.append("| %s | %s | %s | %s | %s | %s | %s |" % (
            case, w["strategy"], fmt_time(w["time_s"]), w.get("certified_roots"), "yes" if w.get("exact") else "no",
            ru["strategy"] if ru else "-", fmt_time(ru["time_s"]) if ru else "-"))
    L.append("")
    if tally:
        L.append("Wins: " + ", ".join("%s %d" % (k, v) for k, v in sorted(tally.items(), key=lambda kv: -kv[1])) + ".")
        L.append("")
    if "float" in a.ariths:
        L.append("## Float variant against verified (sigma %g)" % sigma)
        L.append("")
        L.append("Float runs whose certified-root count differs from the same strategy's verified run (a lost root "
                 "when lower), or whose solution-box count differs.")
        L.append("")
        L.append("| case | strategy | verified roots / boxes | float roots / boxes |")
        L.append("|---|---|---|---|")
        n = 0
        for r in rows:
            if r["arith"] != "float" or r["sigma"] != sigma or r.get("status") != "ok":
                continue
            v = next((x for x in rows if x["case"] == r["case"] and x["arith"] == "verified" and x["sigma"] == sigma
                      and x["prune"] == r["prune"] and x["lp"] == r["lp"] and x.get("status") == "ok"), None)
            if v is None:
                continue
            if (v.get("certified_roots"), v.get("solution_boxes")) != (r.get("certified_roots"), r.get("solution_boxes")):
                n += 1
                L.append("| %s | %s | %s / %s | %s / %s |" % (r["case"], r["strategy"], v.get("certified_roots"),
                                                              v.get("solution_boxes"), r.get("certified_roots"),
                                                              r.get("solution_boxes")))
        if n == 0:
            L.append("| (none) | | | |")
        L.append("")
    L.append("## Notes on the metrics")
    L.append("")
    L.append("- `lp_calls` counts calls of the `lp` contractor (one shrink pass each), `lps_solved` the LPs they "
             "solved (JSON `contractors[].lps_solved`; up to two per primary variable and pass).")
    L.append("- `err_root` (largest distance from a point of a solution box to its cluster's certified root box) is "
             "only defined for certified clusters; `max_distance` is the library's own rigorous bound of the same "
             "(JSON `clusters[].max_distance`). `rigorous_residual` is the largest JSON `solutions[].residual` (an "
             "outward-rounded bound on max_i |f_i| at the centre of the search box, in the sub-problem's variables); "
             "`residual` is recomputed by this script in double precision at the centres of the output boxes, from "
             "the case file.")
    L.append("- Times are the search's wall time on a shared machine (other builds may run at the same time): "
             "compare orders of magnitude, not percents.")
    L.append("")
    with open(path, "w") as f:
        f.write("\n".join(L))


def plots(rows, cases, out):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception as e:  # noqa: BLE001
        print("compare.py: matplotlib unavailable (%s): no plots" % e, file=sys.stderr)
        return []
    labels = [s[0] for s in STRATEGIES]
    colors = {lab: plt.get_cmap("tab10")(i) for i, lab in enumerate(labels)}
    n = len(cases)
    cols = min(4, n)
    nrows = (n + cols - 1) // cols
    written = []

    def series(case, key_x, key_y):
        out = []
        for lab in labels:
            for arith in ("verified", "float"):
                name = lab + ("" if arith == "verified" else " float")
                pts = [(r[key_x], r[key_y]) for r in rows if r["case"] == case and r["strategy"] == name
                       and r.get("status") == "ok" and r.get(key_x) not in (None, "") and r.get(key_y) not in (None, "")
                       and r[key_x] > 0 and r[key_y] > 0]
                if pts:
                    out.append((lab, arith, pts))
        return out

    for fname, title, kx, ky, xl, yl in [
            ("time_vs_error.png", "search time against error", "err", "time_s", "error", "time [s]"),
            ("boxes_vs_sigma.png", "processed boxes against sigma", "sigma", "processed", "sigma", "processed boxes"),
            ("solution_boxes_vs_sigma.png", "solution boxes against sigma", "sigma", "solution_boxes", "sigma",
             "solution boxes")]:
        fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.4 * nrows), squeeze=False)
        handles = {}
        for i, case in enumerate(cases):
            ax = axes[i // cols][i % cols]
            xlabel = xl
            if kx == "err":
                for r in rows:
                    r["err"] = r.get("err_root")
                data = series(case, "err", ky)
                if not data:  # no certified root: fall back on the residual at box centres
                    for r in rows:
                        r["err"] = r.get("residual")
                    data = series(case, "err", ky)
                    xlabel = "residual at box centres"
                else:
                    xlabel = "distance box - certified root"
            else:
                data = series(case, kx, ky)
            for lab, arith, pts in data:
                pts.sort()
                h, = ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o" if arith == "verified" else "x",
                             markersize=3, linestyle="-" if arith == "verified" else "--", color=colors[lab],
                             linewidth=1.2 if arith == "verified" else 0.9)
                handles[(lab, arith)] = h
            ax.set_xscale("log")
            ax.set_yscale("log")
            if kx == "sigma":
                ax.invert_xaxis()
            ax.set_title(case, fontsize=9)
            ax.set_xlabel(xlabel, fontsize=8)
            ax.set_ylabel(yl, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="major", linewidth=0.3)
            if not data:
                ax.text(0.5, 0.5, "no data", ha="center", va="center", transform=ax.transAxes, fontsize=8)
        for k in range(n, nrows * cols):
            axes[k // cols][k % cols].axis("off")
        keys = sorted(handles, key=lambda k: (labels.index(k[0]), k[1] != "verified"))
        ncol = max(2, min(8, 2 * cols, len(keys)))
        legend_rows = (len(keys) + ncol - 1) // ncol
        height = fig.get_size_inches()[1]
        fig.legend([handles[k] for k in keys], [k[0] + ("" if k[1] == "verified" else " (float)") for k in keys],
                   loc="lower center", ncol=ncol, fontsize=7, frameon=False)
        fig.suptitle(title + " (solid: verified, dashed: float)", fontsize=11)
        fig.tight_layout(rect=(0, min(0.5, (0.2 * legend_rows + 0.15) / height), 1, 1 - 0.35 / height))
        fig.savefig(os.path.join(out, fname), dpi=90)
        plt.close(fig)
        written.append(fname)
    return written


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"), help="folder holding the linkbox executable")
    p.add_argument("--out", default=HERE, help="where to write compare.csv, compare.md and the PNGs")
    p.add_argument("--quick", action="store_true",
                   help="tiny sweep (2 sigmas, 1 repetition, cases %s)" % " and ".join(QUICK_CASES))
    p.add_argument("--sets", default="spherical,polynomial,linkages,hard",
                   help="case sets: spherical, polynomial, linkages (the rigid 6R), hard; 'small' = all but linkages")
    p.add_argument("--cases", default="", help="only these case names (file stems), comma-separated")
    p.add_argument("--strategies", default=";".join(s[0] for s in STRATEGIES),
                   help="';'-separated strategy labels (default all: %s)" % "; ".join(s[0] for s in STRATEGIES))
    p.add_argument("--arith", default="verified,float", help="verified,float (default both)")
    p.add_argument("--sigmas", default=",".join("%g" % s for s in DEFAULT_SIGMAS))
    p.add_argument("--summary-sigma", type=float, default=1e-6, help="sigma of the summary tables")
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--repeat-below", type=float, default=5.0, help="repeat only runs faster than this [s]")
    p.add_argument("--time-limit", type=float, default=20.0, help="per run [s]")
    p.add_argument("--exact-time-limit", type=float, default=10.0, help="per run with --lp exact [s]")
    p.add_argument("--jobs", type=int, default=1, help="runs in parallel (timings get noisier)")
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--quiet", action="store_true")
    a = p.parse_args(argv)
    a.argv = argv
    sets = a.sets.split(",")
    if "small" in sets:
        sets = [s for s in sets if s != "small"] + ["spherical", "polynomial", "hard"]
    for s in sets:
        if s not in SETS:
            p.error("unknown case set %r" % s)
    a.sets = list(dict.fromkeys(sets))
    a.cases = [c for c in a.cases.split(",") if c]
    a.strategies = [s for s in a.strategies.split(";") if s]
    known = [s[0] for s in STRATEGIES]
    for s in a.strategies:
        if s not in known:
            p.error("unknown strategy %r (known: %s)" % (s, "; ".join(known)))
    a.ariths = [x for x in a.arith.split(",") if x]
    a.sigmas = sorted({float(s) for s in a.sigmas.split(",") if s}, reverse=True)
    if a.quick:
        a.sigmas = [1e-2, 1e-6]
        a.reps = 1
        a.cases = a.cases or QUICK_CASES
        a.sets = ["spherical", "polynomial"]
        a.time_limit = min(a.time_limit, 5.0)
        a.exact_time_limit = min(a.exact_time_limit, 5.0)
        a.summary_sigma = 1e-6
    a.build = os.path.abspath(a.build)
    a.out = os.path.abspath(a.out)
    return a


def main(argv):
    a = parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    t0 = time.monotonic()
    rows, cases = run_all(a)
    write_csv(rows, os.path.join(a.out, "compare.csv"))
    write_md(rows, cases, a, os.path.join(a.out, "compare.md"), time.monotonic() - t0)
    written = [] if a.no_plots else plots(rows, cases, a.out)
    print("compare.py: %d rows, %d cases, %.1f s -> %s (compare.csv, compare.md%s)" % (
        len(rows), len(cases), time.monotonic() - t0, a.out, "".join(", " + w for w in written)), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
