#!/usr/bin/env python3
"""Planted-root statistics (issue 12, item 3): random systems whose roots are known, of every
kind, solved in verified mode and in the unverified float variant.

Kinds (each system is a pure function of its seed; `KINDS` below gives the mix):
  product    polynomial; each equation a product of random affine forms, mixed by a random
             integer matrix (tests/planted.py): every real root known exactly (rationals)
  dense      polynomial; random dense equations shifted so that one dyadic point is a root;
             for 2 unknowns all real roots are counted independently (exact resultant and
             real-root isolation in sympy, then mpmath at 60 digits), for 3 the count is unknown
  close      product systems with a close pair: two parallel forms 2^-g apart, g in 6..30
  scaled     product systems with variables scaled by 2^k (domains [-2^k, 2^k], |k| <= 4) and
             equations by 2^m (|m| <= 10): coefficients spanning about 1e-4..1e4
  face       product systems with a planted root exactly on the domain boundary (on a face,
             sometimes on an edge or a vertex); other roots may fall on faces too
  spherical  3R spherical loops with random integer axes, closed exactly at a random pose by
             the inverse fixed rotations: R(a1,p1)... is the identity at phi = p (decimals);
             both roots known (a 3R spherical inverse kinematics has two, computed in closed
             form here: a1.R(a2,phi2)a3 = a1.Q a3 fixes phi2, then phi1, phi3 follow)
  sphface    the same with pose angles among 0, +-pi/2, pi (the faces of the half-angle
             sub-problems and the seam), written as "pi/2" etc.
  6r         random DH 6R loops: five DH steps chosen, the sixth link measured from the axes
             (cases/hard/make_linkages.py), closing at the chosen pose to ~1e-15 in double;
             the pose is a root (its neighbour within ~1e-14); the total count is not known
             independently (up to 16)

A planted root is *lost* when no solution box contains it (angles modulo 2 pi), allowing 1e-12
relative for the conversion of exact rationals to doubles (1e-7 for 6R loops, closed in
floating point). It is *certified* when a certified cluster's root box contains it.
A headline "exactly N roots" is *wrong* when the independent count is known and differs, or
when N is smaller than the number of distinct planted roots.

  planted_stats.py case SEED [--kind K]       # print one case (TOML) with its roots
  planted_stats.py run LINKBOX --count N [--first-seed S] [--time-limit 20] [--csv OUT]
                       [--modes verified,float] [--kinds k1,k2] [--save-failures DIR]
  planted_stats.py report CSV [CSV...] --out papers/reliability
  planted_stats.py ci LINKBOX --count 300     # exit 1 on a lost root or a wrong count (verified)
"""
import argparse
import csv
import itertools
import json
import math
import os
import random
import re
import resource
import subprocess
import sys
import tempfile
import time
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "cases", "hard"))
import planted  # noqa: E402

# The mix: one entry per slot of a cycle of 50 systems (seed % 50 picks the slot); 6R loops
# are the slow ones (about a second each), so one in 50.
KINDS = (["product"] * 16 + ["dense"] * 10 + ["close"] * 5 + ["scaled"] * 5 + ["face"] * 5
         + ["spherical"] * 5 + ["sphface"] * 3 + ["6r"])
assert len(KINDS) == 50
# Spread the kinds over the cycle (so that any run of consecutive seeds has every kind).
KINDS = [KINDS[(i * 7) % 50] for i in range(50)]
assert sorted(KINDS) == sorted(["product"] * 16 + ["dense"] * 10 + ["close"] * 5 + ["scaled"] * 5 + ["face"] * 5
                               + ["spherical"] * 5 + ["sphface"] * 3 + ["6r"])


def kind_of(seed):
    return KINDS[seed % len(KINDS)]


# ---------------------------------------------------------------- polynomial systems

def rand_form(rng, n):
    a = [rng.randint(-4, 4) for _ in range(n)]
    if not any(a):
        a[rng.randrange(n)] = 1
    return a, Fraction(rng.randint(-6, 6), 8)


def roots_of(forms, lo, hi):
    """All real roots of the product system in the closed box [lo, hi], or None when a pick is
    singular, two picks give the same root, or a root is near a face without being on it."""
    roots = []
    for pick in itertools.product(*[range(len(f)) for f in forms]):
        x = planted.solve([forms[i][j][0] for i, j in enumerate(pick)], [forms[i][j][1] for i, j in enumerate(pick)])
        if x is None:
            return None
        for v, l, h in zip(x, lo, hi):
            w = (h - l) / 100
            if (l - w < v < l) or (l < v < l + w) or (h - w < v < h) or (h < v < h + w):
                return None
        if all(l <= v <= h for v, l, h in zip(x, lo, hi)):
            roots.append(tuple(x))
    if len(set(roots)) != len(roots):
        return None
    return roots


