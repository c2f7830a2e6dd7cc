#!/usr/bin/env python3
"""Threads in one process: `linkbox solve --threads T` on the classic benchmarks and the
bundled linkages, T = 1 and 2 in the same run (alternating), and whether the answer moved.

  python3 papers/benchmarks/threads.py [--linkbox build/linkbox] [--runs 3] [--threads 1,2]

Writes papers/benchmarks/threads.md and .csv. Per case and thread count, medians over --runs
runs of: wall seconds of the whole command, the search's own wall time (JSON
stats.search_seconds), verification's (verification.seconds), and CPU seconds (user+sys of
the process, every thread). `same`: every run at every thread count gave the same solution
boxes (bit for bit, in order), certified flags and headline as the first one-thread run."""
import argparse
import csv
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CASES = [
    ("cases/benchmarks/kin1.toml", []),
    ("cases/benchmarks/caprasse.toml", []),
    ("cases/benchmarks/redeco8.toml", []),
    ("cases/benchmarks/eco9.toml", []),
    ("cases/linkages/6r-rigid.toml", []),
    ("cases/linkages/cyclohexane.toml", ["--sigma", "0.1"]),
    ("cases/linkages/6r-mobile.toml", ["--sigma", "0.1"]),
    ("cases/linkages/bicyclohexane.toml", ["--sigma", "0.1"]),
    ("cases/spherical/agile-eye.toml", []),
    ("cases/spherical/four-loop.toml", []),
]


def run_once(linkbox, case, flags, threads):
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as t:
        out = t.name
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([linkbox, "solve", os.path.join(ROOT, case), "--quiet", "--json", out, "--threads",
                        str(threads)] + flags, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    if p.returncode not in (0, 4, 5):
        sys.exit(f"{case} --threads {threads}: exit {p.returncode}\n{p.stderr}")
    with open(out) as f:
        r = json.load(f)
    os.unlink(out)
    answer = (json.dumps(r["solutions"], sort_keys=True), r.get("headline"))
    return {"wall": wall, "cpu": cpu, "search": r["stats"]["search_seconds"],
            "verify": r.get("verification", {}).get("seconds", 0.0), "answer": answer,
            "strategy": r.get("strategy", "")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--linkbox", default=os.path.join(ROOT, "build", "linkbox"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--long-after", type=float, default=60,
                    help="a case whose first one-thread run takes longer (CPU s) is run once per thread count")
    ap.add_argument("--only", help="cases whose name contains this")
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    a = ap.parse_args()
    counts = [int(t) for t in a.threads.split(",")]
    rows = []
    for case, flags in CASES:
        if a.only and a.only not in case:
            continue
        runs = {t: [] for t in counts}
        for k in range(a.runs):
            for t in counts:
                runs[t].append(run_once(a.linkbox, case, flags, t))
            if runs[counts[0]][0]["cpu"] > a.long_after:
                break
        first = runs[counts[0]][0]["answer"]
        same = all(r["answer"] == first for t in counts for r in runs[t])
        base = {key: statistics.median(r[key] for r in runs[counts[0]]) for key in ("wall", "search", "verify", "cpu")}
        for t in counts:
            med = {key: statistics.median(r[key] for r in runs[t]) for key in ("wall", "search", "verify", "cpu")}
            rows.append({
                "case": os.path.basename(case)[:-5] + (" " + " ".join(flags) if flags else ""),
                "ran": runs[t][0]["strategy"],
                "threads": t,
                "runs": len(runs[t]),
                "wall_s": round(med["wall"], 3),
                "search_s": round(med["search"], 3),
                "verify_s": round(med["verify"], 3),
                "cpu_s": round(med["cpu"], 3),
                "speedup_wall": round(base["wall"] / med["wall"], 2),
                "speedup_search": round(base["search"] / med["search"], 2) if med["search"] > 0 else "",
                "cpu_ratio": round(med["cpu"] / base["cpu"], 2),
                "same": "yes" if same else "NO",
            })
            r = rows[-1]
            print(f"{r['case']:28s} t={t} wall {r['wall_s']:8.3f} search {r['search_s']:8.3f} verify {r['verify_s']:7.3f} "
                  f"cpu {r['cpu_s']:8.3f}  same {r['same']}", file=sys.stderr)
    with open(os.path.join(a.out, "threads.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    load = os.getloadavg()[0]
    md = os.path.join(a.out, "threads.md")
    # The prose below the table (from its first "## " heading) is written by hand: kept.
    prose = ""
    if os.path.exists(md):
        with open(md) as f:
            text = f.read()
        if "\n## " in text:
            prose = text[text.index("\n## "):]
    with open(md, "w") as f:
        f.write("# Threads in one process\n\n")
        f.write(f"`python3 papers/benchmarks/threads.py --runs {a.runs} --threads {a.threads}` "
                f"({time.strftime('%Y-%m-%d %H:%M')}, {os.cpu_count()} cores, load average {load:.1f} at the end). "
                "Medians over the runs, the thread counts alternating. `wall`: the whole command; `search`: the "
                "search's own wall time; `verify`: verification's; `cpu`: user+sys of every thread. Speed-ups and "
                "the CPU ratio are against the first thread count. `same`: every run gave the first one-thread "
                "run's solution boxes, certified flags and headline.\n\n")
        cols = list(rows[0].keys())
        f.write("| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n")
        for r in rows:
            f.write("| " + " | ".join(str(r[c]) for c in cols) + " |\n")
        f.write(prose)
    sys.exit(1 if any(r["same"] == "NO" for r in rows) else 0)


if __name__ == "__main__":
    main()
