#!/usr/bin/env python3
"""Regenerates Section V (experiments) of Porta, Ros, Thomas, "Multi-loop position analysis
via iterated linear programming" (RSS 2006) with linkbox, beside the paper's figures.

Usage: python3 papers/porta-iterated-lp/section5.py [--build build-papers] [--runs 3]
           [--cases 6r-rigid,6r-mobile,bicyclohexane,cyclohexane] [--time-limit 1800]
           [--prune lp [hc4,lp ...]] [--lp safe]

For every case: the model size (primary / dummy variables; linear / parabolic / hyperbolic
equations), sigma, rho, and the processed / empty / solution / split box counts and the time.
Cases and parameters are the paper's: rigid 6R (sigma = 1e-4), mobile 6R and bicyclohexane
(sigma = 0.1), all with rho = 0.95, plus cyclohexane (sigma = 0.1, rho = 0.95; not in the
paper's text, but CuikSuite's reference timing uses it). By default pruning is the paper's:
the iterated LP relaxation alone (`--prune lp`, safe LP bounds, each variable's lower then
upper bound in turn: `--lp-order given`, Algorithm 2's order), depth-first, one thread.
Several --prune values (e.g. `--prune lp hc4,lp`) give one linkbox row per value; the first
one's JSON is the one kept for the plots.

Times are medians over --runs runs with --no-verify: wall clock of the search (the JSON's
stats.seconds) and the CPU time of the linkbox process (user + system, from getrusage), the
fairer figure on a shared machine. One more run with verification gives the clusters
(certified roots, curves) and the JSON that is kept; its verification time is reported
apart. A run that reaches --time-limit is reported as incomplete with what it had processed;
the case is then not repeated (nor verified).

Writes section5.md and section5.csv beside this script, keeps the JSON of the last run of
each case in runs/<case>.json (plot_curves.py reads them) and its table row in
runs/row-<case>-<prune>.json, and prints the markdown. With --cases, the other cases' rows
are taken from those row files (so a slow case can be re-run alone); --only drops them;
--report-only runs nothing and rewrites the tables from the row files. runs/ is not in git:
where a case's row file is missing (a fresh checkout), both refuse (exit 2) before running.
"""
import argparse
import csv
import datetime
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# Paper figures (Section V). None = not given. "split" for the curve cases is not printed in
# the paper; it is derived as processed - empty - solution (this identity holds for the rigid
# 6R: 47 = 8 + 16 + 23) and flagged as derived.
CASES = {
    "6r-rigid": {
        "file": "cases/linkages/6r-rigid.toml", "sigma": 1e-4, "rho": 0.95, "label": "rigid 6R (Fig. 5)",
        "paper": {"primary": 23, "dummy": 44, "linear": 28, "parabolic": 21, "hyperbolic": 23,
                  "processed": 47, "empty": 8, "solution_boxes": 16, "split": 23, "seconds": 100,
                  "time_note": "about 100 s"},
    },
    "6r-mobile": {
        "file": "cases/linkages/6r-mobile.toml", "sigma": 0.1, "rho": 0.95, "label": "mobile 6R (Fig. 6)",
        "paper": {"primary": 22, "dummy": 29, "linear": None, "parabolic": None, "hyperbolic": None,
                  "processed": 833, "empty": 30, "solution_boxes": 387, "split": None, "seconds": 180,
                  "time_note": "180 s"},
    },
    "bicyclohexane": {
        "file": "cases/linkages/bicyclohexane.toml", "sigma": 0.1, "rho": 0.95, "label": "bicyclohexane (Fig. 8)",
        "paper": {"primary": None, "dummy": None, "linear": None, "parabolic": None, "hyperbolic": None,
                  "processed": 663, "empty": 84, "solution_boxes": 248, "split": None, "seconds": 650,
                  "time_note": "650 s"},
    },
    "cyclohexane": {
        "file": "cases/linkages/cyclohexane.toml", "sigma": 0.1, "rho": 0.95, "label": "cyclohexane (not in the paper)",
        "paper": None,
    },
}
ORDER = ["6r-rigid", "6r-mobile", "bicyclohexane", "cyclohexane"]
MODEL_KEYS = ["primary", "dummy", "linear", "parabolic", "hyperbolic"]


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def model_size(res):
    """The model size: the JSON's top-level `model` when present, otherwise only the totals
    (variables, equations) of the first sub-problem."""
    m = res.get("model")
    if isinstance(m, dict) and all(k in m for k in MODEL_KEYS):
        return {k: m[k] for k in MODEL_KEYS}, "model"
    sub = (res.get("subproblem_stats") or [{}])[0]
    return {"variables": sub.get("variables"), "equations": sub.get("equations")}, "subproblem_stats"


