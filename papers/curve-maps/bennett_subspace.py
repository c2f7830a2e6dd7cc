"""Why the Bennett linkage's curve is not mapped through a symmetry (a float check, no proof).

Every loop of four revolute joints whose parameters repeat with period two has the symmetry
theta -> (-theta3, -theta4, -theta1, -theta2): the mirror in the x axis (Rx(pi) conjugation
turns Rz(t) into Rz(-t) and keeps each link's Tx Rx) composed with swapping the halves. Its
fixed set is u = 0 (theta3 = -theta1, theta4 = -theta2), where Bennett's curve lies. There the
closure T(v) T(-v) = I reads (T(v) M)^2 = I, M = Rx(pi): T(v) M is a half-turn, i.e.
R(v) = (q_0, vec q . p) = 0, two equations in the two unknowns v = (theta1, theta2).

This script finds points of the curve (tan(theta1/2) tan(theta2/2) = sqrt(3)) and prints the
singular values of R's Jacobian there: the second is at rounding level, so on the subspace
the system is still of rank one and gives no regular square system to certify the curve with
(unlike the six-joint loops, verify/symmetric_loop.hpp, whose reduced system is regular).

    /usr/bin/python3 papers/curve-maps/bennett_subspace.py
"""
import numpy as np
from scipy.optimize import minimize_scalar

A1, ALPHA1, A2, ALPHA2 = 1.0, np.pi / 6, 2.0, np.pi / 2  # cases/linkages/bennett.toml


def rz(t):
    m = np.eye(4)
    m[:2, :2] = [[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]]
    return m


def link(a, alpha):
    m = np.eye(4)
    m[1:3, 1:3] = [[np.cos(alpha), -np.sin(alpha)], [np.sin(alpha), np.cos(alpha)]]
    m[0, 3] = a
    return m


def half(t1, t2):
    return rz(t1) @ link(A1, ALPHA1) @ rz(t2) @ link(A2, ALPHA2)


MIRROR = np.diag([1.0, -1.0, -1.0, 1.0])


def qmul(a, b):
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return np.array([a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3, a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
                     a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1, a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0])


def qz(t):
    return np.array([np.cos(t / 2), 0, 0, np.sin(t / 2)])


def qx(t):
    return np.array([np.cos(t / 2), np.sin(t / 2), 0, 0])


def reduced(v):
    """R(v) = (q_0, vec q . p) of T(v) M."""
    q = qmul(qmul(qmul(qmul(qz(v[0]), qx(ALPHA1)), qz(v[1])), qx(ALPHA2)), qx(np.pi))
    p = (half(v[0], v[1]) @ MIRROR)[:3, 3]
    return np.array([q[0], q[1:] @ p])


def closure_error(t1, t2):
    return np.linalg.norm(half(t1, t2) @ half(-t1, -t2) - np.eye(4))


def main():
    ratio = np.sin((ALPHA2 + ALPHA1) / 2) / np.sin((ALPHA2 - ALPHA1) / 2)
    h = 1e-6
    print("theta1  theta2  closure error  |R|  singular values of R's Jacobian")
    for t1 in (0.3, 0.7, 1.2, 2.0):
        guess = 2 * np.arctan(ratio / np.tan(t1 / 2))
        t2 = minimize_scalar(lambda t: closure_error(t1, t), bracket=(guess - 0.01, guess + 0.01)).x
        v = np.array([t1, t2])
        j = np.array([(reduced(v + h * e) - reduced(v - h * e)) / (2 * h) for e in np.eye(2)]).T
        s = np.linalg.svd(j)[1]
        print(f"{t1:.2f}  {t2:.6f}  {closure_error(t1, t2):.1e}  {np.linalg.norm(reduced(v)):.1e}  {s[0]:.3f} {s[1]:.1e}")


if __name__ == "__main__":
    main()
