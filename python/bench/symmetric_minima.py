"""Problems for unseen.py's twentieth set: objectives whose minima are not points but
sets, as a symmetry of the model makes them. A user fitting a factorisation, a direction
or a configuration of points meets them: every minimum has directions along which f
does not change at all, so the Hessian there is singular however well the rest is
conditioned. None of the earlier sets has one (the suite's flat problem has a flat
direction everywhere, not a set of minima curving through the space).

* rayleigh10, rayleigh20: the Rayleigh quotient x'Ax / x'x of a symmetric A with
  eigenvalues 1, 2, ..., n in a random orthonormal basis, f* = 1 along the ray of the
  least eigenvector (both signs): f is constant along every ray, and not defined at 0.
* phase-retrieval8, phase-retrieval16: x from the squares of 4n Gaussian measurements,
  f(x) = mean_i ((a_i'x)^2 - (a_i'x*)^2)^2, f* = 0 at x* and -x*, a quartic whose
  curvature grows with |x|.
* factorisation7, factorisation22: the factors of a matrix of rank r, M = U*V*' (4 x 3
  of rank 1, 6 x 5 of rank 2; n = r(rows + columns)), f(U, V) = |UV' - M|^2 over M's
  entries, f* = 0 on the r^2-dimensional set U*G, V*G^-T for every invertible G.
* thomson10, thomson24: five (twelve) unit charges on a sphere, each placed by its polar
  and azimuthal angles, f the energy sum_{i<j} 1/|p_i - p_j|, f* = 6.474691495 at the
  triangular bipyramid (49.165253058 at the icosahedron) and at every rotation and
  relabelling of it; the angles are periodic, and a charge at a pole leaves its azimuth
  free.

Budgets are 2 000 n evaluations, targets 1e-6 on f - f*, starts uniform in [-3, 3]^n
(for the charges the angles uniform over the sphere's chart, [0, pi] x [-pi, pi]), sigma0 1,
no box.
"""

import numpy as np

from raster_losses import Case


def rayleigh(n):
    """x'Ax / x'x with A's eigenvalues 1 ... n in a random orthonormal basis (the QR of a
    Gaussian matrix); returns (f, x*)."""
    q, _ = np.linalg.qr(np.random.default_rng(2020 + n).standard_normal((n, n)))
    a = q @ np.diag(np.arange(1.0, n + 1.0)) @ q.T

    def f(x):
        x = np.asarray(x, dtype=float)
        return float(x @ a @ x / (x @ x))

    return f, 2.0 * q[:, 0]


def phase_retrieval(n):
    """The misfit of the squared measurements of x; returns (f, x*)."""
    rng = np.random.default_rng(3030 + n)
    a = rng.standard_normal((4 * n, n))
    truth = rng.uniform(-1.0, 1.0, n)
    data = (a @ truth) ** 2

    def f(x):
        r = (a @ np.asarray(x, dtype=float)) ** 2 - data
        return float(np.mean(r * r))

    return f, truth


def factorisation(rows, columns, rank):
    """|UV' - M|^2 for M = U*V*' of the given rank, x = (U, V) row by row; returns
    (f, x*)."""
    rng = np.random.default_rng(4040 + rows * columns)
    u, v = rng.uniform(-1.0, 1.0, (rows, rank)), rng.uniform(-1.0, 1.0, (columns, rank))
    target = u @ v.T

    def f(x):
        x = np.asarray(x, dtype=float)
        r = x[: rows * rank].reshape(rows, rank) @ x[rows * rank:].reshape(columns, rank).T
        return float(np.sum((r - target) ** 2))

    return f, np.concatenate([u.ravel(), v.ravel()])


def thomson(x):
    """The Coulomb energy of unit charges at the polar and azimuthal angles
    (theta_1, phi_1, theta_2, ...) on the unit sphere."""
    x = np.asarray(x, dtype=float)
    theta, phi = x[0::2], x[1::2]
    p = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], 1)
    i, j = np.triu_indices(len(theta), 1)
    return float(np.sum(1.0 / np.linalg.norm(p[i] - p[j], axis=1)))


# The triangular bipyramid: both poles and three charges 120 degrees apart on the equator.
BIPYRAMID = np.array([0.0, 0.0, np.pi, 0.0, np.pi / 2, 0.0,
                      np.pi / 2, 2 * np.pi / 3, np.pi / 2, -2 * np.pi / 3])


def icosahedron():
    """The angles of the icosahedron's twelve vertices: both poles and two rings of five
    at polar angle arctan(2) from them, the rings 36 degrees apart in azimuth."""
    ring = np.arctan(2.0)
    angles = [(0.0, 0.0), (np.pi, 0.0)]
    angles += [(ring, 2 * np.pi * k / 5 - np.pi) for k in range(5)]
    angles += [(np.pi - ring, 2 * np.pi * k / 5 - np.pi + np.pi / 5) for k in range(5)]
    return np.array(angles).ravel()


def _problems():
    out = {}
    for n in (10, 20):
        f, truth = rayleigh(n)
        out[f"rayleigh{n}"] = Case(f, truth, 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))
    for n in (8, 16):
        f, truth = phase_retrieval(n)
        out[f"phase-retrieval{n}"] = Case(f, truth, 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))
    for rows, columns, rank in ((4, 3, 1), (6, 5, 2)):
        f, truth = factorisation(rows, columns, rank)
        n = len(truth)
        out[f"factorisation{n}"] = Case(f, truth, 1.0, None, 2000 * n, 1e-6, (-3.0, 3.0))
    for truth in (BIPYRAMID, icosahedron()):
        k = len(truth) // 2
        chart = (np.tile([0.0, -np.pi], k), np.tile([np.pi, np.pi], k))
        out[f"thomson{2 * k}"] = Case(thomson, truth, 1.0, None, 4000 * k, 1e-6, chart)
    return out


PROBLEMS = _problems()
