"""Bound-constrained problems for unseen.py's fourth set: Hock and Schittkowski's problems
whose only constraints are bounds (Test Examples for Nonlinear Programming Codes, 1981:
problems 2, 3, 4, 5, 25, 45 and 110; 242 from Schittkowski's 1987 supplement), and three
built here so that their minimiser is known exactly: a rotated ill-conditioned quadratic
whose minimum lies on eight of the box's faces, Rosenbrock's function with its minimum in
the box's corner, and Styblinski-Tang's function cut by a face through its best basin.

Each function takes a float vector and returns a float; each problem is (f, lower,
upper, published start, minimiser), with ±inf for an open side. A user of a renderer meets
these shapes whenever a parameter has a physical range: a colour in [0, 1] that wants to
be brighter than white, a distance that must stay positive.
"""

import numpy as np


def hs2(x):
    """Rosenbrock's function with x2 >= 1.5; a second, worse minimum on that face at
    x1 ~ -1.22, on the side the published start (-2, 1) lies."""
    return float(100 * (x[1] - x[0] ** 2) ** 2 + (1 - x[0]) ** 2)


def _hs2_argmin():
    # On the face x2 = 1.5: d/dx1 = 0 is 400 x1^3 - 598 x1 - 2 = 0; the largest root.
    root = max(r.real for r in np.roots([400.0, 0.0, -598.0, -2.0]) if abs(r.imag) < 1e-12)
    for _ in range(5):
        root -= (400 * root ** 3 - 598 * root - 2) / (1200 * root ** 2 - 598)
    return np.array([root, 1.5])


def hs3(x):
    """A linear slope in x2 >= 0 with a weak valley along x1 = x2; minimum (0, 0), f* = 0."""
    return float(x[1] + 1e-5 * (x[1] - x[0]) ** 2)


def hs4(x):
    """Increasing in both coordinates; minimum in the corner (1, 0), f* = 8/3."""
    return float((x[0] + 1) ** 3 / 3 + x[1])


def hs5(x):
    """McCormick's function in [-1.5, 4] x [-3, 3]; interior minimum
    (1/2 - pi/3, -1/2 - pi/3), f* = -sqrt(3)/2 - pi/3."""
    return float(np.sin(x[0] + x[1]) + (x[0] - x[1]) ** 2 - 1.5 * x[0] + 2.5 * x[1] + 1)


GULF_T = np.arange(1, 100) / 100
GULF_Y = 25 + (-50 * np.log(GULF_T)) ** (2 / 3)


def hs25(x):
    """The Gulf research and development function (m = 99) in its box; minimum
    (50, 25, 1.5), f* = 0. x1 >= 0.1 keeps the exponent's divisor away from 0."""
    r = np.exp(-np.abs(GULF_Y - x[1]) ** x[2] / x[0]) - GULF_T
    return float(r @ r)


def hs45(x):
    """2 - x1 x2 x3 x4 x5 / 120 in 0 <= xi <= i: the minimum 1 is the box's far corner."""
    return float(2 - np.prod(x) / 120)


def hs110(x):
    """Paviani's function: sum of ln(xi - 2)^2 + ln(10 - xi)^2 less (prod xi)^0.2 in
    [2.001, 9.999]^10; outside (2, 10) the logarithms are NaN."""
    x = np.asarray(x, dtype=float)
    return float(np.sum(np.log(x - 2) ** 2 + np.log(10 - x) ** 2) - np.prod(x) ** 0.2)


def _hs110_argmin():
    # By symmetry every coordinate is the same t, and f = 10 (ln(t-2)^2 + ln(10-t)^2) - t^2;
    # its derivative changes sign once in [8, 9.9]. Bisection to rounding.
    def slope(t):
        return 20 * (np.log(t - 2) / (t - 2) - np.log(10 - t) / (10 - t)) - 2 * t

    low, high = 8.0, 9.9
    for _ in range(200):
        middle = 0.5 * (low + high)
        if slope(middle) < 0:
            low = middle
        else:
            high = middle
    return np.full(10, 0.5 * (low + high))


HS242_T = np.arange(11, 21) / 100


