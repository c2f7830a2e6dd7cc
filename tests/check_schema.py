#!/usr/bin/env python3
"""Validates what `linkbox solve --json` writes against docs/result.schema.json (JSON Schema
2020-12, python3-jsonschema), for every case file under cases/ (*.toml, *.bch, *.cuik) and for
outputs that carry the keys a plain run may lack:

  - an incomplete run (`--max-boxes 5` on the four-loop mechanism): `stop_reason`, pending boxes;
  - a run with inequalities whose verification proves a cluster infeasible: `verification.
    inequalities`/`infeasible`, a cluster's `inequality`;
  - a curve case run to the end: curve clusters with `crossings` and a proved `map`;
  - a run with --no-verify: no `verification`, `clusters`, `roots`, `headline`.

Each run must end with a result (exit 0 exact, 4 unresolved or 5 incomplete: only an
interrupt, bad input or an internal error exit otherwise), its output must validate, and its `roots` must agree with
the rest: one per distinct certified root (len(roots) == certified_roots), each pointing at a
certified cluster that is not a duplicate, with that cluster's root as its box and its
midpoint inside the box; and `linkbox check` must accept every output with certificates.

    python3 tests/check_schema.py LINKBOX_BINARY [--quick]

--quick runs the special outputs and one small case per reader and kind only (a few seconds).
Runs go two at a time, in a temporary folder. Prints one line per output, the first validation
error of each failure, and exits 1 on any failure."""
import concurrent.futures
import glob
import json
import os
import resource
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMA = os.path.join(ROOT, "docs", "result.schema.json")
WORKERS = 2
RUN_TIMEOUT = 300  # seconds: a run that hangs fails the test instead of hanging it

# Every bundled case runs with these. The box limit, not the clock, is meant to stop the large
# ones, so that their outputs are the same on a fast or a loaded machine.
DEFAULT_LIMITS = ["--max-boxes", "20000", "--time-limit", "20"]
# Lower box limits where 20000 boxes cost ~10 s of CPU or more (measured on one core: rings-6-7
# 12.4 s, bicyclohexane 11 s; everything else is under 2.5 s). A loaded machine would also make
# them hit the 20 s clock first, so their outputs would vary. Both still stop at the box limit
# with pending boxes, as they do at 20000 (rings-6-7 with no solution box yet, either way).
LIMITS = {
    "cases/linkages/rings-6-7.toml": ["--max-boxes", "3000", "--time-limit", "20"],  # ~2 s CPU
    "cases/linkages/bicyclohexane.toml": ["--max-boxes", "10000", "--time-limit", "20"],  # ~3 s CPU, 3 clusters
}
# Started first (the longest runs and validations), so that the two workers end together.
SLOW = {"cases/linkages/bicyclohexane.toml", "cases/linkages/rings-6-7.toml", "cases/spherical/four-loop.toml",
        "cases/hard/linkage-scales.toml", "cases/linkages/6r-mobile.toml", "cases/benchmarks/eco10.toml",
        "cases/benchmarks/eco11.toml", "cases/curves/fourbar-parallelogram.toml", "cases/hard/gimbal-lock.toml",
        "cases/hard/linkage-twist-1e-7.toml"}

# (label, case, flags, what the output must show so that it tests what it is here for)
SPECIAL = [
    ("incomplete", "cases/spherical/four-loop.toml", ["--max-boxes", "5"], "incomplete"),
    # kin-angles-elbow-up has two inequalities; --prune newton ignores them in the search (the
    # case file's comment), so verification proves the elbow-down root infeasible.
    ("inequalities", "cases/polynomial/kin-angles-elbow-up.toml", ["--prune", "newton"], "infeasible"),
    # The case's own settings, no limits: complete, its two closed curves mapped and proved.
    ("curve map", "cases/curves/fourbar-grashof.toml", [], "map"),
    ("no verify", "cases/spherical/wrist.toml", ["--no-verify"], "no-verify"),
]

