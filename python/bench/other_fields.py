"""Problems for unseen.py's tenth set: objectives users from other fields bring, written
here from their textbook definitions. None of hodr's tasks, tests or suites has them.

* A Lennard-Jones cluster of six atoms (chemistry): the pair energy 4(r^-12 - r^-6)
  summed over every pair, n = 18 coordinates. Its global minimum is the octahedron,
  -12.712062 (Wales and Doye's Cambridge Cluster Database), beside a second minimum, the
  capped trigonal bipyramid at -12.302927. The energy is flat along the six directions
  that move or turn the whole cluster and grows as r^-12 where two atoms meet.
* A teacher-student network (machine learning): a network with one hidden layer of four
  tanh units, three inputs and one linear output (n = 21 weights), fitted by mean squared
  error to the outputs of a teacher of the same shape on 50 fixed inputs. f* = 0 at the
  teacher's weights (and at each of their permutations and sign flips).
* A planar arm of ten unit links (robotics): joint angles, each relative to the last link,
  within [-pi, pi], placing the arm's end on a reachable point; f is the squared distance
  to it. Its minima form an eight-dimensional set.
* A camera's pose from twelve known 3D points (vision): a rotation (axis-angle) and a
  translation, n = 6, fitted by the squared reprojection error in pixels of a pinhole
  camera of focal length 500.
* Logistic regression with a small ridge (statistics): 30 weights, 300 correlated
  samples; the minimum is found by Newton's method.
* Three Gaussian peaks fitted to a noiseless spectrum (spectroscopy): amplitude, centre
  and width of each, n = 9, on 100 samples, within a box that keeps the widths positive.
"""

import numpy as np

from raster_losses import Case


# Lennard-Jones.
ATOMS = 6


def lennard_jones(x):
    """Sum over atom pairs of 4(r^-12 - r^-6), x the atoms' coordinates (3 each)."""
    p = x.reshape(-1, 3)
    d = p[:, None, :] - p[None, :, :]
    r2 = (d * d).sum(axis=2)[np.triu_indices(len(p), 1)]
    inv6 = 1.0 / r2**3
    return float(np.sum(4.0 * (inv6 * inv6 - inv6)))


def octahedron():
    """The six atoms at +-a on each axis, a minimising 12 V(a sqrt 2) + 3 V(2a) (the
    gradient is zero there by symmetry), found by Newton's method on that function of a."""

    def energy_terms(a):
        # E(a) = sum_k c_k (4 (s_k a)^-12 - 4 (s_k a)^-6) over the 12 edges and 3 diagonals.
        first = second = 0.0
        for count, s in ((12, np.sqrt(2.0)), (3, 2.0)):
            r = s * a
            first += count * s * (-48 * r**-13 + 24 * r**-7)
            second += count * s * s * (624 * r**-14 - 168 * r**-8)
        return first, second

    a = 0.79
    for _ in range(50):
        first, second = energy_terms(a)
        a -= first / second
    return np.concatenate([s * a * e for e in np.eye(3) for s in (1.0, -1.0)])


def lennard_jones_case():
    """Starts uniform in [-1, 1]^18 (atoms in a cube of side 2, as dense as the cluster;
    two may start close), sigma0 0.25, no box, budget 2000 n, target 1e-6."""
    return Case(lennard_jones, octahedron(), 0.25, None, 2000 * 3 * ATOMS, 1e-6, (-1.0, 1.0))


# A teacher-student network.
INPUTS, HIDDEN, SAMPLES = 3, 4, 50
NETWORK_INPUTS = np.random.default_rng(20).normal(size=(SAMPLES, INPUTS))


def network(x, inputs):
    """Outputs of the network with weights x = (W1 row-major, b1, w2, b2)."""
    w1 = x[: HIDDEN * INPUTS].reshape(HIDDEN, INPUTS)
    b1 = x[HIDDEN * INPUTS: HIDDEN * INPUTS + HIDDEN]
    w2 = x[HIDDEN * INPUTS + HIDDEN: HIDDEN * INPUTS + 2 * HIDDEN]
    b2 = x[-1]
    return np.tanh(inputs @ w1.T + b1) @ w2 + b2


TEACHER = np.random.default_rng(21).normal(size=HIDDEN * INPUTS + 2 * HIDDEN + 1)
TEACHER_OUTPUTS = network(TEACHER, NETWORK_INPUTS)


def student_loss(x):
    residual = network(x, NETWORK_INPUTS) - TEACHER_OUTPUTS
    return float(residual @ residual / SAMPLES)


def network_case():
    """Starts uniform in [-1, 1]^21 (a usual initialisation's range), sigma0 0.5, no box,
    budget 2000 n, target 1e-6."""
    return Case(student_loss, TEACHER, 0.5, None, 2000 * len(TEACHER), 1e-6, (-1.0, 1.0))


# A planar arm.
LINKS = 10
ARM_POSE = np.random.default_rng(22).uniform(-1.0, 1.0, LINKS)


def arm_end(angles):
    heading = np.cumsum(angles)
    return np.array([np.cos(heading).sum(), np.sin(heading).sum()])


ARM_GOAL = arm_end(ARM_POSE)


def arm_distance(x):
    d = arm_end(x) - ARM_GOAL
    return float(d @ d)


