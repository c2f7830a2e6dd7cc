#!/usr/bin/env python3
"""Distributed runs (issue 14): measured speed-up on 1, 2 and 4 ranks, messages and bytes per
box, and a model of 64-1024 ranks that replays the search tree a run records.

  scaling.py measure --linkbox build/linkbox [--runs 3] [--out DIR]   runs -> DIR/scaling-runs.json
  scaling.py model   --linkbox build/linkbox [--out DIR]              records trees, replays them
  scaling.py verify  --linkbox build/linkbox [--runs 3] [--out DIR]   verification over ranks -> DIR/scaling-verify.json
  scaling.py report  [--out DIR]                                      the tables of scaling.md
  scaling.py table   --linkbox build/linkbox [--cores N] [--runs 1]   issue 30's table on this machine

`table` is the one command for any machine: --threads N and mpirun -np N for N = 1, 2, 4, ...
up to the cores (default: all), on four-loop, eco10 and bicyclohexane, as a Markdown table
of search wall time (the JSON's stats.seconds, verification on, median of --runs), with the
speed-up at the largest N. MPI rows need mpirun (on one node without ssh the script sets
OMPI_MCA_plm_rsh_agent=false).

The model replays each recorded box with its measured time and the protocol of
lib/distributed/mpi_solve.cpp: idle slots get sub-problems in index order, then the oldest
pending box of the longest-running search that shares (answered at its next box boundary;
a search with fewer than two pending boxes answers dry, and is not asked again for 20 ms); a racing sub-problem is one unit. Rank 0 serves every message one at a time in
HANDLE seconds (measured), each hop takes HOP seconds, and every rank sends a heartbeat each
BEAT seconds. Merging pieces and refinement are not in the record (they are small here)."""
import argparse
import csv
import heapq
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# case, flags: the three cases of the issue; the linkages both as "auto" runs them (a race, whose
# leader lends boxes) and with a strategy named (no race: boxes given away).
CASES = [
    ("four-loop", "cases/spherical/four-loop.toml", []),
    ("6r-rigid", "cases/linkages/6r-rigid.toml", []),
    ("6r-rigid --prune hc4,newton", "cases/linkages/6r-rigid.toml", ["--prune", "hc4,newton"]),
    ("bicyclohexane", "cases/linkages/bicyclohexane.toml", []),
    ("bicyclohexane --prune hc4,newton/lp", "cases/linkages/bicyclohexane.toml", ["--prune", "hc4,newton/lp"]),
]
RANKS = [1, 2, 4]
BEAT = 0.2
DRY = 0.02  # kDryWait


def mpirun(ranks):
    cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def solved(p):
    """A linkbox run that wrote its result: exit 0 exact, 4 unresolved, 5 incomplete."""
    if p.returncode not in (0, 4, 5):
        raise subprocess.CalledProcessError(p.returncode, p.args)


