"""hodr.minimize (Auto) against pycma at large n, for BENCHMARKS.md: the separable
ellipsoid f(x) = sum_i 10^(3i/(n-1)) (x_i - c_i)^2 (condition 1e6, c uniform in [-1, 1]^n
from a fixed seed), or with --function rotated the same ellipsoid of Q(x - c) for a
random rotation Q (from a fixed seed; not separable, so hodr keeps its full model up to
n = 127), from x0 = 0 with sigma0 = 0.5 and a budget of 200 n evaluations, for hodr's
default, pycma's CMA-ES and pycma's separable CMA-ES (CMA_diagonal). Prints the best f
reached, the evaluations used and the wall time, single-threaded.

    pip install ./python cma
    python python/bench/large_n.py [--dims 40,100] [--budget-per-dim 200]
                                   [--methods hodr,pycma,pycma-sep]
                                   [--function separable|rotated]
"""

import argparse
import os
import time
import warnings

# Single-threaded linear algebra for pycma, as hodr's Auto is.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

import hodr  # noqa: E402

warnings.filterwarnings("ignore")
import cma  # noqa: E402


def ellipsoid(n, rotated=False):
    """The ellipsoid in n dimensions, separable or of Q(x - c) for a random rotation Q."""
    centre = np.random.default_rng(0).uniform(-1.0, 1.0, n)
    scale = 10.0 ** (3.0 * np.arange(n) / (n - 1))
    if not rotated:
        return lambda x: float(np.sum(scale * (np.asarray(x) - centre) ** 2))
    q, r = np.linalg.qr(np.random.default_rng(1).standard_normal((n, n)))
    q *= np.sign(np.diag(r))
    return lambda x: float(np.sum(scale * (q @ (np.asarray(x) - centre)) ** 2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dims", default="40,100")
    parser.add_argument("--budget-per-dim", type=int, default=200)
    parser.add_argument("--methods", default="hodr,pycma,pycma-sep")
    parser.add_argument("--function", choices=("separable", "rotated"), default="separable")
    args = parser.parse_args()
    methods = args.methods.split(",")
    unknown = set(methods) - {"hodr", "pycma", "pycma-sep"}
    if unknown:
        parser.error(f"unknown method(s) {', '.join(sorted(unknown))}")
    print("| n | method | best f (from f(x0)) | evaluations | seconds |")
    print("|---|---|---|---|---|")
    for n in map(int, args.dims.split(",")):
        f = ellipsoid(n, rotated=args.function == "rotated")
        x0, budget = np.zeros(n), args.budget_per_dim * n
        start = f(x0)

        def row(name, best, evaluations, seconds):
            print(f"| {n} | {name} | {best:.2e} ({start:.2e}) | {evaluations} | {seconds:.1f} |",
                  flush=True)

        if "hodr" in methods:
            t = time.perf_counter()
            r = hodr.minimize(f, x0, 0.5, budget=budget, seed=1)
            row("hodr (Auto)", r.fun, r.nfev, time.perf_counter() - t)
        for key, name, extra in (("pycma", "pycma", {}),
                                 ("pycma-sep", "pycma, separable", {"CMA_diagonal": True})):
            if key not in methods:
                continue
            t = time.perf_counter()
            options = {"maxfevals": budget, "verbose": -9, "seed": 1, **extra}
            es = cma.CMAEvolutionStrategy(x0, 0.5, options)
            es.optimize(f)
            row(name, es.result.fbest, es.result.evaluations, time.perf_counter() - t)


if __name__ == "__main__":
    main()
