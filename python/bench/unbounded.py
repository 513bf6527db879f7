"""Objectives without a minimum, for BENCHMARKS.md: how soon hodr.minimize (Auto, no
budget) and pycma (CMA-ES, defaults) notice and stop, and how each run ends. A loss with
a sign error or a missing regulariser looks like this (unbounded below, or bounded below
with its infimum at infinity, as a saturating unit's); a run that never returns is the
failure to avoid. 10 seeds each, from x0 = 0 with sigma0 = 1; pycma gets two
coordinates where the problem has one (it needs n >= 2) and a cap of 10^5 evaluations.
Prints, per problem and solver, the ways runs ended and the median evaluations.

    pip install ./python cma
    python python/bench/unbounded.py
"""

import warnings

import numpy as np

import hodr

warnings.filterwarnings("ignore")
import cma  # noqa: E402

# name: (f, n)
PROBLEMS = {
    "slope, n = 1 (f = x)": (lambda x: float(x[0]), 1),
    "slope, n = 10 (f = sum of x)": (lambda x: float(np.sum(x)), 10),
    "-exp(x0) + sum of the other squares, n = 5": (lambda x: float(-np.exp(x[0]) + x[1:] @ x[1:]), 5),
    "-log(1 + x^2), n = 1": (lambda x: float(-np.log1p(x[0] ** 2)), 1),
    # Bounded below, the infimum 0 approached as x0 grows: no minimum to converge to.
    "exp(-x0) + sum of the other squares, n = 5": (lambda x: float(np.exp(-x[0]) + x[1:] @ x[1:]), 5),
    "1 - tanh(x0) + sum of the other squares, n = 5": (lambda x: float(1 - np.tanh(x[0]) + x[1:] @ x[1:]), 5),
    # An asymptote as slow as 1/|x0|: its gains never settle; hodr ends by its cap.
    "1/(1 + |x0|) + sum of the other squares, n = 5": (lambda x: float(1 / (1 + abs(x[0])) + x[1:] @ x[1:]), 5),
}


def run_hodr(f, n, seed):
    """(how the run ended, evaluations)."""
    res = hodr.minimize(f, np.zeros(n), 1.0, seed=seed)
    return res.message.split(" (")[0], res.nfev


def run_cma(f, n, seed):
    """(pycma's first stopping condition, evaluations)."""
    m = max(n, 2)
    es = cma.CMAEvolutionStrategy(np.zeros(m), 1.0, {"seed": seed + 1, "verbose": -9, "maxfevals": 100_000})
    es.optimize(lambda x: f(x[:n]))
    return next(iter(es.stop())), es.result.evaluations


def main():
    print("| problem | hodr (Auto) | pycma |")
    print("|---|---|---|")
    for name, (f, n) in PROBLEMS.items():
        cells = []
        for solver in (run_hodr, run_cma):
            runs = [solver(f, n, seed) for seed in range(10)]
            ends = sorted({end for end, _ in runs})
            median = int(np.median([e for _, e in runs]))
            cells.append(f"{', '.join(ends)}; median {median}")
        print(f"| {name} | {cells[0]} | {cells[1]} |")


if __name__ == "__main__":
    main()
