#!/usr/bin/env python3
"""Random polynomial systems whose real roots are known exactly.

Each equation starts as a product of affine forms a.x - b (a: small integers, b: multiples
of 1/8), so the roots are the solutions of the linear systems that pick one form per
equation; they are computed in exact rational arithmetic (fractions). The equations are
then mixed by a random integer matrix: the roots stay the same, the product structure that
propagation would exploit is gone ("sums of products of affine forms"). Every coefficient
is a dyadic rational, so the case file states the system exactly.

Options plant close pairs of roots (two parallel forms 2^-k apart), add redundant
equations (more equations than unknowns), and a random DH-free variety of shapes.

  planted.py --seed 7 --unknowns 3 --degrees 2,2,3 [--gap 10] [--extra 1] > case.toml
  planted.py ... --roots       # prints the planted roots in the domain, one per line
"""
import argparse
import itertools
import random
from fractions import Fraction


def solve(a, b):
    """Exact solution of a x = b (square), or None when singular."""
    n = len(a)
    m = [list(map(Fraction, row)) + [Fraction(v)] for row, v in zip(a, b)]
    for c in range(n):
        p = next((r for r in range(c, n) if m[r][c] != 0), None)
        if p is None:
            return None
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c and m[r][c] != 0:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][n] / m[i][i] for i in range(n)]


def poly_mul(p, q):
    r = {}
    for ep, cp in p.items():
        for eq, cq in q.items():
            e = tuple(x + y for x, y in zip(ep, eq))
            r[e] = r.get(e, 0) + cp * cq
    return {e: c for e, c in r.items() if c != 0}


def poly_add(p, q, k=1):
    r = dict(p)
    for e, c in q.items():
        r[e] = r.get(e, 0) + k * c
    return {e: c for e, c in r.items() if c != 0}


def affine(a, b):
    n = len(a)
    p = {tuple(1 if k == i else 0 for k in range(n)): Fraction(a[i]) for i in range(n) if a[i] != 0}
    p[(0,) * n] = -Fraction(b)
    return {e: c for e, c in p.items() if c != 0}


def decimal(c):
    """A dyadic rational as an exact decimal string."""
    num, den = c.numerator, c.denominator
    k = den.bit_length() - 1
    assert den == 1 << k
    digits = num * 5**k
    s = str(abs(digits)).rjust(k + 1, "0")
    out = s[: len(s) - k] + ("." + s[len(s) - k:] if k else "")
    out = out.rstrip("0").rstrip(".") if "." in out else out
    return ("-" if digits < 0 else "") + out


def term(e, names):
    return "*".join(n if p == 1 else f"{n}^{p}" for n, p in zip(names, e) if p)


def generate(seed, n, degrees, gap_exp=None, extra=0, bound=1):
    rng = random.Random(seed)
    while True:
        forms = []
        for d in degrees:
            eq = []
            for _ in range(d):
                a = [rng.randint(-4, 4) for _ in range(n)]
                if not any(a):
                    a[rng.randrange(n)] = 1
                eq.append((a, Fraction(rng.randint(-6, 6), 8)))
            forms.append(eq)
        if gap_exp:  # a close pair: a second form parallel to the first, 2^-gap_exp away
            a, b = forms[0][0]
            forms[0][1] = (a, b + Fraction(1, 2**gap_exp))
        roots, ok = [], True
        for pick in itertools.product(*[range(len(f)) for f in forms]):
            x = solve([forms[i][j][0] for i, j in enumerate(pick)], [forms[i][j][1] for i, j in enumerate(pick)])
            if x is None:
                ok = False
                break
            near_face = all(-bound - Fraction(1, 100) < v < bound + Fraction(1, 100) for v in x) and any(
                min(abs(v - bound), abs(v + bound)) < Fraction(1, 100) for v in x)
            if near_face:  # keep roots off the faces, inside or out: this tests counts, not faces
                ok = False
                break
            if all(-bound < v < bound for v in x):
                roots.append(x)
        if not ok or len(set(map(tuple, roots))) != len(roots) or not roots:
            continue
        products = []
        for eq in forms:
            p = {(0,) * n: Fraction(1)}
            for a, b in eq:
                p = poly_mul(p, affine(a, b))
            products.append(p)
        m = len(degrees) + extra
        while True:
            mix = [[rng.randint(-3, 3) for _ in range(len(products))] for _ in range(m)]
            if solve(mix[: len(products)], [0] * len(products)) is not None:
                break
        eqs = []
        for row in mix:
            p = {}
            for k, q in zip(row, products):
                p = poly_add(p, q, k)
            eqs.append(p)
        if any(not e for e in eqs):
            continue
        return eqs, roots


def to_toml(seed, n, degrees, eqs, roots, gap_exp, extra, bound):
    names = [f"x{i + 1}" for i in range(n)]
    lines = [
        f"# Planted-root system (tests/planted.py --seed {seed} --unknowns {n} --degrees "
        f"{','.join(map(str, degrees))}{f' --gap {gap_exp}' if gap_exp else ''}{f' --extra {extra}' if extra else ''}).",
        f"# expected: exactly {len(roots)} roots",
        'kind = "polynomial"',
        f'name = "planted-{seed}"',
        "variables = [",
    ]
    lines += [f'  {{ name = "{v}", domain = [{-bound}, {bound}] }},' for v in names]
    lines.append("]")
    lines.append("equations = [")
    for p in eqs:
        parts = []
        for e, c in sorted(p.items(), reverse=True):
            t = term(e, names)
            mag = decimal(abs(c))
            body = (mag if not t else (t if mag == "1" else f"{mag}*{t}"))
            parts.append(("- " if c < 0 else "+ ") + body)
        s = " ".join(parts)
        lines.append(f'  "{s[2:] if s.startswith("+ ") else "-" + s[2:]}",')
    lines.append("]")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--unknowns", type=int, default=3)
    ap.add_argument("--degrees", default="2,2,2")
    ap.add_argument("--gap", type=int, default=None, help="plant a close pair 2^-GAP apart")
    ap.add_argument("--extra", type=int, default=0, help="redundant equations (more equations than unknowns)")
    ap.add_argument("--roots", action="store_true", help="print the planted roots instead of the case")
    a = ap.parse_args()
    degrees = [int(d) for d in a.degrees.split(",")]
    assert len(degrees) == a.unknowns, "one degree per equation, as many equations as unknowns"
    eqs, roots = generate(a.seed, a.unknowns, degrees, a.gap, a.extra)
    if a.roots:
        for r in roots:
            print(" ".join(repr(float(v)) for v in r))
    else:
        print(to_toml(a.seed, a.unknowns, degrees, eqs, roots, a.gap, a.extra, 1), end="")


if __name__ == "__main__":
    main()
