#!/usr/bin/env python3
"""Benchmark (not a test): the iterated-LP pruning of Porta, Ros, Thomas (RSS 2006) with the
two LP backends, `--lp safe` (CLP + Neumaier-Shcherbina bound, the default) and `--lp exact`
(CLP's basis checked and repaired in rational arithmetic, CGAL's exact QP solver as the
fall-back; every answer the exact optimum rounded outward or an exact Farkas proof), on the rigid 6R, cyclohexane and mobile 6R, beside CuikSuite's
reference times (same authors' successor of the paper's code, measured on this kind of
machine; lib/README.md).

Usage: python3 papers/porta-iterated-lp/benchmark_lp.py [--build build-papers] [--runs 3]
           [--time-limit 600] [--cases 6r-rigid,cyclohexane,6r-mobile[,bicyclohexane]]

Each case runs `linkbox solve --prune lp --lp {safe,exact}` with the Section V parameters
(rigid 6R sigma = 1e-4; the others sigma = 0.1; rho = 0.95), depth-first, one thread, without
verification (--no-verify: only the search is timed). The two backends alternate run by run in
the same invocation, so both see the same machine load. Times are medians over --runs runs of
the wall clock and of the CPU time of the linkbox process. A run that reaches --time-limit is
reported as a timeout (with what it had processed) and that backend is not repeated on that case.

Writes benchmark_lp.md and benchmark_lp.csv beside this script and prints the markdown.
"""
import argparse
import csv
import datetime
import json
import os
import statistics
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
from section5 import CASES, cpu_model, solve_once  # noqa: E402

# CuikSuite, one process, CPU seconds (lib/README.md, "Peers").
CUIK = {"6r-rigid": 0.9, "cyclohexane": 5.5, "6r-mobile": 45.0, "bicyclohexane": 887.0}
DEFAULT_CASES = ["6r-rigid", "cyclohexane", "6r-mobile"]
BACKENDS = ["safe", "exact"]


class Opts:
    def __init__(self, lp, time_limit):
        self.prune, self.lp, self.time_limit = "lp", lp, time_limit


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build-papers"))
    ap.add_argument("--runs", type=int, default=3, help="runs per case and backend; medians (default 3)")
    ap.add_argument("--time-limit", type=float, default=600, help="seconds per run, 0 = none (default 600)")
    ap.add_argument("--cases", nargs="+", default=None, help="subset (comma- or space-separated); default %s" % ",".join(DEFAULT_CASES))
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite benchmark_lp.md/.csv from the last run's raw results (runs/benchmark_lp.raw.json)")
    args = ap.parse_args()
    raw_path = os.path.join(args.out, "runs", "benchmark_lp.raw.json")
    if args.report_only:
        with open(raw_path) as f:
            raw = json.load(f)
        return report(raw, args.out)
    binary = os.path.join(os.path.abspath(args.build), "linkbox")
    if not os.access(binary, os.X_OK):
        sys.exit("no linkbox binary at %s" % binary)
    keys = DEFAULT_CASES if not args.cases else [k for c in args.cases for k in c.split(",") if k]
    for k in keys:
        if k not in CASES:
            sys.exit("unknown case %r" % k)
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    load = os.getloadavg()[0]
    tmp = tempfile.mkdtemp(prefix="linkbox-benchmark-lp-")
    results = {}
    for key in keys:
        case = dict(CASES[key])
        per = {b: {"wall": [], "cpu": [], "last": None, "timeout": False, "error": None} for b in BACKENDS}
        for i in range(args.runs):
            for b in BACKENDS:
                r = per[b]
                if r["timeout"] or r["error"]:
                    continue
                out = os.path.join(tmp, "%s-%s.json" % (key, b))
                opts = Opts(b, args.time_limit)
                res, wall, cpu, err = solve_once(binary, case, opts, out, extra=["--no-verify"])
                if err and err.startswith("killed"):
                    r["timeout"], r["last"] = True, None
                    r["timeout_wall"], r["timeout_cpu"] = wall, None
                    print("  %s --lp %s run %d: %s" % (key, b, i + 1, err), file=sys.stderr, flush=True)
                    continue
                if err:
                    r["error"] = err
                    continue
                # Keep only what the report needs (not the solution boxes).
                res = {k: res.get(k) for k in ("stats", "contractors", "complete", "stop_reason", "parameters")}
                r["last"] = res
                if not res.get("complete", True):
                    r["timeout"] = True
                    r["timeout_wall"], r["timeout_cpu"] = res["stats"]["seconds"], cpu
                    print("  %s --lp %s run %d: incomplete (%s) after %.0f s, %d processed" % (
                        key, b, i + 1, res.get("stop_reason"), res["stats"]["seconds"], res["stats"]["processed"]), file=sys.stderr, flush=True)
                    continue
                r["wall"].append(res["stats"]["seconds"])
                r["cpu"].append(cpu)
                print("  %s --lp %s run %d: %.2f s wall, %.2f s CPU" % (key, b, i + 1, r["wall"][-1], cpu), file=sys.stderr, flush=True)
        results[key] = per
    raw = {"started": started, "load": load, "runs": args.runs, "time_limit": args.time_limit, "cases": keys,
           "cpu": cpu_model(), "cores": os.cpu_count() or 0, "results": results}
    os.makedirs(os.path.dirname(raw_path), exist_ok=True)
    with open(raw_path, "w") as f:
        json.dump(raw, f, indent=1)
    return report(raw, args.out)