# --quick: one small case per reader and per kind, and the case whose failed certificates
# have unbounded images.
QUICK = [
    "cases/spherical/wrist.toml",
    "cases/polynomial/circle-line.toml",
    "cases/polynomial/kin-angles.toml",
    "cases/benchmarks/kin1.bch",
    "cases/benchmarks/cyclohexan3d.cuik",
    "cases/hard/close-roots-unresolved.toml",
    "cases/linkages/6r-rigid-limits.toml",
]


def case_files():
    found = []
    for ext in ("toml", "bch", "cuik"):
        found += glob.glob(os.path.join(ROOT, "cases", "**", "*." + ext), recursive=True)
    return sorted(os.path.relpath(f, ROOT) for f in found)


def run(binary, case, flags, out):
    """Runs one solve; returns (exit code, wall seconds, CPU seconds, stderr's tail)."""
    cmd = [binary, "solve", case, "--json", out, "--quiet", "--threads", "1"] + flags
    start = time.monotonic()
    with open(out + ".log", "w+") as log:
        p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=log)
        timer = threading.Timer(RUN_TIMEOUT, p.kill)
        timer.start()
        try:
            _, status, usage = os.wait4(p.pid, 0)
        finally:
            timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)  # reaped here; Popen must not wait again
        log.seek(0)
        tail = log.read()[-2000:]
    return p.returncode, time.monotonic() - start, usage.ru_utime + usage.ru_stime, tail


def roots_problems(j):
    """What is inconsistent in `roots` (empty when verification did not run)."""
    if "roots" not in j:
        return []
    problems = []
    roots, clusters = j["roots"], j["clusters"]
    if len(roots) != j["certified_roots"]:
        problems.append("%d roots listed, certified_roots says %d" % (len(roots), j["certified_roots"]))
    if j["verification"]["certified_roots"] != j["certified_roots"]:
        problems.append("verification.certified_roots %d, certified_roots %d"
                        % (j["verification"]["certified_roots"], j["certified_roots"]))
    distinct = [k for k, c in enumerate(clusters) if c["status"] == "certified" and "duplicate_of" not in c]
    if [r["cluster"] for r in roots] != distinct:
        problems.append("roots point at clusters %s, the distinct certified ones are %s"
                        % ([r["cluster"] for r in roots], distinct))
    n = len(j["variables"])
    for i, r in enumerate(roots):
        where = "roots/%d" % i
        if len(r["midpoint"]) != n or len(r["box"]) != n:
            problems.append("%s: %d midpoint coordinates and %d intervals for %d variables"
                            % (where, len(r["midpoint"]), len(r["box"]), n))
        for v, (m, (lo, hi)) in enumerate(zip(r["midpoint"], r["box"])):
            if not lo <= m <= hi:
                problems.append("%s: midpoint %r of %s outside [%r, %r]" % (where, m, j["variables"][v], lo, hi))
        if r["cluster"] < len(clusters) and clusters[r["cluster"]].get("root") != r["box"]:
            problems.append("%s: box differs from cluster %d's root" % (where, r["cluster"]))
    return problems


def special_problems(j, expect):
    """What the output lacks that it is here to test."""
    if expect == "incomplete":
        ok = not j["complete"] and j.get("stop_reason") == "box limit reached" and j["pending_boxes"] > 0
    elif expect == "infeasible":
        ok = (j["verification"].get("inequalities", 0) > 0 and j["verification"].get("infeasible", 0) > 0
              and any(c["status"] == "infeasible" and "inequality" in c for c in j["clusters"]))
    elif expect == "map":
        ok = j["complete"] and any(c.get("map", {}).get("proved") for c in j["clusters"])
    elif expect == "no-verify":
        ok = not any(k in j for k in ("verification", "clusters", "roots", "headline", "certified_roots"))
    else:
        ok = True
    return [] if ok else ["the output does not show what this run is for (%s)" % expect]


VALIDATOR = None  # one per worker process, made by load_validator


def load_validator():
    global VALIDATOR
    import jsonschema
    with open(SCHEMA) as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    VALIDATOR = jsonschema.Draft202012Validator(schema)


