#!/usr/bin/env python3
"""linkbox beside IbexSolve on IbexSolve's own benchmark files (the 129 given in
../shared/corpus/ibex-solver/, see ../shared/corpus/README.md), both run on this machine in one run.

  /usr/bin/python3 papers/benchmarks/corpus.py run --linkbox build/linkbox   # runs, then renders
  /usr/bin/python3 papers/benchmarks/corpus.py render                        # renders only

`run` calls ../shared/tools/corpus.py `run` for both tools with the harness's commands
(`linkbox solve FILE --threads 1 --cpu-limit 8`, `ibexsolve FILE --timeout=8 --eps-min=1e-8`: both
limits count CPU time, so load on the machine cuts neither tool short),
one run at a time by default (--workers 1: the machine has 2 cores, and one is left to the rest),
linkbox then IbexSolve on each file, into corpus.csv. Each run's output and linkbox's JSON are
kept in --logs. `render` writes corpus.md and corpus.png from corpus.csv. CPU time (user+sys of
the whole process), not wall time, is compared, since other work may run on the machine.
"""
import argparse
import csv
import json
import math
import pathlib
import re
import shlex
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
SHARED = HERE.parents[2] / "shared"
FLOOR = 0.01  # CPU seconds below this count as this in ratios, as the harness's summarize does
TOOLS = ("linkbox", "ibexsolve")

# What was found by hand in the logs (linkbox's JSON, IbexSolve's report) of the run corpus.csv
# holds, on files where the counts differ or something is left unresolved, and on odd runs.
OUTSIDE = ("domain [1e-8, 2*pi-1e-8]: the roots with every x_i = 0 and every x_i = 2*pi lie 1e-8 outside it; linkbox "
           "certifies the latter and proves it outside the domain by its angle (since 5358a90; before, it was "
           "left unresolved, on the domain inequality's boundary), so does not count it")
NOTES = {
    "non-polynom/Trigo1-0005.bch": OUTSIDE + "; IbexSolve does not report it: both count the 3 roots inside.",
    "non-polynom/Trigo1-0012.bch": OUTSIDE + " (IbexSolve stopped at its limit).",
    "non-polynom/Trigo1-0014.bch": OUTSIDE + " (IbexSolve stopped at its limit).",
    "non-polynom/Trigo1-0100sp.bch": (
        "domain [0.1, 2*pi]: the only root, every x_i = 2*pi, lies on the domain's edge; IbexSolve calls "
        "its box 'unknown'. linkbox certifies it (since d18359d): lifted, it is the rational point "
        "c_i = 1, s_i = 0, SE = -100, where every equation is exactly 0, and its angle 2*pi lies inside "
        "the domain's outward upper end (docs/verification.md, exact roots)."),
    "non-polynom/Trigonometric-05.bch": (
        "domain [0, 2*pi-1e-3]: 10 of the 32 roots have some x_i = 0, on the domain's edge; IbexSolve "
        "calls their boxes 'unknown'. linkbox certifies them at their exact points (since d18359d: "
        "each x_i is 0 or pi/2, so (cos, sin) is (1, 0) or (0, 1), rational)."),
    "non-polynom/Trigo1-1000sp.bch": (
        "linkbox's search ends at the limit with one solution box (every x_i = 2*pi, as in "
        "Trigo1-0100sp); certifying it in 2001 unknowns took minutes until c8d533c (30 tightening "
        "rounds at 0.5 s, an SVD of the 2001 x 2001 Jacobian), about 7 s since. IbexSolve's set-up "
        "of the 1000 unknowns does not end before the harness's hard limit. On 2026-12-06 (an Intel Xeon "
        "machine, another run beside it) the search reached the limit with its one box still pending, so nothing was certified."),
}
EDGE = ("finished in 7.4-7.6 CPU s in the 2026-11-26 run; on 2026-11-28, with other work on the "
        "machine, the same search (same strategy, same boxes) needs 8.0-9.3 s, past the limit.")
