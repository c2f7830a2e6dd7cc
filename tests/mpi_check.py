#!/usr/bin/env python3
"""Distributed runs (issue 14) against one process, through the CLI under mpirun.

  mpi_check.py MPIRUN LINKBOX same CASE [FLAGS...]  same roots, headline and boxes with 3 ranks
  mpi_check.py MPIRUN LINKBOX lend                  a race's leader lends boxes, same boxes
  mpi_check.py MPIRUN LINKBOX limit                 a box limit stops every rank, pending boxes come back
  mpi_check.py MPIRUN LINKBOX interrupt             SIGINT to mpirun: partial JSON, non-zero exit
  mpi_check.py MPIRUN LINKBOX fault                 a rank that dies or hangs ends the run, exit != 0
  mpi_check.py MPIRUN LINKBOX bad-input             exit 2 with file:line, said once
  mpi_check.py MPIRUN LINKBOX handoff               linkbox without linkbox-mpi beside it: alone it
                                                    runs, under mpirun it exits 3 naming the program

Every run has a timeout: a hang fails the test instead of stalling the suite."""
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMEOUT = 120


# Under the sanitizers (.ci/run): Open MPI's libraries are built without frame pointers, so
# the fast unwinder stops inside them and LeakSanitizer cannot match what they keep for good
# against .ci/lsan.supp (by library name); the slow unwinder walks through them.
if "fast_unwind_on_malloc" not in os.environ.get("ASAN_OPTIONS", "fast_unwind_on_malloc"):
    os.environ["ASAN_OPTIONS"] += ":fast_unwind_on_malloc=0"
SANITIZERS = [v for v in ("ASAN_OPTIONS", "LSAN_OPTIONS", "UBSAN_OPTIONS") if v in os.environ]


def mpirun(mpi, ranks, env=None):
    cmd = [mpi, "--oversubscribe", "-np", str(ranks)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    for name in list(env or {}) + SANITIZERS:
        cmd += ["-x", name]
    return cmd


def run(cmd, env=None):
    full = dict(os.environ, **(env or {}))
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT, env=full)
    return p.returncode, p.stdout + p.stderr


def solve(mpi, linkbox, case, flags, out, ranks=None, env=None):
    cmd = (mpirun(mpi, ranks, env) if ranks else []) + [linkbox, "solve", os.path.join(ROOT, case), "--quiet",
                                                         "--json", out] + flags
    return run(cmd, env)


def load(path):
    with open(path) as f:
        return json.load(f)


failures = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


# What a distributed run must reproduce: the certified roots, the headline, the solution boxes
# in search-tree order (with their sub-problem and certification), the counts of the search,
# and every cluster's verification (certificates, roots, crossings), verified on any rank.
def comparable(j):
    stats = {k: j["stats"][k] for k in ("processed", "empty", "split", "solution_boxes", "certified_in_search")}
    return {"headline": j["headline"], "certified_roots": j["certified_roots"], "solutions": j["solutions"],
            "complete": j["complete"], "stats": stats, "clusters": j["clusters"]}


def same(mpi, linkbox, tmp, case, flags):
    one, many = os.path.join(tmp, "one.json"), os.path.join(tmp, "many.json")
    code, text = solve(mpi, linkbox, case, flags, one)
    check(code in (0, 4, 5), f"one process solves {case} {' '.join(flags)} (exit {code})")
    code, text = solve(mpi, linkbox, case, flags, many, ranks=3)
    check(code in (0, 4, 5), f"3 ranks solve it (exit {code}){'' if code in (0, 4, 5) else ': ' + text[-2000:]}")
    if failures:
        return
    a, b = comparable(load(one)), comparable(load(many))
    check(a["complete"] and a["solutions"], "the single run is complete and finds solution boxes")
    for key in a:
        check(a[key] == b[key], f"{key} identical to one process")
    d = load(many)["distributed"]
    check(d["ranks"] == 3 and d["boxes"] >= a["stats"]["processed"], f"3 ranks reported their boxes ({d})")
    # Rank 0 keeps two clusters per thread; the rest are spread as threads free up.
    v, threads = d["verification"], d["threads_per_rank"]
    check(v["clusters"] == len(a["clusters"]), f"the clusters were verified over the ranks ({v})")
    if v["clusters"] > 2 * threads * 3:
        check(v["clusters_on_other_ranks"] > 0, f"other ranks verified clusters ({v['clusters_on_other_ranks']})")
    return d


