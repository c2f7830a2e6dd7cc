#!/usr/bin/env python3
"""Builds the hard linkage cases of this folder from a known configuration.

Six joint axes (lines p_i + s u_i) are placed in space so that consecutive axes have the
common normals wanted (lengths, twists); the Denavit-Hartenberg parameters (a_i, alpha_i,
d_i) and the joint angles theta_i are then measured from the lines, so the loop
prod_i Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i) = I closes at the printed theta (checked
here in double precision). Run: python3 cases/hard/make_linkages.py  (prints the TOML links
and the configuration; the .toml files were written from its output).
"""
import math


def add(a, b): return [x + y for x, y in zip(a, b)]
def sub(a, b): return [x - y for x, y in zip(a, b)]
def mul(a, s): return [x * s for x in a]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def unit(a): return mul(a, 1 / math.sqrt(dot(a, a)))


def rotate(v, axis, angle):
    """Rodrigues: v rotated about the unit axis."""
    c, s = math.cos(angle), math.sin(angle)
    return add(add(mul(v, c), mul(cross(axis, v), s)), mul(axis, dot(axis, v) * (1 - c)))


def chain(first_u, steps):
    """Axes from DH steps (theta, d, a, alpha) applied along the chain: returns lines (p, u)
    of joints 1..len(steps)+1 and the normals x_i. Joint 1 is the z axis through the origin
    with x_0 = first_u's perpendicular given."""
    p, z, x = [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], first_u
    lines = [(p, z)]
    for theta, d, a, alpha in steps:
        x = rotate(x, z, theta)
        p = add(add(p, mul(z, d)), mul(x, a))
        z = rotate(z, x, alpha)
        lines.append((p, z))
    return lines


def measure(lines):
    """DH parameters of the closed loop through the given axes (the last wraps to the first)."""
    n = len(lines)
    normals = []
    for i in range(n):
        (p, u), (q, v) = lines[i], lines[(i + 1) % n]
        c = cross(u, v)
        x = unit(c)
        a = dot(sub(q, p), x)
        alpha = math.atan2(dot(c, x), dot(u, v))
        # Feet of the common normal: p + s u and q + t v with (q + t v) - (p + s u) = a x.
        w = sub(q, p)
        uv = dot(u, v)
        s = (dot(w, u) - uv * dot(w, v)) / (1 - uv * uv)
        t = (uv * dot(w, u) - dot(w, v)) / (1 - uv * uv)
        normals.append(dict(x=x, a=a, alpha=alpha, foot_in=s, foot_out=t))
    entries = []
    for i in range(n):
        prev, cur = normals[i - 1], normals[i]
        u = lines[i][1]
        theta = math.atan2(dot(cross(prev["x"], cur["x"]), u), dot(prev["x"], cur["x"]))
        d = cur["foot_in"] - prev["foot_out"]
        entries.append(dict(theta=theta, d=d, a=cur["a"], alpha=cur["alpha"]))
    return entries


def mat_mul(A, B): return [[sum(A[i][k] * B[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def dh(theta, d, a, alpha):
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]]


def closure_error(entries):
    T = [[float(i == j) for j in range(4)] for i in range(4)]
    for e in entries:
        T = mat_mul(T, dh(e["theta"], e["d"], e["a"], e["alpha"]))
    return max(abs(T[i][j] - float(i == j)) for i in range(3) for j in range(4))


def close(steps, lines):
    """Entries of the loop: joints 2..n-1 and links 1..n-1 as chosen (exact decimals), the
    closing link n and the angles/offsets of joints 1 and n measured from the lines."""
    measured = measure(lines)
    entries = [dict(theta=t, d=d, a=a, alpha=al) for (t, d, a, al) in steps] + [measured[-1]]
    for i in (0, len(entries) - 1):
        entries[i]["theta"], entries[i]["d"] = measured[i]["theta"], measured[i]["d"]
    return entries


def show(name, entries):
    print("#", name, "closure error", closure_error(entries))
    for i, e in enumerate(entries):
        print('  { joint = "theta%d", link = "L%d", a = %r, d = %r, alpha = %r },' % (
            i + 1, i + 1, e["a"], e["d"], e["alpha"]))
    print("# theta =", ", ".join("%r" % e["theta"] for e in entries))


def main():
    # Link lengths 1e-3 ... 1e3 in one loop: five chosen DH steps, the sixth link measured.
    scale_steps = [
        (0.3, 0.0, 1e-3, 1.1),
        (-0.9, 0.2, 1e3, 0.7),
        (1.7, -4.0, 2.5, 1.9),
        (0.4, 30.0, 1.0e3, 1.3),
        (-2.1, 0.5, 0.07, 0.8),
    ]
    show("linkage-scales", close(scale_steps, chain([1.0, 0.0, 0.0], scale_steps)))

    # A twist of 1e-7 between joints 3 and 4 (nearly parallel axes 0.8 apart: locally planar).
    twist_steps = [
        (0.5, 0.1, 0.6, 1.2),
        (-0.7, 0.3, 0.9, 0.5),
        (1.1, 0.0, 0.8, 1e-7),
        (0.6, -0.2, 0.7, 1.4),
        (-1.3, 0.4, 0.5, 0.9),
    ]
    show("linkage-twist-1e-7", close(twist_steps, chain([1.0, 0.0, 0.0], twist_steps)))


if __name__ == "__main__":
    main()
