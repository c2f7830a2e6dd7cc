#!/usr/bin/env python3
"""The soundness oracle of the safe LP backend on the full set (issue 13).

Records every LP relaxation (LINKBOX_LP_RECORD, lib/prune/lp/lp_record.hpp) of complete
`linkbox solve --prune lp --lp safe --lp-order given` searches on the bundled cases, then re-solves each recorded
min/max exactly (the hidden test "LP oracle on a record file" of tests/unit/prune/test_lp_oracle.cpp:
ExactLp, i.e. CLP's basis checked and repaired in rationals, with CGAL's QP solver
independently on a sample and on every infeasibility claim) and checks that

  - every safe lower bound (min) is <= the exact optimum and every upper bound (max) >= it
    ("wrong side" must be 0),
  - every infeasibility the safe backend claims (it discards a box) is exactly infeasible
    (CGAL), and
  - ExactLp and CGAL agree to the bit where both ran,

and reports how far the safe bounds lie from the exact ones.

Usage: python3 papers/porta-iterated-lp/lp_oracle.py [--build build] [--every 1]
           [--cgal-every 200] [--cgal-cap 200] [--cases 6r-rigid,cyclohexane,...]

Writes lp_oracle.md beside this script and prints it. The record files go to a temporary
directory (about 15 MB per case).
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# name -> (case file, extra solve arguments)
CASES = {
    "6r-rigid": ("cases/linkages/6r-rigid.toml", []),
    "cyclohexane": ("cases/linkages/cyclohexane.toml", ["--sigma", "0.1"]),
    "6r-mobile": ("cases/linkages/6r-mobile.toml", ["--sigma", "0.1"]),
    "wrist": ("cases/spherical/wrist.toml", []),
    "agile-eye": ("cases/spherical/agile-eye.toml", []),
}
DEFAULT = ["6r-rigid", "cyclohexane", "6r-mobile", "wrist", "agile-eye"]


def run_case(build, key, every, cgal_every, cgal_cap, tmp):
    case_file, extra = CASES[key]
    record = os.path.join(tmp, key + ".rec")
    if os.path.exists(record):
        os.remove(record)
    env = dict(os.environ, LINKBOX_LP_RECORD=record, LINKBOX_LP_RECORD_EVERY=str(every))
    cmd = [os.path.join(build, "linkbox"), "solve", os.path.join(ROOT, case_file), "--prune", "lp", "--lp", "safe", "--lp-order", "given",
           "--quiet", "--no-verify", "--json", os.path.join(tmp, key + ".json")] + extra
    p = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL)
    if p.returncode not in (0, 4, 5):  # exact, unresolved, incomplete: a result was written
        raise subprocess.CalledProcessError(p.returncode, p.args)
    with open(os.path.join(tmp, key + ".json")) as f:
        result = json.load(f)
    env = dict(os.environ, LINKBOX_LP_ORACLE_RECORD=record, LINKBOX_LP_ORACLE_CGAL_EVERY=str(cgal_every),
               LINKBOX_LP_ORACLE_CGAL_CAP=str(cgal_cap))
    t0 = time.process_time()
    started = time.time()
    out = subprocess.run([os.path.join(build, "linkbox_unit_tests"), "LP oracle on a record file"], env=env,
                         capture_output=True, text=True)
    m = re.search(r"^LP oracle: (\{.*\})$", out.stdout, re.M)
    if not m:
        sys.exit("oracle run failed on %s:\n%s\n%s" % (key, out.stdout[-3000:], out.stderr[-3000:]))
    stats = json.loads(m.group(1))
    stats["passed"] = out.returncode == 0
    stats["seconds"] = time.time() - started
    stats["complete"] = result.get("complete")
    stats["record_mb"] = os.path.getsize(record) / 1e6
    del t0
    os.remove(record)
    return stats


def fmt(x):
    return "%.2g" % x if x else "0"


def report(rows, args, started):
    lines = ["# LP oracle: safe bounds against the exact optimum", ""]
    lines.append("`python3 papers/porta-iterated-lp/lp_oracle.py` (%s; %s; CGAL on every "
                 "%s-th bounded solve, at most %s CGAL solves per case, plus every infeasibility claim). Each case "
                 "runs `linkbox solve --prune lp --lp safe --lp-order given` to completion (the curves at sigma 0.1, the rest at "
                 "their default), recording every LP relaxation with its successive column bounds; each recorded "
                 "min/max is then solved exactly (ExactLp: CLP's basis checked and repaired in rationals, CGAL's "
                 "QP solver when that fails)." % (started, "every loaded LP recorded" if args.every == 1 else
                                                  "every %d-th loaded LP recorded" % args.every, args.cgal_every,
                                                  args.cgal_cap))
    lines.append("")
    lines.append("| case | LPs | solves (min/max) | safe: bounded / infeasible / unknown | wrong side | infeasible claims confirmed by CGAL / refuted | exactly empty, only bounded by safe | ExactLp vs CGAL: compared / mismatched | exact strictly tighter |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    tot = {}
    for key, s in rows:
        for k in ("lps", "solves", "safe_bounded", "safe_infeasible", "safe_unknown", "wrong_side", "infeasible_confirmed",
                  "infeasible_refuted", "missed_infeasible", "cgal_compared", "cgal_mismatch", "exact_tighter"):
            tot[k] = tot.get(k, 0) + s[k]
        lines.append("| %s | %d | %d | %d / %d / %d | **%d** | %d / **%d** | %d | %d / **%d** | %d |" % (
            key, s["lps"], s["solves"], s["safe_bounded"], s["safe_infeasible"], s["safe_unknown"], s["wrong_side"],
            s["infeasible_confirmed"], s["infeasible_refuted"], s["missed_infeasible"], s["cgal_compared"],
            s["cgal_mismatch"], s["exact_tighter"]))
    lines.append("| **all** | %d | %d | %d / %d / %d | **%d** | %d / **%d** | %d | %d / **%d** | %d |" % (
        tot["lps"], tot["solves"], tot["safe_bounded"], tot["safe_infeasible"], tot["safe_unknown"], tot["wrong_side"],
        tot["infeasible_confirmed"], tot["infeasible_refuted"], tot["missed_infeasible"], tot["cgal_compared"],
        tot["cgal_mismatch"], tot["exact_tighter"]))
    lines.append("")
    lines.append("Distance |exact - safe| where both are bounded (absolute; and relative to the column's width at the time of the solve), quantiles:")
    lines.append("")
    lines.append("| case | p50 | p90 | p99 | max | relative p50 | p90 | p99 | max |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    for key, s in rows:
        d, r = s["distance"], s["relative"]
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            key, fmt(d["p50"]), fmt(d["p90"]), fmt(d["p99"]), fmt(d["max"]), fmt(r["p50"]), fmt(r["p90"]), fmt(r["p99"]),
            fmt(r["max"])))
    lines.append("")
    lines.append("How the exact optima were reached (ExactLp's paths over the replay): ")
    lines.append("")
    lines.append("| case | basis checked | repaired | Farkas | CGAL fall-back | exact pivots | oracle wall [s] |")
    lines.append("|---|---|---|---|---|---|---|")
    for key, s in rows:
        p = s["paths"]
        lines.append("| %s | %d | %d | %d | %d | %d | %.0f |" % (key, p["basis"], p["repaired"], p["farkas"], p["fallback"],
                                                           p["pivots"], s["seconds"]))
    lines.append("")
    ok = tot["wrong_side"] == 0 and tot["infeasible_refuted"] == 0 and tot["cgal_mismatch"] == 0
    lines.append("Verdict: %s" % ("no safe bound on the wrong side of the exact optimum, every infeasibility claim "
                                   "exact, ExactLp and CGAL identical where compared." if ok else
                                   "**FAILED**: see the bold columns."))
    lines.append("")
    lines.append("\"exactly empty, only bounded by safe\": LPs the exact solver finds infeasible where the safe backend "
                 "returned a bound (sound, it only loses pruning). A large distance is a weak safe bound, never a "
                 "wrong one: it comes from CLP stopping early (iteration cap) or from duals whose Neumaier-Shcherbina "
                 "correction is large; the median is at the last bits. The CI test (`ctest -R 'LP oracle'`) runs the same "
                 "checks on a few boxes of each linkage and the whole wrist search.")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(HERE, "lp_oracle.md"), "w") as f:
        f.write(text)
    print(text)
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--every", type=int, default=1, help="record every k-th loaded LP (default 1: all)")
    ap.add_argument("--cgal-every", type=int, default=200)
    ap.add_argument("--cgal-cap", type=int, default=200)
    ap.add_argument("--cases", nargs="+", default=None)
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    keys = DEFAULT if not args.cases else [k for c in args.cases for k in c.split(",") if k]
    started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    tmp = tempfile.mkdtemp(prefix="linkbox-lp-oracle-")
    rows = []
    for key in keys:
        if key not in CASES:
            sys.exit("unknown case %r" % key)
        s = run_case(build, key, args.every, args.cgal_every, args.cgal_cap, tmp)
        print("%s: %s" % (key, json.dumps(s)), file=sys.stderr)
        rows.append((key, s))
    return report(rows, args, started)


if __name__ == "__main__":
    sys.exit(main())
