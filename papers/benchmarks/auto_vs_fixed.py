#!/usr/bin/env python3
"""`auto` beside each strategy it races, on IbexSolve's benchmark files (the given half).

  /usr/bin/python3 papers/benchmarks/auto_vs_fixed.py run --linkbox build/linkbox   # runs, then renders
  /usr/bin/python3 papers/benchmarks/auto_vs_fixed.py render                        # renders only

Issue 27 asks that `auto` be within 1.5x of the best fixed strategy on every file that some
strategy finishes. `run` solves each file with `--prune auto` and with each of the candidates
`auto` races on a system that clipping does not take (`hc4,newton`, `hc4,newton/lp`,
`hc4,newton,taylor`), `--threads 1 --cpu-limit LIMIT --no-verify`, one run at a time, and records
the CPU time (user+sys of the process, from the kernel) and the JSON's strategy and boxes.
Files: those that linkbox or IbexSolve finished in corpus.csv (the others time out under every
strategy). `render` writes auto_vs_fixed.md from auto_vs_fixed.csv.
"""
import argparse
import csv
import json
import math
import os
import pathlib
import resource
import subprocess
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
SHARED = HERE.parents[2] / "shared"
STRATEGIES = ("auto", "hc4,newton", "hc4,newton/lp", "hc4,newton,taylor")
FIELDS = ("file", "strategy", "exit_code", "cpu_s", "complete", "winner", "solutions", "processed")
FLOOR = 0.01  # CPU seconds below this count as this in ratios


def finished_files(corpus_csv):
    with open(corpus_csv, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    done = {r["file"] for r in rows if r["status"] == "complete" or (r["tool"] == "linkbox" and r["exit_code"] == "4")}
    return sorted(done)


def children_cpu():
    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime + u.ru_stime


def solve(linkbox, path, strategy, limit):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.json")
        cmd = [linkbox, "solve", str(path), "--threads", "1", "--cpu-limit", str(limit), "--no-verify",
               "--prune", strategy, "--json", out, "--quiet"]
        before = children_cpu()
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=4 * limit + 60)
        cpu = children_cpu() - before
        doc = json.load(open(out)) if os.path.exists(out) else {}
    stats = doc.get("stats", {})
    return {"exit_code": p.returncode, "cpu_s": "%.3f" % cpu, "complete": doc.get("complete", ""),
            "winner": doc.get("strategy", ""), "solutions": len(doc.get("solutions", [])),
            "processed": stats.get("processed", "")}


def run(args):
    started = utc_now()
    files = finished_files(args.corpus_csv)
    bench = pathlib.Path(args.bench)
    kept = load(args.csv) if args.only or args.files else {}
    with open(args.csv, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for i, name in enumerate(files):
            for s in STRATEGIES:
                if (args.only and s not in args.only) or (args.files and name not in args.files):
                    if s in kept.get(name, {}):
                        w.writerow(kept[name][s])
                    continue
                r = solve(args.linkbox, bench / name, s, args.limit)
                r.update(file=name, strategy=s)
                w.writerow(r)
                f.flush()
            print("%d/%d %s" % (i + 1, len(files), name), flush=True)
    version = subprocess.run([args.linkbox, "--version"], capture_output=True, text=True).stdout.strip()
    meta = {"linkbox": version, "started": started, "ended": utc_now(), "note": args.note or ""}
    meta_of(args.csv).write_text(json.dumps(meta) + "\n", encoding="utf-8")
    render(args)


def utc_now():
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())


def meta_of(path):
    return path.with_name(path.name + ".meta.json")


def load(path):
    table = {}
    with open(path, newline="", encoding="utf-8") as f:
        for r in csv.DictReader(f):
            table.setdefault(r["file"], {})[r["strategy"]] = r
    return table


def finished(r):
    return r is not None and str(r["complete"]) == "True"


def run_line(path):
    if not meta_of(path).exists():
        return "Run: not recorded."
    m = json.loads(meta_of(path).read_text())
    return "Run: %s, from %s to %s (UTC). %s" % (m["linkbox"], m["started"], m["ended"], m["note"])


def render(args):
    table = load(args.csv)
    lines = ["# `auto` beside the strategies it races", "",
             "Regenerate (about 20 minutes on two cores): `/usr/bin/python3 papers/benchmarks/auto_vs_fixed.py run "
             "--linkbox build/linkbox`; `render` rewrites this page from `auto_vs_fixed.csv`.", "",
             "Each file of the given half that linkbox or IbexSolve finished in `corpus.csv`, solved with each "
             "strategy, `--threads 1 --cpu-limit %g --no-verify`, one run at a time; CPU seconds (user+sys). "
             "Ratio: auto's CPU over the best fixed strategy's (floor %g s); `limit`: stopped by the limit."
             % (args.limit, FLOOR), "", run_line(args.csv), "",
             "| file | " + " | ".join(STRATEGIES) + " | auto's winner | auto / best |",
             "|---|" + "--:|" * len(STRATEGIES) + "---|--:|"]
    ratios, over = [], []
    for name in sorted(table):
        rs = table[name]
        cells = [("%.2f" % float(rs[s]["cpu_s"])) + ("" if finished(rs.get(s)) else " limit") if s in rs else ""
                 for s in STRATEGIES]
        fixed = [max(float(rs[s]["cpu_s"]), FLOOR) for s in STRATEGIES[1:] if finished(rs.get(s))]
        ratio = ""
        if fixed:
            auto = max(float(rs["auto"]["cpu_s"]), FLOOR)
            x = auto / min(fixed) if finished(rs.get("auto")) else float("inf")
            ratios.append(x)
            ratio = "%.2f" % x
            if x > 1.5:
                over.append((name, ratio))
        lines.append("| %s | %s | %s | %s |" % (name, " | ".join(cells), rs["auto"]["winner"] if "auto" in rs else "",
                                                ratio))
    finite = [x for x in ratios if math.isfinite(x)]
    g = math.exp(sum(math.log(x) for x in finite) / len(finite)) if finite else float("nan")
    summary = ["", "## Summary", "",
               "- Files some fixed strategy finishes: %d; `auto` finishes %d of them." % (len(ratios), len(finite)),
               "- auto / best fixed, geometric mean over those auto finishes: %.2f; worst: %.2f." %
               (g, max(ratios) if ratios else float("nan")),
               "- Over 1.5x (%d): %s." % (len(over), ", ".join("%s %s" % o for o in over) or "none")]
    args.csv.with_suffix(".md").write_text("\n".join(lines[:8] + summary + ["", "## Per file", ""] + lines[8:]) + "\n",
                                           encoding="utf-8")
    print("\n".join(summary))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run every strategy into auto_vs_fixed.csv, then render")
    r.add_argument("--linkbox", default="build/linkbox")
    r.add_argument("--bench", default=str(SHARED / "corpus" / "ibex-solver"))
    r.add_argument("--corpus-csv", default=str(HERE / "corpus.csv"), help="which files finished")
    r.add_argument("--only", nargs="*", help="run these strategies again, keep the others' rows in --csv")
    r.add_argument("--files", nargs="*", help="run these files again (as in corpus.csv), keep the others' rows in --csv")
    d = sub.add_parser("render", help="write auto_vs_fixed.md from auto_vs_fixed.csv")
    for p in (r, d):
        p.add_argument("--csv", type=pathlib.Path, default=HERE / "auto_vs_fixed.csv")
        p.add_argument("--limit", type=float, default=8)
    r.add_argument("--note", help="said on the page, e.g. what else ran on the machine")
    args = ap.parse_args()
    (run if args.cmd == "run" else render)(args)


if __name__ == "__main__":
    main()
