"""Problems for unseen.py's eighteenth set: parameters that span decades, passed in their
own units, as a new user passes a learning rate, a regularisation weight or a rate
constant. Such a parameter matters in proportion to its size: f moves as much between
1e-6 and 1e-5 as between 0.1 and 1, so the distance over which it matters shrinks by
orders of magnitude as it approaches a small optimum, and no one scale sigma0 fits the
whole box. None of the earlier sets has such a parameter in linear units (the epidemic's
initial share and the rod's conductivities are passed as exponents).

* decades2, decades4, decades6, decades10: every even coordinate x_i in [1e-8, 1] costs
  (log10 x_i - log10 t_i)^2 with t_i = 10^-(2 + i/2) (1e-2, 1e-3, ... 1e-6), every odd
  one (x_i - 0.5)^2 in [0, 1]; f* = 0. Along an even coordinate f is concave above
  e*t_i, so a quadratic model sees negative curvature there, and at t_i its curvature is
  0.38/t_i^2: at n = 10, 10^11 times an odd coordinate's.
* kinetics3: consecutive first-order reactions A -> B -> C -> D from pure A, rate
  constants k = (0.2, 3e-3, 4e-5) in [1e-7, 10], the concentrations of B, C and D read
  at 40 times spaced evenly in log time from 0.1 to 1e6 (Bateman's closed form), f the
  mean squared misfit over the data's mean square, f* = 0 at the truth.

Starts are uniform in the box in each coordinate's own units (so mostly within a decade
of its top, as a user's first guess of a rate often is), sigma0 a quarter of the box's
width, the target 1e-6 on f, the budget 2 000 n evaluations.
"""

import numpy as np

from raster_losses import Case

LOW = 1e-8


def targets(n):
    """t_i: 10^-(2 + i/2) on even i, 0.5 on odd i."""
    return np.array([10.0 ** -(2 + i // 2) if i % 2 == 0 else 0.5 for i in range(n)])


def decades(n):
    """The bowl in log10 of the even coordinates and in the odd ones, and its box."""
    t = targets(n)
    even = np.arange(n) % 2 == 0
    log_t = np.log10(np.where(even, t, 1.0))

    def f(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            logs = np.log10(np.where(even, x, 1.0))
        d = np.where(even, logs - log_t, x - t)
        return float(d @ d)

    low = np.where(even, LOW, 0.0)
    high = np.ones(n)
    return Case(f, t, (high - low) / 4.0, (low, high), 2000 * n, 1e-6, (low, high))


KINETICS_TRUTH = np.array([0.2, 3e-3, 4e-5])
KINETICS_TIMES = np.logspace(-1.0, 6.0, 40)


def concentrations(k):
    """B, C and D of A -> B -> C -> D (rates k1, k2, k3) from A = 1 at KINETICS_TIMES,
    by Bateman's solution (distinct rates)."""
    k1, k2, k3 = k
    e1, e2, e3 = (np.exp(-r * KINETICS_TIMES) for r in (k1, k2, k3))
    b = k1 / (k2 - k1) * (e1 - e2)
    c = k1 * k2 * (e1 / ((k2 - k1) * (k3 - k1)) + e2 / ((k1 - k2) * (k3 - k2))
                   + e3 / ((k1 - k3) * (k2 - k3)))
    d = 1.0 - e1 - b - c
    return np.concatenate([b, c, d])


def kinetics():
    data = concentrations(KINETICS_TRUTH)
    energy = float(np.mean(data ** 2))

    def f(x):
        with np.errstate(all="ignore"):
            r = concentrations(np.asarray(x, dtype=float)) - data
            value = float(np.mean(r * r)) / energy
        return value if np.isfinite(value) else np.inf

    low, high = np.full(3, 1e-7), np.full(3, 10.0)
    return Case(f, KINETICS_TRUTH, (high - low) / 4.0, (low, high), 6000, 1e-6, (low, high))


PROBLEMS = {f"decades{n}": decades(n) for n in (2, 4, 6, 10)}
PROBLEMS["kinetics3"] = kinetics()

#: The coordinates that span decades, for a run that declares them (unseen.py's
#: --log-scale): the even ones of decadesN, every rate constant of kinetics3.
LOG_SCALE = {name: np.arange(len(case.x_opt)) % 2 == 0 for name, case in PROBLEMS.items()}
LOG_SCALE["kinetics3"] = np.ones(3, dtype=bool)
