"""How soon a run without a budget ends on a smooth problem, for BENCHMARKS.md: hodr's
default (`hodr.minimize` with no budget) against pycma and BOBYQA at their stopping rules,
and how close to f* each ends. A user who calls a minimiser without a budget pays for its
stopping rule; a run that goes on long after the last digit of f stopped changing wastes
that, and one that stops early leaves accuracy behind.

    pip install ./python cma nlopt
    python python/bench/stopping.py [--seeds 5] [--dims 2,5,10,20] [--solvers hodr,pycma,BOBYQA]
        [--problems sphere,...]

Problems (f* known): the sphere about c with f* = 0 and with f* = 10 (an offset makes
f's rounding 16 ulps of 10 instead of 0's, so no run resolves the last 10^-15 of f - f*),
a rotated ellipsoid (condition 10^6, f* = 10), Rosenbrock's function with f* = 0 and
with f* = 10 (its curved valley makes the models at the minimum's last scales
mispredict, unlike the sphere's), and
three computed in single precision, as a GPU renderer's loss is (x rounded to float32 on
its way in, f on its way out): the sphere about 0.3, which float32 does not hold (f* the
least value on float32's grid), the sphere + 10 about 0.5, and Rosenbrock's function + 1;
at n = 2, 5, 10 and 20, from a start uniform in [-3, 3]^n with sigma0 = 1, no bounds.

Solvers, each left to stop by itself (a cap of 10^6 evaluations marks a run that does
not): hodr's default; `cma.fmin2` with pycma's default options (tolfun 1e-11, tolx 1e-11,
no restarts); nlopt's `LN_BOBYQA` with initial step sigma0 and xtol_rel 1e-12 (the setting
the other benches give it; nlopt has no default).

Per problem and solver: the median evaluations to the end, the median evaluations to
f - f* <= 1e-8 (where the run gets there) and the largest f - f* at the end, over the
seeds.
"""

import argparse
import warnings

import numpy as np

import hodr

warnings.filterwarnings("ignore")

CAP = 1_000_000


def sphere(offset):
    return lambda x: offset + float(np.sum((x - 0.5) ** 2))


def ellipsoid(n):
    """10 + sum_i 10^(6 i/(n-1)) y_i^2, y = Q(x - 0.5), Q a rotation fixed per n."""
    rng = np.random.default_rng(n)
    q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    weights = 10.0 ** (6.0 * np.arange(n) / (n - 1))
    return lambda x: 10.0 + float(weights @ (q @ (x - 0.5)) ** 2)


def rosenbrock(x):
    return float(np.sum(100.0 * (x[1:] - x[:-1] ** 2) ** 2 + (1.0 - x[:-1]) ** 2))


def single(f):
    """f of x rounded to float32, rounded to float32."""
    return lambda x: float(np.float32(f(np.asarray(x, dtype=np.float32).astype(np.float64))))


def sphere_at(centre):
    return lambda x: float(np.sum((x - centre) ** 2))


# name: (make f for n, f* for n)
PROBLEMS = {
    "sphere": (lambda n: sphere(0.0), lambda n: 0.0),
    "sphere + 10": (lambda n: sphere(10.0), lambda n: 10.0),
    "rotated ellipsoid + 10": (ellipsoid, lambda n: 10.0),
    "Rosenbrock": (lambda n: rosenbrock, lambda n: 0.0),
    "Rosenbrock + 10": (lambda n: lambda x: 10.0 + rosenbrock(x), lambda n: 10.0),
    "sphere about 0.3 in float32": (lambda n: single(sphere_at(0.3)),
                                    lambda n: single(sphere_at(0.3))(np.full(n, 0.3))),
    "sphere + 10 in float32": (lambda n: single(sphere(10.0)), lambda n: 10.0),
    "Rosenbrock + 1 in float32": (lambda n: single(lambda x: 1.0 + rosenbrock(x)),
                                  lambda n: 1.0),
}


class Counted:
    """f with a count of evaluations, the first at which f - f* <= 1e-8, and the least
    value seen."""

    def __init__(self, f, f_opt):
        self.f, self.f_opt = f, f_opt
        self.evaluations, self.hit, self.least = 0, None, np.inf

    def __call__(self, x):
        if self.evaluations >= CAP:
            raise StopIteration
        self.evaluations += 1
        v = self.f(np.asarray(x, dtype=float))
        self.least = min(self.least, v)
        if self.hit is None and v - self.f_opt <= 1e-8:
            self.hit = self.evaluations
        return v


def run_hodr(f, x0, seed):
    try:
        hodr.minimize(f, x0, 1.0, seed=seed)
    except StopIteration:
        pass


def run_cma(f, x0, seed):
    import cma

    try:
        cma.fmin2(f, x0, 1.0, {"verbose": -9, "seed": seed + 1})
    except StopIteration:
        pass


def run_bobyqa(f, x0, seed):
    import nlopt

    opt = nlopt.opt(nlopt.LN_BOBYQA, len(x0))
    opt.set_min_objective(lambda x, grad: f(x))
    opt.set_initial_step(1.0)
    opt.set_xtol_rel(1e-12)
    try:
        opt.optimize(x0)
    except (nlopt.RoundoffLimited, RuntimeError, ValueError, StopIteration):
        pass


SOLVERS = {"hodr": run_hodr, "pycma": run_cma, "BOBYQA": run_bobyqa}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--dims", default="2,5,10,20")
    parser.add_argument("--solvers", default=",".join(SOLVERS))
    parser.add_argument("--problems", default=",".join(PROBLEMS),
                        help="comma-separated names as in the table")
    args = parser.parse_args()
    names = args.problems.split(",")
    for name in names:
        if name not in PROBLEMS:
            parser.error(f"unknown problem {name!r} (choose from {', '.join(PROBLEMS)})")
    solvers = [SOLVERS[name] for name in args.solvers.split(",")]
    print("| problem | n | " + " | ".join(args.solvers.split(",")) + " |")
    print("|---|---|" + "---|" * len(solvers))
    for name in names:
        make, optimum = PROBLEMS[name]
        for n in (int(d) for d in args.dims.split(",")):
            f, f_opt = make(n), optimum(n)
            cells = []
            for solver in solvers:
                ends, hits, gaps = [], [], []
                for seed in range(args.seeds):
                    x0 = np.random.default_rng(seed).uniform(-3.0, 3.0, n)
                    counted = Counted(f, f_opt)
                    solver(counted, x0, seed)
                    ends.append(counted.evaluations)
                    hits.append(counted.hit)
                    gaps.append(counted.least - f_opt)
                reached = [h for h in hits if h is not None]
                to_target = f"{int(np.median(reached))}" if len(reached) * 2 > len(hits) else "-"
                capped = " (cap)" if max(ends) >= CAP else ""
                cells.append(f"{int(np.median(ends))}{capped} / {to_target} / {max(gaps):.0e}")
            print(f"| {name} | {n} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
