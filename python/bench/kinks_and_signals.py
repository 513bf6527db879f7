"""Problems for unseen.py's nineteenth set: kinks that run along curves or across rotated
axes, and a signal's parameters fitted to its samples. The earlier sets' kinks lie along
the coordinate axes (the L1 and L-infinity norms, Alpine) or at the minimum only; here
they are where a user's minimax or absolute-value loss puts them.

* crescent2, mifflin2, lq2: classic two-dimensional test functions of nonsmooth
  optimisation (Makela and Neittaanmaki, "Nonsmooth Optimization", 1992), each the
  maximum of two smooth pieces or a smooth function plus a kink along a circle, with the
  minimum on the kink:
  crescent f = max(x^2 + (y - 1)^2 + y - 1, -x^2 - (y - 1)^2 + y + 1), f* = 0 at (0, 0);
  mifflin f = -x + 2(x^2 + y^2 - 1) + 1.75|x^2 + y^2 - 1|, f* = -1 at (1, 0);
  lq f = max(-x - y, -x - y + x^2 + y^2 - 1), f* = -sqrt(2) at (1/sqrt 2, 1/sqrt 2).
* minimax-fit8, minimax-fit16: the coefficients c of a polynomial of degree 7 (15) in
  the Chebyshev basis, fitted to another such polynomial's values at 101 (201) evenly
  spaced points of [-1, 1] in the largest error, f(c) = max_t |sum_k (c_k - c*_k)
  T_k(t)|: an L-infinity norm of a linear map (kinks across rotated directions), f* = 0
  at c*.
* cusps10, cusps20: the sum of square roots sum_i |y_i|^(1/2) of y = Q(x - x*) for a
  random rotation Q: a cusp (unbounded slope) at the minimum along every rotated axis,
  f* = 0; the target 1e-3 asks every |y_i| below about 1e-8.
* sinusoid3, sinusoid-long3: amplitude, angular frequency and phase of a sine fitted to
  100 samples on [0, 10] (500 on [0, 50]), f the mean squared misfit, f* = 0 at
  (1.3, 2.7, 0.4) in the box [0, 3] x [0.5, 5] x [-pi, pi] ((1.3, 6.7, 0.4) in
  [0, 3] x [0.5, 10] x [-pi, pi]): a frequency search, whose misfit has a local minimum
  every ~0.6 (~0.13) in frequency.

Budgets are 2 000 n evaluations (3 000 for the sines), targets 1e-6 on f (1e-3 for the
cusps), starts uniform in [-3, 3]^n (in the box for the sines), sigma0 1 (a quarter of
each side of a sine's box).
"""

import numpy as np

from raster_losses import Case


def crescent(x):
    a, b = x
    return float(max(a * a + (b - 1) ** 2 + b - 1, -a * a - (b - 1) ** 2 + b + 1))


def mifflin(x):
    a, b = x
    r = a * a + b * b - 1
    return float(-a + 2 * r + 1.75 * abs(r))


def lq(x):
    a, b = x
    return float(max(-a - b, -a - b + a * a + b * b - 1))


def minimax_fit(degree, points):
    """max_t |sum_k (c_k - c*_k) T_k(t)| over `points` evenly spaced t in [-1, 1], c*
    drawn once; returns (f, c*)."""
    t = np.linspace(-1.0, 1.0, points)
    basis = np.polynomial.chebyshev.chebvander(t, degree)
    truth = np.random.default_rng(19).uniform(-1.0, 1.0, degree + 1)
    values = basis @ truth

    def f(c):
        return float(np.max(np.abs(basis @ np.asarray(c, dtype=float) - values)))

    return f, truth


def cusps(n):
    """sum_i |y_i|^(1/2), y = Q(x - x*), Q from the QR of a Gaussian matrix drawn once."""
    rng = np.random.default_rng(1019)
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    truth = rng.uniform(-1.0, 1.0, n)

    def f(x):
        y = q @ (np.asarray(x, dtype=float) - truth)
        return float(np.sum(np.sqrt(np.abs(y))))

    return f, truth


def sinusoid(span, samples, truth, top):
    """The mean squared misfit of a sine a sin(wt + p) to `truth`'s at `samples` evenly
    spaced t in [0, span], with its box (frequencies from 0.5 to `top`)."""
    times = np.linspace(0.0, span, samples)
    data = truth[0] * np.sin(truth[1] * times + truth[2])

    def f(x):
        a, w, p = x
        residual = a * np.sin(w * times + p) - data
        return float(np.mean(residual * residual))

    low, high = np.array([0.0, 0.5, -np.pi]), np.array([3.0, top, np.pi])
    return Case(f, truth, (high - low) / 4.0, (low, high), 3000, 1e-6, (low, high))


def _problems():
    out = {
        "crescent2": Case(crescent, np.array([0.0, 0.0]), 1.0, None, 4000, 1e-6, (-3.0, 3.0)),
        "mifflin2": Case(mifflin, np.array([1.0, 0.0]), 1.0, None, 4000, 1e-6, (-3.0, 3.0)),
        "lq2": Case(lq, np.full(2, 1.0 / np.sqrt(2.0)), 1.0, None, 4000, 1e-6, (-3.0, 3.0)),
    }
    for degree, points in ((7, 101), (15, 201)):
        f, truth = minimax_fit(degree, points)
        n = degree + 1
        out[f"minimax-fit{n}"] = Case(f, truth, 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))
    for n in (10, 20):
        f, truth = cusps(n)
        out[f"cusps{n}"] = Case(f, truth, 1.0, None, 2000 * n, 1e-3, (-3.0, 3.0))
    out["sinusoid3"] = sinusoid(10.0, 100, np.array([1.3, 2.7, 0.4]), 5.0)
    out["sinusoid-long3"] = sinusoid(50.0, 500, np.array([1.3, 6.7, 0.4]), 10.0)
    return out


PROBLEMS = _problems()
