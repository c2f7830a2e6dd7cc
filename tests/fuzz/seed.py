#!/usr/bin/env python3
"""Adds the bundled inputs to the fuzz corpora (tests/fuzz/corpus/<target>/), each file named by
the SHA-1 of its contents as libFuzzer names its own. run.sh --seed calls it; run.sh's merge then
keeps only the seeds that add coverage.

  case_toml   every TOML file under cases/ and tests/data/
  expression  every string in those files that parses as an expression, plus a few by hand
  check_json  results of `linkbox solve --json` on the check target's three fixed cases
              (needs --linkbox-build with a built linkbox_cli, or --linkbox)
  minibex     every .bch file in the repository, plus the grammar example of minibex_file.cpp
  cuik        every .cuik file in the repository, plus the grammar example of cuik_file.cpp
"""
import argparse
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import tomllib

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent

EXPRESSIONS = [
    "x^2 + y^2 - 1", "x*y - 1/2 - 1e-6", "2^3^2", "-x^2", "pi/2", "acos(-1/3)", "sqrt(2)/2",
    "-0.7448995469549714", "(x + y + z)^3 - 1.5e-3*x", "sin(pi/7)*x - cos(x)", "x = y + 1",
    "x^2 <= y", "x + y > 0.5", "tan(1)", "exp(1) - log(3)*z", "x^(1/2)", ".5e+2", "atan(1)*4 - pi",
    "[0.9, 1.1]*x^2 - 1", "x <= [1, 2]", "[1/3, 1/3]*y",
]

MINIBEX = """Constants
  a = 0.25;  n = 2;  f in 0;
  k in [0.9, 1.1];
  c[3] = (1; 2.5; -a);
Variables
  x in [-1, 1];  y in [0, pi/2], v[n] in [-10, 10];
  t in [-pi, pi];
Constraints
  x^2 + sqr(y) = k;
  v(1)*v[1] - c(2)*x = a + f;
  v(2) - sin(a)*y = cos(t);
  x - y = ln(2) + [-0.1, 0.1]*sin(t);
  x + y <= 1;
  sqrt(y) > 0.1;
end
"""

CUIK = """[CONSTANTS]
d := 20
a := 0.25
[SYSTEM VARS]
x : [-2, 2]
y : [-d, d]
[SECONDARY VARS]
s : [0, 1]
[SYSTEM EQS]
x^2 + y^2 = 1;
2*x*y - a*s = 0;
x*y >= -0.5;
[COORD EQS]
s - SIN(PI/6)*x = 0;
[SEARCH]
DEPTH FIRST
"""

# The check target's fixed cases (targets.cpp), with the options their results need.
CHECK_CASES = [
    ("cases/spherical/wrist.toml", []),
    ("cases/hard/gimbal-lock.toml", ["--sigma", "1e-2"]),
    ("cases/polynomial/circle-line.toml", []),
]


def add(target, data):
    if isinstance(data, str):
        data = data.encode()
    folder = HERE / "corpus" / target
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / hashlib.sha1(data).hexdigest()
    if not path.exists():
        path.write_bytes(data)
        return 1
    return 0


def repo_files(pattern):
    return sorted(p for p in ROOT.rglob(pattern)
                  if not any(part.startswith("build") or part.startswith(".") for part in p.relative_to(ROOT).parts))


def strings_in(node):
    if isinstance(node, str):
        yield node
    elif isinstance(node, dict):
        for v in node.values():
            yield from strings_in(v)
    elif isinstance(node, list):
        for v in node:
            yield from strings_in(v)


def seed_case_toml():
    files = [p for p in repo_files("*.toml") if p.parts[len(ROOT.parts)] in ("cases", "tests")]
    return sum(add("case_toml", p.read_bytes()) for p in files)


def seed_expression():
    n = sum(add("expression", e) for e in EXPRESSIONS)
    for p in (ROOT / "cases").rglob("*.toml"):
        try:
            doc = tomllib.loads(p.read_text())
        except (tomllib.TOMLDecodeError, UnicodeDecodeError):
            continue
        for s in strings_in(doc):
            if any(c.isdigit() or c in "+-*/^" for c in s) and "\n" not in s and len(s) < 400:
                n += add("expression", s)
    return n


def trimmed(result, keep=4):
    """A long curve result cut to its first `keep` members per cluster (and their solution
    boxes and crossings), still a valid result, so that seeds stay small (-max_len)."""
    used = []
    for c in result["clusters"]:
        used += [tuple(m) for m in c["members"][:keep]]
    old = {}
    seen = {}
    for s in result["solutions"]:
        k = seen.get(s["subproblem"], 0)
        seen[s["subproblem"]] = k + 1
        old[(s["subproblem"], k)] = s
    solutions, renumber, count = [], {}, {}
    for key, s in old.items():
        if key in used:
            renumber[key] = (key[0], count.get(key[0], 0))
            count[key[0]] = count.get(key[0], 0) + 1
            solutions.append(s)
    result["solutions"] = solutions
    for c in result["clusters"]:
        c["members"] = [list(renumber[tuple(m)]) for m in c["members"][:keep]]
        c["boxes"] = len(c["members"])
        if "crossings" in c:
            c["crossings"] = [x for x in c["crossings"] if x["member"] < keep]
    return result


def seed_check_json(linkbox):
    if not linkbox:
        print("seed.py: check_json needs --linkbox or --linkbox-build; skipped", file=sys.stderr)
        return 0
    n = 0
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        for case, options in CHECK_CASES:
            out = pathlib.Path(tmp) / "result.json"
            subprocess.run([linkbox, "solve", str(ROOT / case), "--quiet", *options, "--json", str(out)],
                           check=True, stdout=subprocess.DEVNULL, env=env)
            data = out.read_bytes()
            if len(data) > 16384:
                data = json.dumps(trimmed(json.loads(data)), indent=1).encode()
            n += add("check_json", data)
    return n


def seed_peer(target, pattern, example):
    return add(target, example) + sum(add(target, p.read_bytes()) for p in repo_files(pattern))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("targets", nargs="*", default=["case_toml", "expression", "check_json", "minibex", "cuik"])
    ap.add_argument("--linkbox", help="the linkbox executable (for check_json seeds)")
    ap.add_argument("--linkbox-build", help="a build folder: builds its linkbox_cli and uses it")
    a = ap.parse_args()
    linkbox = a.linkbox
    if not linkbox and a.linkbox_build and "check_json" in a.targets:
        subprocess.run(["cmake", "--build", a.linkbox_build, "-j2", "--target", "linkbox_cli"], check=True,
                       stdout=subprocess.DEVNULL)
        linkbox = str(pathlib.Path(a.linkbox_build) / "linkbox")
    seeders = {
        "case_toml": seed_case_toml,
        "expression": seed_expression,
        "check_json": lambda: seed_check_json(linkbox),
        "minibex": lambda: seed_peer("minibex", "*.bch", MINIBEX),
        "cuik": lambda: seed_peer("cuik", "*.cuik", CUIK),
    }
    for t in a.targets:
        print(f"seed.py: {t}: {seeders[t]()} new seed(s)")


if __name__ == "__main__":
    main()
