#!/usr/bin/env python3
"""The map plot from a result: solve a curve case, draw it with papers/curve-maps/plot_map.py,
and require a PNG with the Grashof four-bar's two proved components drawn (the script reads
the JSON's `map` as linkbox writes it).

Usage: plot_map_check.py LINKBOX_BINARY
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    linkbox = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "grashof.json")
        subprocess.run([linkbox, "solve", os.path.join(ROOT, "cases/curves/fourbar-grashof.toml"), "--json", out,
                        "--quiet"], check=True, stdout=subprocess.DEVNULL)
        png = os.path.join(tmp, "grashof.png")
        done = subprocess.run([sys.executable, os.path.join(ROOT, "papers/curve-maps/plot_map.py"), out, "--vars", "c1,s3",
                               "--out", png], capture_output=True, text=True)
        if done.returncode != 0:
            print(done.stdout + done.stderr)
            return 1
        if "2 proved components drawn" not in done.stdout:
            print("expected the two closed curves drawn:", done.stdout)
            return 1
        with open(png, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                print("not a PNG:", png)
                return 1
        print("1 passed, 0 failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