def mix(rng, forms, extra=0):
    n = len(forms)
    products = []
    for eq in forms:
        p = {(0,) * n: Fraction(1)}
        for a, b in eq:
            p = planted.poly_mul(p, planted.affine(a, b))
        products.append(p)
    while True:
        m = [[rng.randint(-3, 3) for _ in range(n)] for _ in range(n + extra)]
        if planted.solve(m[:n], [0] * n) is not None:
            break
    eqs = []
    for row in m:
        p = {}
        for k, q in zip(row, products):
            p = planted.poly_add(p, q, k)
        eqs.append(p)
    return eqs if all(eqs) else None


def shape(rng, kind):
    """Unknowns and degrees: mostly 2 unknowns, some 3, a few 4 (kept small: the runs are
    meant to take well under a second each)."""
    u = rng.random()
    n = 2 if u < (0.85 if kind == "close" else 0.8) else (3 if u < 0.98 else 4)
    if n == 2:
        degrees = [rng.randint(1, 3), rng.randint(2, 3)]
    elif n == 3:
        degrees = rng.choice([[2, 2, 2], [1, 2, 3], [1, 2, 2], [1, 1, 2], [1, 1, 3]])
    else:
        degrees = rng.choice([[1, 1, 2, 2], [1, 1, 1, 2], [1, 1, 1, 3]])
    rng.shuffle(degrees)
    return n, degrees


def product_system(rng, variant):
    """product / close / face / scaled: returns (eqs, roots, domains, note)."""
    while True:
        n, degrees = shape(rng, variant)
        note = ""
        if variant == "close" and degrees[0] < 2:
            degrees[0] = 2
        forms = [[rand_form(rng, n) for _ in range(d)] for d in degrees]
        lo, hi = [Fraction(-1)] * n, [Fraction(1)] * n
        if variant == "close":
            g = rng.randint(6, 30)
            a, b = forms[0][0]
            forms[0][1] = (a, b + Fraction(1, 2**g))
            note = f"close pair: parallel forms 2^-{g} apart"
        if variant == "face":
            faces = rng.sample(range(n), rng.choice([1, 1, 1, 2, n]))
            p = [Fraction(rng.randint(-7, 7), 8) for _ in range(n)]
            for j in faces:
                p[j] = Fraction(rng.choice([-1, 1]))
            for eq in forms:  # the first form of each equation passes through p
                a, _ = eq[0]
                eq[0] = (a, sum(Fraction(x) * y for x, y in zip(a, p)))
            note = f"root {tuple(str(v) for v in p)} on {len(faces)} face(s)"
        roots = roots_of(forms, lo, hi)
        if not roots:
            continue
        if variant == "face" and tuple(p) not in roots:
            continue
        if variant == "close":  # both roots of some close pair in the domain
            sub = [forms[0][:2]] + forms[1:]
            inside = roots_of(sub, lo, hi)
            if inside is None or len(inside) < 2:
                continue
        eqs = mix(rng, forms)
        if eqs is None:
            continue
        if variant == "scaled":
            k = [rng.randint(-3, 3) for _ in range(n)]
            s = [Fraction(2) ** e for e in k]
            eqs = [{e: c / math.prod(si ** ei for si, ei in zip(s, e)) for e, c in p.items()} for p in eqs]
            # each equation scaled by 2^m so that its largest coefficient is about 2^0..2^10
            scaled = []
            for p in eqs:
                big = max(abs(c) for c in p.values())
                f = Fraction(2) ** (rng.randint(0, 10) - big.numerator.bit_length() + big.denominator.bit_length())
                scaled.append({e: c * f for e, c in p.items()})
            eqs = scaled
            roots = [tuple(v * si for v, si in zip(r, s)) for r in roots]
            lo, hi = [-si for si in s], list(s)
            mags = [abs(c) for p in eqs for c in p.values()]
            note = f"variables scaled by 2^{k}; |coefficients| {float(min(mags)):.1e}..{float(max(mags)):.1e}"
        return eqs, roots, list(zip(lo, hi)), note


