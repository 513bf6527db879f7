"""Problems for unseen.py's sixteenth set: a simulation's parameters fitted to what it
produced, as a scientist fits a model of a process to measurements. None of hodr's tasks,
tests or suites has them, and none of the earlier sets fits the output of a time-stepped
simulation.

* A damped oscillation (n = 4): A·exp(-z t)·cos(w t + p) sampled at 80 times in [0, 10],
  fitted in amplitude A, damping z, frequency w and phase p.
* Predators and prey (n = 4): Lotka and Volterra's equations, x' = a x - b x y,
  y' = d x y - c y from (10, 10), integrated by the classical Runge-Kutta scheme with
  steps of 0.05 to t = 15 and both populations read every 0.5 (60 values).
* An epidemic (n = 3): the SIR equations S' = -b S I, I' = b S I - g I with the infected
  share I(0) = 10^e, integrated as above with steps of 0.5 to day 100 and I read every
  five days; b and 10^e trade off while the epidemic grows.
* Lorenz's equations (n = 3): x' = s (y - x), y' = x (r - z) - y, z' = x y - b z from
  (1, 1, 1), integrated with steps of 0.01 to t = 15 and x, y, z read every 0.1 (450
  values). The flow is chaotic, so f is rugged: along each parameter's axis through the
  truth it has 85-244 local minima within the box (1 500 points a line), and it is
  smooth only near the truth (f = 2.8e-5 at 0.01 from it in r).
* Heat in a rod (n = 20 and 50): u_t = (k(s) u_s)_s on [0, 1] with u = 0 at both ends,
  k constant on each of n cells, exp of the parameters; backward Euler with 25 steps of
  0.002 from u(0) = sin(pi s) + sin(3 pi s)/2 on the n - 1 interior nodes, u read at
  every fifth step: an inverse problem, each cell's conductivity seen through the
  temperature's slope across it, the truth 0.5 sin(2 pi s) at the cells' middles.

The data are the simulation's own output at the true parameters, so f* = 0 there; each
f is the mean squared misfit over the data's mean square, so f(x) is the share of the
data's energy the fit misses. Starts are uniform in the box, sigma0 a quarter of its
width in each coordinate, the target 1e-6 on f, the budget 500 n evaluations; 2 000 n
for the oscillation, a formula that costs microseconds, and for Lorenz's equations, on
which no solver met the target in 500 n from most starts.
"""

import math

import numpy as np

from raster_losses import Case

OSCILLATOR_TIMES = np.linspace(0.0, 10.0, 80)


def oscillation(x):
    """A·exp(-z t)·cos(w t + p) at OSCILLATOR_TIMES for x = (A, z, w, p)."""
    a, z, w, p = x
    return a * np.exp(-z * OSCILLATOR_TIMES) * np.cos(w * OSCILLATOR_TIMES + p)


def rk4(derivative, state, step, steps, every):
    """The classical Runge-Kutta scheme on a state of three floats (u, v, w), `steps`
    steps of `step` from `state`; the state after every `every` steps, as a list of
    triples. (Written out for three floats: a loop over the state's entries cost the
    two-population problems ten times as much.)"""
    u, v, w = state
    half, sixth = 0.5 * step, step / 6.0
    out = []
    for k in range(1, steps + 1):
        a1, b1, c1 = derivative(u, v, w)
        a2, b2, c2 = derivative(u + half * a1, v + half * b1, w + half * c1)
        a3, b3, c3 = derivative(u + half * a2, v + half * b2, w + half * c2)
        a4, b4, c4 = derivative(u + step * a3, v + step * b3, w + step * c3)
        u += sixth * (a1 + 2.0 * (a2 + a3) + a4)
        v += sixth * (b1 + 2.0 * (b2 + b3) + b4)
        w += sixth * (c1 + 2.0 * (c2 + c3) + c4)
        if k % every == 0:
            out.append((u, v, w))
    return out


def predators_and_prey(x):
    """Both populations every 0.5 to t = 15 for x = (a, b, c, d), from (10, 10)."""
    a, b, c, d = (float(t) for t in x)

    def derivative(prey, predators, _):
        meet = prey * predators
        return (a * prey - b * meet, d * meet - c * predators, 0.0)

    return np.array([s[:2] for s in rk4(derivative, (10.0, 10.0, 0.0), 0.05, 300, 10)]).ravel()