def solve_once(binary, case, args, out_json, extra=()):
    """Runs linkbox once; returns (parsed JSON, wall seconds, CPU seconds of the child, error)."""
    cmd = [binary, "solve", os.path.join(ROOT, case["file"]), "--bisect", "widest", "--prune", args.prune, "--lp", args.lp,
           "--lp-order", "given",
           "--sigma", repr(case["sigma"]), "--rho", repr(case["rho"]), "--quiet", "--json", out_json]
    if args.time_limit > 0:
        cmd += ["--time-limit", repr(float(args.time_limit))]
    cmd += list(extra)
    if os.path.exists(out_json):
        os.remove(out_json)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    # The solver checks --time-limit between boxes, so one slow box (an exact LP can take
    # minutes) overshoots it; the watchdog only guards against a hang.
    timeout = max(2 * args.time_limit, args.time_limit + 600) if args.time_limit > 0 else None
    try:
        proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, time.monotonic() - t0, None, "killed after %.0f s: did not stop at its time limit" % timeout
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if proc.returncode not in (0, 4, 5) or not os.path.exists(out_json):
        return None, wall, cpu, "exit code %d: %s" % (proc.returncode, proc.stderr.strip()[-500:])
    with open(out_json) as f:
        return json.load(f), wall, cpu, None


def run_case(binary, key, args, json_dir, first=True):
    case = CASES[key]
    out_json = os.path.join(json_dir, key + (".json" if first else "--prune-%s.json" % args.prune.replace(",", "-")))
    walls, cpus, results, error = [], [], [], None
    for i in range(args.runs):
        res, wall, cpu, err = solve_once(binary, case, args, out_json, extra=["--no-verify"])
        if err:
            error = err
            break
        results.append(res)
        walls.append(res["stats"]["seconds"])
        cpus.append(cpu)
        if not res.get("complete", True):
            break  # hit the time limit: do not repeat
        print("  %s --prune %s run %d/%d: %.2f s wall, %.2f s CPU, %d processed" % (
            key, args.prune, i + 1, args.runs, walls[-1], cpu, res["stats"]["processed"]),
              file=sys.stderr, flush=True)
    row = {"case": key, "label": case["label"], "sigma": case["sigma"], "rho": case["rho"], "runs": len(results), "error": error,
           "prune": args.prune}
    if not results:
        return row
    res = results[-1]
    # The search's figures come from the runs without verification: a verified run of a
    # symmetric six-joint loop also narrows its curve boxes for the map (`narrow` in the JSON).
    searches = list(results)
    verify_seconds = verify_cpu = None
    if res.get("complete", True) and not error:
        # One more run with verification (clusters, certified roots, curves): its JSON is kept.
        print("  %s --prune %s: one more run with verification" % (key, args.prune), file=sys.stderr, flush=True)
        res_v, _, cpu_v, err = solve_once(binary, case, args, out_json)
        if err:
            error = "verification run: " + err
        else:
            results.append(res_v)
            res = res_v
            verify_seconds = (res.get("verification") or {}).get("seconds")
            verify_cpu = cpu_v
    st = searches[-1]["stats"]
    size, size_src = model_size(res)
    counts = {(r["stats"]["processed"], r["stats"]["empty"], r["stats"]["split"], r["stats"]["solution_boxes"]) for r in searches}
    clusters = res.get("clusters") or []
    status_count = {}
    crossings = [0, 0]
    for c in clusters:
        status_count[c["status"]] = status_count.get(c["status"], 0) + 1
        if c["status"] == "curve":
            crossings[0] += c.get("crossings_certified", 0)
            n = c.get("crossings", 0)
            crossings[1] += len(n) if isinstance(n, list) else int(n)
    row.update({
        "size": size, "size_source": size_src,
        "processed": st["processed"], "empty": st["empty"], "split": st["split"], "solution_boxes": st["solution_boxes"],
        "shrinks": st.get("shrinks"), "subproblems": st.get("subproblems"),
        "wall": statistics.median(walls), "cpu": statistics.median(cpus),
        "verify_seconds": verify_seconds, "verify_cpu": verify_cpu, "crossings": crossings,
        "complete": res.get("complete", True), "stop_reason": res.get("stop_reason"),
        "deterministic": len(counts) == 1,
        "clusters": len(clusters), "cluster_status": status_count,
        "headline": res.get("headline"),
        # A symmetric six-joint loop's verified run narrows its curve boxes for the map.
        "narrowed": [res["parameters"]["narrow"], res["stats"]["solution_boxes"]]
        if (res.get("parameters") or {}).get("narrow") else None,
        "json": os.path.relpath(out_json, ROOT),
    })
    return row