def dense_system(rng):
    """Random dense equations, shifted so that the dyadic point p is a root with a regular
    Jacobian. Returns (eqs, [p], domains, true_count or None, note)."""
    while True:
        n = rng.choice([2, 2, 2, 3])
        degrees = [rng.choice([2, 3]) for _ in range(n)] if n == 2 else [2] * n
        p = [Fraction(rng.randint(-7, 7), 8) for _ in range(n)]
        eqs = []
        for d in degrees:
            g = {}
            for e in itertools.product(range(d + 1), repeat=n):
                if sum(e) <= d and rng.random() < 0.8:
                    c = rng.randint(-5, 5)
                    if c:
                        g[e] = Fraction(c)
            val = sum(c * math.prod(pi ** ei for pi, ei in zip(p, e)) for e, c in g.items())
            g[(0,) * n] = g.get((0,) * n, 0) - val
            g = {e: c for e, c in g.items() if c != 0}
            eqs.append(g)
        if any(not g or max(map(sum, g)) < 1 for g in eqs):
            continue
        jac = [[sum(c * e[j] * math.prod(pi ** (ei - (k == j)) for k, (pi, ei) in enumerate(zip(p, e)))
                    for e, c in g.items() if e[j] > 0) for j in range(n)] for g in eqs]
        if planted.solve(jac, [0] * n) is None:
            continue
        count, note = (count_2d(eqs) if n == 2 else (None, "count not known independently"))
        if n == 2 and count is None:
            continue  # ambiguous (a root at a face, a singular root): draw another
        if count == "no sympy":
            count = None
        return eqs, [tuple(p)], [(Fraction(-1), Fraction(1))] * n, count, note


def count_2d(eqs):
    """Real roots of two polynomials in [-1, 1]^2: exact resultant in y and exact real-root
    isolation in x (sympy), then the y's by mpmath at 60 digits. (count, note), count None
    when ambiguous (a root within 1e-6 of a face, a singular or tangent root)."""
    try:
        import mpmath
        import sympy as sp
    except ImportError:  # CI's Debian has no sympy: the count is then left unchecked
        return "no sympy", "count not known (sympy missing)"
    mpmath.mp.dps = 60
    x, y = sp.symbols("x y")
    P = [sp.Poly(sum(sp.Rational(c.numerator, c.denominator) * x**e[0] * y**e[1] for e, c in g.items()), x, y)
         for g in eqs]
    R = sp.Poly(sp.resultant(P[0].as_expr(), P[1].as_expr(), y), x)
    if R.is_zero:
        return None, "common component"
    mpq = lambda q: mpmath.mpf(int(sp.Rational(q).p)) / int(sp.Rational(q).q)  # noqa: E731
    Rc = [mpq(c) for c in R.all_coeffs()]
    dR = [c * (len(Rc) - 1 - i) for i, c in enumerate(Rc[:-1])]
    eps6 = sp.Rational(1, 10**6)
    roots = []
    for (a, b), mult in R.intervals(eps=sp.Rational(1, 10**15)):
        if b < -1 - eps6 or a > 1 + eps6:
            continue
        if abs(a + 1) < eps6 or abs(a - 1) < eps6:
            return None, "root near a face"
        xv = mpq(a) if a == b else mpmath.findroot(lambda t: mpmath.polyval(Rc, t), ((mpq(a) + mpq(b)) / 2),
                                                   df=lambda t: mpmath.polyval(dR, t)) if mult == 1 else (mpq(a) + mpq(b)) / 2
        if not -1 <= xv <= 1:
            continue
        ys = None
        for k in (0, 1):
            q = [sum((mpq(c) * xv**i for (i, j), c in P[k].terms() if j == d), mpmath.mpf(0))
                 for d in range(P[k].degree(y), -1, -1)]
            while q and abs(q[0]) < mpmath.mpf(10) ** -40:
                q = q[1:]
            if len(q) < 2:
                continue
            cand = mpmath.polyroots(q, maxsteps=400, extraprec=400) if len(q) > 2 else [-q[1] / q[0]]
            ys = [mpmath.re(r) for r in cand if abs(mpmath.im(r)) < mpmath.mpf(10) ** -25]
            other = P[1 - k]
            ys = [yv for yv in ys
                  if abs(sum(mpq(c) * xv**i * yv**j for (i, j), c in other.terms())) < mpmath.mpf(10) ** -20]
            break
        if ys is None:
            return None, "identically zero at a resultant root"
        inside = 0
        for yv in ys:
            if abs(abs(yv) - 1) < 1e-6:
                return None, "root near a face"
            if -1 <= yv <= 1:
                roots.append((xv, yv))
                inside += 1
        if mult > 1 and inside:
            return None, "multiple resultant root (singular or tangent)"
    for r1, r2 in itertools.combinations(roots, 2):
        if max(abs(r1[0] - r2[0]), abs(r1[1] - r2[1])) < 1e-20:
            return None, "duplicate root"
    return len(roots), "all real roots counted (resultant)"


