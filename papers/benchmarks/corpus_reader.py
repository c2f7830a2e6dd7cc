#!/usr/bin/env python3
"""What the Minibex reader refuses on IbexSolve's benchmark files, before and after a change,
and how the newly read files solve beside IbexSolve's recorded results.

  python3 papers/benchmarks/corpus_reader.py --before OLD/linkbox --after build/linkbox \\
      --bench ../shared/corpus/ibex-solver --ibex-csv ../shared/corpus/results-f58dc38.csv \\
      --out papers/benchmarks/corpus-reader.md

A file is refused when `linkbox solve FILE --max-boxes 1 --no-verify --quiet` exits 2 (the
reader and the formulation, no search); refusals are grouped by the feature their message
names. Each file read by --after but not by --before is then solved with `--threads 1
--time-limit 8`, and its certified root count is set beside IbexSolve's row of the CSV.
"""
import argparse
import collections
import csv
import json
import pathlib
import re
import subprocess
import tempfile

# A run that has not written its result by then is stopped (the time limit bounds the search,
# not the verification).
OUTER_TIMEOUT = 140

# (reason, pattern of the refusal message), first match wins.
REASONS = [
    ("interval constant", r"interval constant|given an interval \('in'\)"),
    ("sin/cos/tan of variables", r"(sin|cos|tan) of an expression with variables"),
    ("angle also used outside sin/cos/tan", r"is used inside (sin|cos|tan)"),
    ("angle argument not affine / units", r"(affine|integer multiples|unit)"),
    ("domain wider than a turn", r"wider than"),
    ("tan pole", r"pole of tan"),
    ("exp of variables", r"exp of an expression with variables"),
    ("log of variables", r"log of an expression with variables"),
    ("unsupported function", r"function '\w+' is not supported"),
    ("inequalities only", r"every constraint is an inequality"),
    ("inequality", r"inequality"),
    ("unbounded domain", r"has no domain|must be finite"),
    ("division by variables", r"division by an expression with variables"),
    ("divisor may be 0 on the domain", r"division by an expression that may be 0"),
    ("function of a quotient whose divisor may be 0", r"has a divisor that may be 0"),
    ("function outside its domain", r"outside the domain of"),
    ("function value unbounded on the domain", r"value is not bounded"),
]


def reason_of(message):
    for name, pattern in REASONS:
        if re.search(pattern, message):
            if name == "unsupported function":
                return "unsupported function (" + re.search(r"function ('\w+')", message).group(1) + ")"
            return name
    return "other: " + message[:60]


def refusal(linkbox, path):
    """The refusal message, or None when the file is read."""
    p = subprocess.run([linkbox, "solve", str(path), "--max-boxes", "1", "--no-verify", "--quiet"],
                       capture_output=True, text=True, timeout=120)
    if p.returncode != 2:
        return None
    lines = [l for l in (p.stderr + p.stdout).splitlines() if l.strip()]
    return lines[-1] if lines else "exit 2"


def solve(linkbox, path, limit):
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "r.json"
        try:
            subprocess.run([linkbox, "solve", str(path), "--threads", "1", "--time-limit", str(limit), "--quiet",
                            "--json", str(out)], capture_output=True, text=True, timeout=OUTER_TIMEOUT)
        except subprocess.TimeoutExpired:
            return {"status": f"no result in {OUTER_TIMEOUT} s"}
        if not out.exists():
            return {"status": "error"}
        j = json.loads(out.read_text())
    status = "complete" if j.get("complete") else "timeout"
    return {"status": status, "certified": j.get("certified_roots"), "exact": j["verification"]["exact"],
            "headline": j.get("headline", ""), "cpu": j["stats"].get("cpu_seconds")}


def ibex_rows(csv_path):
    rows = {}
    with open(csv_path) as f:
        for r in csv.DictReader(f):
            if r["tool"] == "ibexsolve":
                rows[r["file"]] = r
    return rows


