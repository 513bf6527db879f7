"""The problems of `python/bench/unseen.py` as stated: each minimiser lies in its box and
its start range, and no point near it within the box is lower, so that f* = f(x*) is a
target a solver can reach and cannot undercut nearby."""

import pathlib
import sys

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "bench"))

import unseen  # noqa: E402


@pytest.mark.parametrize("name", sorted(unseen.PROBLEMS))
def test_the_stated_minimiser_is_a_minimum_within_the_box(name):
    problem = unseen.PROBLEMS[name]
    x_opt = problem.x_opt
    assert x_opt.shape == (problem.n,)
    f_opt = problem.f_opt
    assert np.isfinite(f_opt)
    if problem.box is not None:
        low, high = problem.box
        assert np.all((low <= x_opt) & (x_opt <= high))
    # Points 1e-4 away along random directions, and along each axis both ways, held in
    # the box: none lower than f* by more than f's rounding there.
    rng = np.random.default_rng(0)
    steps = [1e-4 * d / np.linalg.norm(d) for d in rng.normal(size=(100, problem.n))]
    steps += [s * 1e-4 * e for e in np.eye(problem.n) for s in (1.0, -1.0)]
    slack = 1e-12 * max(1.0, abs(f_opt))
    for step in steps:
        x = x_opt + step
        if problem.box is not None:
            x = np.clip(x, *problem.box)
        value = problem.f(x)
        assert not value < f_opt - slack, (name, step, value - f_opt)


@pytest.mark.parametrize("name", sorted(unseen.PROBLEMS))
def test_starts_lie_in_the_box(name):
    problem = unseen.PROBLEMS[name]
    for seed in range(3):
        x0 = unseen.draw_start(problem, np.random.default_rng(seed))
        assert x0.shape == (problem.n,)
        if problem.box is not None:
            assert np.all((problem.box[0] <= x0) & (x0 <= problem.box[1]))
