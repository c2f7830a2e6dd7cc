#!/usr/bin/env python3
"""Classic systems from the literature, none of them in IbexSolve's benchmark folder's given
half, written as Minibex files: a check of linkbox beside IbexSolve on systems nobody tuned
either for (papers/reliability/classic.md). Run it here to rewrite the .bch files.

Sources: Katsura, cyclic-n, Reimer-n and Noon-n as in the PoSSo / PHCpack test suites; Trinks
(the 6-equation form); Morgan's combustion system; Moré, Garbow and Hillstrom's test functions
(Powell singular, Powell badly scaled, helical valley, Freudenstein-Roth, Beale, Brown badly
scaled, box three-dimensional, Chebyquad, variably dimensioned, Bard, Wood, extended Powell
singular, Rosenbrock); Chandrasekhar's H-equation discretised (Moré's form, multiplied out)."""
import pathlib

HERE = pathlib.Path(__file__).resolve().parent


def write(name, variables, equations, note):
    lines = [f"// {note}", "Variables"]
    lines += [f"{v} in {d};" for v, d in variables]
    lines += ["", "Constraints"] + [f"{e} = 0;" for e in equations] + ["end", ""]
    (HERE / f"{name}.bch").write_text("\n".join(lines))


def katsura(n):
    x = [f"x{i}" for i in range(n + 1)]
    xa = lambda i: x[abs(i)] if abs(i) <= n else "0"
    eqs = []
    for m in range(n):
        terms = [f"{xa(l)}*{xa(m - l)}" for l in range(-n, n + 1) if abs(l) <= n and abs(m - l) <= n]
        eqs.append(" + ".join(terms) + f" - {x[m]}")
    eqs.append(x[0] + "".join(f" + 2*{v}" for v in x[1:]) + " - 1")
    write(f"katsura-{n}", [(v, "[-1,1]") for v in x], eqs, f"Katsura-{n}: {n + 1} unknowns")


def cyclic(n):
    x = [f"x{i}" for i in range(1, n + 1)]
    eqs = []
    for k in range(1, n):
        eqs.append(" + ".join("*".join(x[(i + j) % n] for j in range(k)) for i in range(n)))
    eqs.append("*".join(x) + " - 1")
    write(f"cyclic-{n}", [(v, "[-10,10]") for v in x], eqs, f"cyclic-{n}")


def reimer(n):
    x = [f"x{i}" for i in range(1, n + 1)]
    eqs = []
    for p in range(2, n + 2):
        eqs.append("".join(f" {'+' if j % 2 == 0 else '-'} {v}^{p}" for j, v in enumerate(x)).lstrip(" +") + " - 0.5")
    write(f"reimer-{n}", [(v, "[-10,10]") for v in x], eqs, f"Reimer-{n}")


def noon(n):
    x = [f"x{i}" for i in range(1, n + 1)]
    eqs = []
    for i, v in enumerate(x):
        others = " + ".join(f"{w}^2" for j, w in enumerate(x) if j != i)
        eqs.append(f"{v}*({others}) - 1.1*{v} + 1")
    write(f"noon-{n}", [(v, "[-10,10]") for v in x], eqs, f"Noon-{n}")


def chebyquad(n):
    # (1/n) sum_j T_i(2 x_j - 1) = b_i, b_i = 0 for odd i and -1/(i^2 - 1) for even i.
    x = [f"x{j}" for j in range(1, n + 1)]
    def cheb(i, y):
        t0, t1 = "1", y
        if i == 1:
            return t1
        polys = ["1", y]
        for _ in range(2, i + 1):
            polys.append(f"(2*{y}*({polys[-1]}) - ({polys[-2]}))")
        return polys[i]
    eqs = []
    for i in range(1, n + 1):
        b = "0" if i % 2 else f"(-1/{i * i - 1})"
        eqs.append("(" + " + ".join(cheb(i, f"(2*{v} - 1)") for v in x) + f")/{n} - {b}")
    write(f"chebyquad-{n}", [(v, "[0,1]") for v in x], eqs, f"Chebyquad-{n} (More, Garbow, Hillstrom 35)")


for n in (4, 5, 6, 7):
    katsura(n)
cyclic(5)
for n in (4, 5):
    reimer(n)
for n in (3, 4, 5):
    noon(n)
for n in (2, 3, 4, 5):
    chebyquad(n)

write("trinks", [(v, "[-10,10]") for v in "wpztsb"], [
    "45*p + 35*s - 165*b - 36",
    "35*p + 40*z + 25*t - 27*s",
    "15*w + 25*s*p + 30*z - 18*t - 165*b^2",
    "-9*w + 15*t*p + 20*s*z",
    "w*p + 2*z*t - 11*b^3",
    "99*w - 11*b*s + 3*b^2"], "Trinks (six equations)")

write("combustion", [(f"x{i}", "[-1,1]") for i in range(1, 11)], [
    "x2 + 2*x6 + x9 + 2*x10 - 1e-5",
    "x3 + x8 - 3e-5",
    "x1 + x3 + 2*x5 + 2*x8 + x9 + x10 - 5e-5",
    "x4 + 2*x7 - 1e-5",
    "0.5140437e-7*x5 - x1^2",
    "0.1006932e-6*x6 - 2*x2^2",
    "0.7816278e-15*x7 - x4^2",
    "0.1496236e-6*x8 - x1*x3",
    "0.6194411e-7*x9 - x1*x2",
    "0.2089296e-14*x10 - x1*x2^2"], "Morgan's combustion system: badly scaled")