def poly_toml(name, comment, domains, eqs):
    names = [f"x{i + 1}" for i in range(len(domains))]
    lines = [f"# {c}" for c in comment] + ['kind = "polynomial"', f'name = "{name}"', "variables = ["]
    lines += [f'  {{ name = "{v}", domain = [{planted.decimal(lo)}, {planted.decimal(hi)}] }},'
              for v, (lo, hi) in zip(names, domains)]
    lines += ["]", "equations = ["]
    for p in eqs:
        parts = []
        for e, c in sorted(p.items(), reverse=True):
            t = planted.term(e, names)
            mag = planted.decimal(abs(c))
            parts.append(("- " if c < 0 else "+ ") + (mag if not t else (t if mag == "1" else f"{mag}*{t}")))
        s = " ".join(parts)
        lines.append(f'  "{s[2:] if s.startswith("+ ") else "-" + s[2:]}",')
    lines.append("]")
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- spherical loops

def rot(axis, ang):
    """Rotation matrix about a unit axis (Rodrigues)."""
    x, y, z = axis
    c, s, t = math.cos(ang), math.sin(ang), 1 - math.cos(ang)
    return [[c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t]]


def mm(A, B): return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def mv(A, v): return [sum(A[i][k] * v[k] for k in range(3)) for i in range(3)]
def dot3(a, b): return sum(x * y for x, y in zip(a, b))
def cross3(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def unit3(a): return [x / math.sqrt(dot3(a, a)) for x in a]


def spherical_count(axes, pose):
    """Roots of R(a1,phi1) R(a2,phi2) R(a3,phi3) = Q (Q the pose's), phi in a full turn each:
    a1 . R(a2,phi2) a3 = a1 . Q a3 is A cos + B sin + C = c (two roots, one when tangent), and
    phi1, phi3 follow uniquely when R(a2,phi2) a3 is not parallel to a1. None if degenerate."""
    a1, a2, a3 = (unit3(a) for a in axes)
    Q = mm(mm(rot(a1, pose[0]), rot(a2, pose[1])), rot(a3, pose[2]))
    c = dot3(a1, mv(Q, a3))
    A = dot3(a1, a3) - dot3(a2, a1) * dot3(a2, a3)
    B = dot3(a1, cross3(a2, a3))
    C = dot3(a1, a2) * dot3(a2, a3)
    r2, rhs = A * A + B * B, c - C
    if r2 < 1e-6 or abs(r2 - rhs * rhs) < 1e-6 * r2:
        return None
    if abs(cross3(a1, a2)[0]) + abs(cross3(a1, a2)[1]) + abs(cross3(a1, a2)[2]) < 1e-9:
        return None
    for phi2 in (math.atan2(B, A) + math.acos(rhs / math.sqrt(r2)), math.atan2(B, A) - math.acos(rhs / math.sqrt(r2))):
        u = mv(rot(a2, phi2), a3)
        if math.sqrt(dot3(cross3(u, a1), cross3(u, a1))) < 1e-6:
            return None
    return 2


def spherical_system(rng, face):
    names = ["phi1", "phi2", "phi3"]
    while True:
        axes = []
        for _ in range(3):
            a = [rng.randint(-3, 3) for _ in range(3)]
            if any(a):
                axes.append(a)
        if len(axes) < 3:
            continue
        if face:
            exprs = [rng.choice(["0", "pi/2", "-pi/2", "pi"]) for _ in range(3)]
            for j in rng.sample(range(3), rng.randint(0, 1)):  # sometimes one generic angle
                exprs[j] = f"{rng.randint(-3141, 3141) / 1000}"
            pose = [float(eval(e.replace("pi", "math.pi"))) for e in exprs]
        else:
            pose = [rng.randint(-3141592, 3141592) / 10**6 for _ in range(3)]
            exprs = [f"{v}" for v in pose]
        count = spherical_count(axes, pose)
        if count is None:
            continue
        lines = [
            f"# Random spherical 3R loop closed at the pose phi = ({', '.join(exprs)}) by the",
            "# inverse fixed rotations (tests/planted_stats.py); two roots in all (closed form).",
            'kind = "spherical"', 'name = "planted-spherical"', f"joints = {json.dumps(names)}", "",
            "[[loops]]", 'name = "loop"', "factors = [",
        ]
        lines += [f'  {{ joint = "{j}", axis = {a} }},' for j, a in zip(names, axes)]
        for a, e in reversed(list(zip(axes, exprs))):
            neg = e[1:] if e.startswith("-") else ("-" + e if e != "0" else "0")
            lines.append(f'  {{ axis = {a}, angle = "{neg}" }},')
        lines.append("]")
        return "\n".join(lines) + "\n", [tuple(pose)], names, count, "pose " + ", ".join(exprs)


# ---------------------------------------------------------------- 6R loops

def sixr_system(rng):
    from make_linkages import chain, close, closure_error
    while True:
        steps = []
        for _ in range(5):
            steps.append((rng.randint(-3000, 3000) / 1000, rng.randint(-500, 500) / 1000,
                          rng.randint(100, 1500) / 1000, rng.randint(200, 2900) / 1000))
        try:
            entries = close(steps, chain([1.0, 0.0, 0.0], steps))
        except ZeroDivisionError:
            continue
        err = closure_error(entries)
        if err > 1e-12 or abs(math.sin(entries[-1]["alpha"])) < 0.05:
            continue
        pose = tuple(e["theta"] for e in entries)
        lines = [
            "# Random DH 6R loop closing at the planted pose (tests/planted_stats.py; five DH steps",
            f"# chosen, the sixth link measured; closure error {err:.0e} in double):",
            "#   theta = (" + ", ".join(repr(t) for t in pose) + ")",
            'kind = "linkage"', 'name = "planted-6r"', 'ground = "L6"', "", "[[loops]]", 'name = "ring"', "links = [",
        ]
        for i, e in enumerate(entries):
            lines.append(f'  {{ joint = "theta{i + 1}", link = "L{i + 1}", a = {e["a"]!r}, d = {e["d"]!r}, alpha = {e["alpha"]!r} }},')
        lines.append("]")
        return "\n".join(lines) + "\n", [pose], [f"theta{i + 1}" for i in range(6)], f"closure {err:.0e}"


# ---------------------------------------------------------------- one system

def check_roots(eqs, roots):
    """The generator's own check: every planted root is an exact root of every equation."""
    for r in roots:
        for p in eqs:
            assert sum(c * math.prod(v ** e for v, e in zip(r, ex)) for ex, c in p.items()) == 0, (r, p)


def system(seed, kind=None):
    """dict(kind, seed, toml, roots (tuples of Fraction or float), names, angular, count, tol, note)"""
    kind = kind or kind_of(seed)
    rng = random.Random(f"planted-stats-{kind}-{seed}")
    if kind in ("product", "close", "face", "scaled"):
        eqs, roots, domains, note = product_system(rng, kind)
        check_roots(eqs, roots)
        n = len(domains)
        comment = [f"Planted-root system: tests/planted_stats.py case {seed} --kind {kind}", note,
                   f"expected: exactly {len(roots)} roots in the domain (all known, exact rationals)"]
        comment += ["root: " + " ".join(str(v) for v in r) for r in roots]
        return dict(kind=kind, seed=seed, toml=poly_toml(f"planted-{kind}-{seed}", comment, domains, eqs), roots=roots,
                    names=[f"x{i + 1}" for i in range(n)], angular=False, count=len(roots), tol=1e-12, note=note,
                    unknowns=n)
    if kind == "dense":
        eqs, roots, domains, count, note = dense_system(rng)
        check_roots(eqs, roots)
        n = len(domains)
        comment = [f"Planted-root system: tests/planted_stats.py case {seed} --kind dense", note,
                   f"expected: {'exactly %d roots' % count if count is not None else 'at least the planted root'}",
                   "planted root: " + " ".join(str(v) for v in roots[0])]
        return dict(kind=kind, seed=seed, toml=poly_toml(f"planted-dense-{seed}", comment, domains, eqs), roots=roots,
                    names=[f"x{i + 1}" for i in range(n)], angular=False, count=count, tol=1e-12, note=note, unknowns=n)
    if kind in ("spherical", "sphface"):
        toml, roots, names, count, note = spherical_system(rng, kind == "sphface")
        return dict(kind=kind, seed=seed, toml=toml, roots=roots, names=names, angular=True, count=count, tol=1e-12,
                    note=note, unknowns=3)
    if kind == "6r":
        toml, roots, names, note = sixr_system(rng)
        return dict(kind=kind, seed=seed, toml=toml, roots=roots, names=names, angular=True, count=None, tol=1e-7,
                    note=note, unknowns=6)
    raise ValueError(kind)


# ---------------------------------------------------------------- running

def contains(box, root, names, varnames, angular, tol):
    for name, v in zip(names, root):
        lo, hi = box[varnames.index(name)]
        v = float(v)
        t = tol * max(1.0, abs(v))
        if angular:
            if not any(lo - t <= v + k * 2 * math.pi <= hi + t for k in (-2, -1, 0, 1, 2)):
                return False
        elif not (lo - t <= v <= hi + t):
            return False
    return True


def run_one(linkbox, sysd, mode, time_limit, work):
    path = os.path.join(work, f"case-{sysd['seed']}.toml")
    with open(path, "w") as f:
        f.write(sysd["toml"])
    out = os.path.join(work, "out.json")
    if os.path.exists(out):
        os.remove(out)
    args = [linkbox, "solve", path, "--quiet", "--json", out, "--time-limit", str(time_limit), "--threads", "1"]
    if mode == "float":
        args += ["--arith", "float"]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    p = subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=time_limit * 3 + 60)
    wall = time.monotonic() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    row = dict(seed=sysd["seed"], kind=sysd["kind"], mode=mode, unknowns=sysd["unknowns"], planted=len(sysd["roots"]),
               true_count="" if sysd["count"] is None else sysd["count"], cpu=round(cpu, 4), wall=round(wall, 4),
               exit=p.returncode)
    if p.returncode not in (0, 4, 5) or not os.path.exists(out):  # 4 unresolved, 5 incomplete
        row.update(complete=0, lost=len(sysd["roots"]), certified=0, claim="", claim_wrong=0,
                   headline="exit %d: %s" % (p.returncode, p.stderr.strip()[:200].replace("\n", " ")),
                   certified_roots=0, clusters=0, solutions=0, search_cpu="")
        return row
    r = json.load(open(out))
    varnames = r["variables"]
    boxes = [s["box"] for s in r["solutions"]]
    roots_cert = [c["root"] for c in r["clusters"] if c.get("status") == "certified" and c.get("root")]
    lost = sum(1 for root in sysd["roots"]
               if not any(contains(b, root, sysd["names"], varnames, sysd["angular"], sysd["tol"]) for b in boxes))
    cert = sum(1 for root in sysd["roots"]
               if any(contains(b, root, sysd["names"], varnames, sysd["angular"], sysd["tol"]) for b in roots_cert))
    m = re.match(r"exactly (\d+) root", r["headline"])
    claim = int(m.group(1)) if m else ""
    wrong = 0
    if m:
        if sysd["count"] is not None:
            wrong = int(claim != sysd["count"])
        else:
            wrong = int(claim < len(sysd["roots"]))
    row.update(complete=int(bool(r["complete"])), lost=lost, certified=cert, claim=claim, claim_wrong=wrong,
               headline=r["headline"][:160], certified_roots=r.get("certified_roots", 0), clusters=len(r["clusters"]),
               solutions=len(boxes), search_cpu=round(r["stats"].get("cpu_seconds", 0), 4))
    return row


