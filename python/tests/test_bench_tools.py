"""The bookkeeping of the benchmarks in `python/bench`: what a run held after each budget."""

import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "bench"))

import anytime  # noqa: E402
import unseen  # noqa: E402


def test_best_within_is_the_lowest_value_among_the_first_evaluations():
    values = iter([5.0, 3.0, float("nan"), 4.0, 1.0])
    counted = unseen.Counted(lambda x: next(values), f_opt=0.0, target=1e-9, budget=10)
    for _ in range(5):
        counted(np.zeros(1))
    assert [counted.best_within(k) for k in range(7)] == [None, 5.0, 3.0, 3.0, 3.0, 1.0, 1.0]


def test_a_run_that_reaches_the_target_holds_it_at_every_later_budget():
    counted = unseen.Counted(lambda x: float(x @ x), f_opt=0.0, target=0.5, budget=10)
    for x in ([2.0], [0.5], [1.0]):
        try:
            counted(np.array(x))
        except unseen.Spent:
            break
    assert counted.hit == 2
    assert counted.best_within(2) == counted.best_within(100) == 0.25


def test_gaps_never_grow_with_the_budget():
    problem = unseen.PROBLEMS["beale2"]
    gaps = anytime.gaps_within("hodr", problem._replace(budget=60), 3, [4, 20, 60])
    assert len(gaps) == 3 and all(len(g) == 3 for g in gaps)
    for early, late in zip(gaps, gaps[1:]):
        assert all(b <= a for a, b in zip(early, late))
    assert all(np.isfinite(g) for g in gaps[-1])
