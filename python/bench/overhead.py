"""Per-evaluation overhead of hodr.minimize (Auto) against pycma (cma.fmin2) on a cheap
function, for BENCHMARKS.md: both minimise it from x0 = 1 with sigma0 = 1 under the same
evaluation budget, single-threaded, and the time per evaluation is the run's wall time
over its evaluations (the function itself costs about a microsecond).

The functions: the sphere f(x) = x·x, and a separable ellipsoid
f(x) = Σᵢ 10^(6i/(n−1)) (xᵢ − 0.3)² (condition 10⁶), on which Auto takes many short
iterations (a model fit each) while it learns the metric.

With --target, each run instead stops at the end of the first iteration (hodr: its
callback) or generation (pycma: ftarget) whose best value is at most the target, and the
table gives each optimiser's evaluations and wall time to it and the ratio of the times:
what a user waits for on a function that costs nothing. With --seeds K (K > 1) both run
on seeds 1 … K, each run once, and the cells are the medians over the seeds that reach
the target, with how many do.

    pip install ./python cma
    python python/bench/overhead.py [--dims 2,5,10,20,50,100] [--budget-per-dim 100]
        [--function sphere|ellipsoid] [--target 1e-8 [--seeds 5]]
"""

import argparse
import os
import time
import warnings

# Single-threaded linear algebra for pycma, as hodr's Auto is: a multi-threaded BLAS on a
# shared machine measures the contention, not the method.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

import hodr  # noqa: E402

warnings.filterwarnings("ignore")
import cma  # noqa: E402


def sphere(x):
    return float(np.dot(x, x))


def ellipsoid_of(n):
    """The separable ellipsoid of condition 10⁶ in n dimensions, minimum at x = 0.3."""
    weights = 10.0 ** (6.0 * np.arange(n) / max(n - 1, 1))

    def ellipsoid(x):
        d = x - 0.3
        return float(np.dot(weights, d * d))

    return ellipsoid


def per_evaluation(run):
    """Seconds per evaluation of run() -> (evaluations, best value), the fastest of three."""
    seconds, evaluations, _ = fastest(run)
    return seconds / evaluations


def optimisers(fun, x0, budget, target=None, seed=1):
    """hodr's and pycma's runs of fun from x0 with sigma0 = 1, `budget` evaluations and
    the given seed, each stopping at the end of the first iteration (hodr: its callback)
    or generation (pycma: ftarget) whose best value is at most `target`, if given; each
    returns (evaluations, best value)."""

    def ours():
        stop = None if target is None else (lambda x, f: f <= target)
        result = hodr.minimize(fun, x0, 1.0, budget=budget, seed=seed, callback=stop)
        return result.nfev, result.fun

    def theirs():
        options = {"maxfevals": budget, "verbose": -9, "seed": seed, "tolfun": 0,
                   "tolx": 0, "tolfunhist": 0, "tolstagnation": budget}
        if target is not None:
            options["ftarget"] = target
        es = cma.fmin2(fun, x0, 1.0, options)[1]
        return es.countevals, es.result.fbest

    return ours, theirs


def function_of(name, n):
    """The named benchmark function in n dimensions."""
    return sphere if name == "sphere" else ellipsoid_of(n)


def fastest(run, repeats=3):
    """(seconds, evaluations, best value) of run() -> (evaluations, best value), the
    fastest of `repeats` (the runs are deterministic: the same evaluations each time)."""
    best = None
    for _ in range(repeats):
        start = time.perf_counter()
        evaluations, value = run()
        seconds = time.perf_counter() - start
        if best is None or seconds < best[0]:
            best = (seconds, evaluations, value)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dims", default="2,5,10,20,50,100")
    parser.add_argument("--budget-per-dim", type=int, default=100)
    parser.add_argument("--function", choices=("sphere", "ellipsoid"), default="sphere")
    parser.add_argument("--target", type=float, default=None)
    parser.add_argument("--seeds", type=int, default=1)
    args = parser.parse_args()
    if args.seeds < 1:
        parser.error("--seeds must be at least 1")
    if args.target is not None:
        to_target(args)
        return
    print("| n | budget | hodr µs/evaluation | pycma µs/evaluation | ratio |")
    print("|---|---|---|---|---|")
    for n in map(int, args.dims.split(",")):
        budget = args.budget_per_dim * n
        ours, theirs = optimisers(function_of(args.function, n), np.ones(n), budget)
        a, b = per_evaluation(ours) * 1e6, per_evaluation(theirs) * 1e6
        print(f"| {n} | {budget} | {a:.1f} | {b:.1f} | {a / b:.2f} |", flush=True)


def to_target(args):
    """The --target table: evaluations and wall time to the target (medians over the
    seeds that reach it, with --seeds)."""
    seeds = range(1, args.seeds + 1)
    repeats = 3 if args.seeds == 1 else 1
    print("| n | hodr evaluations | hodr ms | pycma evaluations | pycma ms | hodr ÷ pycma time |")
    print("|---|---|---|---|---|---|")
    for n in map(int, args.dims.split(",")):
        reached = ([], [])
        for seed in seeds:
            runs = optimisers(function_of(args.function, n), np.ones(n),
                              args.budget_per_dim * n, args.target, seed)
            for found, run in zip(reached, runs):
                seconds, evaluations, value = fastest(run, repeats)
                if value <= args.target:
                    found.append((seconds, evaluations))
        cells = []
        for found in reached:
            if found:
                cells.append((float(np.median([s for s, _ in found])),
                              float(np.median([e for _, e in found])), len(found)))
            else:
                cells.append((None, None, 0))
        (a, ea, ka), (b, eb, kb) = cells

        def show(x, scale, digits, count):
            if x is None:
                return "—"
            share = "" if args.seeds == 1 else f" ({count}/{args.seeds})"
            return f"{x * scale:.{digits}f}{share}"

        ratio = "—" if a is None or b is None else f"{a / b:.2g}"
        print(f"| {n} | {show(ea, 1, 0, ka)} | {show(a, 1e3, 2, ka)} | "
              f"{show(eb, 1, 0, kb)} | {show(b, 1e3, 2, kb)} | {ratio} |", flush=True)


if __name__ == "__main__":
    main()