NOTES["polynom/BroydenTri-0090.bch"] = ("linkbox finishes near the limit: 7.4-7.6 CPU s in the 2026-11-26 run, "
                                        "8.0-9.3 s on 2026-11-28 with other work on the machine (past the limit), "
                                        "7.1 s on 2026-11-29 with the race's cap asked between LPs (d4a943b). "
                                        "On 2026-12-06 (an Intel Xeon machine, the auto_vs_fixed run beside it) it timed out: "
                                        "run alone there it took 12.1 CPU s with c8c514f's build and 12.8 s with e65e965's, "
                                        "their races' work figures equal: the machine, not the change, moved it.")
NOTES["polynom/Redeco9.bch"] = "linkbox " + EDGE
NOTES["non-polynom/trigonometric-05.bch"] = NOTES["non-polynom/Trigonometric-05.bch"]
NOTES["non-polynom/SjirkBoon.bch"] = (
    "linkbox timed out in the 2026-11-29 09:40 run: the race handed the lead to hc4,newton/lp on tree "
    "shares below 0.001 (8.8 s alone, against 4.8 s for hc4,newton alone). Since a minimum tree share "
    "before the lead changes hands (753f3ee, papers/decisions/solve-driver.md) it finishes, as here.")


def cpu_limited(linkbox, logs):
    """The harness gives linkbox --time-limit T, which counts wall time, where IbexSolve's --timeout
    counts CPU time: this wrapper passes linkbox --cpu-limit T instead."""
    path = pathlib.Path(logs) / "linkbox-cpu-limit"
    path.parent.mkdir(parents=True, exist_ok=True)
    real = shlex.quote(str(pathlib.Path(linkbox).resolve()))
    path.write_text('#!/bin/bash\nexec %s "${@/#--time-limit/--cpu-limit}"\n' % real)
    path.chmod(0o755)
    return str(path)


def run(args):
    for p in (args.csv, meta_of(args.csv)):
        if p.exists() and not args.resume:
            p.unlink()
    linkbox = cpu_limited(args.linkbox, args.logs)
    cmd = [sys.executable, str(SHARED / "tools" / "corpus.py"), "run", "--linkbox", linkbox,
           "--ibexsolve", args.ibexsolve, "--bench", args.bench, "--out", str(args.csv),
           "--limit", str(args.limit), "--workers", str(args.workers),
           "--logs", args.logs, "--keep-json", "--resume"]
    subprocess.run(cmd, check=True)
    render(args)


def meta_of(path):
    return path.with_name(path.name + ".meta.jsonl")


def normalize(r):
    """The harness counts any exit but 0 as an error; linkbox's exit 4 means complete with something
    left unresolved, and 5 incomplete (its limit stopped it): such rows are read as such. Exit -9:
    the hard kill took the `timeout` wrapper along, and the CPU time of the tool with it."""
    if r["exit_code"] == "-9":
        r["cpu_s"] = ""
    if r["tool"] == "linkbox" and r["status"] == "error" and r["exit_code"] in ("4", "5"):
        if r["exit_code"] == "4":
            r["status"] = "complete"
        else:
            r["status"] = "timeout" if "time limit" in r["headline"] else "incomplete"
        r["error"] = ""
    return r