def timed(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    solved(subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def measure(args):
    path = os.path.join(args.out, "scaling-runs.json")
    runs = json.load(open(path)) if args.append and os.path.exists(path) else []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.json")
        for rep in range(args.runs):
            for name, case, flags in CASES:
                if (args.only and args.only not in name) or (args.skip and args.skip in name):
                    continue
                for ranks in RANKS:
                    # 1 rank: the plain executable (what a user without MPI runs).
                    cmd = ([] if ranks == 1 else mpirun(ranks)) + [args.linkbox, "solve", os.path.join(ROOT, case),
                                                                   "--quiet", "--no-verify", "--json", out] + flags
                    wall, cpu = timed(cmd)
                    j = json.load(open(out))
                    row = {"case": name, "ranks": ranks, "rep": rep, "wall": wall, "cpu": cpu,
                           "search": j["stats"]["seconds"], "boxes": j["stats"]["processed"],
                           "distributed": j.get("distributed"), "load": os.getloadavg()[0]}
                    runs.append(row)
                    print(json.dumps(row), flush=True)
    with open(path, "w") as f:
        json.dump(runs, f, indent=1)


# Verification over the ranks: the one case whose verification is long (its curve's clusters).
VERIFY_CASES = [("bicyclohexane", "cases/linkages/bicyclohexane.toml", [])]


def verify(args):
    path = os.path.join(args.out, "scaling-verify.json")
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.json")
        for rep in range(args.runs):
            for name, case, flags in VERIFY_CASES:
                for ranks in RANKS:
                    cmd = ([] if ranks == 1 else mpirun(ranks)) + [args.linkbox, "solve", os.path.join(ROOT, case),
                                                                   "--quiet", "--json", out] + flags
                    solved(subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
                    j = json.load(open(out))
                    d = (j.get("distributed") or {}).get("verification", {})
                    row = {"case": name, "ranks": ranks, "rep": rep, "verification": j["verification"]["seconds"],
                           "clusters": len(j["clusters"]), "headline": j["headline"],
                           "elsewhere": d.get("clusters_on_other_ranks", 0),
                           "messages": d.get("messages", 0) - d.get("heartbeat_messages", 0), "bytes": d.get("bytes", 0),
                           "load": os.getloadavg()[0]}
                    runs.append(row)
                    print(json.dumps(row), flush=True)
    with open(path, "w") as f:
        json.dump(runs, f, indent=1)


def by_case_and_ranks(path):
    by = defaultdict(list)
    for r in json.load(open(path)):
        by[(r["case"], r["ranks"])].append(r)
    return by


def verify_report(args):
    path = os.path.join(args.out, "scaling-verify.json")
    if not os.path.exists(path):
        return
    print("\n| case | ranks | clusters | verification s (median) | speed-up | clusters on other ranks | messages | bytes / cluster | same headline | runs |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    by = by_case_and_ranks(path)
    for name, _, _ in VERIFY_CASES:
        base = statistics.median(x["verification"] for x in by[(name, 1)])
        for ranks in RANKS:
            rs = by.get((name, ranks))
            if not rs:
                continue
            v = statistics.median(x["verification"] for x in rs)
            same = all(x["headline"] == by[(name, 1)][0]["headline"] for x in rs)
            print(f"| {name} | {ranks}{' (2 cores: oversubscribed)' if ranks > 2 else ''} | {rs[0]['clusters']} | {v:.2f} | "
                  f"{base / v:.2f} | {statistics.median(x['elsewhere'] for x in rs):g} | "
                  f"{statistics.median(x['messages'] for x in rs):g} | "
                  f"{statistics.median(x['bytes'] / x['clusters'] for x in rs):.0f} | {'yes' if same else 'NO'} | {len(rs)} |")


# ---- the model -----------------------------------------------------------------------------

def complete(tree):
    return all(p + c in tree for p, (_, split) in tree.items() if split for c in "01")


def load_tree(path):
    """Per sub-problem: a tree {path: (seconds, split)}, or a race (several candidates): the
    winner's tree (the complete one), which its leader lends out like a tree, and the losers'
    summed seconds, which stay on the owner."""
    subs = defaultdict(lambda: defaultdict(dict))
    with open(path) as f:
        for row in csv.DictReader(f):
            subs[int(row["subproblem"])][int(row["candidate"])][row["path"]] = (float(row["seconds"]), row["outcome"] == "x")
    units = []
    for i in sorted(subs):
        cands = subs[i]
        if len(cands) > 1:
            winner = next(k for k, t in cands.items() if complete(t))
            losers = sum(s for k, c in cands.items() if k != winner for s, _ in c.values())
            units.append(("race", (cands[winner], losers)))
        else:
            units.append(("tree", next(iter(cands.values()))))
    return units


class Model:
    def __init__(self, units, slots, hop, handle, auto):
        self.units, self.slots, self.hop, self.handle, self.auto = units, slots, hop, handle, auto
        self.free = 0.0  # rank 0 busy until
        self.messages = 0
        # heartbeats take this share of rank 0 (each rank's beat in, rank 0's beat out)
        self.beat_load = 2 * slots * handle / BEAT

    def serve(self, t):
        """A message reaching rank 0 at t is handled at the returned time."""
        if self.beat_load >= 1:
            return float("inf")
        start = max(t, self.free)
        self.free = start + self.handle / (1 - self.beat_load)
        self.messages += 1
        return self.free

    def run(self):
        n = self.slots
        hop = self.hop
        events = []  # (time, seq, kind, worker)
        seq = 0
        state = [None] * n  # per worker: dict(unit, kind, pending(list), started, dry_until)
        next_unit = 0
        unit_id = 0
        busy_time = 0.0

        def push(t, kind, w):
            nonlocal seq
            heapq.heappush(events, (t, seq, kind, w))
            seq += 1

        for w in range(n):
            push(hop, "ask", w)
        end = 0.0
        thieves = {}  # victim -> thief
        while events:
            t, _, kind, w = heapq.heappop(events)
            if kind not in ("ask", "retry", "next"):  # an idle worker's request is not work
                end = max(end, t)
            if kind in ("ask", "retry", "next"):  # w is idle and asks rank 0 (or rank 0 tries again for it)
                t0 = self.serve(t) if kind != "retry" else t
                # sub-problems are queued at each slot in batches: the next one starts at once
                begin = t if kind == "next" else t0 + hop
                if next_unit < len(self.units):
                    k, data = self.units[next_unit]
                    next_unit += 1
                    unit_id += 1
                    self.messages += 1
                    # under "auto" rank 0 learns from a heartbeat that the sub-problem shares; a
                    # race's owner also runs the losers' turns (their seconds, when its own
                    # boxes are done: a race ends when the winner's last box is in)
                    tree, serial = data if k == "race" else (data, 0.0)
                    state[w] = {"id": unit_id, "kind": "tree", "tree": tree, "pending": [""], "start": begin,
                                "dry_until": 0, "asked": False, "auto": self.auto, "serial": serial}
                    push(begin, "box", w)
                else:
                    victims = [v for v in range(n) if state[v] and state[v]["kind"] == "tree" and v not in thieves
                               and t0 >= state[v]["start"] + (BEAT if state[v]["auto"] else 0)
                               and t0 >= state[v]["dry_until"]]
                    if not victims:  # tried again at rank 0's next message (one arrives every hop or so)
                        push(t0 + 2 * hop, "retry", w)
                        continue
                    v = min(victims, key=lambda v: state[v]["id"])
                    thieves[v] = w
                    self.messages += 1
                    state[v]["asked"] = t0 + hop
            elif kind == "box":  # w starts its next box, or answers a steal first
                s = state[w]
                if s["asked"] and t >= s["asked"]:
                    s["asked"] = False
                    thief = thieves.pop(w)
                    t1 = self.serve(t + hop)
                    if len(s["pending"]) >= 2:
                        node = s["pending"].pop(0)
                        unit_id += 1
                        self.messages += 1
                        state[thief] = {"id": unit_id, "kind": "tree", "tree": s["tree"], "pending": [node],
                                        "start": t1 + hop, "dry_until": 0, "asked": False, "auto": False, "serial": 0.0}
                        push(t1 + hop, "box", thief)
                    else:
                        s["dry_until"] = t1 + DRY
                        push(t1 + hop, "ask", thief)
                if not s["pending"]:
                    busy_time += s["serial"]
                    push(t + s["serial"], "done", w)
                    s["serial"] = 0.0
                    continue
                path = s["pending"].pop()
                seconds, split = s["tree"][path]
                busy_time += seconds
                if split:  # depth-first: the lower half next
                    for child in (path + "1", path + "0"):
                        if child in s["tree"]:
                            s["pending"].append(child)
                push(t + seconds, "box", w)
            elif kind == "done":
                state[w] = None
                for v, thief in list(thieves.items()):
                    if v == w:
                        del thieves[v]
                        push(t, "ask", thief)
                push(t, "next", w) if next_unit < len(self.units) else push(t + hop, "ask", w)
            if next_unit >= len(self.units) and all(s is None for s in state) and not any(
                    e[2] in ("box", "done") for e in events):
                break
        return end, busy_time


def model(args):
    runs = json.load(open(os.path.join(args.out, "scaling-runs.json"))) if os.path.exists(
        os.path.join(args.out, "scaling-runs.json")) else []
    # From runs with many messages: in a short run the count is dominated by the end (joining
    # the slots), not by serving messages.
    handles = [r["distributed"]["handling_seconds"] / r["distributed"]["handled"] for r in runs
               if r.get("distributed") and r["distributed"].get("handled", 0) > 1000]
    handle = statistics.median(handles) if handles else 20e-6
    path = os.path.join(args.out, "scaling-model.json")
    results = {"handle": handle, "hop": args.hop, "cases": {}}
    if os.path.exists(path):  # the cases modelled before (--only) stay
        results["cases"] = json.load(open(path))["cases"]
    with tempfile.TemporaryDirectory() as tmp:
        for name, case, flags in CASES:
            if args.only and args.only not in name:
                continue
            rec = os.path.join(args.out, name.split()[0] + ("-" + flags[1].replace(",", "-").replace("/", "-") if flags else "") + ".tree.csv")
            if not os.path.exists(rec):
                solved(subprocess.run([args.linkbox, "solve", os.path.join(ROOT, case), "--quiet", "--no-verify",
                                       "--record-tree", rec, "--json", os.path.join(tmp, "r.json")] + flags,
                                      stdout=subprocess.DEVNULL))
            units = load_tree(rec)
            rows = []
            for p in [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024]:
                m = Model(units, p, args.hop, handle, "--prune" not in flags)
                makespan, busy = m.run()
                rows.append({"ranks": p, "makespan": makespan, "busy": busy, "messages": m.messages,
                             "rank0_load": m.messages * handle / makespan + m.beat_load})
            base = rows[0]["makespan"]
            for r in rows:
                r["speedup"] = base / r["makespan"]
            boxes = sum(len(d) if k == "tree" else len(d[0]) for k, d in units)
            results["cases"][name] = {"rows": rows, "units": len(units), "tree_boxes": boxes,
                                      "critical_path": critical_path(units)}
            print(name, json.dumps(results["cases"][name]["rows"][-1]), flush=True)
    with open(path, "w") as f:
        json.dump(results, f, indent=1)


def critical_path(units):
    """The longest chain that cannot be split: a tree's longest root-to-leaf chain, plus for a
    race the losers' seconds (on its owner)."""
    worst = 0.0
    for kind, data in units:
        serial = 0.0
        if kind == "race":
            data, serial = data
        best = {}
        for path in sorted(data, key=len, reverse=True):
            s, split = data[path]
            best[path] = s + max((best.get(path + c, 0) for c in "01"), default=0)
        worst = max(worst, serial + best.get("", 0))
    return worst


def report(args):
    print("| case | ranks | wall s (median) | search s | CPU s | speed-up (wall) | speed-up (search) | CPU ratio | messages / box | bytes / box | boxes given | runs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    by = by_case_and_ranks(os.path.join(args.out, "scaling-runs.json"))
    for name, _, _ in CASES:
        if (name, 1) not in by:
            continue
        base = by[(name, 1)]
        bw, bs, bc = (statistics.median(x[k] for x in base) for k in ("wall", "search", "cpu"))
        for ranks in RANKS:
            rs = by.get((name, ranks))
            if not rs:
                continue
            w, s, c = (statistics.median(x[k] for x in rs) for k in ("wall", "search", "cpu"))
            d = [x["distributed"] for x in rs if x["distributed"]]
            if d:
                mb = statistics.median((x["messages"] - x["heartbeat_messages"]) / max(1, x["boxes"]) for x in d)
                bb = statistics.median((x["bytes"] - x["heartbeat_bytes"]) / max(1, x["boxes"]) for x in d)
                given = statistics.median(x["boxes_given"] for x in d)
                extra = f"{mb:.3g} | {bb:.3g} | {given:g}"
            else:
                extra = "- | - | -"
            print(f"| {name} | {ranks}{' (2 cores: oversubscribed)' if ranks > 2 else ''} | {w:.2f} | {s:.2f} | {c:.2f} | "
                  f"{bw / w:.2f} | {bs / s:.2f} | {c / bc:.2f} | {extra} | {len(rs)} |")
    verify_report(args)
    path = os.path.join(args.out, "scaling-model.json")
    if not os.path.exists(path):
        return
    m = json.load(open(path))
    print(f"\nModel: rank 0 handles a message in {m['handle'] * 1e6:.1f} us (measured), a hop takes {m['hop'] * 1e3:.2f} ms\n")
    print("| case | units | critical path s | " + " | ".join(f"{r['ranks']}" for r in next(iter(m['cases'].values()))['rows']) + " |")
    print("|---|---|---|" + "---|" * len(next(iter(m['cases'].values()))['rows']))
    for name, c in m["cases"].items():
        print(f"| {name} speed-up | {c['units']} | {c['critical_path']:.3g} | " +
              " | ".join(f"{r['speedup']:.1f}" for r in c["rows"]) + " |")
        print(f"| {name} rank 0 load | | | " + " | ".join(f"{r['rank0_load']:.2f}" for r in c["rows"]) + " |")


# Issue 30's table: label, case, flags, "threads" or "mpi".
TABLE = [
    ("four-loop `--threads N`", "cases/spherical/four-loop.toml", [], "threads"),
    ("four-loop `mpirun -np N`", "cases/spherical/four-loop.toml", [], "mpi"),
    ("eco10 `--threads N` (auto)", "cases/benchmarks/eco10.toml", [], "threads"),
    ("bicyclohexane `--threads N` (auto)", "cases/linkages/bicyclohexane.toml", [], "threads"),
    ("bicyclohexane `mpirun -np N --prune hc4,newton/lp`", "cases/linkages/bicyclohexane.toml",
     ["--prune", "hc4,newton/lp"], "mpi"),
    ("bicyclohexane `mpirun -np N` (auto)", "cases/linkages/bicyclohexane.toml", [], "mpi"),
]


def search_seconds(cmd, out):
    """The search's wall time of one run (any exit code: limits and unresolved clusters end
    non-zero), or None when it wrote no result."""
    if os.path.exists(out):
        os.remove(out)
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=1800)
    return json.load(open(out))["stats"]["seconds"] if os.path.exists(out) else None


def table(args):
    cores = args.cores or os.cpu_count()
    counts = [n for n in (1, 2, 4, 8, 16, 32, 64, 128, 256) if n <= cores]
    have_mpi = subprocess.run(["which", "mpirun"], capture_output=True).returncode == 0
    os.environ.setdefault("OMPI_MCA_plm_rsh_agent", "false")
    print(f"| run | " + " | ".join(str(n) for n in counts) + f" | speed-up at {counts[-1]} |")
    print("|---|" + "---|" * (len(counts) + 1))
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.json")
        for label, case, flags, mode in TABLE:
            if mode == "mpi" and not have_mpi:
                continue
            cells = []
            for n in counts:
                base = [args.linkbox, "solve", os.path.join(ROOT, case), "--quiet", "--json", out] + flags
                cmd = base + ["--threads", str(n)] if mode == "threads" else (mpirun(n) if n > 1 else []) + base
                times = [t for t in (search_seconds(cmd, out) for _ in range(args.runs)) if t is not None]
                cells.append(statistics.median(times) if times else None)
            shown = " | ".join("-" if t is None else f"{t:.2f}" for t in cells)
            speedup = f"{cells[0] / cells[-1]:.1f}x" if cells[0] and cells[-1] else "-"
            print(f"| {label} | {shown} | {speedup} |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=["measure", "model", "verify", "report", "table"])
    ap.add_argument("--linkbox", default=os.path.join(ROOT, "build", "linkbox"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--only", help="cases whose name contains this")
    ap.add_argument("--skip", help="not the cases whose name contains this")
    ap.add_argument("--append", action="store_true", help="add to the runs already measured")
    ap.add_argument("--hop", type=float, default=3e-4, help="seconds per message hop (polling + MPI latency)")
    ap.add_argument("--cores", type=int, help="table: the largest N (default: every core)")
    args = ap.parse_args()
    {"measure": measure, "model": model, "verify": verify, "report": report, "table": table}[args.what](args)


if __name__ == "__main__":
    sys.exit(main())
