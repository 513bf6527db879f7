"""Problems from outside the project's suites, tried as a new user would: hodr's default
against pycma and BOBYQA, each at its defaults, for BENCHMARKS.md.

    pip install ./python cma nlopt
    python python/bench/unseen.py [--seeds 10] [--problems ackley10,griewank10]

Classic test functions from their published definitions (Ackley, Griewank, Levy,
Styblinski-Tang, Rastrigin, Rosenbrock, a rotated ellipsoid, the sum of different powers,
the L1 and L-infinity norms; Griewank and Rastrigin also rotated about their minimum, which
takes away what an axis-aligned search gains on a separable function) and shapes a renderer's loss takes (a narrow well on a flat
plateau, a staircase, a minimum in a corner of the box, units that differ by 10^6, a region
where the objective fails with NaN, a wall of +inf beside the minimum, a minimum on the edge
of a step), none of them in hodr's suite, tests or tasks. Each
problem states its dimension, box (or none), scale sigma0, budget and target; every solver
gets the same statement and the same start, uniform in [-3, 3]^n from the seed. A run
succeeds when an evaluated point comes within the target of f* (COCO's rule); the table
gives the successes and the median evaluations of the successful runs, and hodr's median
over pycma's where both solve at least half of the runs.

Solvers: `hodr.minimize` with the budget; `cma.fmin2` with its IPOP restarts (9, doubling
the population: pycma's documented way for multi-modal functions); nlopt's `LN_BOBYQA`,
restarted from a new uniform start until the budget is spent (initial step sigma0, the
box where the problem has one).
"""

import argparse
import time
import warnings

import numpy as np

import hodr

warnings.filterwarnings("ignore")


class Spent(Exception):
    """The budget is used up (raised to stop a solver that would go on)."""


class Counted:
    """f with COCO's bookkeeping: evaluations, the first that reached the target."""

    def __init__(self, f, f_opt, target, budget):
        self.f, self.f_opt, self.target, self.budget = f, f_opt, target, budget
        self.evaluations = 0
        self.hit = None

    def __call__(self, x):
        if self.evaluations >= self.budget:
            raise Spent
        self.evaluations += 1
        value = self.f(np.asarray(x, dtype=float))
        if self.hit is None and np.isfinite(value) and value - self.f_opt <= self.target:
            self.hit = self.evaluations
        return value


def ackley(x):
    y = x - 0.7
    n = len(x)
    return float(-20 * np.exp(-0.2 * np.sqrt(y @ y / n)) - np.exp(np.cos(2 * np.pi * y).sum() / n)
                 + 20 + np.e)


def griewank(x):
    y = x - 1.3
    return float(1 + y @ y / 4000 - np.prod(np.cos(y / np.sqrt(np.arange(1, len(x) + 1)))))


def levy(x):
    w = 1 + (x - 1) / 4
    body = (w[:-1] - 1) ** 2 * (1 + 10 * np.sin(np.pi * w[:-1] + 1) ** 2)
    return float(np.sin(np.pi * w[0]) ** 2 + body.sum()
                 + (w[-1] - 1) ** 2 * (1 + np.sin(2 * np.pi * w[-1]) ** 2))


STYBLINSKI_MIN = -39.16616570377142  # per coordinate, at x = -2.903534...


def styblinski_tang(x):
    return float(0.5 * np.sum(x**4 - 16 * x**2 + 5 * x) - STYBLINSKI_MIN * len(x))


def rastrigin(x):
    y = x - 0.5
    return float(10 * len(x) + np.sum(y**2 - 10 * np.cos(2 * np.pi * y)))


def rotation(n, seed):
    """A random rotation (Q of a Gaussian matrix's QR), fixed by the seed."""
    return np.linalg.qr(np.random.default_rng(seed).normal(size=(n, n)))[0]


ROTATION_5, ROTATION_10 = rotation(5, 3), rotation(10, 4)


def rotated_rastrigin(x):
    return rastrigin(0.5 + ROTATION_5 @ (x - 0.5))


def rotated_griewank(x):
    return griewank(1.3 + ROTATION_10 @ (x - 1.3))


def rosenbrock(x):
    return float(np.sum(100 * (x[1:] - x[:-1] ** 2) ** 2 + (1 - x[:-1]) ** 2))


def staircase_rosenbrock(x):
    return float(np.floor(10 * rosenbrock(x)) / 10)


ROTATION_30 = rotation(30, 5)


def ellipsoid_30(x):
    z = ROTATION_30 @ (x - 0.5)
    return float(np.dot(1e6 ** (np.arange(30) / 29), z * z))


def different_powers(x):
    y = np.abs(x - 0.2)
    return float(np.sqrt(np.sum(y ** (2 + 4 * np.arange(len(x)) / (len(x) - 1)))))


def l1(x):
    return float(np.abs(x - 0.3).sum())


def linf(x):
    return float(np.abs(x - 0.3).max())


def needle(x):
    d = x - 1.7
    return float(1 - np.exp(-(d @ d) / (2 * 0.3**2)))


CORNER = np.array([7.0, -9.0, 0.5, 6.0, 0.0])


def corner(x):
    return float(np.sum((x - CORNER) ** 2))


UNITS = np.array([1e3, 1e-3, 1.0, 1e2, 1e-2])


def units(x):
    return float(np.sum((x * UNITS - 1.0) ** 2))


BALL_CENTRE = np.array([1.3, 1.3, 0.0, 0.0])


def failing(x):
    if x @ x > 4.0:
        return float("nan")
    return float(np.sum((x - BALL_CENTRE) ** 2))


WALL_CENTRE = np.concatenate([[9.5], np.zeros(9)])


