"""Image losses for unseen.py's ninth set: shapes drawn on a 32 x 32 grey image and
compared with a target image of the same shapes at known parameters, as a user who
brings a small renderer of their own writes them. None of hodr's tasks, tests or suites
draws them; the rasteriser is written here from the textbook rules.

The image covers [0, 32]^2 in pixel units, pixel (i, j) the square [j, j + 1] x [i, i + 1],
on a black background (0). Shapes are painted in order, each opaque, over what is below:
a pixel becomes (1 - a) * below + a * grey, a the share of the pixel the shape covers.
The loss is the mean squared difference from the target over the 1024 pixels, so f* = 0
at the stated parameters (and wherever the image matches exactly).

Three ways to cover a pixel, three kinds of loss a renderer gives:

* rectangles with their exact area coverage (anti-aliased): the loss is continuous,
  piecewise polynomial, with kinks where an edge crosses a pixel boundary;
* discs sampled at pixel centres (no anti-aliasing): the loss is piecewise constant, flat
  until an edge passes a pixel centre;
* triangles sampled at 4 x 4 points per pixel (a rasteriser's multisampling): piecewise
  constant on a sixteenth of a pixel's area.
"""

from typing import NamedTuple

import numpy as np

SIDE = 32
EDGES = np.arange(SIDE + 1, dtype=float)
# Pixel centres and the 4 x 4 subsample positions of every pixel, row-major.
CENTRES = np.arange(SIDE) + 0.5
SUBSAMPLES = (np.arange(4 * SIDE) + 0.5) / 4


def interval_coverage(lo, hi):
    """The length of [lo, hi] within each pixel column's [j, j + 1] (0 where hi <= lo)."""
    return np.clip(np.minimum(hi, EDGES[1:]) - np.maximum(lo, EDGES[:-1]), 0.0, 1.0)


def paint(image, coverage, grey):
    """Paints an opaque shape of `grey` covering each pixel's share `coverage` over it."""
    image *= 1.0 - coverage
    image += grey * coverage


def rectangles(x):
    """The image of k grey rectangles, x = (cx, cy, half width, half height, grey) per
    rectangle, with each pixel's exact covered area. Half sizes count by magnitude."""
    image = np.zeros((SIDE, SIDE))
    for cx, cy, a, b, grey in np.reshape(x, (-1, 5)):
        a, b = abs(a), abs(b)
        paint(image, np.outer(interval_coverage(cy - b, cy + b),
                              interval_coverage(cx - a, cx + a)), grey)
    return image


def discs(x, greys):
    """The image of discs x = (cx, cy, radius) per disc, of the given greys, each pixel
    inside or out by its centre alone."""
    image = np.zeros((SIDE, SIDE))
    for (cx, cy, r), grey in zip(np.reshape(x, (-1, 3)), greys):
        inside = ((CENTRES[None, :] - cx) ** 2 + (CENTRES[:, None] - cy) ** 2) <= r * r
        paint(image, inside.astype(float), grey)
    return image


def triangles(x, greys):
    """The image of triangles x = (x0, y0, x1, y1, x2, y2) per triangle, of the given
    greys, each pixel covered by the share of its 4 x 4 subsamples that lie inside (on
    the same side of all three edges, either winding). Only the pixels of the triangle's
    bounding box are sampled; none outside it can be inside."""
    image = np.zeros((SIDE, SIDE))
    for v, grey in zip(np.reshape(x, (-1, 3, 2)), greys):
        (j0, i0), (j1, i1) = (np.clip(np.floor(v.min(axis=0)), 0, SIDE).astype(int),
                              np.clip(np.ceil(v.max(axis=0)), 0, SIDE).astype(int))
        if j1 <= j0 or i1 <= i0:
            continue
        sx, sy = SUBSAMPLES[None, 4 * j0:4 * j1], SUBSAMPLES[4 * i0:4 * i1, None]
        sides = [(v[(k + 1) % 3, 0] - v[k, 0]) * (sy - v[k, 1])
                 - (v[(k + 1) % 3, 1] - v[k, 1]) * (sx - v[k, 0]) for k in range(3)]
        inside = (((sides[0] >= 0) & (sides[1] >= 0) & (sides[2] >= 0))
                  | ((sides[0] <= 0) & (sides[1] <= 0) & (sides[2] <= 0)))
        coverage = inside.reshape(i1 - i0, 4, j1 - j0, 4).mean(axis=(1, 3))
        paint(image[i0:i1, j0:j1], coverage, grey)
    return image