def limit(mpi, linkbox, tmp):
    full, part = os.path.join(tmp, "full.json"), os.path.join(tmp, "part.json")
    case = "cases/spherical/agile-eye.toml"
    code, _ = solve(mpi, linkbox, case, [], full)
    check(code == 0, "one process solves the agile eye")
    code, text = solve(mpi, linkbox, case, ["--max-boxes", "200"], part, ranks=3)
    check(code == 5, f"a box limit ends as incomplete, exit 5 (exit {code})")
    if failures:
        return
    j, f = load(part), load(full)
    check(not j["complete"] and "box limit" in j["headline"], f"incomplete, and says why: {j['headline']}")
    check(j["pending_boxes"] > 0 and j["volume_left"] > 0, f"pending boxes listed: {j['pending_boxes']}")
    check(j["stats"]["processed"] < f["stats"]["processed"], "stopped before the end")
    # Soundness: a partial run never claims a root the whole run does not have.
    roots = {json.dumps(r["box"]) for r in f["solutions"]}
    check(all(json.dumps(r["box"]) in roots for r in j["solutions"]), "its solution boxes are the whole run's")


SKIP = 77  # ctest's SKIP_RETURN_CODE for this script


def interrupt(mpi, linkbox, tmp):
    if "ASAN_OPTIONS" in os.environ:
        # mpirun kills the ranks a fixed time after forwarding the signal. After a stop, rank 0
        # reports each sub-problem never reached as a one-process run does (its sub-problem
        # built, for its domain): ~0.3 ms each in release, ~20 ms under ASan, so the four-loop's
        # ~4 000 took 80 s and the kill came first. The release build runs this test.
        print("skipped under the sanitizers: the stop path outlasts mpirun's kill timer (see the comment)")
        sys.exit(SKIP)
    out = os.path.join(tmp, "interrupted.json")
    # A search that runs for minutes; mpirun kills the ranks a second after forwarding SIGTERM
    # unless told to wait longer.
    env = {"OMPI_MCA_odls_base_sigkill_timeout": "10"}
    cmd = mpirun(mpi, 3) + [linkbox, "solve", os.path.join(ROOT, "cases/spherical/four-loop.toml"), "--prune",
                            "hc4,newton", "--json", out]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=dict(os.environ, **env))
    start = time.time()
    seen = ""
    while "sub-problems" not in seen and time.time() - start < TIMEOUT:  # the search has begun
        seen += p.stderr.readline()
    p.send_signal(signal.SIGINT)
    try:
        rest = p.communicate(timeout=TIMEOUT)[1]
    except subprocess.TimeoutExpired:
        p.kill()
        check(False, "the interrupted run ends")
        return
    check(p.returncode != 0, f"exit non-zero after an interrupt ({p.returncode})")
    check(os.path.exists(out), "the partial JSON is written" + ("" if os.path.exists(out) else ": " + rest[-1500:]))
    if os.path.exists(out):
        j = load(out)
        check(not j["complete"] and j["pending_boxes"] > 0, f"incomplete with pending boxes ({j['pending_boxes']})")
        check("interrupted" in json.dumps(j), "says it was interrupted")