def arm_case():
    """Joint limits [-pi, pi], starts anywhere within them, sigma0 0.5, budget 2000 n,
    target 1e-8 (a distance of 1e-4 link lengths)."""
    return Case(arm_distance, ARM_POSE, 0.5, (-np.pi, np.pi), 2000 * LINKS, 1e-8,
                (-np.pi, np.pi))


# A camera's pose.
FOCAL = 500.0
SCENE = np.random.default_rng(23).uniform([-1.0, -1.0, 4.0], [1.0, 1.0, 6.0], size=(12, 3))
POSE = np.array([0.1, -0.15, 0.05, 0.2, -0.1, 0.3])


def rotate(axis_angle, points):
    """Rodrigues' rotation of each row of `points` by the axis-angle vector."""
    angle = np.sqrt(axis_angle @ axis_angle)
    if angle < 1e-12:
        return points + np.cross(axis_angle, points)
    k = axis_angle / angle
    return (points * np.cos(angle) + np.cross(k, points) * np.sin(angle)
            + np.outer(points @ k, k) * (1.0 - np.cos(angle)))


def project(pose):
    camera = rotate(pose[:3], SCENE) + pose[3:]
    return FOCAL * camera[:, :2] / camera[:, 2:]


OBSERVED = project(POSE)


def reprojection_error(x):
    d = project(x) - OBSERVED
    return float(np.sum(d * d))


def pose_case():
    """Starts within 0.3 rad and 0.5 units of the pose in each coordinate, sigma0 0.1, no
    box, budget 2000 n, target 1e-6 px^2."""
    spread = np.array([0.3, 0.3, 0.3, 0.5, 0.5, 0.5])
    return Case(reprojection_error, POSE, 0.1, None, 2000 * 6, 1e-6,
                (POSE - spread, POSE + spread))


# Logistic regression.
FEATURES, OBSERVATIONS, RIDGE = 30, 300, 1e-3


def logistic_data():
    rng = np.random.default_rng(24)
    mixing = rng.normal(size=(FEATURES, FEATURES)) / np.sqrt(FEATURES) + np.eye(FEATURES)
    design = rng.normal(size=(OBSERVATIONS, FEATURES)) @ mixing
    truth = rng.normal(size=FEATURES) / np.sqrt(FEATURES)
    labels = rng.uniform(size=OBSERVATIONS) < 1.0 / (1.0 + np.exp(-design @ truth))
    return design, np.where(labels, 1.0, -1.0)


DESIGN, SIGNS = logistic_data()


def logistic_loss(x):
    margins = SIGNS * (DESIGN @ x)
    return float(np.mean(np.logaddexp(0.0, -margins)) + 0.5 * RIDGE * (x @ x))


def logistic_minimiser():
    """Newton's method from 0 on the strictly convex loss, to machine precision."""
    x = np.zeros(FEATURES)
    for _ in range(50):
        margins = SIGNS * (DESIGN @ x)
        p = 1.0 / (1.0 + np.exp(margins))  # sigmoid(-margin)
        gradient = -(DESIGN.T @ (SIGNS * p)) / OBSERVATIONS + RIDGE * x
        weights = p * (1.0 - p)
        hessian = (DESIGN.T * weights) @ DESIGN / OBSERVATIONS + RIDGE * np.eye(FEATURES)
        x -= np.linalg.solve(hessian, gradient)
    return x


def logistic_case():
    """Starts uniform in [-1, 1]^30, sigma0 0.5, no box, budget 2000 n, target 1e-6."""
    return Case(logistic_loss, logistic_minimiser(), 0.5, None, 2000 * FEATURES, 1e-6,
                (-1.0, 1.0))


# Three Gaussian peaks.
GRID = np.linspace(-3.0, 3.0, 100)
PEAKS = np.array([1.0, -1.0, 0.3, 0.6, 0.2, 0.5, 0.8, 1.3, 0.2])  # (amplitude, centre, width) x 3


def spectrum(x):
    a, c, w = x.reshape(3, 3).T
    return (a[:, None] * np.exp(-0.5 * ((GRID[None, :] - c[:, None]) / w[:, None]) ** 2)).sum(0)


MEASURED = spectrum(PEAKS)


def peak_misfit(x):
    d = spectrum(x) - MEASURED
    return float(d @ d)


def peaks_case():
    """Box: amplitudes [0, 2], centres [-3, 3], widths [0.05, 2]; starts anywhere with
    amplitudes [0.2, 1.5], centres [-2, 2], widths [0.1, 1]; sigma0 a quarter of each
    start range's width; budget 2000 n, target 1e-6."""
    low = np.tile([0.0, -3.0, 0.05], 3)
    high = np.tile([2.0, 3.0, 2.0], 3)
    start_low = np.tile([0.2, -2.0, 0.1], 3)
    start_high = np.tile([1.5, 2.0, 1.0], 3)
    return Case(peak_misfit, PEAKS, (start_high - start_low) / 4, (low, high), 2000 * 9, 1e-6,
                (start_low, start_high))


PROBLEMS = {
    "lennard-jones6": lennard_jones_case(),
    "teacher-network21": network_case(),
    "arm10": arm_case(),
    "camera-pose6": pose_case(),
    "logistic30": logistic_case(),
    "gaussian-peaks9": peaks_case(),
}
