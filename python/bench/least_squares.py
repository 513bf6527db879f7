"""Nonlinear least-squares problems of Moré, Garbow and Hillstrom ("Testing unconstrained
optimization software", ACM TOMS 7, 1981), the set on which derivative-free methods are
usually compared (Moré and Wild, "Benchmarking derivative-free optimization algorithms",
SIAM J. Optim. 20, 2009): each function returns the residual vector r(x), and the
objective is f = r·r. unseen.py states each problem once: its published start and a
minimiser (the published one where it is given in closed form, else found by a local
search from the start and refined to the digits f resolves, or, for the square systems
at large n, by `root`). The scalable ones take any n (extended Powell, a multiple of 4;
extended Rosenbrock, of 2).
"""

import numpy as np


def helical_valley(x):
    """n = 3, a helix-shaped valley; its angle jumps by 1 across the half-plane
    x1 = 0, x2 < 0, as the published arctan branches do."""
    turn = np.arctan2(x[1], x[0]) / (2 * np.pi)
    if turn < -0.25:
        turn += 1.0
    return np.array([10 * (x[2] - 10 * turn), 10 * (np.hypot(x[0], x[1]) - 1), x[2]])


def wood(x):
    """n = 4, Colville's function as residuals (m = 6)."""
    return np.array([10 * (x[1] - x[0] ** 2), 1 - x[0], np.sqrt(90) * (x[3] - x[2] ** 2),
                     1 - x[2], np.sqrt(10) * (x[1] + x[3] - 2), (x[1] - x[3]) / np.sqrt(10)])


def brown_badly_scaled(x):
    """n = 2, its minimiser (10^6, 2·10^-6)."""
    return np.array([x[0] - 1e6, x[1] - 2e-6, x[0] * x[1] - 2])


def freudenstein_roth(x):
    """n = 2, a local minimum 48.98 at (11.41, -0.8968) beside the global 0 at (5, 4)."""
    return np.array([-13 + x[0] + ((5 - x[1]) * x[1] - 2) * x[1],
                     -29 + x[0] + ((x[1] + 1) * x[1] - 14) * x[1]])


def powell_badly_scaled(x):
    """n = 2, its minimiser about (1.1·10^-5, 9.1)."""
    return np.array([1e4 * x[0] * x[1] - 1, np.exp(-x[0]) + np.exp(-x[1]) - 1.0001])


BOX_T = 0.1 * np.arange(1, 11)


def box_3d(x):
    """n = 3, m = 10: zero at (1, 10, 1), (10, 1, -1) and wherever x1 = x2, x3 = 0."""
    return (np.exp(-BOX_T * x[0]) - np.exp(-BOX_T * x[1])
            - x[2] * (np.exp(-BOX_T) - np.exp(-10 * BOX_T)))


BARD_Y = np.array([0.14, 0.18, 0.22, 0.25, 0.29, 0.32, 0.35, 0.39, 0.37, 0.58, 0.73, 0.96,
                   1.34, 2.10, 4.39])
BARD_U = np.arange(1, 16, dtype=float)
BARD_V = 16 - BARD_U
BARD_W = np.minimum(BARD_U, BARD_V)


def bard(x):
    """n = 3, m = 15."""
    return BARD_Y - (x[0] + BARD_U / (BARD_V * x[1] + BARD_W * x[2]))


KOWALIK_Y = np.array([0.1957, 0.1947, 0.1735, 0.1600, 0.0844, 0.0627, 0.0456, 0.0342,
                      0.0323, 0.0235, 0.0246])
KOWALIK_U = np.array([4, 2, 1, 0.5, 0.25, 0.167, 0.125, 0.1, 0.0833, 0.0714, 0.0625])


def kowalik_osborne(x):
    """n = 4, m = 11, a rational model of enzyme kinetics."""
    u = KOWALIK_U
    return KOWALIK_Y - x[0] * (u * u + u * x[1]) / (u * u + u * x[2] + x[3])