def epidemic(x):
    """The infected share every five days to day 100 for x = (b, g, e), I(0) = 10^e."""
    b, g, e = (float(t) for t in x)
    infected = 10.0 ** e

    def derivative(susceptible, ill, _):
        spread = b * susceptible * ill
        return (-spread, spread - g * ill, 0.0)

    return np.array([s[1] for s in rk4(derivative, (1.0 - infected, infected, 0.0), 0.5, 200,
                                       10)])


def lorenz(x):
    """x, y and z every 0.1 to t = 15 for x = (s, r, b): Lorenz's equations x' = s (y -
    x), y' = x (r - z) - y, z' = x y - b z from (1, 1, 1), in steps of 0.01."""
    s, r, b = (float(t) for t in x)

    def derivative(p, q, w):
        return (s * (q - p), p * (r - w) - q, p * q - b * w)

    return np.array(rk4(derivative, (1.0, 1.0, 1.0), 0.01, 1500, 10)).ravel()


def rod(cells):
    """The rod's interior temperatures at steps 5, 10, ..., 25 as a function of the log
    conductivities x of its `cells` cells: backward Euler, (I - dt A) u_next = u, A the
    conservative finite-difference operator (k_i (u_{i+1} - u_i) - k_{i-1} (u_i -
    u_{i-1})) / h^2, from u(0) = sin(pi s) + sin(3 pi s)/2 on the interior nodes."""
    nodes = np.arange(1, cells) / cells
    start = np.sin(math.pi * nodes) + 0.5 * np.sin(3.0 * math.pi * nodes)
    h2 = (1.0 / cells) ** 2

    def heat(x):
        k = np.exp(np.asarray(x, dtype=float))
        operator = (np.diag(-(k[:-1] + k[1:])) + np.diag(k[1:-1], 1)
                    + np.diag(k[1:-1], -1)) / h2
        step = np.linalg.inv(np.eye(cells - 1) - 0.002 * operator)
        u, out = start, []
        for j in range(1, 26):
            u = step @ u
            if j % 5 == 0:
                out.append(u)
        return np.concatenate(out)

    return heat


def misfit(simulate, truth):
    """f(x) = mean((simulate(x) - data)^2) / mean(data^2), the data simulate(truth);
    +inf where the simulation overflows."""
    data = simulate(truth)
    energy = float(np.mean(data ** 2))

    def f(x):
        with np.errstate(over="ignore", invalid="ignore"):
            r = simulate(np.asarray(x, dtype=float)) - data
            value = float(np.mean(r * r)) / energy
        return value if math.isfinite(value) else math.inf

    return f


def case(simulate, truth, low, high, budget_per_dim):
    """Starts uniform in the box [low, high], sigma0 a quarter of its width."""
    truth = np.asarray(truth, dtype=float)
    low = np.broadcast_to(np.asarray(low, dtype=float), truth.shape).copy()
    high = np.broadcast_to(np.asarray(high, dtype=float), truth.shape).copy()
    return Case(misfit(simulate, truth), truth, (high - low) / 4.0, (low, high),
                budget_per_dim * truth.size, 1e-6, (low, high))


def conductivities(cells):
    """The true log conductivities: 0.5 sin(2 pi s) at the cells' middles."""
    return 0.5 * np.sin(2.0 * math.pi * (np.arange(cells) + 0.5) / cells)


PROBLEMS = {
    "oscillation4": case(oscillation, [1.5, 0.3, 2.2, 0.7], [0.0, 0.0, 0.2, -math.pi],
                         [4.0, 1.5, 5.0, math.pi], 2000),
    "predators4": case(predators_and_prey, [1.1, 0.4, 0.4, 0.1], [0.05, 0.05, 0.05, 0.02],
                       [2.0, 1.0, 1.0, 0.5], 500),
    "epidemic3": case(epidemic, [0.5, 0.2, -3.0], [0.05, 0.02, -6.0], [2.0, 1.0, -1.0],
                      500),
    "lorenz3": case(lorenz, [10.0, 28.0, 8.0 / 3.0], [5.0, 20.0, 1.0], [15.0, 35.0, 4.0],
                    2000),
    "heat20": case(rod(20), conductivities(20), -2.0, 2.0, 500),
    "heat50": case(rod(50), conductivities(50), -2.0, 2.0, 500),
}