def load(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = {(r["file"], r["tool"]): normalize(r) for r in csv.DictReader(f)}
    files = sorted({f for f, _ in rows})
    meta = meta_of(path).read_text().splitlines() if meta_of(path).exists() else []
    meta = [json.loads(line) for line in meta if line.strip()]
    return rows, files, meta


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def done(r):
    return r is not None and r["status"] == "complete"


def roots(r):
    """Distinct certified roots: linkbox's certified_roots, IbexSolve's solution boxes merged."""
    v = num(r["distinct"]) if r["distinct"] else num(r["certified"])
    return None if v is None else int(v)


def ratio(lb, ib):
    return max(num(ib["cpu_s"]), FLOOR) / max(num(lb["cpu_s"]), FLOOR)


def status(r):
    if r is None:
        return "not run"
    return "timeout (killed)" if r["detail"] == "hard-timeout" else r["status"]


def lb_roots(r):
    if not done(r):
        return ""
    if r["exact"] == "yes":
        return "%s exact" % r["certified"]
    return "%s, not exact (%s unresolved)" % (r["certified"], r["unresolved"] or "?")


def ib_roots(r):
    if not done(r):
        return ""
    s = str(roots(r))
    extra = []
    if r["solutions"] and r["solutions"] != s:
        extra.append("%s boxes" % r["solutions"])
    if int(num(r["unknown"]) or 0):
        extra.append("%s unknown" % r["unknown"])
    return s + (" (%s)" % ", ".join(extra) if extra else "")


def refusal(r):
    return re.sub(r"^.*?\.bch:\d+:\s*", "", r["error"] or "exit 2")


def short(text, n=110):
    return text if len(text) <= n else text[:n].rsplit(" ", 1)[0] + " ..."


def explain(f, lb, ib):
    why = []
    if lb["exact"] != "yes":
        unv, unres = int(num(lb["unknown"]) or 0), int(num(lb["unresolved"]) or 0)
        why.append("linkbox: %d cluster(s) left unverified, %d curve(s) (\"%s\")"
                   % (unv, unres - unv, short(lb["headline"])))
    if ib and int(num(ib["unknown"]) or 0):
        why.append("IbexSolve: %s 'unknown' box(es), not counted as roots (\"%s\")"
                   % (ib["unknown"], ib["headline"]))
    if f in NOTES:
        why.append(NOTES[f])
    return "; ".join(why).replace("|", "\\|") or "(not explained)"


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else float("nan")


def table(rows, files):
    out = ["| file | linkbox | linkbox roots (certified) | linkbox CPU s | IbexSolve | "
           "IbexSolve roots (distinct) | IbexSolve CPU s | CPU ibex/linkbox |",
           "|---|---|---|--:|---|---|--:|--:|"]
    for f in files:
        lb, ib = rows.get((f, "linkbox")), rows.get((f, "ibexsolve"))
        both = done(lb) and done(ib)
        out.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            f, status(lb), lb_roots(lb), lb["cpu_s"] or "n/a" if lb else "", status(ib), ib_roots(ib),
            ib["cpu_s"] or "n/a" if ib else "", "%.3g" % ratio(lb, ib) if both else ""))
    return out


def summary(rows, files):
    lb = {f: rows.get((f, "linkbox")) for f in files}
    ib = {f: rows.get((f, "ibexsolve")) for f in files}
    both = [f for f in files if done(lb[f]) and done(ib[f])]
    only = {t: [f for f in files if done(rows.get((f, t))) and f not in both] for t in TOOLS}
    refused = [f for f in files if lb[f] and lb[f]["status"] == "refused"]
    ratios = [ratio(lb[f], ib[f]) for f in both]
    disagree = [f for f in both if roots(lb[f]) != roots(ib[f])]
    out = ["## Totals", ""]
    for t, name in (("linkbox", "linkbox"), ("ibexsolve", "IbexSolve")):
        rs = [rows[(f, t)] for f in files if (f, t) in rows]
        counts = {}
        for r in rs:
            counts[status(r)] = counts.get(status(r), 0) + 1
        exact = sum(1 for r in rs if done(r) and r["exact"] == "yes")
        out.append("- %s finishes %d of %d files (%d exact: every root certified, nothing left "
                   "unresolved); %s." % (name, counts.get("complete", 0), len(files), exact, ", ".join(
                       "%s %d" % kv for kv in sorted(counts.items()) if kv[0] != "complete")))
    short_lb = [f for f in files if lb[f] and lb[f]["status"] == "timeout" and num(lb[f]["cpu_s"])
                and num(lb[f]["cpu_s"]) < 0.9 * float(lb[f]["limit_s"])]
    if short_lb:
        out.append("- linkbox stopped at its limit with less than 90%% of it in CPU time on %d files, "
                   "%d of them finished by IbexSolve." % (len(short_lb), sum(done(ib[f]) for f in short_lb)))
    out.append("- Both finish %d files. CPU ratio IbexSolve/linkbox on them (floor %g s), geometric "
               "mean: **%.3g** (above 1: linkbox faster); linkbox faster by 2x or more on %d, "
               "IbexSolve on %d, within 2x on %d." % (
                   len(both), FLOOR, geomean(ratios), sum(x >= 2 for x in ratios),
                   sum(x <= 0.5 for x in ratios), sum(0.5 < x < 2 for x in ratios)))
    out.append("- Root counts agree on %d of the %d; they differ on %d (below)."
               % (len(both) - len(disagree), len(both), len(disagree)))
    for t, name, other in (("linkbox", "linkbox", "ibexsolve"), ("ibexsolve", "IbexSolve", "linkbox")):
        out.append("- Finished by %s alone (%d): %s." % (name, len(only[t]), ", ".join(
            "%s (%s %s at %s CPU s)" % (f, other, status(rows.get((f, other))), rows[(f, other)]["cpu_s"])
            for f in only[t]) or "none"))
    out += ["", "### Refused by linkbox (%d)" % len(refused), ""]
    out += ["- %s: %s" % (f, refusal(lb[f])) for f in refused] or ["none"]
    odd = [f for f in both if f in disagree or lb[f]["exact"] != "yes" or ib[f]["exact"] != "yes"]
    out += ["", "### Where both finish: counts that differ (%d), or something left unresolved (%d)"
            % (len(disagree), len(odd) - len(disagree)), "",
            "| file | linkbox roots | IbexSolve roots | counts | why |", "|---|---|---|---|---|"]
    out += ["| %s | %s | %s | %s | %s |" % (f, lb_roots(lb[f]), ib_roots(ib[f]),
                                           "differ" if f in disagree else "same", explain(f, lb[f], ib[f]))
            for f in odd]
    rest = [f for f in files if f in NOTES and f not in odd]
    out += ["", "### Other runs explained", ""] + ["- %s: %s" % (f, NOTES[f]) for f in rest]
    return out


