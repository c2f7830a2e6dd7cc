#!/usr/bin/env python3
"""linkbox beside IbexSolve on classic systems from the literature that are not in IbexSolve's
benchmark folder's given half (cases/classic/, written by cases/classic/make_classic.py): a
check on systems neither tool was tuned for, run and rendered like papers/benchmarks/corpus.md.

  /usr/bin/python3 papers/reliability/classic.py run --linkbox build/linkbox   # runs, then renders
  /usr/bin/python3 papers/reliability/classic.py render                        # renders only

Both tools with a CPU limit of 30 s, one run at a time, into classic.csv; classic.md beside it.
"""
import argparse
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "papers" / "benchmarks"))
import corpus  # noqa: E402  (the same harness call, loading and tables as corpus.md)

# What was found by hand in the runs' logs, for the files where the tools differ.
NOTES = {
    "katsura-4.bch": "(1, 0, 0, 0, 0) is a root on the domain's face x0 = 1; IbexSolve calls its box 'unknown', "
                     "linkbox certifies it at its exact rational point (docs/verification.md, exact roots).",
    "katsura-5.bch": "as katsura-4: the root (1, 0, ..., 0) on the face x0 = 1.",
    "combustion.bch": "unknowns from 6e-11 to 1.5e-5 and coefficients down to 2e-15: the Jacobian's plain "
                      "reciprocal condition is below 1e-14 at every root, though each is regular; linkbox "
                      "inverts it equilibrated (newton/regular_inverse.hpp) and certifies all four.",
    "beale.bch": "three equations in two unknowns; linkbox certifies (3, 1/2) as an exact root of all three "
                 "(the square subsystem's unique root, where the third is exactly 0).",
    "brown-badly-scaled.bch": "three equations in two unknowns; 2e-6 is not a double: the search uses an interval "
                              "around it, and its exact value is kept beside it (model/exact_coefficients.hpp), so "
                              "linkbox certifies (1e6, 2e-6) as an exact root of all three (argument \"exact root\").",
    "powell-singular.bch": "the only root, 0, has a singular Jacobian (rank 2): neither tool certifies it.",
    "extended-powell-8.bch": "two copies of Powell singular: the root 0 is singular, neither tool certifies it.",
    "variably-dimensioned-4.bch": "six equations in four unknowns; linkbox certifies (1, 1, 1, 1) as an exact root "
                                  "of all six (argument \"exact root\").",
    "wood-integer.bch": "six equations in four unknowns with the root (1, 1, 1, 1); the weight 1/3 is not a double, "
                        "but the quotient of integers is kept exactly beside its interval, so linkbox certifies "
                        "(1, 1, 1, 1) as an exact root of all six.",
    "box-3d.bch": "besides (1, 10, 1) and (10, 1, -1), the line x1 = x2, x3 = 0 is in the solution set: "
                  "neither tool finishes covering it at its precision.",
}


def run(args):
    csv = HERE / "classic.csv"
    for p in (csv, corpus.meta_of(csv)):
        if p.exists():
            p.unlink()
    linkbox = corpus.cpu_limited(args.linkbox, args.logs)
    subprocess.run([sys.executable, str(corpus.SHARED / "tools" / "corpus.py"), "run", "--linkbox", linkbox,
                    "--ibexsolve", args.ibexsolve, "--bench", str(ROOT / "cases" / "classic"), "--out", str(csv),
                    "--limit", str(args.limit), "--workers", "1", "--logs", args.logs, "--keep-json"], check=True)
    render(args)


def render(_args):
    csv = HERE / "classic.csv"
    rows, files, meta = corpus.load(csv)
    corpus.NOTES = NOTES
    m = meta[0] if meta else {}
    started = sorted(r["started"] for r in rows.values() if r["started"])
    lines = ["# Classic systems outside IbexSolve's folder: linkbox beside IbexSolve", "",
             "Regenerate: `/usr/bin/python3 papers/reliability/classic.py run --linkbox build/linkbox` "
             "(about 5 minutes; `render` rewrites this page from `classic.csv`).", "",
             "The %d files of `cases/classic/` (Katsura, cyclic, Reimer, Noon, Chebyquad, Trinks, Morgan's "
             "combustion system, Chandrasekhar's H-equation and Moré-Garbow-Hillstrom test functions; "
             "`make_classic.py` writes them), "
             "run by `../shared/tools/corpus.py` as in `papers/benchmarks/corpus.md` with a CPU limit of "
             "%s s, one run at a time; machine %s, %s cores, runs from %s to %s (UTC)." % (
                 len(files), m.get("limit", "?"), m.get("host", "?"), m.get("nproc", "?"),
                 started[0] if started else "?", started[-1] if started else "?"), ""]
    lines += corpus.summary(rows, files) + ["", "## Per file", ""] + corpus.table(rows, files)
    (HERE / "classic.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("wrote", HERE / "classic.md")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--linkbox", default="build/linkbox")
    r.add_argument("--ibexsolve", default=str(corpus.SHARED / "peers" / "ibex" / "ibexsolve"))
    r.add_argument("--limit", type=float, default=30)
    r.add_argument("--logs", default="/tmp/linkbox-classic-logs")
    sub.add_parser("render")
    args = ap.parse_args()
    (run if args.cmd == "run" else render)(args)


if __name__ == "__main__":
    main()
