"""Fit the two rate constants of a biexponential decay, a fast one in [1e-3, 10] and a
slow one in [1e-7, 1e-2] per second, by declaring them ``log_scale``.

A rate matters in proportion to its size: the data change as much between 1e-5 and 1e-4
as between 1 and 10, so no one sigma0 in seconds⁻¹ fits the box. With ``log_scale``,
Auto searches log10 of the rates, sigma0 in decades there, while the model below still
receives the rates themselves.

    python python/examples/rate_constants.py
"""

import numpy as np

import hodr

TIMES = np.logspace(-2.0, 6.0, 60)  # seconds
TRUTH = np.array([0.8, 2e-4, 0.3])  # fast rate, slow rate (1/s), fast share


def decay(p):
    """y(t) = a e^(-k1 t) + (1 - a) e^(-k2 t) for p = (k1, k2, a)."""
    k1, k2, a = p
    return a * np.exp(-k1 * TIMES) + (1.0 - a) * np.exp(-k2 * TIMES)


DATA = decay(TRUTH)


def misfit(p):
    """Mean squared difference of the model's curve from the data."""
    return float(np.mean((decay(p) - DATA) ** 2))


def main():
    bounds = [(1e-3, 10.0), (1e-7, 1e-2), (0.0, 1.0)]
    x0 = [1.0, 1e-3, 0.5]
    # sigma0: one decade for each rate, 0.25 for the share.
    declared = hodr.minimize(misfit, x0, [1.0, 1.0, 0.25], bounds=bounds,
                             log_scale=[True, True, False], budget=600, seed=1)
    # The same problem in the rates' own units, sigma0 a quarter of each side.
    plain = hodr.minimize(misfit, x0, [2.5, 2.5e-3, 0.25], bounds=bounds, budget=600, seed=1)
    for name, res in (("log_scale", declared), ("own units", plain)):
        first = next((e for e, f in zip(res.history["nfev"], res.history["fun"]) if f <= 1e-12),
                     None)
        print(f"{name:>9}: k1 = {res.x[0]:.4g}, k2 = {res.x[1]:.4g}, a = {res.x[2]:.4g}, "
              f"misfit {res.fun:.2g}, first below 1e-12 after {first} evaluations")
    return declared, plain


if __name__ == "__main__":
    main()