def header(rows, meta, png):
    m = meta[0] if meta else {}
    started = sorted(r["started"] for r in rows.values() if r["started"])
    tools = m.get("tools", {})
    limit = m.get("limit", "8")
    return [
        "# linkbox beside IbexSolve on IbexSolve's benchmark files", "",
        "Regenerate (runs both tools, 20-40 minutes on two cores; `render` alone rewrites this page "
        "and the plot from `corpus.csv`):", "",
        "```sh",
        "/usr/bin/python3 papers/benchmarks/corpus.py run --linkbox build/linkbox",
        "/usr/bin/python3 papers/benchmarks/corpus.py render",
        "```", "",
        "Machine: %s, %s, %s cores; runs from %s to %s (UTC), %s at a time, while other work ran "
        "on the machine, so CPU time (user+sys of the whole process: reading, search, "
        "verification, output) is compared, not wall time." % (
            m.get("host", "?"), m.get("cpu", "?"), m.get("nproc", "?"),
            started[0] if started else "?", started[-1] if started else "?", m.get("workers", "?")),
        "",
        "The %d files of `../shared/corpus/ibex-solver/` (IbexSolve's `benchs/solver`, the given half; "
        "see `../shared/corpus/README.md`), run by `../shared/tools/corpus.py` with a limit of %s s:" % (
            len({f for f, _ in rows}), limit), "",
    ] + ["- %s (%s): `%s %s`" % (t, v.get("version", "?"), t, " ".join(v.get("args", [])[1:]))
         for t, v in tools.items()] + [
        "",
        "Status: `complete`, the tool ended its search by itself (IbexSolve also when some boxes are "
        "left 'unknown'); `timeout`, its own limit stopped it (`timeout (killed)`: the harness killed "
        "it at 2T+30 s, e.g. IbexSolve's set-up of 1000 unknowns, which its limit does not count); "
        "`refused`, linkbox's reader exits 2 on a feature it does not support. linkbox roots: "
        "certified roots, `exact` when every root is certified and nothing is left unresolved. "
        "IbexSolve roots: its solution boxes merged when they meet or one lies in the other's "
        "unicity box (it often reports one root as several adjacent boxes); 'unknown' boxes are "
        "not counted. CPU ratio: IbexSolve's CPU over linkbox's (floor %g s), where both finish." % FLOOR,
        "",
        "Both limits count CPU time: IbexSolve's --timeout that of its search (not its set-up), and "
        "linkbox's --time-limit, which `corpus.py run` passes as `--cpu-limit` (the wrapper "
        "`linkbox-cpu-limit` it writes into the logs folder), that of its search as well. So other "
        "work on the machine cuts neither tool short.",
        "",
        "![CPU time per file](%s)" % png, "",
    ]


