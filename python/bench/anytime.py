"""What each solver holds after a small budget: hodr's default against pycma and BOBYQA on
unseen.py's problems, at budgets of a few evaluations per dimension, for BENCHMARKS.md.

    pip install ./python cma nlopt
    python python/bench/anytime.py [--seeds 10] [--at 10,30,100] [--problems ackley10,...]
        [--solvers hodr,pycma,BOBYQA]

A user whose objective is a render of seconds has a budget of tens of evaluations per
parameter, not unseen.py's 2 000, and keeps the best point found by then. Each run gets
the row's problem, start and seed as unseen.py states them, with the budget the largest of
--at (evaluations per dimension) times n (the row's own where that is smaller); the
lowest f - f* among its first k*n evaluations is what a caller with budget k*n holds
(hodr is anytime: its first k*n evaluations are the same whatever the budget; pycma's and
BOBYQA's do not depend on it either). A run ends at the row's target, as in unseen.py, and
holds that value from there on.

Each line gives, at one budget, every solver's median lowest f - f* over the seeds (the
lower of the two middle runs) with the runs within the target by then. The summary gives,
per budget and opponent, on how many rows hodr's median is lower, equal (both at the
target or the same value) and higher, and the geometric mean over rows of hodr's median
over the opponent's, each median first raised to the row's target (a run at the target
has done all it was asked).
"""

import argparse
import math
import time

import numpy as np

import unseen


def gaps_within(solver, problem, seeds, checkpoints):
    """For each checkpoint (evaluations), the runs' lowest f - f* within it (inf where
    nothing finite was found)."""
    gaps = [[] for _ in checkpoints]
    f_opt = problem.f_opt
    for seed in range(seeds):
        x0 = unseen.draw_start(problem, np.random.default_rng(seed))
        counted = unseen.Counted(problem.f, f_opt, problem.target, problem.budget,
                                 problem.failures, seed)
        try:
            unseen.SOLVERS[solver](counted, x0, problem, seed)
        except unseen.Spent:
            pass
        for row, k in zip(gaps, checkpoints):
            best = counted.best_within(k)
            row.append(np.inf if best is None else best - f_opt)
    return gaps


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--at", default="10,30,100",
                        help="budgets, in evaluations per dimension (comma-separated)")
    parser.add_argument("--problems", default=",".join(unseen.PROBLEMS))
    parser.add_argument("--solvers", default=",".join(unseen.SOLVERS))
    args = parser.parse_args()
    try:
        per_dim = sorted({int(k) for k in args.at.split(",")})
    except ValueError:
        parser.error(f"--at takes whole numbers of evaluations per dimension, got {args.at!r}")
    if per_dim[0] < 1:
        parser.error(f"--at takes budgets of at least 1 evaluation per dimension, got {args.at!r}")
    if args.seeds < 1:
        parser.error(f"--seeds must be at least 1, got {args.seeds}")
    names = unseen.chosen(parser, args.problems, unseen.PROBLEMS, "problem")
    solvers = unseen.chosen(parser, args.solvers, unseen.SOLVERS, "solver")
    others = [s for s in solvers if s != "hodr"] if "hodr" in solvers else []
    print("| problem | n | evaluations | target | " + " | ".join(
        f"{s} median f − f* (runs at target)" for s in solvers) + " |")
    print("|---|---|---|---|" + "---|" * len(solvers))
    # tally[k][opponent] = [lower, equal, higher, sum of log ratios, rows]
    tally = {k: {s: [0, 0, 0, 0.0, 0] for s in others} for k in per_dim}
    start = time.perf_counter()
    for name in names:
        problem = unseen.PROBLEMS[name]
        checkpoints = [k * problem.n for k in per_dim]
        problem = problem._replace(budget=min(problem.budget, checkpoints[-1]))
        gaps = {s: gaps_within(s, problem, args.seeds, checkpoints) for s in solvers}
        for i, (k, evaluations) in enumerate(zip(per_dim, checkpoints)):
            if evaluations > problem.budget:
                continue
            medians = {s: unseen.lower_median(gaps[s][i]) for s in solvers}
            cells = [f"{medians[s]:.3g} ({sum(g <= problem.target for g in gaps[s][i])}"
                     f"/{args.seeds})" for s in solvers]
            print(f"| {name} | {problem.n} | {evaluations} | {problem.target:g} | "
                  + " | ".join(cells) + " |", flush=True)
            ours = max(medians.get("hodr", np.inf), problem.target)
            for s in others:
                theirs = max(medians[s], problem.target)
                counts = tally[k][s]
                counts[0 if ours < theirs else 1 if ours == theirs else 2] += 1
                if np.isfinite(ours) and np.isfinite(theirs):
                    counts[3] += math.log(ours / theirs)
                    counts[4] += 1
    print(f"\n{time.perf_counter() - start:.0f} s")
    if others:
        print("\n| evaluations per dimension | opponent | hodr lower / equal / higher "
              "| hodr ÷ opponent, geometric mean |")
        print("|---|---|---|---|")
        for k in per_dim:
            for s in others:
                lower, equal, higher, logs, rows = tally[k][s]
                mean = f"{math.exp(logs / rows):.3g}" if rows else "—"
                print(f"| {k} | {s} | {lower} / {equal} / {higher} | {mean} |")


if __name__ == "__main__":
    main()
