"""Per-evaluation overhead of hodr.minimize (Auto) against pycma (cma.fmin2) on the
sphere, for BENCHMARKS.md: both minimise f(x) = x·x from x0 = 1 with sigma0 = 1 under the
same evaluation budget, single-threaded, and the time per evaluation is the run's wall
time over its evaluations (the sphere itself costs well under a microsecond).

    pip install ./python cma
    python python/bench/overhead.py [--dims 2,5,10,20,50,100] [--budget-per-dim 100]
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


def per_evaluation(run):
    """Seconds per evaluation of run() -> evaluations, the fastest of three."""
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        evaluations = run()
        best = min(best, (time.perf_counter() - start) / evaluations)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dims", default="2,5,10,20,50,100")
    parser.add_argument("--budget-per-dim", type=int, default=100)
    args = parser.parse_args()
    print("| n | budget | hodr µs/evaluation | pycma µs/evaluation | ratio |")
    print("|---|---|---|---|---|")
    for n in map(int, args.dims.split(",")):
        budget = args.budget_per_dim * n
        x0 = np.ones(n)

        def ours():
            return hodr.minimize(sphere, x0, 1.0, budget=budget, seed=1).nfev

        def theirs():
            options = {"maxfevals": budget, "verbose": -9, "seed": 1, "tolfun": 0,
                       "tolx": 0, "tolfunhist": 0, "tolstagnation": budget}
            es = cma.fmin2(sphere, x0, 1.0, options)[1]
            return es.countevals

        a, b = per_evaluation(ours) * 1e6, per_evaluation(theirs) * 1e6
        print(f"| {n} | {budget} | {a:.1f} | {b:.1f} | {a / b:.2f} |", flush=True)


if __name__ == "__main__":
    main()
