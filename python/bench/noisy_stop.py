"""How a run without a budget ends on a noisy objective, for BENCHMARKS.md: hodr's
default (`hodr.minimize` with no budget) against pycma at its default stopping rules. A
Monte Carlo renderer is such an objective; a minimiser called on it without a budget
should return in reasonable time with a point about as close as the noise allows.

    pip install ./python cma
    python python/bench/noisy_stop.py [--seeds 5] [--dims 2,5,10] [--noise 0.01,0.1] [--solvers hodr,pycma]

Problem: q(x) = sum_i (x_i - 1)^2 + s N, N a standard normal drawn afresh at every call,
from x0 = 0 with sigma0 = 1, no bounds. hodr is called as a user without a seeded
renderer would call it (a plain `fun(x)`, `noisy` left False: Auto notices the noise).
pycma (`cma.fmin2`, default options) is read at its mean, `xfavorite`, the point it
recommends under noise. A cap of 10^7 evaluations marks a run that does not stop.

Per noise level, dimension and solver: how the runs ended, the median evaluations to the
end, the median seconds, and the median and largest distance |x - 1| of the returned
point.
"""

import argparse
import time
import warnings

import numpy as np

import hodr

warnings.filterwarnings("ignore")

CAP = 10_000_000


class Capped(Exception):
    """Raised by the objective at the cap."""


def objective(n, noise, seed):
    """(f, its evaluation count so far as a one-element list)."""
    rng = np.random.default_rng(1000 + seed)
    count = [0]

    def f(x):
        count[0] += 1
        if count[0] > CAP:
            raise Capped
        return float(np.sum((np.asarray(x) - 1.0) ** 2)) + noise * rng.standard_normal()

    return f, count


def run_hodr(n, noise, seed):
    """(how the run ended, evaluations, returned point)."""
    f, count = objective(n, noise, seed)
    try:
        res = hodr.minimize(f, np.zeros(n), 1.0, seed=seed)
        return res.message.split(" (")[0], count[0], res.x
    except Capped:
        return "cap", CAP, None


def run_cma(n, noise, seed):
    """(pycma's stopping conditions, evaluations, its mean)."""
    import cma

    f, count = objective(n, noise, seed)
    try:
        _, es = cma.fmin2(f, np.zeros(n), 1.0, {"verbose": -9, "seed": seed + 1})
        return ", ".join(es.stop()), count[0], es.result.xfavorite
    except Capped:
        return "cap", CAP, None


SOLVERS = {"hodr": run_hodr, "pycma": run_cma}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--dims", default="2,5,10")
    parser.add_argument("--noise", default="0.01,0.1")
    parser.add_argument("--solvers", default=",".join(SOLVERS))
    args = parser.parse_args()
    print("| noise s | n | solver | ends | evaluations | seconds | distance: median / max |")
    print("|---|---|---|---|---|---|---|")
    for noise in (float(s) for s in args.noise.split(",")):
        for n in (int(d) for d in args.dims.split(",")):
            for name in args.solvers.split(","):
                ends, evals, secs, dists = [], [], [], []
                for seed in range(args.seeds):
                    start = time.perf_counter()
                    end, count, x = SOLVERS[name](n, noise, seed)
                    secs.append(time.perf_counter() - start)
                    ends += end.split(", ")
                    evals.append(count)
                    dists.append(np.inf if x is None else float(np.linalg.norm(np.asarray(x) - 1.0)))
                print(
                    f"| {noise} | {n} | {name} | {', '.join(sorted(set(ends)))} | "
                    f"{int(np.median(evals))} | {np.median(secs):.1f} | "
                    f"{np.median(dists):.3f} / {max(dists):.3f} |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