def first_error(j):
    import jsonschema
    error = jsonschema.exceptions.best_match(VALIDATOR.iter_errors(j))
    if error is None:
        return None
    path = "/" + "/".join(str(p) for p in error.absolute_path)
    message = error.message
    if len(message) > 300:  # it quotes a large instance: say which rule failed instead
        message = "fails %s %s" % (error.validator, json.dumps(error.validator_value)[:200])
    return "%s: %s (schema: %s)" % (path, message, "/".join(str(p) for p in error.absolute_schema_path))


def check(binary, tmp, k, job):
    """Runs one job and validates its output (in a worker process: validation is CPU-bound)."""
    name, case, flags, expect = job
    out = os.path.join(tmp, "%02d.json" % k)
    rc, wall, cpu, tail = run(binary, case, flags, out)
    problems = []
    if rc not in (0, 4, 5):  # exact, unresolved, incomplete: a result was written
        killed = " (killed: over %d s)" % RUN_TIMEOUT if rc == -9 and wall >= RUN_TIMEOUT else ""
        problems.append("exit code %d%s: %s" % (rc, killed, tail.strip()[-500:]))
    else:
        try:
            with open(out) as f:
                j = json.load(f)
        except (OSError, ValueError) as e:
            problems.append("no JSON: %s" % e)
        else:
            error = first_error(j)
            if error:
                problems.append(error)
            else:
                problems += roots_problems(j) + special_problems(j, expect) + check_problems(binary, case, out, j)
    return wall, cpu, problems


def check_problems(binary, case, out, j):
    """`linkbox check` must accept every fresh result that has certificates."""
    if "clusters" not in j:
        return []
    r = subprocess.run([binary, "check", out, "--case", os.path.join(ROOT, case)], cwd=ROOT,
                       capture_output=True, text=True, timeout=RUN_TIMEOUT)
    return [] if r.returncode == 0 else ["linkbox check exits %d: %s" % (r.returncode, r.stderr.strip()[-500:])]


def main():
    args = sys.argv[1:]
    quick = "--quick" in args
    args = [a for a in args if a != "--quick"]
    if len(args) != 1:
        sys.exit(__doc__)
    binary = os.path.abspath(args[0])
    if not os.access(binary, os.X_OK):
        sys.exit("not an executable: " + binary)
    try:
        load_validator()  # here first: a broken schema or a missing jsonschema fails at once
    except ImportError:
        sys.exit("check_schema.py needs python3-jsonschema (.ci/install installs it)")

    cases = QUICK if quick else case_files()
    missing = [c for c in cases + [s[1] for s in SPECIAL] if not os.path.exists(os.path.join(ROOT, c))]
    if missing:
        sys.exit("missing case files: " + ", ".join(missing))
    jobs = [(c, c, LIMITS.get(c, DEFAULT_LIMITS), None) for c in cases]
    jobs += [("%s (%s)" % (c, label), c, flags, expect) for label, c, flags, expect in SPECIAL]
    # The longest first, so that the two workers finish together.
    order = sorted(range(len(jobs)), key=lambda k: jobs[k][1] not in SLOW)

    start = time.monotonic()
    failures = 0
    with tempfile.TemporaryDirectory(prefix="linkbox-schema-") as tmp:
        with concurrent.futures.ProcessPoolExecutor(WORKERS, initializer=load_validator) as pool:
            futures = {k: pool.submit(check, binary, tmp, k, jobs[k]) for k in order}
            for k, (name, _, flags, _) in enumerate(jobs):
                wall, cpu, problems = futures[k].result()
                failures += bool(problems)
                print("%-4s %-58s %6.1f s wall %6.1f s CPU  %s"
                      % ("FAIL" if problems else "ok", name, wall, cpu, " ".join(flags)), flush=True)
                for p in problems:
                    print("     " + p, flush=True)
    elapsed = time.monotonic() - start
    ours = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)  # the workers, and linkbox under them
    print("%d outputs, %d failed; %.1f s wall, %.1f s CPU in all"
          % (len(jobs), failures, elapsed, ours.ru_utime + ours.ru_stime + children.ru_utime + children.ru_stime))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