def walled(x):
    """+inf outside the ball of radius 10 (a constraint the function enforces itself, as
    a renderer does with parameters it cannot draw), its minimum 0.5 inside the wall."""
    if x @ x >= 100.0:
        return float("inf")
    return float(np.sum((x - WALL_CENTRE) ** 2))


def jump(x):
    """A bowl centred at 0.5 with a step of 1 where x[0] > 0: the minimum, 0.25, lies on
    the step's edge, at x[0] = 0 exactly."""
    return float(np.sum((x - 0.5) ** 2) + (1.0 if x[0] > 0 else 0.0))


# name: (f, n, f*, sigma0, box or None, budget, target)
PROBLEMS = {
    "ackley10": (ackley, 10, 0.0, 2.0, (-5, 5), 20_000, 1e-6),
    "griewank10": (griewank, 10, 0.0, 3.0, (-10, 10), 20_000, 1e-6),
    "levy8": (levy, 8, 0.0, 2.0, (-10, 10), 16_000, 1e-6),
    "styblinski-tang5": (styblinski_tang, 5, 0.0, 2.0, (-5, 5), 10_000, 1e-6),
    "rastrigin5": (rastrigin, 5, 0.0, 2.0, (-5, 5), 10_000, 1e-6),
    "griewank10-rotated": (rotated_griewank, 10, 0.0, 3.0, (-10, 10), 20_000, 1e-6),
    "rastrigin5-rotated": (rotated_rastrigin, 5, 0.0, 2.0, (-5, 5), 10_000, 1e-6),
    "rosenbrock20": (rosenbrock, 20, 0.0, 0.5, None, 40_000, 1e-6),
    "ellipsoid30": (ellipsoid_30, 30, 0.0, 1.0, None, 60_000, 1e-6),
    "different-powers20": (different_powers, 20, 0.0, 1.0, None, 40_000, 1e-6),
    "l1-10": (l1, 10, 0.0, 1.0, None, 20_000, 1e-6),
    "linf10": (linf, 10, 0.0, 1.0, None, 20_000, 1e-6),
    "needle5": (needle, 5, 0.0, 1.0, (-5, 5), 10_000, 1e-6),
    "staircase-rosenbrock4": (staircase_rosenbrock, 4, 0.0, 0.5, None, 8_000, 1e-9),
    "corner5": (corner, 5, corner(np.clip(CORNER, -5, 5)), 1.0, (-5, 5), 10_000, 1e-6),
    "units5": (units, 5, 0.0, 1.0, None, 10_000, 1e-6),
    "nan-region4": (failing, 4, 0.0, 0.5, None, 8_000, 1e-6),
    "walled10": (walled, 10, 0.0, 3.0, None, 20_000, 1e-6),
    "jump10": (jump, 10, 0.25, 1.0, None, 20_000, 1e-6),
}


def run_hodr(f, x0, sigma0, box, budget, seed):
    bounds = None if box is None else [box] * len(x0)
    hodr.minimize(f, x0, sigma0, bounds=bounds, budget=budget, seed=seed)


def run_cma(f, x0, sigma0, box, budget, seed):
    import cma

    options = {"maxfevals": budget, "verbose": -9, "seed": seed + 1}
    if box is not None:
        options["bounds"] = list(box)
    cma.fmin2(f, x0, sigma0, options, restarts=9, incpopsize=2)


def run_bobyqa(f, x0, sigma0, box, budget, seed):
    import nlopt

    rng = np.random.default_rng(10_000 + seed)
    n = len(x0)
    while f.evaluations < budget and f.hit is None:
        opt = nlopt.opt(nlopt.LN_BOBYQA, n)
        if box is not None:
            opt.set_lower_bounds([box[0]] * n)
            opt.set_upper_bounds([box[1]] * n)
        opt.set_min_objective(lambda x, grad: f(x))
        opt.set_initial_step(sigma0)
        opt.set_maxeval(budget - f.evaluations)
        opt.set_xtol_rel(1e-12)
        try:
            opt.optimize(x0)
        except (nlopt.RoundoffLimited, RuntimeError, ValueError):
            pass
        x0 = rng.uniform(-3.0, 3.0, n)


SOLVERS = {"hodr": run_hodr, "pycma": run_cma, "BOBYQA": run_bobyqa}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--problems", default=",".join(PROBLEMS))
    args = parser.parse_args()
    names = args.problems.split(",")
    for name in names:
        if name not in PROBLEMS:
            parser.error(f"unknown problem {name!r} (choose from {', '.join(PROBLEMS)})")
    print("| problem | n | budget | target | " + " | ".join(
        f"{s} solved / median evaluations" for s in SOLVERS) + " | hodr ÷ pycma |")
    print("|---|---|---|---|" + "---|" * (len(SOLVERS) + 1))
    start = time.perf_counter()
    for name in names:
        f, n, f_opt, sigma0, box, budget, target = PROBLEMS[name]
        cells, medians = [], {}
        for solver, run in SOLVERS.items():
            hits = []
            for seed in range(args.seeds):
                x0 = np.random.default_rng(seed).uniform(-3.0, 3.0, n)
                counted = Counted(f, f_opt, target, budget)
                try:
                    run(counted, x0, sigma0, box, budget, seed)
                except Spent:
                    pass
                hits.append(counted.hit)
            solved = sorted(h for h in hits if h is not None)
            median = solved[(len(solved) - 1) // 2] if solved else None
            if 2 * len(solved) >= args.seeds:
                medians[solver] = median
            cells.append(f"{len(solved)}/{args.seeds} / {median if median else '—'}")
        ratio = (f"{medians['hodr'] / medians['pycma']:.2f}"
                 if "hodr" in medians and "pycma" in medians else "—")
        print(f"| {name} | {n} | {budget} | {target:g} | " + " | ".join(cells) + f" | {ratio} |",
              flush=True)
    print(f"\n{time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
