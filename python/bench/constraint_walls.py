"""Problems for unseen.py's eleventh set: a constraint the objective enforces itself, the
way a user writes one without a constrained solver, where the minimum lies on the
constraint. None of hodr's tasks, tests or suites has them.

The bowl ||x - 1||^2 cut by the half-space sum(x) <= n/2 through its interior: the
minimum, n/4, lies on the cut at x_i = 1/2. Beyond the cut the objective returns

* inf (wall-inf2, wall-inf5, wall-inf10) or NaN (wall-nan5): a failure, as a renderer
  fails on parameters it cannot draw;
* the bowl plus 100 or plus 1e10 (wall-plus100-5, wall-plus1e10-5): a constant penalty,
  a step at the minimum;
* 1e10 alone (wall-const1e10-2, wall-const1e10-5, wall-const1e10-10; added on
  2026-12-05, after the set's first run): "return a big number where the parameters are
  not allowed", a plateau beyond a step at the minimum; and, as a control, the same
  with the bowl centred at 0.2, its minimum inside (inside-const1e10-10);
* the bowl plus 1000 times the violation (wall-exact5): an exact penalty, continuous, a
  kink at the minimum (a control).

Starts uniform in [-3, 3]^n (about half of them beyond the cut), sigma0 1, no box, budget
2000 n, target 1e-6.
"""

import numpy as np

from raster_losses import Case


def walled(beyond, centre=1.0):
    """The bowl ||x - centre||^2 where sum(x) <= n/2, `beyond(q, violation)` elsewhere."""

    def f(x):
        x = np.asarray(x, dtype=float)
        q = float(np.sum((x - centre) ** 2))
        violation = float(np.sum(x)) - 0.5 * len(x)
        return q if violation <= 0.0 else beyond(q, violation)

    return f


def case(beyond, n):
    return Case(walled(beyond), np.full(n, 0.5), 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))


def inside(beyond, n):
    """The bowl centred at 0.2 instead, its minimum inside, sum(x) = 0.2 n < n/2."""
    return Case(walled(beyond, 0.2), np.full(n, 0.2), 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))


def fail(value):
    """`value` wherever the constraint is broken: a failure (inf, NaN) or a plateau."""
    return lambda q, violation: value


PROBLEMS = {
    "wall-inf2": case(fail(float("inf")), 2),
    "wall-inf5": case(fail(float("inf")), 5),
    "wall-inf10": case(fail(float("inf")), 10),
    "wall-nan5": case(fail(float("nan")), 5),
    "wall-plus100-5": case(lambda q, violation: q + 100.0, 5),
    "wall-plus1e10-5": case(lambda q, violation: q + 1e10, 5),
    "wall-const1e10-2": case(fail(1e10), 2),
    "wall-const1e10-5": case(fail(1e10), 5),
    "wall-const1e10-10": case(fail(1e10), 10),
    "inside-const1e10-10": inside(fail(1e10), 10),
    "wall-exact5": case(lambda q, violation: q + 1000.0 * violation, 5),
}