def hs242(x):
    """Box's exponential fit in [0, 10]^3; minimum (1, 10, 1) on the face x2 = 10, f* = 0."""
    r = (np.exp(-x[0] * HS242_T) - np.exp(-x[1] * HS242_T)
         - x[2] * (np.exp(-HS242_T) - np.exp(-10 * HS242_T)))
    return float(r @ r)


def _face_quadratic(n=20, seed=20261130):
    """f(x) = (x - c)' A (x - c) / 2 - f0 in [0, 1]^n, A = R diag(10^(4 i / (n - 1))) R'
    (R a random rotation, condition 10^4). The minimiser x* is chosen first: four
    coordinates on the lower face, four on the upper, the rest inside; then the gradient
    g there, positive on the lower faces, negative on the upper, zero inside (the KKT
    conditions), and c = x* - A^-1 g. Convex, so x* is the only minimum; f* = 0."""
    rng = np.random.default_rng(seed)
    rotation, _ = np.linalg.qr(rng.normal(size=(n, n)))
    hessian = rotation @ np.diag(10.0 ** (4 * np.arange(n) / (n - 1))) @ rotation.T
    x_opt = rng.uniform(0.2, 0.8, n)
    gradient = np.zeros(n)
    x_opt[:4], gradient[:4] = 0.0, rng.uniform(0.5, 2.0, 4)
    x_opt[4:8], gradient[4:8] = 1.0, -rng.uniform(0.5, 2.0, 4)
    centre = x_opt - np.linalg.solve(hessian, gradient)
    offset = 0.5 * (x_opt - centre) @ hessian @ (x_opt - centre)

    def f(x):
        d = np.asarray(x, dtype=float) - centre
        return float(0.5 * d @ hessian @ d - offset)

    return f, x_opt


face_quadratic, FACE_QUADRATIC_ARGMIN = _face_quadratic()


def rosenbrock(x):
    """Rosenbrock's function; with the box [-2, 1]^n its minimum (1, ..., 1) is the box's
    corner, where the gradient vanishes."""
    return float(np.sum(100 * (x[1:] - x[:-1] ** 2) ** 2 + (1 - x[:-1]) ** 2))


def styblinski_tang(x):
    """Styblinski and Tang's function, sum of (xi^4 - 16 xi^2 + 5 xi) / 2. In [-2, 5]^n
    the face xi = -2 cuts its best basin (-2.90): per coordinate -29 there against -25.03
    at the other basin's bottom (2.75), which fills most of the box; f* = -29 n."""
    return float(np.sum(x ** 4 - 16 * x ** 2 + 5 * x) / 2)


INF = np.inf

# name: (f, lower, upper, published start (or None: uniform in the box), minimiser)
PROBLEMS = {
    "hs2": (hs2, [-INF, 1.5], [INF, INF], [-2, 1], _hs2_argmin()),
    "hs3": (hs3, [-INF, 0], [INF, INF], [10, 1], [0, 0]),
    "hs4": (hs4, [1, 0], [INF, INF], [1.125, 0.125], [1, 0]),
    "hs5": (hs5, [-1.5, -3], [4, 3], [0, 0], [0.5 - np.pi / 3, -0.5 - np.pi / 3]),
    "hs25": (hs25, [0.1, 0, 0], [100, 25.6, 5], [100, 12.5, 3], [50, 25, 1.5]),
    "hs45": (hs45, np.zeros(5), np.arange(1, 6), np.full(5, 2), np.arange(1, 6)),
    "hs110": (hs110, np.full(10, 2.001), np.full(10, 9.999), np.full(10, 9), _hs110_argmin()),
    "hs242": (hs242, np.zeros(3), np.full(3, 10), [2.5, 10, 10], [1, 10, 1]),
    "face-quadratic20": (face_quadratic, np.zeros(20), np.ones(20), None,
                         FACE_QUADRATIC_ARGMIN),
    "corner-rosenbrock10": (rosenbrock, np.full(10, -2), np.ones(10), None, np.ones(10)),
    "cut-styblinski-tang10": (styblinski_tang, np.full(10, -2), np.full(10, 5), None,
                              np.full(10, -2)),
}
