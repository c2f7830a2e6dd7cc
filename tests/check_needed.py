#!/usr/bin/env python3
"""Fails when an executable needs a shared library it should not load (CMakeLists.txt: `linkbox`
loads no MPI library, and with LINKBOX_STATIC_DEPS none of the libraries it links statically).

  check_needed.py EXECUTABLE NAME...   each NAME a library's stem, e.g. libmpi for libmpi.so.40"""
import re
import subprocess
import sys


def needed(executable):
    out = subprocess.run(["readelf", "-d", executable], capture_output=True, text=True, check=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out)


def main():
    executable, names = sys.argv[1], sys.argv[2:]
    libs = needed(executable)
    if not libs:
        print(f"FAILED  {executable}: readelf lists no needed library at all")
        return 1
    bad = [lib for lib in libs if lib.split(".so")[0] in names]
    print(f"{executable} needs: {' '.join(libs)}")
    for lib in bad:
        print(f"FAILED  {executable} needs {lib}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
