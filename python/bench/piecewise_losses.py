"""Problems for unseen.py's fifteenth set: losses made of pieces, as a statistician writes
them when the squared error is the wrong loss. None of hodr's tasks, tests or suites has
them, and none of the earlier sets has a kink count above n or a count of points as f.

* Least absolute deviations (robust regression): half the mean of |b_i - a_i . x| over
  m > n samples with Laplace noise (the pinball loss below at q = 1/2), n = 10 and 30.
  f is convex and piecewise linear, kinked on m hyperplanes at every angle; its minimum
  is a vertex on n of them (the seventh set's rotated L1 norm has n, all through it).
* Quantile regression: such data under the pinball loss of quantile q = 0.9, q·r for
  r >= 0 and (q - 1)·r below, r = b_i - a_i . x: the kinks are lopsided; n = 10.
* Misclassified points (a classifier's error rate): the share of m points on the wrong
  side of the hyperplane a . x = 0, x its n weights (a bias among them), for points that
  a teacher's weights separate with a margin; n = 10 (200 points) and 30 (600). f is
  piecewise constant, a staircase of plateaus of height 1/m, f* = 0 on a cone of
  separating weights.

The minimiser of each regression is stored as its basis, the n rows whose residuals vanish
there (found once by scipy.optimize.linprog, HiGHS, on the loss written as a linear
program); the vertex is solved for from them and checked against the loss's optimality
condition (a zero subgradient) when the module loads, so a change of data fails loudly.
"""

import numpy as np

from raster_losses import Case


def regression_data(n, m, seed):
    """A design of m rows (a column of ones, then Gaussian features) and responses from
    weights uniform in [-1, 1] plus Laplace noise of scale 0.5, fixed by the seed."""
    rng = np.random.default_rng(seed)
    design = np.column_stack([np.ones(m), rng.standard_normal((m, n - 1))])
    weights = rng.uniform(-1.0, 1.0, n)
    return design, design @ weights + rng.laplace(0.0, 0.5, m)


def pinball(design, responses, q):
    """The mean pinball loss of quantile q (q = 1/2: half the mean absolute deviation)."""

    def f(x):
        r = responses - design @ np.asarray(x, dtype=float)
        return float(np.mean(np.maximum(q * r, (q - 1.0) * r)))

    return f


def pinball_minimiser(design, responses, q, basis):
    """The vertex where the residuals of the rows `basis` (n of them) vanish, checked to
    minimise the mean pinball loss of quantile q.

    Raises RuntimeError where it does not: the optimality condition is a zero
    subgradient, Σ_{i off B} s_i a_i + Σ_{i in B} t_i a_i = 0, with s_i = q where the
    residual b_i - a_i . x is positive, q - 1 where it is negative, and each t_i within
    [q - 1, q], B the basis."""
    basis = np.asarray(basis)
    x = np.linalg.solve(design[basis], responses[basis])
    r = responses - design @ x
    off = np.ones(len(r), dtype=bool)
    off[basis] = False
    pull = np.where(r[off] > 0.0, q, q - 1.0) @ design[off]
    t = np.linalg.solve(design[basis].T, -pull)
    if np.any(t < q - 1.0 - 1e-9) or np.any(t > q + 1e-9):
        raise RuntimeError(f"pinball vertex not optimal: t in [{t.min()}, {t.max()}]")
    return x


def regression_case(n, m, q, seed, basis):
    """Starts uniform in [-3, 3]^n, sigma0 1, no box, budget 2000 n, target 1e-6."""
    design, responses = regression_data(n, m, seed)
    return Case(pinball(design, responses, q), pinball_minimiser(design, responses, q, basis),
                1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))


def classification_case(n, m, seed):
    """m points with a column of ones and n - 1 Gaussian features, labelled by a teacher's
    weights (uniform in [-1, 1]) and kept where their margin |a . w| / |w| exceeds 0.05;
    f the share of points x puts on the wrong side. Starts uniform in [-3, 3]^n, sigma0
    1, no box, budget 2000 n, target 1e-6 (every point right)."""
    rng = np.random.default_rng(seed)
    teacher = rng.uniform(-1.0, 1.0, n)
    rows = []
    while len(rows) < m:
        a = np.concatenate([[1.0], rng.standard_normal(n - 1)])
        if abs(a @ teacher) > 0.05 * np.linalg.norm(teacher):
            rows.append(a)
    design = np.array(rows)
    labels = np.sign(design @ teacher)

    def f(x):
        return float(np.mean(labels * (design @ np.asarray(x, dtype=float)) <= 0.0))

    return Case(f, teacher, 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))


PROBLEMS = {
    "lad10": regression_case(10, 60, 0.5, 21, [10, 31, 34, 39, 43, 44, 46, 47, 50, 52]),
    "lad30": regression_case(30, 150, 0.5, 22, [
        11, 12, 20, 28, 33, 38, 42, 45, 48, 52, 55, 57, 59, 60, 67, 86, 95, 102, 108, 113,
        115, 126, 128, 131, 132, 134, 141, 142, 145, 147]),
    "quantile10": regression_case(10, 60, 0.9, 23, [0, 18, 21, 23, 27, 30, 34, 48, 51, 56]),
    "misclassified10": classification_case(10, 200, 24),
    "misclassified30": classification_case(30, 600, 25),
}