def fmt(v, derived=False):
    if v is None:
        return "–"
    return ("%s*" % v) if derived else str(v)


def paper_cells(p):
    """Paper's row cells: model size, counts, time; split derived when not printed."""
    split, derived = p["split"], False
    if split is None:
        split, derived = p["processed"] - p["empty"] - p["solution_boxes"], True
    return [fmt(p["primary"]), fmt(p["dummy"]), fmt(p["linear"]), fmt(p["parabolic"]), fmt(p["hyperbolic"]),
            fmt(p["processed"]), fmt(p["empty"]), fmt(p["solution_boxes"]), fmt(split, derived)], split, derived


def our_size_cells(row):
    s = row["size"]
    if row["size_source"] == "model":
        return [str(s[k]) for k in MODEL_KEYS]
    return ["%s vars total" % s["variables"], "", "%s eqs total" % s["equations"], "", ""]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build-papers"), help="build directory holding the linkbox binary")
    ap.add_argument("--runs", type=int, default=3, help="runs per case; times are medians (default 3)")
    ap.add_argument("--cases", nargs="+", default=None,
                    help="subset of %s (comma- or space-separated); default all" % ",".join(ORDER))
    ap.add_argument("--time-limit", type=float, default=1800, help="seconds per run, 0 = none (default 1800)")
    ap.add_argument("--prune", nargs="+", default=["lp"],
                    help="contractor list(s) for --prune, one linkbox row each (default lp, the paper's)")
    ap.add_argument("--lp", default="safe", choices=["safe", "exact"], help="LP backend (default safe)")
    ap.add_argument("--only", action="store_true",
                    help="with --cases: tables hold only these cases (default: other cases' rows are kept from runs/row-*.json)")
    ap.add_argument("--report-only", action="store_true",
                    help="run nothing: rewrite section5.md/.csv from runs/row-*.json")
    ap.add_argument("--out", default=HERE, help="where section5.md/.csv and runs/ go (default: beside this script)")
    args = ap.parse_args()
    binary = os.path.join(os.path.abspath(args.build), "linkbox")
    if not args.report_only and not os.access(binary, os.X_OK):
        sys.exit("no linkbox binary at %s (build it: cmake --build %s --target linkbox_cli)" % (binary, args.build))
    keys = ORDER if not args.cases else [k for c in args.cases for k in c.split(",") if k]
    for k in keys:
        if k not in CASES:
            sys.exit("unknown case %r (known: %s)" % (k, ", ".join(ORDER)))
    json_dir = os.path.join(args.out, "runs")
    os.makedirs(json_dir, exist_ok=True)
    if (args.cases or args.report_only) and not args.only:
        # The other cases' rows come from earlier runs here (runs/ is not in git): refuse
        # before running rather than write tables that silently lack them.
        run_keys = [] if args.report_only else keys
        missing = [k for k in ORDER if k not in run_keys and
                   not any(n.startswith("row-%s-" % k) and n.endswith(".json") for n in os.listdir(json_dir))]
        if missing:
            print("section5.py: no earlier rows for %s in %s (a fresh checkout has none): run them too, or "
                  "pass --only to write tables of these cases alone" % (", ".join(missing), json_dir), file=sys.stderr)
            sys.exit(2)
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    rows = []
    if args.report_only:
        keys = []  # no runs: every row comes from runs/row-*.json
    # The slow bicyclohexane runs last, so that the quick cases are done first; rows keep
    # the paper's order.
    for k in sorted(keys, key=lambda k: (k == "bicyclohexane", keys.index(k))):
        for n, prune in enumerate(args.prune):
            print("solving %s --prune %s ..." % (k, prune), file=sys.stderr, flush=True)
            rows.append(run_case(binary, k, argparse.Namespace(prune=prune, lp=args.lp, runs=args.runs, time_limit=args.time_limit),
                                 json_dir, first=(n == 0)))
    for r in rows:
        r.update({"started": started, "load": load, "time_limit": args.time_limit, "runs_requested": args.runs, "lp": args.lp})
        with open(os.path.join(json_dir, "row-%s-%s.json" % (r["case"], r["prune"].replace(",", "-"))), "w") as f:
            json.dump(r, f, indent=1)
    if (args.cases or args.report_only) and not args.only:
        # Keep the other cases' rows from earlier invocations (runs/row-*.json), so that one
        # slow case can be re-run alone.
        for k in ORDER:
            if k in keys:
                continue
            for name in sorted(os.listdir(json_dir)):
                if name.startswith("row-%s-" % k) and name.endswith(".json"):
                    with open(os.path.join(json_dir, name)) as f:
                        rows.append(json.load(f))
    order = [k for k in ORDER if k in {r["case"] for r in rows}]
    rows.sort(key=lambda r: order.index(r["case"]))  # stable: prune variants stay in order
    sessions = {}
    for r in rows:
        sessions.setdefault((r["started"], r["load"], r["time_limit"], r["runs_requested"], r["lp"]), []).append(r["case"])

    # CSV: one paper row and one linkbox row per case.
    with open(os.path.join(args.out, "section5.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "source", "prune", "primary", "dummy", "linear", "parabolic", "hyperbolic", "sigma", "rho",
                    "processed", "empty", "solution_boxes", "split", "seconds", "cpu_seconds", "complete", "runs",
                    "clusters", "certified", "note"])
        done = set()
        for r in rows:
            p = CASES[r["case"]]["paper"]
            if p and r["case"] not in done:
                done.add(r["case"])
                _, split, derived = paper_cells(p)
                w.writerow([r["case"], "paper", ""] + [p[k] if p[k] is not None else "" for k in MODEL_KEYS] +
                           [r["sigma"], r["rho"], p["processed"], p["empty"], p["solution_boxes"], split, p["seconds"], "",
                            "true", "", "", "", "Pentium 4 2.6 GHz, glpk" + ("; split derived = processed-empty-solution" if derived else "")])
            if r.get("error") and not r["runs"]:
                w.writerow([r["case"], "linkbox", r["prune"]] + [""] * 17 + ["error: " + r["error"]])
                continue
            s = r["size"]
            size = [s[k] for k in MODEL_KEYS] if r["size_source"] == "model" else [s["variables"], "", s["equations"], "", ""]
            w.writerow([r["case"], "linkbox", r["prune"]] + size +
                       [r["sigma"], r["rho"], r["processed"], r["empty"], r["solution_boxes"], r["split"],
                        "%.3f" % r["wall"], "%.3f" % r["cpu"], str(r["complete"]).lower(), r["runs"],
                        r["clusters"], r["cluster_status"].get("certified", 0),
                        ("" if r["complete"] else "incomplete: %s" % r["stop_reason"]) +
                        ("" if r["size_source"] == "model" else "; model size = totals of subproblem_stats[0] (variables, equations)")])

    lines = ["# Section V of Porta, Ros, Thomas (RSS 2006), regenerated", "",
             "linkbox `solve --prune P` (P in the source column), depth-first, one thread; times are medians of up to N runs "
             "(a run that reaches the time limit is not repeated). Machine: %s, %d cores (shared); the paper used a "
             "Pentium 4 at 2.6 GHz with glpk. Runs:" % (cpu_model(), os.cpu_count() or 0), ""] + [
             "- %s: %s; `--lp %s`, N = %d, time limit %s, load average %.1f at the start" % (
                 st, ", ".join(dict.fromkeys(cs)), lp, n, ("%g s" % tl) if tl > 0 else "none", ld)
             for (st, ld, tl, n, lp), cs in sessions.items()] + ["",
             "| case | source | primary | dummy | L | P | H | sigma | rho | processed | empty | solution | split | time [s] | CPU [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    notes = []
    done = set()
    for r in rows:
        p = CASES[r["case"]]["paper"]
        first = "" if r["case"] in done else r["label"]
        if p and r["case"] not in done:
            cells, _, _ = paper_cells(p)
            lines.append("| %s | paper | %s | %g | %g | %s | %s | |" % (first, " | ".join(cells[:5]), r["sigma"], r["rho"],
                                                                      " | ".join(cells[5:]), p["time_note"]))
            first = ""
        done.add(r["case"])
        if r.get("error") and not r["runs"]:
            lines.append("| %s | linkbox `%s` | error: %s |||||||||||||" % (first, r["prune"], r["error"].replace("|", "/")))
            continue
        src = "linkbox `%s`" % r["prune"]
        if not r["complete"]:
            src += ", **incomplete** (%s)" % r["stop_reason"]
        lines.append("| %s | %s | %s | %g | %g | %d | %d | %d | %d | %.2f | %.2f |" % (
            first, src, " | ".join(our_size_cells(r)), r["sigma"], r["rho"], r["processed"], r["empty"],
            r["solution_boxes"], r["split"], r["wall"], r["cpu"]))
        cs = ", ".join("%d %s" % (n, st) for st, n in sorted(r["cluster_status"].items())) or "none"
        if r["verify_seconds"] is not None:
            ver = "verification %.2f s wall (%.2f s CPU for the whole verified run); headline: \"%s\"" % (
                r["verify_seconds"], r["verify_cpu"], r["headline"])
            if r.get("narrowed"):
                ver += ("; the verified run narrowed the uncertified boxes to %g for the symmetric loop's map "
                        "(%d solution boxes)" % tuple(r["narrowed"]))
            if r["crossings"][1]:
                ver += "; curve crossings certified: %d of %d" % tuple(r["crossings"])
        else:
            ver = "not verified (search incomplete)" if not r["complete"] else "not verified"
        if not r["complete"]:
            ver += "; stopped after %.0f s with %.0f%% of the processed boxes empty" % (
                r["wall"], 100.0 * r["empty"] / max(r["processed"], 1))
            if (r["shrinks"] or 0) < 1.2 * r["processed"]:
                ver += (" and about one shrink pass per box: the LP pass rarely removes more than 1 - rho of a "
                        "box's volume, so nearly every box is emptied or split at once")
        clustered = ("in %d clusters (%s)" % (r["clusters"], cs)) if r["verify_seconds"] is not None else "(not clustered)"
        notes.append("- **%s**, `--prune %s`: %d solution boxes %s; %d shrink passes (%.1f per processed box); "
                     "%s%s" % (r["case"], r["prune"], r["solution_boxes"], clustered, r["shrinks"] or 0,
                               (r["shrinks"] or 0) / max(r["processed"], 1), ver,
                               "" if r["deterministic"] else "; box counts differed between runs (last run shown)"))
        if r.get("error"):
            notes.append("  - a later run failed: %s" % r["error"])
    lines += ["",
              "L, P, H: linear, parabolic, hyperbolic equations. `*`: not printed in the paper, derived as "
              "processed - empty - solution (the identity holds for the paper's rigid 6R: 47 = 8 + 16 + 23). "
              "time: wall clock of the search (the JSON's stats.seconds); CPU: user + system time of the linkbox "
              "process (the machine is shared, so CPU is the steadier figure). Timed runs use `--no-verify`; one more "
              "run with verification (clustering, interval-Newton certification, curve checks) gives the clusters "
              "below and its time is reported separately. JSON of that run (solution boxes, clusters): `runs/<case>.json`; "
              "plots: `plot_curves.py`.", "", "Per case:", ""] + notes
    if any(r.get("size_source") == "subproblem_stats" for r in rows if r["runs"]):
        lines += ["", "The JSON had no `model` field; the model size above is the sub-problem's total variables and equations."]
    lines += ["",
              "Reading the comparison: linkbox's model of a 6R loop is smaller than the paper's (the paper's "
              "vector formulation has more primary and dummy variables), so the box counts are not expected to "
              "match one for one. sigma bounds the longest side of a solution box in the split variables (the "
              "components of the unit vectors, in the paper as here), not in the joint angles, so a solution box of a "
              "curve case spans some tenths of a radian in the plots, and the number of solution boxes depends on "
              "how long the curve is in those variables."]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "section5.md"), "w") as f:
        f.write(text)
    print(text)
    return 1 if any(r.get("error") and not r["runs"] for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