write("powell-singular", [(f"x{i}", "[-10,10]") for i in range(1, 5)], [
    "x1 + 10*x2", "sqrt(5)*(x3 - x4)", "(x2 - 2*x3)^2", "sqrt(10)*(x1 - x4)^2"],
    "Powell singular (MGH 13): one root, at 0, with a singular Jacobian")
write("powell-badly-scaled", [("x1", "[-10,10]"), ("x2", "[-10,10]")], [
    "10000*x1*x2 - 1", "exp(-x1) + exp(-x2) - 1.0001"], "Powell badly scaled (MGH 3): two roots")
write("helical-valley", [("x1", "[-10,10]"), ("x2", "[-10,10]"), ("x3", "[-10,10]")], [
    "10*(x3 - 10*atan2(x2, x1)/(2*pi))", "10*(sqrt(x1^2 + x2^2) - 1)", "x3"],
    "Helical valley (MGH 7): root (1, 0, 0)")
write("freudenstein-roth", [("x1", "[-100,100]"), ("x2", "[-100,100]")], [
    "-13 + x1 + ((5 - x2)*x2 - 2)*x2", "-29 + x1 + ((x2 + 1)*x2 - 14)*x2"],
    "Freudenstein and Roth (MGH 2)")
write("beale", [("x1", "[-10,10]"), ("x2", "[-10,10]")], [
    "1.5 - x1*(1 - x2)", "2.25 - x1*(1 - x2^2)", "2.625 - x1*(1 - x2^3)"],
    "Beale (MGH 5): three equations in two unknowns, root (3, 0.5)")
write("brown-badly-scaled", [("x1", "[-1e7,1e7]"), ("x2", "[-1e7,1e7]")], [
    "x1 - 1e6", "x2 - 2e-6", "x1*x2 - 2"],
    "Brown badly scaled (MGH 4): three equations in two unknowns, root (1e6, 2e-6)")
write("box-3d", [("x1", "[0,20]"), ("x2", "[0,20]"), ("x3", "[-5,5]")], [
    f"exp(-{t}*x1) - exp(-{t}*x2) - x3*(exp(-{t}) - exp(-10*{t}))" for t in ("0.1", "0.2", "0.3")],
    "Box three-dimensional (MGH 12) with m = 3: roots (1, 10, 1), (10, 1, -1) and the line x1 = x2, x3 = 0")


def variably_dimensioned(n):
    x = [f"x{i}" for i in range(1, n + 1)]
    s = " + ".join(f"{j + 1}*({v} - 1)" for j, v in enumerate(x))
    write(f"variably-dimensioned-{n}", [(v, "[-10,10]") for v in x], [f"{v} - 1" for v in x] + [s, f"({s})^2"],
          f"Variably dimensioned (MGH 25), n = {n}: {n + 2} equations, the root (1, ..., 1)")


def chandrasekhar(n, c):
    # h_i (1 - c/(2n) sum_j mu_i h_j / (mu_i + mu_j)) = 1, mu_i = (i - 1/2)/n.
    h = [f"h{i}" for i in range(1, n + 1)]
    mu = [(2 * i - 1) / (2 * n) for i in range(1, n + 1)]
    eqs = []
    for i, hi in enumerate(h):
        terms = " + ".join(f"{mu[i] / (mu[i] + mu[j]):.17g}*{hj}" for j, hj in enumerate(h))
        eqs.append(f"{hi}*(1 - {c / (2 * n):.17g}*({terms})) - 1")
    write(f"chandrasekhar-{n}", [(v, "[-10,10]") for v in h], eqs, f"Chandrasekhar's H-equation, n = {n}, c = {c}")


variably_dimensioned(4)
chandrasekhar(6, 0.9)
BARD_Y = [0.14, 0.18, 0.22, 0.25, 0.29, 0.32, 0.35, 0.39, 0.37, 0.58, 0.73, 0.96, 1.34, 2.10, 4.39]
write("bard", [("x1", "[-10,10]"), ("x2", "[0.1,10]"), ("x3", "[0.1,10]")], [
    f"{y} - (x1 + {i}/({16 - i}*x2 + {min(i, 16 - i)}*x3))" for i, y in enumerate(BARD_Y, 1)],
    "Bard (MGH 8): 15 equations in 3 unknowns with no root (least squares residual 8.2e-3)")
write("wood-integer", [(f"x{i}", "[-10,10]") for i in range(1, 5)], [
    "10*(x2 - x1^2)", "1 - x1", "9*(x4 - x3^2)", "1 - x3", "3*(x2 + x4 - 2)", "(x2 - x4)/3"],
    "after Wood (MGH 14), with integer weights: 6 equations in 4 unknowns, the root (1, 1, 1, 1)")
write("extended-powell-8", [(f"x{i}", "[-10,10]") for i in range(1, 9)], [
    e for k in (0, 4) for e in (f"x{k + 1} + 10*x{k + 2}", f"sqrt(5)*(x{k + 3} - x{k + 4})",
                                f"(x{k + 2} - 2*x{k + 3})^2", f"sqrt(10)*(x{k + 1} - x{k + 4})^2")],
    "Extended Powell singular (MGH 22), n = 8: the one root 0, singular")
write("rosenbrock", [("x1", "[-10,10]"), ("x2", "[-10,10]")], ["10*(x2 - x1^2)", "1 - x1"],
      "Rosenbrock (MGH 1): root (1, 1)")