FIELDS = ["seed", "kind", "mode", "unknowns", "planted", "true_count", "cpu", "wall", "search_cpu", "exit", "complete",
          "lost", "certified", "claim", "claim_wrong", "certified_roots", "clusters", "solutions", "headline"]


def defect(row):
    """Verified-mode defects: a lost planted root in a complete run, a wrong exact count, a crash."""
    return row["mode"] == "verified" and (
        (row["lost"] and row["complete"]) or row["claim_wrong"] or row["exit"] not in (0, 4, 5))


def cmd_run(a):
    modes = a.modes.split(",")
    kinds = a.kinds.split(",") if a.kinds else None
    out = open(a.csv, "a" if a.append else "w", newline="") if a.csv else None
    w = csv.DictWriter(out, FIELDS) if out else None
    if w and not a.append:
        w.writeheader()
    defects, done, t0 = [], 0, time.time()
    totals = {m: dict(lost=0, wrong=0, incomplete=0, cpu=0.0) for m in modes}
    with tempfile.TemporaryDirectory() as work:
        seed = a.first_seed
        while done < a.count:
            k = kind_of(seed)
            if kinds and k not in kinds:
                seed += 1
                continue
            sysd = system(seed)
            for mode in modes:
                row = run_one(a.linkbox, sysd, mode, a.time_limit, work)
                t = totals[mode]
                t["lost"] += row["lost"] if row["complete"] else 0
                t["wrong"] += row["claim_wrong"]
                t["incomplete"] += 1 - row["complete"]
                t["cpu"] += row["cpu"]
                if w:
                    w.writerow(row)
                if defect(row):
                    defects.append(row)
                    print(f"DEFECT seed {seed} ({k}, {mode}): lost {row['lost']} of {row['planted']}, "
                          f"headline '{row['headline']}', true count {row['true_count']}", flush=True)
                    if a.save_failures:
                        os.makedirs(a.save_failures, exist_ok=True)
                        with open(os.path.join(a.save_failures, f"{k}-{seed}.toml"), "w") as f:
                            f.write(sysd["toml"])
            done += 1
            seed += 1
            if out and done % 100 == 0:
                out.flush()
                print(f"{done} systems, {time.time() - t0:.0f} s, " + "; ".join(
                    f"{m}: lost {t['lost']}, wrong {t['wrong']}, incomplete {t['incomplete']}, cpu {t['cpu']:.0f} s"
                    for m, t in totals.items()), flush=True)
    print(f"{done} systems (seeds {a.first_seed}..{seed - 1}): " + "; ".join(
        f"{m}: lost roots (complete runs) {t['lost']}, wrong exact counts {t['wrong']}, incomplete {t['incomplete']}, "
        f"cpu {t['cpu']:.1f} s" for m, t in totals.items()))
    return defects