OSBORNE_Y = np.array([0.844, 0.908, 0.932, 0.936, 0.925, 0.908, 0.881, 0.850, 0.818, 0.784,
                      0.751, 0.718, 0.685, 0.658, 0.628, 0.603, 0.580, 0.558, 0.538, 0.522,
                      0.506, 0.490, 0.478, 0.467, 0.457, 0.448, 0.438, 0.431, 0.424, 0.420,
                      0.414, 0.411, 0.406])
OSBORNE_T = 10.0 * np.arange(33)


def osborne1(x):
    """n = 5, m = 33, a sum of two exponentials fitted to data."""
    t = OSBORNE_T
    return OSBORNE_Y - (x[0] + x[1] * np.exp(-t * x[3]) + x[2] * np.exp(-t * x[4]))


BIGGS_T = 0.1 * np.arange(1, 14)
BIGGS_Y = np.exp(-BIGGS_T) - 5 * np.exp(-10 * BIGGS_T) + 3 * np.exp(-4 * BIGGS_T)


def biggs_exp6(x):
    """n = 6, m = 13, zero at (1, 10, 1, 5, 4, 3); a local minimum 5.66·10^-3."""
    t = BIGGS_T
    return (x[2] * np.exp(-t * x[0]) - x[3] * np.exp(-t * x[1]) + x[5] * np.exp(-t * x[4])
            - BIGGS_Y)


WATSON_T = np.arange(1, 30) / 29


def watson(x):
    """n = 6, m = 31, a polynomial fit to an ODE's solution; ill-conditioned."""
    n = len(x)
    powers = WATSON_T[:, None] ** np.arange(n)
    slope = powers[:, : n - 1] @ (np.arange(1, n) * x[1:])
    value = powers @ x
    return np.concatenate([slope - value**2 - 1, [x[0], x[1] - x[0] ** 2 - 1]])


def penalty1(x):
    """n = 10, m = 11: a small penalty on x - 1 against ‖x‖² = 1/4."""
    return np.concatenate([np.sqrt(1e-5) * (x - 1), [x @ x - 0.25]])


def brown_almost_linear(x):
    """n = 10, zero at x = 1 (and elsewhere); a product among sums."""
    n = len(x)
    return np.concatenate([x[:-1] + x.sum() - (n + 1), [np.prod(x) - 1]])


def chebyquad(x):
    """n = 8, m = 8: the x_j as nodes of a quadrature, the residuals its errors on the
    shifted Chebyshev polynomials T_1 ... T_8 over [0, 1]."""
    n = len(x)
    y = 2 * x - 1
    prev, cur = np.ones(n), y
    out = []
    for i in range(1, n + 1):
        exact = -1.0 / (i * i - 1) if i % 2 == 0 else 0.0
        out.append(cur.mean() - exact)
        prev, cur = cur, 2 * y * cur - prev
    return np.array(out)


def variably_dimensioned(x):
    """n = 10, m = 12, zero at x = 1; quartic along (1, 2, ..., n)."""
    s = np.arange(1, len(x) + 1) @ (x - 1)
    return np.concatenate([x - 1, [s, s * s]])


def jennrich_sampson(x):
    """n = 2, m = 10."""
    i = np.arange(1, 11)
    return 2 + 2 * i - (np.exp(i * x[0]) + np.exp(i * x[1]))


GAUSSIAN_Y = np.array([0.0009, 0.0044, 0.0175, 0.0540, 0.1295, 0.2420, 0.3521, 0.3989,
                       0.3521, 0.2420, 0.1295, 0.0540, 0.0175, 0.0044, 0.0009])
GAUSSIAN_T = (8 - np.arange(1, 16)) / 2


def gaussian(x):
    """n = 3, m = 15, a Gaussian bump fitted to its rounded values."""
    return x[0] * np.exp(-x[1] * (GAUSSIAN_T - x[2]) ** 2 / 2) - GAUSSIAN_Y


BROWN_DENNIS_T = np.arange(1, 21) / 5


