#!/usr/bin/env python3
"""Runs every bundled case with fixed settings and compares the JSON results of two builds,
ignoring timings: a refactoring must not change a single box, certificate or headline.

    python3 tests/same_results.py run BINARY OUTDIR     # writes OUTDIR/<case>-<strategy>.json
    python3 tests/same_results.py diff DIR_A DIR_B      # exit 1 and the first differences if any

Runs are limited by box count (never by time), so they are deterministic.
"""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# case, flags. Covers every bundled case and each contractor, verified and float.
RUNS = [
    ("cases/spherical/wrist.toml", ["--prune", "trapezoid"]),
    ("cases/spherical/agile-eye.toml", ["--prune", "trapezoid"]),
    ("cases/spherical/four-loop.toml", ["--prune", "trapezoid"]),
    ("cases/spherical/wrist.toml", ["--prune", "trapezoid,newton", "--arith", "float"]),
    ("cases/linkages/6r-rigid.toml", ["--prune", "hc4,lp", "--sigma", "1e-3"]),
    ("cases/linkages/6r-mobile.toml", ["--prune", "lp", "--sigma", "0.1", "--max-boxes", "400"]),
    ("cases/linkages/cyclohexane.toml", ["--prune", "lp", "--sigma", "0.1"]),
    ("cases/linkages/bicyclohexane.toml", ["--prune", "lp", "--sigma", "0.1", "--max-boxes", "60"]),
    ("cases/linkages/rings-6-7.toml", ["--prune", "hc4,lp", "--sigma", "1e-3", "--max-boxes", "300"]),
    ("cases/polynomial/circle-line.toml", ["--prune", "hc4,newton"]),
    ("cases/polynomial/planted-cubic.toml", ["--prune", "lp"]),
    ("cases/polynomial/planted-cubic.toml", ["--prune", "hc4", "--arith", "float"]),
    ("cases/polynomial/planted-cubic.toml", ["--prune", "newton", "--lp", "exact"]),
    ("cases/hard/wrist-faces.toml", ["--prune", "trapezoid"]),
    ("cases/hard/close-roots.toml", ["--prune", "newton", "--sigma", "1e-10"]),
    ("cases/hard/close-roots-unresolved.toml", ["--prune", "hc4,lp", "--sigma", "1e-9"]),
    ("cases/hard/tangent-circle-line.toml", ["--prune", "hc4", "--sigma", "1e-6"]),
    ("cases/hard/wrist-twist-1e-7.toml", ["--prune", "trapezoid", "--sigma", "1e-8"]),
    ("cases/hard/linkage-scales.toml", ["--prune", "hc4,lp", "--sigma", "1e-3"]),
    ("cases/hard/no-root.toml", ["--prune", "hc4,lp", "--sigma", "1e-8"]),
    ("cases/hard/gimbal-lock.toml", ["--prune", "trapezoid", "--sigma", "1e-2"]),
    # The default (the auto race), one thread and two, and each reader.
    ("cases/spherical/agile-eye.toml", []),
    ("cases/spherical/four-loop.toml", ["--threads", "2"]),
    ("cases/linkages/cyclohexane.toml", []),
    ("cases/linkages/6r-mobile.toml", ["--threads", "2"]),
    ("cases/benchmarks/kin1.toml", ["--threads", "2"]),
    ("cases/benchmarks/eco9.bch", []),
    ("cases/benchmarks/caprasse.bch", ["--threads", "2"]),
    ("cases/benchmarks/cyclohexan3d.cuik", ["--max-boxes", "3000"]),
    ("cases/polynomial/kin-angles.toml", []),
    # Curve maps.
    ("cases/curves/fourbar-grashof.toml", []),
    ("cases/curves/fourbar-half-domain.toml", ["--prune", "hc4,newton"]),
    ("cases/curves/fourbar-parallelogram.toml", []),
    ("cases/curves/circle-3d.toml", ["--threads", "2"]),
]

TIMING_KEYS = {"seconds", "cpu_seconds", "search_seconds", "wall_seconds", "time", "lp_microseconds", "us_per_lp"}
# Statistics summed over threads in whatever order they finish: equal up to rounding.
SUMMED_KEYS = {"volume_removed"}


def run_name(case, flags):
    stem = os.path.splitext(os.path.basename(case))[0]
    tag = "_".join(f.lstrip("-") for f in flags).replace(",", "+") or "default"
    stem += "-" + os.path.splitext(case)[1][1:]
    return f"{stem}__{tag}.json"


def strip(obj):
    if isinstance(obj, dict):
        out = {k: strip(v) for k, v in obj.items() if k not in TIMING_KEYS}
        if isinstance(out.get("case_file"), str):  # the same case from another checkout
            out["case_file"] = "cases/" + out["case_file"].split("cases/", 1)[-1]
        return out
    if isinstance(obj, list):
        return [strip(v) for v in obj]
    return obj


def first_difference(a, b, path="$"):
    if type(a) is not type(b):
        return f"{path}: {type(a).__name__} vs {type(b).__name__}"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k}: only in {'second' if k not in a else 'first'}"
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: length {len(a)} vs {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    if path.rsplit(".", 1)[-1] in SUMMED_KEYS and isinstance(a, float):
        return None if abs(a - b) <= 1e-9 * max(abs(a), abs(b)) else f"{path}: {a!r} vs {b!r}"
    return None if a == b else f"{path}: {a!r} vs {b!r}"


def run(binary, outdir):
    os.makedirs(outdir, exist_ok=True)
    for case, flags in RUNS:
        out = os.path.join(outdir, run_name(case, flags))
        cmd = [binary, "solve", os.path.join(ROOT, case), *flags, "--quiet", "--json", out]
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        print(f"{r.returncode} {run_name(case, flags)}", flush=True)
        if r.returncode not in (0, 4, 5):  # exact, unresolved, incomplete: a result
            print(r.stderr, file=sys.stderr)


def diff(a_dir, b_dir):
    bad = 0
    for case, flags in RUNS:
        name = run_name(case, flags)
        pa, pb = os.path.join(a_dir, name), os.path.join(b_dir, name)
        if not (os.path.exists(pa) and os.path.exists(pb)):
            print(f"MISSING {name}")
            bad += 1
            continue
        with open(pa) as fa, open(pb) as fb:
            d = first_difference(strip(json.load(fa)), strip(json.load(fb)))
        if d:
            print(f"DIFFERS {name}: {d}")
            bad += 1
    print("identical apart from timings" if not bad else f"{bad} run(s) differ")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("run", "diff"):
        sys.exit(__doc__)
    if sys.argv[1] == "run":
        run(os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3]))
    else:
        sys.exit(diff(sys.argv[2], sys.argv[3]))