def cmd_ci(a):
    a.modes, a.csv, a.append, a.kinds, a.save_failures = "verified", None, False, None, None
    defects = cmd_run(a)
    for d in defects:
        print("FAIL", d)
    sys.exit(1 if defects else 0)


# ---------------------------------------------------------------- report

ORDER = ["product", "dense", "close", "scaled", "face", "spherical", "sphface", "6r"]


def quantile(xs, q):
    xs = sorted(xs)
    if not xs:
        return float("nan")
    k = (len(xs) - 1) * q
    i = int(k)
    return xs[i] if i + 1 >= len(xs) else xs[i] + (xs[i + 1] - xs[i]) * (k - i)


def report(paths, outdir):
    """table.md (per kind and mode), time and certified-fraction plots (PNG) in outdir."""
    rows = []
    for p in paths:
        rows += list(csv.DictReader(open(p)))
    for r in rows:
        for k in ("planted", "cpu", "complete", "lost", "certified", "claim_wrong", "exit"):
            r[k] = float(r[k]) if k == "cpu" else int(r[k])
    os.makedirs(outdir, exist_ok=True)
    kinds = [k for k in ORDER if any(r["kind"] == k for r in rows)]
    by = {(k, m): [r for r in rows if r["kind"] == k and r["mode"] == m] for k in kinds + ["all"] for m in ("verified", "float")}
    for m in ("verified", "float"):
        by[("all", m)] = [r for r in rows if r["mode"] == m]
    lines = ["| kind | systems (verified) | planted roots | lost, verified | lost, float | certified (verified) | "
             "time verified: median / p90 / max [s] | time float: median / p90 / max [s] | "
             "\"exactly N\" claims (count known) | wrong \"exactly N\" | incomplete verified / float |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for k in kinds + ["all"]:
        v, f = by[(k, "verified")], by[(k, "float")]
        if not v:
            continue
        planted_n = sum(r["planted"] for r in v)
        lost_v = sum(r["lost"] for r in v if r["complete"])
        lost_vi = sum(r["lost"] for r in v if not r["complete"])
        lost_f = sum(r["lost"] for r in f)
        cert = sum(r["certified"] for r in v)
        claims = sum(1 for r in v if r["claim"] != "")
        known = sum(1 for r in v if r["claim"] != "" and r["true_count"] != "")
        wrong = sum(r["claim_wrong"] for r in v)
        wrong_f = sum(r["claim_wrong"] for r in f)
        inc_v = sum(1 for r in v if not r["complete"])
        inc_f = sum(1 for r in f if not r["complete"])
        tv = [r["cpu"] for r in v]
        tf = [r["cpu"] for r in f]
        ft = (f"{quantile(tf, .5):.3f} / {quantile(tf, .9):.3f} / {max(tf):.2f}" if tf else "-")
        lines.append(
            f"| {k} | {len(v)} | {planted_n} | {lost_v}" + (f" (+{lost_vi} in incomplete runs)" if lost_vi else "")
            + f" | {lost_f} of {sum(r['planted'] for r in f)} ({(100 * lost_f / max(1, sum(r['planted'] for r in f))):.1f}%)"
            + f" in {len(f)} systems"
            + f" | {cert} ({100 * cert / planted_n:.1f}%) | {quantile(tv, .5):.3f} / {quantile(tv, .9):.3f} / {max(tv):.2f}"
            + f" | {ft} | {claims} ({known}) | {wrong}" + (f" (float: {wrong_f})" if wrong_f else "")
            + f" | {inc_v} / {inc_f} |")
    # Verified runs that do not state "exactly N": how many give each reason (one run may give several).
    reasons = {}
    for r in by[("all", "verified")]:
        if r["claim"] == "":
            h = r["headline"]
            m = re.search(r"\((.*)", h)
            parts = (m.group(1).rstrip(")").split("; ") if m else [h])
            if m and not h.endswith(")"):
                parts = parts[:-1]  # cut at 160 characters: the last reason is incomplete
            merged = []
            for part in parts:
                if merged and merged[-1] == "root certified":
                    merged[-1] += "; " + part
                else:
                    merged.append(part)
            for part in merged:
                part = re.sub(r":? \d+ clusters?$", "", part.strip())
                reasons.setdefault(part, {}).setdefault(r["kind"], 0)
                reasons[part][r["kind"]] += 1
    lines += ["", "Verified runs without an exact count, by the reason the headline gives (runs; one run may give "
              "several reasons; the headlines in the CSV are cut at 160 characters):", "",
              "| reason | " + " | ".join(kinds) + " |", "|---|" + "---|" * len(kinds)]
    for part, ks in sorted(reasons.items(), key=lambda x: -sum(x[1].values())):
        lines.append(f"| {part} | " + " | ".join(str(ks.get(k, "")) for k in kinds) + " |")
    # Cross-check where no independent count exists (dense in 3 unknowns, 6R loops): the float
    # variant's certified roots (certified by the same interval Newton test) against the
    # verified "exactly N".
    fl = {(r["seed"], r["kind"]): r for r in by[("all", "float")]}
    odd = []
    for r in by[("all", "verified")]:
        f = fl.get((r["seed"], r["kind"]))
        if r["claim"] != "" and f and int(f["certified_roots"] or 0) > int(r["claim"]):
            odd.append(f"seed {r['seed']} ({r['kind']}): verified 'exactly {r['claim']}', float certified {f['certified_roots']}")
    unknown = [r for r in by[("all", "verified")] if r["claim"] != "" and r["true_count"] == ""]
    lines += ["", f"Exact counts without an independent count ({len(unknown)} runs: dense systems in 3 unknowns, "
              f"6R loops): the float variant certified more roots than the verified \"exactly N\" in {len(odd)} of them"
              + (": " + "; ".join(odd[:20]) if odd else ".")]
    with open(os.path.join(outdir, "table.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, m in zip(axes, ("verified", "float")):
        for k in kinds:
            ts = sorted(r["cpu"] for r in by[(k, m)])
            if ts:
                ax.plot(ts, [(i + 1) / len(ts) for i in range(len(ts))], label=f"{k} ({len(ts)})")
        ax.set_xscale("log")
        ax.set_xlabel("CPU seconds per system (process, incl. ~0.04 s start-up)")
        ax.set_title(f"{m} mode: distribution of solve times")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("fraction of systems solved within")
    for ax in axes:
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "time.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4.6))
    xs = range(len(kinds))
    cert = [sum(r["certified"] for r in by[(k, "verified")]) / max(1, sum(r["planted"] for r in by[(k, "verified")]))
            for k in kinds]
    exact = [sum(1 for r in by[(k, "verified")] if r["claim"] != "") / max(1, len(by[(k, "verified")])) for k in kinds]
    lostf = [sum(r["lost"] for r in by[(k, "float")]) / max(1, sum(r["planted"] for r in by[(k, "float")])) for k in kinds]
    ax.bar([x - 0.27 for x in xs], cert, 0.27, label="planted roots certified (verified)")
    ax.bar(list(xs), exact, 0.27, label="systems with an exact count (verified)")
    ax.bar([x + 0.27 for x in xs], lostf, 0.27, label="planted roots lost (float variant)")
    ax.set_xticks(list(xs))
    ax.set_xticklabels(kinds)
    ax.set_ylim(0, 1.05)
    ax.set_ylabel("fraction")
    ax.set_title("Planted roots certified (verified mode) and lost (float variant)", fontsize=11)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3)
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "certified.png"), dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("case")
    c.add_argument("seed", type=int)
    c.add_argument("--kind", choices=sorted(set(KINDS)))
    for name in ("run", "ci"):
        r = sub.add_parser(name)
        r.add_argument("linkbox")
        r.add_argument("--count", type=int, default=300)
        r.add_argument("--first-seed", type=int, default=0)
        r.add_argument("--time-limit", type=float, default=20)
        if name == "run":
            r.add_argument("--modes", default="verified,float")
            r.add_argument("--kinds", default=None)
            r.add_argument("--csv", default=None)
            r.add_argument("--append", action="store_true")
            r.add_argument("--save-failures", default=None)
    rp = sub.add_parser("report")
    rp.add_argument("csv", nargs="+")
    rp.add_argument("--out", required=True)
    a = ap.parse_args()
    if a.cmd == "case":
        s = system(a.seed, a.kind)
        print(s["toml"], end="")
    elif a.cmd == "run":
        cmd_run(a)
    elif a.cmd == "ci":
        cmd_ci(a)
    else:
        report(a.csv, a.out)


if __name__ == "__main__":
    main()