def report(raw, out_dir):
    keys, results = raw["cases"], raw["results"]

    def cells(r):
        """(status, wall, cpu, processed, empty, solution, runs)"""
        if r["error"] and r["last"] is None:
            return ("error", None, None, None, None, None, 0)
        if r["timeout"] and r["last"] is None:  # killed by the watchdog: no JSON
            return ("killed", r["timeout_wall"], None, None, None, None, 1)
        st = r["last"]["stats"]
        if r["timeout"]:
            return ("timeout", r["timeout_wall"], r["timeout_cpu"], st["processed"], st["empty"], st["solution_boxes"], 1)
        return ("ok", statistics.median(r["wall"]), statistics.median(r["cpu"]), st["processed"], st["empty"],
                st["solution_boxes"], len(r["wall"]))

    with open(os.path.join(out_dir, "benchmark_lp.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "sigma", "rho", "lp", "status", "runs", "seconds", "cpu_seconds", "processed", "empty",
                    "solution_boxes", "cuiksuite_cpu_seconds", "time_limit"])
        for key in keys:
            for b in BACKENDS:
                s, wall, cpu, pr, em, so, n = cells(results[key][b])
                w.writerow([key, CASES[key]["sigma"], CASES[key]["rho"], b, s, n,
                            "" if wall is None else "%.3f" % wall, "" if cpu is None else "%.3f" % cpu,
                            "" if pr is None else pr, "" if em is None else em, "" if so is None else so,
                            CUIK.get(key, ""), raw["time_limit"]])

    def t(s, v):
        if s == "error":
            return "error"
        if s == "killed":
            return "> %.0f (killed)" % v if v is not None else "killed"
        if s == "timeout":
            return "> %.0f (timeout)" % v if v is not None else "timeout"
        return "%.2f" % v

    def counts(s, pr, em, so):
        if pr is None:
            return "– (killed)"
        return "%d / %d / %d%s" % (pr, em, so, " (so far)" if s == "timeout" else "")

    lines = ["# LP backends: `--lp safe` vs `--lp exact` (benchmark)", "",
             "linkbox `solve --prune lp --no-verify`, rho = 0.95, depth-first, one thread; medians of up to %d runs per "
             "backend, the backends alternating; time limit %s per run. Machine: %s, %d cores, load average %.1f at the "
             "start (%s; the machine is shared, so CPU time is the steadier figure)." % (
                 raw["runs"], ("%g s" % raw["time_limit"]) if raw["time_limit"] > 0 else "none", raw["cpu"],
                 raw["cores"], raw["load"], raw["started"]), "",
             "| case | sigma | CuikSuite CPU [s] | safe: wall [s] | safe: CPU [s] | safe: processed / empty / solution "
             "| exact: wall [s] | exact: CPU [s] | exact: processed / empty / solution | exact / safe (CPU) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for key in keys:
        row = ["%s" % key, "%g" % CASES[key]["sigma"], "%g" % CUIK[key] if key in CUIK else "–"]
        c = {}
        for b in BACKENDS:
            s, wall, cpu, pr, em, so, n = c[b] = cells(results[key][b])
            if s == "error":
                row += ["error: %s" % results[key][b]["error"].replace("|", "/")[:120], "", ""]
            else:
                row += [t(s, wall), t(s, cpu), counts(s, pr, em, so)]
        if c["safe"][0] == "ok" and c["exact"][0] == "ok" and c["safe"][2]:
            row.append("%.1f" % (c["exact"][2] / c["safe"][2]))
        elif c["safe"][0] == "ok" and c["exact"][0] == "timeout" and c["safe"][2] and c["exact"][2]:
            row.append("> %.0f" % (c["exact"][2] / c["safe"][2]))
        else:
            row.append("–")
        lines.append("| " + " | ".join(row) + " |")
    lines += ["", "Time per call of the LP contractor (one shrink pass: up to two LPs per variable), its own seconds / "
              "calls in the last run; meaningful for a timeout too:", ""]
    for key in keys:
        parts = []
        for b in BACKENDS:
            last = results[key][b]["last"]
            lp = [c for c in (last or {}).get("contractors", []) if c.get("name") == "lp"]
            if lp and lp[0]["calls"]:
                parts.append("%s %.3g ms (%d calls)" % (b, 1000 * lp[0]["seconds"] / lp[0]["calls"], lp[0]["calls"]))
            else:
                parts.append("%s –" % b)
        lines.append("- %s: %s" % (key, "; ".join(parts)))
    lines += ["", "How the exact backend reached its answers in the last run (`contractors[].lp_paths`): CLP's basis "
              "checked optimal in rationals / repaired by exact simplex pivots / infeasible by a Farkas certificate "
              "checked in rationals / CGAL's QP solver from scratch; and the exact pivots over all repairs:", ""]
    for key in keys:
        last = results[key]["exact"]["last"]
        lp = [c for c in (last or {}).get("contractors", []) if c.get("name") == "lp"]
        p = lp[0].get("lp_paths") if lp else None
        if p:
            lines.append("- %s: basis %d, repaired %d, Farkas %d, CGAL fall-back %d; %d pivots" % (
                key, p.get("basis", 0), p.get("repaired", 0), p.get("farkas", 0), p.get("fallback", 0), p.get("pivots", 0)))
        else:
            lines.append("- %s: –" % key)
    missing = [k for k in CUIK if k not in keys]
    lines += ["",
              "CuikSuite (CLP, not rigorous: it trusts the float LP's infeasibility and gives no existence proof), "
              "one process, CPU seconds, from lib/README.md: 6R %g s, cyclohexane %g s, mobile 6R %g s, bicyclohexane %g s%s. "
              "Its sigma for these timings is not recorded, so the comparison is of orders of magnitude. "
              "The paper's own times (Pentium 4, glpk) are in section5.md." % (
                  CUIK["6r-rigid"], CUIK["cyclohexane"], CUIK["6r-mobile"], CUIK["bicyclohexane"],
                  (" (%s not run here: see section5.py)" % ", ".join(missing)) if missing else ""),
              "",
              "A timeout: the run reached --time-limit (linkbox checks it every 16 processed boxes, so a run with "
              "exact LPs overshoots it by up to 16 boxes' work) and reports what it had processed; \"killed\": it had "
              "not stopped at max(2 x limit, limit + 600 s) wall and was killed by this script, leaving no counts. "
              "A backend that times out is not repeated on that case.",
              "",
              "`safe` bounds each LP optimum from the float solution's dual (Neumaier-Shcherbina) and excludes a box "
              "only on a checked certificate; `exact` returns every LP's exact optimum rounded outward (CLP's warm "
              "basis checked primal and dual feasible in fraction-free integer arithmetic, repaired by exact pivots "
              "when it is not, CGAL's QP solver with Gmpzf when the repair fails) or an exact Farkas proof. The "
              "safe bounds lie within ~1e-14 of the exact ones (lp_oracle.md), so the box counts should agree; they "
              "can still differ a little, since each backend's float point steers which LPs are skipped; a "
              "difference is flagged below."]
    for key in keys:
        a, b = cells(results[key]["safe"]), cells(results[key]["exact"])
        if a[0] == "ok" and b[0] == "ok" and a[3:6] != b[3:6]:
            lines.append("- %s: box counts differ between safe %s and exact %s." % (key, a[3:6], b[3:6]))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "benchmark_lp.md"), "w") as f:
        f.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
