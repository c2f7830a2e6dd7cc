#!/usr/bin/env python3
"""table1.py on the Python package: the same table, each case solved in this process by
`linkbox` (pip install, see README.md) instead of the executable and its JSON file.

Usage: python3 papers/shabani-spherical/table1_package.py [--runs 5] [--out DIR]
"""
import os
import statistics
import sys

import linkbox

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import table1  # noqa: E402


def run(_binary, case, runs):
    """table1.run's contract: the result JSON of the last run, and the median search time."""
    loaded = linkbox.load(os.path.join(table1.ROOT, case))
    results = [loaded.solve(bisect="widest", sigma=table1.SIGMA, rho=table1.RHO) for _ in range(runs)]
    return results[-1].data, statistics.median(r.stats["seconds"] for r in results)


if __name__ == "__main__":
    table1.run = run
    sys.exit(table1.main())