def table(rows, header):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def compare(mine, ibex):
    if not ibex or ibex["status"] != "complete" or mine["status"] != "complete":
        return ""
    same = mine["certified"] == int(ibex["distinct"] or 0)
    return ("same" if same else "differs") + ("" if mine["exact"] else " (not exact)")


def why_not_exact(mine):
    """The headline of a complete run that states no exact count, without the bulky detail."""
    if mine["status"] != "complete" or mine.get("exact"):
        return ""
    return re.sub(r"; straddles.*", ")", mine["headline"])[:110].replace("|", "\\|")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", required=True)
    ap.add_argument("--bench", required=True)
    ap.add_argument("--ibex-csv", required=True)
    ap.add_argument("--limit", type=float, default=8)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    bench = pathlib.Path(a.bench)
    files = sorted(bench.rglob("*.bch"))
    before, after = {}, {}
    for f in files:
        name = str(f.relative_to(bench))
        before[name] = refusal(a.before, f)
        after[name] = refusal(a.after, f)
    count = {k: collections.Counter(reason_of(m) for m in d.values() if m) for k, d in
             (("before", before), ("after", after))}
    reasons = sorted(set(count["before"]) | set(count["after"]), key=lambda r: -count["before"][r])
    refused = [[r, count["before"][r], count["after"][r]] for r in reasons]
    refused.append(["**total refused**", sum(count["before"].values()), sum(count["after"].values())])

    ibex = ibex_rows(a.ibex_csv)
    newly = [n for n in before if before[n] and not after[n]]
    solved = []
    for n in newly:
        m = solve(a.after, bench / n, a.limit)
        i = ibex.get(n, {})
        solved.append([n, reason_of(before[n]), m["status"], m.get("certified", ""), "yes" if m.get("exact") else "",
                       i.get("status", ""), i.get("distinct", ""), compare(m, i), why_not_exact(m)])
    still = [[n, after[n].split(": ", 1)[-1][:140].replace("|", "\\|")] for n in sorted(after) if after[n]]

    both = [r for r in solved if r[-2]]
    text = f"""# IbexSolve's benchmark files: what the reader refuses

Regenerate (about 10 minutes on two cores; `--before` is a build of the commit before the
change):

```sh
python3 papers/benchmarks/{pathlib.Path(__file__).name} --before OLD/linkbox --after build/linkbox \\
    --bench ../shared/corpus/ibex-solver --ibex-csv ../shared/corpus/results-f58dc38.csv \\
    --out papers/benchmarks/corpus-reader.md
```

The {len(files)} files of `{bench.name}/`. Refused: `linkbox solve FILE --max-boxes 1 --no-verify
--quiet` exits 2. Grouped by the feature the message names; a file counts under the first
refusal the reader meets, so a file refused before for sin/cos that also uses exp or divides
by variables counts there after.

{table(refused, ["reason", "before", "after"])}

## Newly read files, solved

`linkbox solve FILE --threads 1 --time-limit {a.limit:g}` beside IbexSolve's row of
`{pathlib.Path(a.ibex_csv).name}` (`ibexsolve FILE --timeout=8 --eps-min=1e-8`; `distinct` is its
number of distinct roots). `compare` is set where both finish: `same` when linkbox's
certified count equals IbexSolve's distinct roots, `(not exact)` when linkbox states no exact
count (its headline says why). Both finish on {len(both)} files; the counts agree on
{sum(r[-2].startswith("same") for r in both)}, {sum(r[-2] == "same" for r in both)} of them exact.

{table(solved, ["file", "was refused for", "linkbox", "certified", "exact", "ibexsolve", "distinct", "compare", "linkbox's headline when not exact"])}

Where a complete run states no exact count here, its headline says why. A run with no result
in {OUTER_TIMEOUT} s finished its search within the time limit but was still verifying (the
time limit does not bound verification).

## Still refused

{table(still, ["file", "message"])}
"""
    pathlib.Path(a.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