class Case(NamedTuple):
    """A problem of a set, its fields in the order of unseen.py's Problem: the loss,
    its true parameters, sigma0, the box (lower, upper) or None, the budget, the target
    on f - f* and the start range (low, high) (also other_fields.py's)."""

    f: object
    x_opt: np.ndarray
    sigma0: object
    box: object
    budget: int
    target: float
    start: tuple


def loss(render, x_opt):
    """The mean squared difference of render(x) from render(x_opt)."""
    target = render(x_opt)

    def f(x):
        return float(np.mean((render(np.asarray(x, dtype=float)) - target) ** 2))

    return f


def tiled(per_shape, k):
    return np.tile(np.asarray(per_shape, dtype=float), k)


def rectangle_case(truth, target):
    """Grey rectangles: positions in pixels (sigma0 2, box [0, 32], starts [4, 28]), half
    sizes (sigma0 2, box [0.5, 16], starts [2, 8]) and greys (sigma0 0.2, box [0, 1],
    starts [0.05, 0.95]): parameters in two units, as a shape's place and colour are."""
    truth = np.asarray(truth, dtype=float).ravel()
    k = len(truth) // 5
    return Case(loss(rectangles, truth), truth, tiled([2, 2, 2, 2, 0.2], k),
                (tiled([0, 0, 0.5, 0.5, 0], k), tiled([32, 32, 16, 16, 1], k)),
                2000 * len(truth), target,
                (tiled([4, 4, 2, 2, 0.05], k), tiled([28, 28, 8, 8, 0.95], k)))


# Two rectangles that overlap a little, the second on top.
GREY_RECTANGLES_2 = [[11, 13, 6, 4, 0.35], [20, 19, 4, 7, 0.8]]
# Six in two rows, two of them overlapping; no edge hidden wholly, so every parameter
# shows in the image.
GREY_RECTANGLES_6 = [[6.5, 9, 4.5, 4.5, 0.3], [16, 7.5, 4, 5, 0.55], [25.5, 9, 4.5, 3, 0.9],
                     [8, 22, 4, 6, 0.7], [17, 24, 6, 4, 0.45], [26.5, 21, 3, 7, 0.2]]
DISC_GREYS = [0.4, 0.7, 1.0]
DISCS = [[9, 10, 5], [22, 11, 6], [15, 23, 4.5]]
TRIANGLE_GREYS = [0.6, 1.0]
TRIANGLES = [[6, 6, 20, 8, 10, 22], [26, 12, 24, 28, 14, 26]]


def disc_case():
    """Three discs of known greys: centres (box [0, 32], starts [4, 28]) and radii (box
    [1, 12], starts [2, 7]), sigma0 2. The target 1e-6 is below one wrong pixel's
    0.09 / 1024: the image must match exactly."""
    truth = np.asarray(DISCS, dtype=float).ravel()
    return Case(loss(lambda x: discs(x, DISC_GREYS), truth), truth, tiled([2, 2, 2], 3),
                (tiled([0, 0, 1], 3), tiled([32, 32, 12], 3)), 2000 * 9, 1e-6,
                (tiled([4, 4, 2], 3), tiled([28, 28, 7], 3)))


def triangle_case():
    """Two triangles of known greys: six vertex coordinates each (sigma0 2, box [0, 32],
    starts [4, 28]). The target 1e-7 is below one wrong subsample's (0.4 / 16)^2 / 1024:
    every subsample must match."""
    truth = np.asarray(TRIANGLES, dtype=float).ravel()
    return Case(loss(lambda x: triangles(x, TRIANGLE_GREYS), truth), truth, np.full(12, 2.0),
                (np.zeros(12), np.full(12, 32.0)), 2000 * 12, 1e-7,
                (np.full(12, 4.0), np.full(12, 28.0)))


PROBLEMS = {
    "grey-rectangles10": rectangle_case(GREY_RECTANGLES_2, 1e-6),
    "grey-rectangles30": rectangle_case(GREY_RECTANGLES_6, 1e-6),
    "discs9": disc_case(),
    "triangles12": triangle_case(),
}
