"""hodr's default optimiser, pycma and BOBYQA on COCO's `bbob` (or `bbob-mixint`, or
`bbob-noisy`) suite, for BENCHMARKS.md.

Each solver runs on every function and instance of the suite in the given dimensions
with COCO's standard observer, then COCO's own post-processing (cocopp) compares them:

    pip install ./python cma nlopt coco-experiment cocopp six matplotlib
    python python/bench/coco_bbob.py --solver hodr  --dims 2,3,5,10 --budget 1000
    python python/bench/coco_bbob.py --solver cma   --dims 2,3,5,10 --budget 1000
    python python/bench/coco_bbob.py --solver bobyqa --dims 2,3,5,10 --budget 1000
    python -m cocopp -o ppdata exdata/bbob-hodr* exdata/bbob-cma* exdata/bbob-bobyqa*

`--functions 17,18` (or a range, `10-14`) runs a subset of the suite's functions, as
COCO numbers them. At the end the script prints, per function and dimension, how many
instances hit COCO's final target (f - f* <= 1e-8) within the budget and their median
evaluations. `--suite bbob-mixint` runs the mixed-integer suite (integer
variables: plateaus) in its own dimensions (5, 10, 20, ...), where the solvers see the
same continuous box and the suite rounds the integer coordinates. `--suite bbob-noisy`
runs COCO's noisy functions f101-f130, which draw fresh noise at every call: every
solver gets them as plain functions, hodr without `noisy=True` (it is not told).

Every solver gets the same problem statement: COCO's initial solution, a scale of 2 (a
fifth of the [-5, 5] box, pycma's usual choice on bbob), the box as bounds where the
solver takes bounds (hodr, BOBYQA; pycma runs unbounded, as in COCO's own examples) and
a budget of `budget`·n evaluations, spent in independent restarts from uniform points
in [-4, 4]ⁿ until the budget is used or the final target is hit. Solver settings are
each library's defaults: hodr `minimize` (Auto), `cma.fmin2`, nlopt's `LN_BOBYQA` with
its default interpolation set and a relative x tolerance of 1e-12.
"""

import argparse
import time

import numpy as np

SIGMA0 = 2.0


def run_hodr(problem, x0, budget, seed):
    import hodr

    bounds = list(zip(problem.lower_bounds, problem.upper_bounds))
    # With a budget Auto spends all of it (fresh descents about its best point); the
    # callback ends the run once COCO's final target is hit, as the restart loop does.
    hodr.minimize(problem, x0, SIGMA0, bounds=bounds, budget=budget, seed=seed,
                  callback=lambda x, f: problem.final_target_hit)


def run_cma(problem, x0, budget, seed):
    import warnings

    warnings.filterwarnings("ignore")
    import cma

    cma.fmin2(problem, x0, SIGMA0, {"maxfevals": budget, "verbose": -9, "seed": seed + 1})


def run_bobyqa(problem, x0, budget, seed):
    import nlopt

    opt = nlopt.opt(nlopt.LN_BOBYQA, len(x0))
    opt.set_lower_bounds(problem.lower_bounds)
    opt.set_upper_bounds(problem.upper_bounds)
    opt.set_min_objective(lambda x, grad: float(problem(x)))
    # BOBYQA refuses an initial trust region wider than half of a coordinate's range
    # (the integer coordinates of bbob-mixint have narrow ones).
    width = np.asarray(problem.upper_bounds) - np.asarray(problem.lower_bounds)
    opt.set_initial_step(np.minimum(SIGMA0, 0.45 * width))
    opt.set_maxeval(budget)
    opt.set_xtol_rel(1e-12)
    try:
        opt.optimize(np.clip(x0, problem.lower_bounds, problem.upper_bounds))
    except (nlopt.RoundoffLimited, RuntimeError, ValueError):
        pass  # ends the restart; COCO has logged every evaluation


SOLVERS = {"hodr": run_hodr, "cma": run_cma, "bobyqa": run_bobyqa}


def main():
    import cocoex

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--solver", choices=sorted(SOLVERS), required=True)
    parser.add_argument("--suite", default="bbob", choices=["bbob", "bbob-mixint", "bbob-noisy"])
    parser.add_argument("--dims", default="2,3,5,10")
    parser.add_argument("--budget", type=int, default=1000, help="evaluations per dimension")
    parser.add_argument("--instances", default="1-15")
    parser.add_argument("--functions", default=None,
                        help="function indices, e.g. 17,18 or 10-14 (default: all)")
    args = parser.parse_args()
    solve = SOLVERS[args.solver]
    options = f"dimensions:{args.dims} instance_indices:{args.instances}"
    if args.functions:
        options += f" function_indices:{args.functions}"
    suite = cocoex.Suite(args.suite, "", options)
    folder = f"{args.suite}-{args.solver}"
    observer = cocoex.Observer(args.suite, f"result_folder: {folder} algorithm_name: {args.solver}")
    rng = np.random.default_rng(0)
    start = time.perf_counter()
    hits = {}
    for k, problem in enumerate(suite):
        problem.observe_with(observer)
        budget = args.budget * problem.dimension
        x0 = problem.initial_solution
        restart = 0
        while problem.evaluations < budget and not problem.final_target_hit:
            solve(problem, x0, budget - problem.evaluations, seed=restart)
            restart += 1
            x0 = rng.uniform(-4.0, 4.0, problem.dimension)
        key = (problem.id_function, problem.dimension)
        hits.setdefault(key, []).append(problem.evaluations if problem.final_target_hit else None)
        problem.free()
        if k % 60 == 0:
            print(f"{args.solver}: {k + 1}/{len(suite)} problems, {time.perf_counter() - start:.0f} s",
                  flush=True)
    print(f"{args.solver}: done in {time.perf_counter() - start:.0f} s")
    print("function, n: instances whose run hit the final target (f - f* <= 1e-8) within the"
          " budget, and the median evaluations of those")
    for (function, n), runs in sorted(hits.items()):
        solved = sorted(e for e in runs if e is not None)
        median = solved[(len(solved) - 1) // 2] if solved else "-"
        print(f"  f{function:02d}, {n}: {len(solved)}/{len(runs)}, {median}")


if __name__ == "__main__":
    main()
