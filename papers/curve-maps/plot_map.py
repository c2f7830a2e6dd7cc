#!/usr/bin/env python3
"""Draws the certified map of a result: `linkbox solve CASE --json OUT.json`, then

    python3 papers/curve-maps/plot_map.py OUT.json [--vars x,y] [--out OUT.png]

Each component of every mapped curve cluster in its own colour (the solution boxes its arcs
cover, projected on two output variables), certified isolated roots as red dots, regions
where no arc was proved (possible singular points) as black squares, proved singular points
as black stars, other solution boxes
(unmapped curves, unresolved clusters) in grey. The two variables default to the pair with
the widest extent over the solution boxes. The title is the result's headline.
"""
import argparse
import json
import os
import sys
import textwrap
from fractions import Fraction

try:
    import matplotlib
except ImportError:
    # Debian's python3-matplotlib is in /usr/bin/python3's site-packages; another python3
    # first on PATH (e.g. pyenv) does not see it.
    if os.path.exists("/usr/bin/python3") and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("matplotlib is missing: apt-get install python3-matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402


def solution_boxes(res):
    """(sub-problem, index within it) -> box in the output variables."""
    boxes, seen = {}, {}
    for s in res["solutions"]:
        sub = s["subproblem"]
        k = seen.get(sub, 0)
        seen[sub] = k + 1
        boxes[(sub, k)] = s["box"]
    return boxes


def widest_pair(boxes, count):
    def extent(i):
        return max(b[i][1] for b in boxes) - min(b[i][0] for b in boxes)
    order = sorted(range(count), key=extent, reverse=True)
    return order[0], order[1 if count > 1 else 0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result")
    ap.add_argument("--vars", help="the two output variables to plot, e.g. c1,s1")
    ap.add_argument("--out", help="PNG to write (default: the result's name with .png)")
    args = ap.parse_args()
    with open(args.result) as f:
        res = json.load(f)
    names = res["variables"]
    boxes = solution_boxes(res)
    if not boxes:
        sys.exit("%s: no solution boxes to draw" % args.result)
    if args.vars:
        want = args.vars.split(",")
        if len(want) != 2 or any(v not in names for v in want):
            sys.exit("--vars needs two of: %s" % ", ".join(names))
        i, j = names.index(want[0]), names.index(want[1])
    else:
        i, j = widest_pair(list(boxes.values()), len(names))
    colours = plt.get_cmap("tab10")
    fig, ax = plt.subplots(figsize=(6.4, 6.0))
    drawn, component = set(), 0
    for c in res.get("clusters") or []:
        members = [tuple(m) for m in c["members"]]
        cmap = c.get("map")
        if cmap and cmap.get("proved"):
            owner = {}  # member index -> component of an arc made in it
            for k, comp in enumerate(cmap["components"]):
                for a in comp["arcs"]:
                    owner[cmap["arcs"][a]["member"]] = k
            # A symmetric loop's arc also covers members it made no arc in: the nearest
            # member with an arc names their component.
            with_arc = sorted(owner)
            centre = lambda m: [(lo + hi) / 2 for lo, hi in boxes[members[m]]]
            for m in range(len(members)):
                if m not in owner:
                    d = [sum((x - y) ** 2 for x, y in zip(centre(m), centre(a))) for a in with_arc] \
                        if len(cmap["components"]) > 1 else [0]
                    owner[m] = owner[with_arc[d.index(min(d))]]
            for k, comp in enumerate(cmap["components"]):
                colour = colours(component % 10)
                kind = "branch" if comp.get("singular_ends") else "closed curve" if comp["closed"] else "open arc"
                label = "%s %d (%d arcs)" % (kind, component + 1, len(comp["arcs"]))
                for n, m in enumerate(m for m in range(len(members)) if owner[m] == k):
                    key = members[m]
                    b = boxes[key]
                    ax.add_patch(Rectangle((b[i][0], b[j][0]), b[i][1] - b[i][0], b[j][1] - b[j][0], facecolor=colour,
                                           edgecolor=colour, alpha=0.5, label=label if n == 0 else None))
                    drawn.add(key)
                component += 1
        if cmap:
            for n, r in enumerate(cmap.get("singular_regions", [])):
                ax.plot([(r[i][0] + r[i][1]) / 2], [(r[j][0] + r[j][1]) / 2], "ks", markersize=7,
                        label="possible singular point" if n == 0 and component <= 1 else None)
            # Proved singular points: exact, in the natural unknowns (drawn where those are
            # the output variables, as in the polynomial cases).
            for n, p in enumerate(cmap.get("singular_points", [])):
                if len(p["point"]) == len(names):
                    x = [float(Fraction(v)) for v in p["point"]]
                    ax.plot([x[i]], [x[j]], "k*", markersize=12,
                            label="singular point (%s)" % p["kind"] if n == 0 else None)
        if c["status"] == "certified" and "root" in c and "duplicate_of" not in c:
            r = c["root"]
            ax.plot([(r[i][0] + r[i][1]) / 2], [(r[j][0] + r[j][1]) / 2], "r.", markersize=10)
            drawn.update(members)
    for key, b in boxes.items():
        if key not in drawn:
            ax.add_patch(Rectangle((b[i][0], b[j][0]), b[i][1] - b[i][0], b[j][1] - b[j][0], facecolor="0.6",
                                   edgecolor="0.4", alpha=0.4))
    xs = [v for b in boxes.values() for v in b[i]]
    ys = [v for b in boxes.values() for v in b[j]]
    pad = 0.05 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_ylim(min(ys) - pad, max(ys) + pad)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(names[i])
    ax.set_ylabel(names[j])
    ax.grid(True, linewidth=0.3, alpha=0.5)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8, loc="best")
    ax.set_title("%s\n%s" % (res.get("case", ""), textwrap.fill(res.get("headline", ""), 90)), fontsize=8)
    out = args.out or os.path.splitext(args.result)[0] + ".png"
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("%s: %d proved components drawn" % (out, component))
    return 0


if __name__ == "__main__":
    sys.exit(main())
