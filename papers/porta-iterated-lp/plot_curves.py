#!/usr/bin/env python3
"""Plots the solution boxes of the curve cases of Section V (Porta, Ros, Thomas, RSS 2006)
projected on pairs of joint angles, like the paper's Fig. 6 (mobile 6R) and Fig. 8
(bicyclohexane), and the same for cyclohexane.

Usage: python3 papers/porta-iterated-lp/plot_curves.py [--runs-dir DIR] [--cases ...]
           [--pairs theta1:theta2,theta1:theta3]

Reads runs/<case>.json written by section5.py and writes <case>-boxes.png beside this script.
Each solution box is drawn as a rectangle in the (theta_i, theta_j) plane (its projection;
boxes of a curve overlap in projection). Clusters the verifier certified as isolated roots
are drawn in red (their member boxes, outlined thick, since a certified box is too small to
see at this scale); isolated clusters that are small but not certified are outlined in
orange; everything else (the curve) in blue. Black dots: points where the verifier proved
(interval Newton on a slice) that the curve crosses a box. Angles are in radians.
"""
import argparse
import json
import math
import os
import sys

try:
    import matplotlib
except ImportError:
    # Debian's python3-matplotlib lives in /usr/bin/python3's site-packages; another python3
    # first on PATH (e.g. pyenv) does not see it.
    if os.path.exists("/usr/bin/python3") and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit("matplotlib is missing: apt-get install python3-matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

# Joint-angle pairs per case (names as in the JSON's `variables`).
PAIRS = {
    "6r-mobile": [("theta1", "theta2"), ("theta1", "theta3"), ("theta2", "theta3")],
    "cyclohexane": [("c1-c2", "c2-c3"), ("c1-c2", "c3-c4"), ("c2-c3", "c4-c5")],
    "bicyclohexane": [("c1-c2", "c2-c3"), ("c2-c3", "c7-c8"), ("c3-c4", "c9-c10")],
}
TITLES = {
    "6r-mobile": "mobile 6R (paper Fig. 6)",
    "cyclohexane": "cyclohexane",
    "bicyclohexane": "bicyclohexane (paper Fig. 8)",
}
# A cluster whose hull is at most this wide (radians, every angle) and holds few boxes
# counts as isolated when it is not certified.
ISOLATED_WIDTH = 0.05


def cluster_roles(res):
    """Map (subproblem, index within it) -> role: 'certified', 'isolated' or 'curve'."""
    roles = {}
    for c in res.get("clusters") or []:
        width = max((hi - lo for lo, hi in c["hull"]), default=0.0)
        if c["status"] == "certified":
            role = "certified"
        elif c["status"] != "curve" and width <= ISOLATED_WIDTH:
            role = "isolated"
        else:
            role = "curve"
        for sub, k in c["members"]:
            roles[(sub, k)] = role
    return roles


def crossing_points(res, names):
    """Points where the verifier proved that a curve crosses a box (interval Newton on a
    slice), as {output name: angle}. The certificate's box is in the cluster's natural
    unknowns, half-angle tangents t_<joint> = tan((theta - shift) / 2), where the chart's bit k
    shifts unknown k by a half turn; theta = 2 atan(t) + shift, wrapped to (-pi, pi]."""
    points = []
    for c in res.get("clusters") or []:
        xs = c.get("crossings")
        if c.get("status") != "curve" or not isinstance(xs, list):
            continue
        unknowns = c.get("natural_unknowns") or []
        chart = int(c.get("chart", 0))
        for x in xs:
            box = x.get("box") or []
            if x.get("status") != "certified" or len(box) != len(unknowns):
                continue
            pt = {}
            for k, (u, (lo, hi)) in enumerate(zip(unknowns, box)):
                if not u.startswith("t_") or u[2:] not in names:
                    continue
                theta = 2 * math.atan((lo + hi) / 2) + (math.pi if (chart >> k) & 1 else 0.0)
                pt[u[2:]] = math.remainder(theta, 2 * math.pi)
            if pt:
                points.append(pt)
    return points


def plot_case(key, res, pairs, out_png):
    names = res["variables"]
    idx = {n: i for i, n in enumerate(names)}
    pairs = [(a, b) for a, b in pairs if a in idx and b in idx]
    if not pairs:  # fall back to consecutive angles
        pairs = [(names[i], names[i + 1]) for i in range(min(3, len(names) - 1))]
    roles = cluster_roles(res)
    seen = {}
    boxes = []
    for s in res["solutions"]:
        sub = s["subproblem"]
        k = seen.get(sub, 0)
        seen[sub] = k + 1
        boxes.append((s["box"], roles.get((sub, k), "curve")))
    counts = {r: sum(1 for _, role in boxes if role == r) for r in ("curve", "isolated", "certified")}
    points = crossing_points(res, names)
    style = {
        "curve": dict(facecolor=(0.2, 0.4, 0.8, 0.25), edgecolor=(0.1, 0.2, 0.6, 0.9), linewidth=0.6, zorder=1),
        "isolated": dict(facecolor=(1.0, 0.55, 0.0, 0.6), edgecolor="darkorange", linewidth=2.0, zorder=3),
        "certified": dict(facecolor=(0.9, 0.0, 0.0, 0.7), edgecolor="red", linewidth=2.0, zorder=4),
    }
    fig, axes = plt.subplots(1, len(pairs), figsize=(5.2 * len(pairs), 5.0), squeeze=False)
    for ax, (a, b) in zip(axes[0], pairs):
        i, j = idx[a], idx[b]
        xs, ys = [], []
        for box, role in boxes:
            (x0, x1), (y0, y1) = box[i], box[j]
            w, h = x1 - x0, y1 - y0
            if role != "curve":
                # Make tiny certified / isolated boxes visible (as the paper magnifies its red boxes).
                grow = 0.02
                x0, y0, w, h = x0 - grow, y0 - grow, w + 2 * grow, h + 2 * grow
            ax.add_patch(Rectangle((x0, y0), w, h, **style[role]))
            xs += [x0, x0 + w]
            ys += [y0, y0 + h]
        if points:
            pts = [(q[a], q[b]) for q in points if a in q and b in q]
            ax.plot([x for x, _ in pts], [y for _, y in pts], "k.", markersize=3, zorder=5)
        if xs:
            pad_x = 0.05 * (max(xs) - min(xs) or 1.0)
            pad_y = 0.05 * (max(ys) - min(ys) or 1.0)
            ax.set_xlim(min(xs) - pad_x, max(xs) + pad_x)
            ax.set_ylim(min(ys) - pad_y, max(ys) + pad_y)
        ax.set_xlabel("%s [rad]" % a)
        ax.set_ylabel("%s [rad]" % b)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, linewidth=0.3, alpha=0.5)
    handles = [Rectangle((0, 0), 1, 1, **style["curve"])]
    labels = ["solution box (%d)" % counts["curve"]]
    n_cert = sum(1 for c in res.get("clusters") or [] if c["status"] == "certified")
    n_iso = sum(1 for c in res.get("clusters") or [] if c["status"] != "certified" and c["status"] != "curve"
                and max((hi - lo for lo, hi in c["hull"]), default=0.0) <= ISOLATED_WIDTH)
    if counts["isolated"]:
        handles.append(Rectangle((0, 0), 1, 1, **style["isolated"]))
        labels.append("isolated cluster, not certified (%d clusters, %d boxes; magnified)" % (n_iso, counts["isolated"]))
    if counts["certified"]:
        handles.append(Rectangle((0, 0), 1, 1, **style["certified"]))
        labels.append("certified isolated root (%d roots, %d boxes; magnified)" % (n_cert, counts["certified"]))
    if points:
        handles.append(plt.Line2D([], [], color="k", marker=".", linestyle="none", markersize=5))
        labels.append("certified curve point (%d)" % len(points))
    p = res.get("parameters", {})
    st = res.get("stats", {})
    fig.suptitle("%s: %d solution boxes, sigma = %g, rho = %g, --prune %s%s" % (
        TITLES.get(key, key), len(boxes), p.get("sigma", float("nan")), p.get("rho", float("nan")),
        p.get("prune", "?"), "" if res.get("complete", True) else " (INCOMPLETE: %s, %d processed)" % (
            res.get("stop_reason"), st.get("processed", 0))))
    fig.legend(handles, labels, loc="lower center", ncol=len(handles), frameon=False)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    fig.savefig(out_png, dpi=110)
    plt.close(fig)
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs-dir", default=os.path.join(HERE, "runs"), help="where section5.py put <case>.json")
    ap.add_argument("--cases", nargs="+", default=list(PAIRS), help="cases to plot (default: the curve cases)")
    ap.add_argument("--pairs", default=None, help="override the pairs, e.g. theta1:theta2,theta1:theta3")
    ap.add_argument("--out", default=HERE)
    args = ap.parse_args()
    keys = [k for c in args.cases for k in c.split(",") if k]
    status = 0
    for key in keys:
        path = os.path.join(args.runs_dir, key + ".json")
        if not os.path.exists(path):
            print("%s: no %s (run section5.py --cases %s first)" % (key, path, key), file=sys.stderr)
            status = 1
            continue
        with open(path) as f:
            res = json.load(f)
        pairs = PAIRS.get(key, [])
        if args.pairs:
            pairs = [tuple(p.split(":", 1)) for p in args.pairs.split(",")]
        out_png = os.path.join(args.out, "%s-boxes.png" % key)
        counts = plot_case(key, res, pairs, out_png)
        print("%s: %s (%s)" % (key, os.path.relpath(out_png), ", ".join("%d %s" % (v, k) for k, v in counts.items() if v)))
    return status


if __name__ == "__main__":
    sys.exit(main())