def brown_dennis(x):
    """n = 4, m = 20, whose least value is large (85 822)."""
    t = BROWN_DENNIS_T
    return (x[0] + t * x[1] - np.exp(t)) ** 2 + (x[2] + x[3] * np.sin(t) - np.cos(t)) ** 2


def broyden_tridiagonal(x):
    """n = 10, zero at a point near -0.5."""
    left = np.concatenate([[0.0], x[:-1]])
    right = np.concatenate([x[1:], [0.0]])
    return (3 - 2 * x) * x - left - 2 * right + 1


def discrete_boundary_value(x):
    """n = 10, a two-point boundary-value problem discretised by finite differences."""
    n = len(x)
    h = 1 / (n + 1)
    t = h * np.arange(1, n + 1)
    left = np.concatenate([[0.0], x[:-1]])
    right = np.concatenate([x[1:], [0.0]])
    return 2 * x - left - right + h * h * (x + t + 1) ** 3 / 2


def extended_rosenbrock(x):
    """Any even n, zero at x = 1: Rosenbrock's valley in each pair of coordinates."""
    odd, even = x[0::2], x[1::2]
    return np.concatenate([10 * (even - odd * odd), 1 - odd])


def extended_powell(x):
    """n a multiple of 4, zero at x = 0, where the Hessian is singular: Powell's singular
    function in each group of four."""
    a, b, c, d = x[0::4], x[1::4], x[2::4], x[3::4]
    return np.concatenate([a + 10 * b, np.sqrt(5) * (c - d), (b - 2 * c) ** 2,
                           np.sqrt(10) * (a - d) ** 2])


def discrete_integral_equation(x):
    """Any n, zero at one point: an integral equation discretised by the trapezoid rule;
    every residual depends on every coordinate."""
    n = len(x)
    h = 1 / (n + 1)
    t = h * np.arange(1, n + 1)
    cube = (x + t + 1) ** 3
    below = np.cumsum(t * cube)  # sum over j <= i of t_j (x_j + t_j + 1)^3
    above = np.cumsum(((1 - t) * cube)[::-1])[::-1] - (1 - t) * cube  # over j > i
    return x + h * ((1 - t) * below + t * above) / 2


def broyden_banded(x):
    """Any n, zero at one point near -0.4: each residual couples five coordinates below
    and one above."""
    n = len(x)
    coupling = x * (1 + x)
    out = x * (2 + 5 * x * x) + 1
    for i in range(n):
        out[i] -= coupling[max(0, i - 5):min(n, i + 2)].sum() - coupling[i]
    return out


def linear_full_rank(x, m_per_n=2):
    """Any n, m = 2n: a linear least-squares problem whose least value m - n is taken at
    x = -1."""
    n = len(x)
    m = m_per_n * n
    mean = 2 * x.sum() / m
    return np.concatenate([x - mean - 1, np.full(m - n, -mean - 1)])


def root(residuals, x0, iterations=50):
    """A zero of a square system r(x) = 0 near x0 by Newton's method with a
    central-difference Jacobian; raises if the residuals do not fall to rounding."""
    x = np.asarray(x0, dtype=float).copy()
    n = len(x)
    for _ in range(iterations):
        r = residuals(x)
        if np.abs(r).max() < 1e-15:
            return x
        jacobian = np.empty((n, n))
        for j in range(n):
            step = np.zeros(n)
            step[j] = 1e-6
            jacobian[:, j] = (residuals(x + step) - residuals(x - step)) / 2e-6
        x -= np.linalg.solve(jacobian, r)
    if np.abs(residuals(x)).max() > 1e-13:
        raise ArithmeticError("Newton's method did not converge")
    return x


def objective(residuals):
    """f = r·r for a residual function r."""

    def f(x):
        r = residuals(np.asarray(x, dtype=float))
        return float(r @ r)

    f.__name__ = residuals.__name__
    f.__doc__ = residuals.__doc__
    return f