def fault(mpi, linkbox, tmp):
    out = os.path.join(tmp, "fault.json")
    # Rank 1 dies in the search (after 30 boxes of the four-loop) or in verification (at its
    # first cluster of kin1's 16).
    for phase, case, after in (("search", "cases/spherical/four-loop.toml", "30"), ("verify", "cases/benchmarks/kin1.toml", "0")):
        for how in ("exit", "hang"):
            env = {"LINKBOX_MPI_TEST_DIE_RANK": "1", "LINKBOX_MPI_TEST_DIE_HOW": how, "LINKBOX_MPI_TEST_DIE_AFTER": after,
                   "LINKBOX_MPI_TEST_DIE_IN": phase, "LINKBOX_MPI_TIMEOUT": "3"}
            try:
                code, text = solve(mpi, linkbox, case, [], out, ranks=3, env=env)
            except subprocess.TimeoutExpired:
                check(False, f"a rank that {how}s in {phase} ends the run within {TIMEOUT} s")
                continue
            check(code != 0, f"a rank that {how}s in {phase}: exit non-zero ({code})")
            if how == "hang":
                check(code == 3 and "rank 1 sent nothing for 3 s" in text, "the silent rank is named, exit 3: " + text[-600:])


def bad_input(mpi, linkbox, tmp):
    bad = os.path.join(tmp, "bad.toml")
    with open(bad, "w") as f:
        f.write('kind = "polynomial"\nname = "bad"\nvariables = [ { name = "x", domain = [0, 1] } ]\nequations = [ "x +" ]\n')
    code, text = run(mpirun(mpi, 3) + [linkbox, "solve", bad, "--quiet"])
    check(code == 2, f"bad input: exit 2 ({code})")
    check(text.count(bad + ":4") == 1, "file:line said once, by rank 0: " + text[-800:])
    code, text = run(mpirun(mpi, 3) + [linkbox, "solve", bad, "--checkpoint", os.path.join(tmp, "c.ckpt")])
    check(code == 2 and text.count("not under mpirun") == 1, "checkpoints are refused, once")


def handoff(mpi, linkbox):
    # A folder beside the build's, not the temporary one: that may be mounted noexec.
    with tempfile.TemporaryDirectory(dir=os.path.dirname(os.path.abspath(linkbox))) as alone:
        copy = os.path.join(alone, "linkbox")
        with open(linkbox, "rb") as src, open(copy, "wb") as dst:
            dst.write(src.read())
        os.chmod(copy, 0o755)
        case = os.path.join(ROOT, "cases/spherical/agile-eye.toml")
        code, text = run([copy, "solve", case, "--quiet"])
        check(code == 0, f"alone, linkbox needs no linkbox-mpi ({code}): " + text[-300:])
        code, text = run(mpirun(mpi, 1) + [copy, "solve", case, "--quiet"])
        check(code == 3 and os.path.join(alone, "linkbox-mpi") + " could not start" in text,
              f"under mpirun, a missing linkbox-mpi is named, exit 3 ({code}): " + text[-600:])


def main():
    mpi, linkbox, what = sys.argv[1], sys.argv[2], sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        if what == "same":
            same(mpi, linkbox, tmp, sys.argv[4], sys.argv[5:])
        elif what == "steal":
            # One sub-problem that does not race: the idle ranks can only get boxes by asking.
            d = same(mpi, linkbox, tmp, "cases/linkages/6r-rigid.toml", ["--prune", "hc4,newton"])
            if d is not None:
                check(d["boxes_given"] > 0, f"idle ranks got subtrees ({d['boxes_given']} boxes given)")
        elif what == "lend":
            # One sub-problem whose strategies race: its leader lends boxes to the idle ranks
            # and the race still ends at one process's box.
            d = same(mpi, linkbox, tmp, "cases/benchmarks/redeco8.toml", [])
            if d is not None:
                check(d["boxes_given"] > 0, f"the race lent boxes ({d['boxes_given']} boxes)")
        elif what == "limit":
            limit(mpi, linkbox, tmp)
        elif what == "interrupt":
            interrupt(mpi, linkbox, tmp)
        elif what == "fault":
            fault(mpi, linkbox, tmp)
        elif what == "bad-input":
            bad_input(mpi, linkbox, tmp)
        elif what == "handoff":
            handoff(mpi, linkbox)
        else:
            print(__doc__)
            return 2
    n = len(failures)
    print(f"{'all checks hold' if not n else str(n) + ' check(s) failed'}")
    return 1 if n else 0


if __name__ == "__main__":
    sys.exit(main())
