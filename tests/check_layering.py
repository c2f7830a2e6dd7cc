#!/usr/bin/env python3
"""Fails when a source file includes a project header from a folder its folder may not use
(lib/README.md, "Rules"): the data flows one way, case file -> input -> formulate -> solve
(prune) -> verify -> report, and no layer reaches back up."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# folder -> folders (or single headers) it may include, besides itself.
ALLOWED = {
    "interval": set(),
    "model": {"interval"},
    "input": {"interval", "model"},
    "formulate": {"interval", "model", "input"},
    "newton": {"interval", "model"},
    # prune depends on the model (and the shared Newton kernel) only.
    "prune": {"interval", "model", "newton"},
    "solve": {"interval", "model", "input", "formulate", "newton", "prune"},
    # verify never depends on a contractor: from solve and prune only the plain result data.
    "verify": {"interval", "model", "formulate", "newton", "solve/result.hpp", "prune/counters.hpp"},
    # report serialises; it proves nothing (no certification entry points).
    # A curve map is written as verify writes it for MPI (exact JSON), one format for both.
    "report": {"interval", "model", "input", "formulate", "solve", "prune", "verify/cluster_report.hpp",
               "verify/curve_map_json.hpp", "newton/certify.hpp"},
    # distributed runs solve's searches and verify's clusters over MPI processes; it proves
    # nothing of its own (each cluster is verify_cluster's, sent back as exact JSON).
    "distributed": {"interval", "model", "input", "formulate", "solve", "prune", "verify/certify_case.hpp",
                    "verify/cluster_json.hpp"},
    "cli": {"interval", "model", "input", "formulate", "solve", "prune", "verify", "report", "newton", "distributed"},
}

INCLUDE = re.compile(r'#include "([a-z_]+)/([^"]+)"')

# The search (Algorithm 1, its look-ahead: lib/solve/search*, lookahead*) sees the processes that
# take its boxes only through solve/lending.hpp: not MPI, not distributed/, not how pieces of a
# sub-problem travel and merge (solve/share.hpp), not the driver above it (solve_case, strategy).
SEARCH_FILES = re.compile(r"^lib/solve/(search[a-z_]*|lookahead)\.(hpp|cpp)$")
SEARCH_MAY_INCLUDE = {"interval", "model", "prune"} | {
    f"solve/{h}.hpp" for h in ("lending", "params", "budget", "box_log", "search_state", "result", "bisector",
                               "certifier", "search", "search_step", "search_core", "lookahead")}
ANY_INCLUDE = re.compile(r'#include ["<]([^">]+)[">]')


def search_include_error(rel, line):
    """Why `line` of search file `rel` breaks the search's rule, or None."""
    m = ANY_INCLUDE.match(line.strip())
    if not m:
        return None
    name = m.group(1)
    if name.startswith("mpi"):
        return f"{rel}: the search may not include <{name}>: it sees other processes only through solve/lending.hpp"
    if "/" not in name or line.strip().startswith("#include <"):
        return None
    if name in SEARCH_MAY_INCLUDE or name.split("/")[0] in SEARCH_MAY_INCLUDE:
        return None
    return (f"{rel}: the search may not include {name}: it sees lending only through solve/lending.hpp "
            "(lib/README.md, Rules)")


def folder_of(path):
    rel = os.path.relpath(path, ROOT).split(os.sep)
    return rel[0] if rel[0] == "verify" else rel[1]


def main():
    bad = []
    for top in ("lib", "verify"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            for name in files:
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                here = folder_of(path)
                rel = os.path.relpath(path, ROOT).replace(os.sep, "/")
                with open(path) as f:
                    for n, line in enumerate(f, 1):
                        if SEARCH_FILES.match(rel):
                            why = search_include_error(f"{rel}:{n}", line)
                            if why:
                                bad.append(why)
                        m = INCLUDE.match(line.strip())
                        if not m or m.group(1) == here:
                            continue
                        allowed = ALLOWED.get(here, set())
                        if m.group(1) not in allowed and f"{m.group(1)}/{m.group(2)}" not in allowed:
                            bad.append(f"{os.path.relpath(path, ROOT)}:{n}: {here}/ may not include {m.group(1)}/{m.group(2)}")
    for b in bad:
        print(b)
    print("layering holds" if not bad else f"{len(bad)} include(s) break the layering")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