def plot(rows, files, limit, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    kinds = {  # (linkbox finishes, IbexSolve finishes) -> marker, colour, label
        (True, True): ("o", "tab:blue", "both finish"),
        (True, False): ("^", "tab:green", "IbexSolve stopped at its limit"),
        (False, True): ("v", "tab:red", "linkbox stopped at its limit"),
        (False, False): ("x", "tab:gray", "both stopped"),
    }
    pts = {k: [] for k in kinds}
    for f in files:
        lb, ib = rows.get((f, "linkbox")), rows.get((f, "ibexsolve"))
        if not lb or not ib or lb["status"] == "refused" or not lb["cpu_s"] or not ib["cpu_s"]:
            continue
        pts[(done(lb), done(ib))].append((max(num(ib["cpu_s"]), FLOOR), max(num(lb["cpu_s"]), FLOOR)))
    fig, ax = plt.subplots(figsize=(6.5, 6))
    for k, (m, c, label) in kinds.items():
        if pts[k]:
            ax.scatter(*zip(*pts[k]), marker=m, color=c, label="%s (%d)" % (label, len(pts[k])), s=30)
    lo, hi = FLOOR / 1.5, max(x for p in pts.values() for xy in p for x in xy) * 1.5
    ax.plot([lo, hi], [lo, hi], "k-", lw=0.8, label="same CPU time")
    for s in (10, 0.1):
        ax.plot([lo, hi], [lo * s, hi * s], "k:", lw=0.5)
    ax.text(0.97, 0.30, "linkbox faster", transform=ax.transAxes, ha="right", color="gray")
    ax.text(0.03, 0.95, "IbexSolve faster", transform=ax.transAxes, color="gray")
    ax.axvline(limit, color="gray", ls="--", lw=0.6)
    ax.axhline(limit, color="gray", ls="--", lw=0.6)
    ax.set(xscale="log", yscale="log", xlim=(lo, hi), ylim=(lo, hi), xlabel="IbexSolve CPU s",
           ylabel="linkbox CPU s", title="CPU time per file (limit %g s dashed; dotted: 10x)" % limit)
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def render(args):
    rows, files, meta = load(args.csv)
    limit = float(meta[0]["limit"]) if meta else 8.0
    md, png = args.csv.with_suffix(".md"), args.csv.with_suffix(".png")
    lines = header(rows, meta, png.name) + summary(rows, files) + ["", "## Per file", ""] + table(rows, files)
    md.write_text("\n".join(lines) + "\n", encoding="utf-8")
    plot(rows, files, limit, png)
    print("wrote %s and %s" % (md, png))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run both tools into corpus.csv, then render")
    r.add_argument("--linkbox", default="build/linkbox")
    r.add_argument("--ibexsolve", default=str(SHARED / "peers" / "ibex" / "ibexsolve"))
    r.add_argument("--bench", default=str(SHARED / "corpus" / "ibex-solver"))
    r.add_argument("--limit", type=float, default=8)
    r.add_argument("--workers", type=int, default=1, help="runs at a time (default 1: 2 cores here)")
    r.add_argument("--logs", default="/tmp/linkbox-corpus-logs", help="each run's output and JSON")
    r.add_argument("--resume", action="store_true", help="keep corpus.csv and run what it lacks")
    d = sub.add_parser("render", help="write corpus.md and corpus.png from corpus.csv")
    for p in (r, d):
        p.add_argument("--csv", type=pathlib.Path, default=HERE / "corpus.csv",
                       help="the runs (default: %(default)s); the page and plot go beside it")
    args = ap.parse_args()
    (run if args.cmd == "run" else render)(args)


if __name__ == "__main__":
    main()
