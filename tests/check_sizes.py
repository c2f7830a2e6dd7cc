#!/usr/bin/env python3
"""Fails when a file in lib/ or verify/ is over MAX_FILE lines, or a function body there is
over MAX_FUNCTION lines (lib/README.md, "Contributing"): one concept per file, functions
short enough to read at once.

A function body is a brace block opened after a parameter list's ')' (with optional const,
noexcept, override, a trailing return type or a constructor's initialisers) at a point that
is not inside another function; lambdas inside a function count toward that function.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_FILE = 500
MAX_FUNCTION = 100

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|namespace|class|struct|enum|union)\b")
SIGNATURE_END = re.compile(r"\)\s*(const)?\s*(noexcept)?\s*(override)?\s*(->\s*[\w:<>,\s*&]+)?\s*(:.*)?$")


def code_only(line):
    line = re.sub(r'"([^"\\]|\\.)*"', '""', line)
    line = re.sub(r"'([^'\\]|\\.)*'", "''", line)
    return re.sub(r"//.*", "", line)


def functions(lines):
    """(first line, length, signature) of each outermost function body."""
    depth, start, start_depth, statement = 0, None, 0, ""
    for n, raw in enumerate(lines, 1):
        for ch in code_only(raw):
            if ch == "{":
                head = statement.strip()
                if start is None and SIGNATURE_END.search(head) and not CONTROL.search(head):
                    start, start_depth, signature = n, depth, head
                depth += 1
                statement = ""
            elif ch == "}":
                depth -= 1
                if start is not None and depth == start_depth:
                    yield start, n - start + 1, signature[-80:]
                    start = None
                statement = ""
            elif ch == ";":
                statement = ""
            else:
                statement += ch
        statement += " "


def main():
    bad = []
    for top in ("lib", "verify"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, top)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, ROOT)
                with open(path) as f:
                    lines = f.read().split("\n")
                if len(lines) > MAX_FILE:
                    bad.append(f"{rel}: {len(lines)} lines (at most {MAX_FILE}): split it by concept")
                for first, length, signature in functions(lines):
                    if length > MAX_FUNCTION:
                        bad.append(f"{rel}:{first}: a function of {length} lines (at most {MAX_FUNCTION}): {signature}")
    for b in bad:
        print(b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
