"""Problems for unseen.py's twelfth set: classic test functions that none of the earlier
sets had, written from their published definitions (Surjanovic and Bingham's Virtual
Library of Simulation Experiments; Jamil and Yang, "A literature survey of benchmark
functions for global optimisation problems", 2013). None of hodr's tasks, tests or
suites has them.

Two-dimensional, in their published boxes: Himmelblau (four global minima), Goldstein-
Price, Booth, Matyas, McCormick, the three-hump camel, Bukin 6 (a curved ridge with a kink
along it), drop-wave, Eggholder and the Hoelder table (rugged, their minima on or near the
box's edge), cross-in-tray and Shubert (18 global minima among 760 local ones). Higher
dimensions, without a box: Colville (n = 4), Perm 0,d,beta with beta = 10 (n = 4, badly
scaled), Qing (n = 5, 2^5 global minima at +-sqrt(i)), Chung-Reynolds (n = 10, a quartic
minimum), Schwefel 2.22 (n = 10, kinks along every axis) and Powell's sum of different
powers |x_i|^(i+1) (n = 5).

Each states its box (starts uniform in it, sigma0 a quarter of its width) or none (starts
uniform in [-3, 3]^n, sigma0 1), budget 2000 n, and target 1e-6, or 1e-4 on the rugged
rows. Where the published minimiser is given to five or six digits (Eggholder, the Hoelder
table, cross-in-tray, Shubert), the one stated is a local search's from it (nlopt's
BOBYQA and Nelder-Mead, run once), which matches the published least value.
"""

import numpy as np

from raster_losses import Case


def himmelblau(x):
    return float((x[0] ** 2 + x[1] - 11) ** 2 + (x[0] + x[1] ** 2 - 7) ** 2)


def goldstein_price(x):
    a, b = x
    p = 1 + (a + b + 1) ** 2 * (19 - 14 * a + 3 * a * a - 14 * b + 6 * a * b + 3 * b * b)
    q = 30 + (2 * a - 3 * b) ** 2 * (18 - 32 * a + 12 * a * a + 48 * b - 36 * a * b + 27 * b * b)
    return float(p * q)


def booth(x):
    return float((x[0] + 2 * x[1] - 7) ** 2 + (2 * x[0] + x[1] - 5) ** 2)


def matyas(x):
    return float(0.26 * (x[0] ** 2 + x[1] ** 2) - 0.48 * x[0] * x[1])


def mccormick(x):
    a, b = x
    return float(np.sin(a + b) + (a - b) ** 2 - 1.5 * a + 2.5 * b + 1)


def three_hump_camel(x):
    a, b = x
    return float(2 * a * a - 1.05 * a**4 + a**6 / 6 + a * b + b * b)


def bukin6(x):
    return float(100 * np.sqrt(abs(x[1] - 0.01 * x[0] ** 2)) + 0.01 * abs(x[0] + 10))


def drop_wave(x):
    r2 = x[0] ** 2 + x[1] ** 2
    return float(-(1 + np.cos(12 * np.sqrt(r2))) / (0.5 * r2 + 2))


def eggholder(x):
    a, b = x
    return float(-(b + 47) * np.sin(np.sqrt(abs(b + a / 2 + 47)))
                 - a * np.sin(np.sqrt(abs(a - (b + 47)))))


def holder_table(x):
    a, b = x
    return float(-abs(np.sin(a) * np.cos(b) * np.exp(abs(1 - np.sqrt(a * a + b * b) / np.pi))))


def cross_in_tray(x):
    a, b = x
    inner = abs(np.sin(a) * np.sin(b) * np.exp(abs(100 - np.sqrt(a * a + b * b) / np.pi)))
    return float(-0.0001 * (inner + 1) ** 0.1)


def shubert(x):
    i = np.arange(1, 6)
    return float(np.prod([np.sum(i * np.cos((i + 1) * xi + i)) for xi in x]))


def colville(x):
    a, b, c, d = x
    return float(100 * (a * a - b) ** 2 + (a - 1) ** 2 + (c - 1) ** 2 + 90 * (c * c - d) ** 2
                 + 10.1 * ((b - 1) ** 2 + (d - 1) ** 2) + 19.8 * (b - 1) * (d - 1))


def perm(x, beta=10.0):
    """Perm 0,d,beta: sum_i (sum_j (j + beta)(x_j^i - j^-i))^2, its minimum 0 at x_j = 1/j."""
    d = len(x)
    j = np.arange(1, d + 1)
    return float(sum(np.sum((j + beta) * (x**i - 1.0 / j**i)) ** 2 for i in range(1, d + 1)))


def qing(x):
    return float(np.sum((x**2 - np.arange(1, len(x) + 1)) ** 2))


def chung_reynolds(x):
    return float((x @ x) ** 2)


def schwefel222(x):
    a = np.abs(x)
    return float(np.sum(a) + np.prod(a))


def powell_sum(x):
    return float(np.sum(np.abs(x) ** np.arange(2, len(x) + 2)))


def boxed(f, x_opt, low, high, target=1e-6):
    """A problem in the box [low, high] (scalars or per coordinate): starts uniform in it,
    sigma0 a quarter of its width."""
    x_opt = np.asarray(x_opt, dtype=float)
    low = np.broadcast_to(np.asarray(low, dtype=float), x_opt.shape)
    high = np.broadcast_to(np.asarray(high, dtype=float), x_opt.shape)
    return Case(f, x_opt, (high - low) / 4, (low, high), 2000 * len(x_opt), target, (low, high))


def open_(f, x_opt, target=1e-6):
    """A problem without a box: starts uniform in [-3, 3]^n, sigma0 1."""
    x_opt = np.asarray(x_opt, dtype=float)
    return Case(f, x_opt, 1.0, None, 2000 * len(x_opt), target, (-3.0, 3.0))


MCCORMICK_X = (1 - 2 * np.pi / 3) / 2

PROBLEMS = {
    "himmelblau2": boxed(himmelblau, [3, 2], -5, 5),
    "goldstein-price2": boxed(goldstein_price, [0, -1], -2, 2),
    "booth2": boxed(booth, [1, 3], -10, 10),
    "matyas2": boxed(matyas, [0, 0], -10, 10),
    "mccormick2": boxed(mccormick, [MCCORMICK_X, MCCORMICK_X - 1], [-1.5, -3], [4, 4]),
    "three-hump-camel2": boxed(three_hump_camel, [0, 0], -5, 5),
    "bukin6-2": boxed(bukin6, [-10, 1], [-15, -3], [-5, 3], 1e-4),
    "drop-wave2": boxed(drop_wave, [0, 0], -5.12, 5.12),
    "eggholder2": boxed(eggholder, [512, 404.231805012], -512, 512, 1e-4),
    "holder-table2": boxed(holder_table, [8.05502347765, 9.66459002944], -10, 10, 1e-4),
    "cross-in-tray2": boxed(cross_in_tray, [1.3494065975, 1.3494065975], -10, 10, 1e-4),
    "shubert2": boxed(shubert, [-7.08350640681, 4.85805687783], -10, 10, 1e-4),
    "colville4": open_(colville, np.ones(4)),
    "perm4": open_(perm, 1.0 / np.arange(1, 5)),
    "qing5": open_(qing, np.sqrt(np.arange(1, 6))),
    "chung-reynolds10": open_(chung_reynolds, np.zeros(10)),
    "schwefel222-10": open_(schwefel222, np.zeros(10)),
    "powell-sum5": open_(powell_sum, np.zeros(5)),
}
