"""What a map knows: the space its own scans swept free and the places they hit, as a coverage grid.

A line map built from a robot's scans says nothing about the places those
scans never reached.  A scan taken later may look into such a hole (a room the
robot passed by, a corner behind a pillar); the beams that end there are not
evidence against the pose, and a relocalization that counts them as such
rejects right poses in partial maps.  Conversely a beam that ends where the
mapping scans looked straight through is evidence *against* the pose: the map
saw free space there.

:func:`build_coverage` rasterises the mapping scans at their poses into a grid
of three states:

* ``UNKNOWN``: no mapping beam passed or ended here;
* ``FREE``: a mapping beam passed through (short of its end by ``clearance``);
* ``WALL``: a mapping beam ended here (within one cell), whatever else passed.

:meth:`Coverage.classify` reads the state under points;
:func:`map_noise` measures how far the mapping scans' points lie from the map's
walls (the map's own blur, added to the scan's range noise in the thresholds
of :mod:`cga_lessons.relocalization.verify`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from cga_lessons import checks

from .inputs import check_scans_at_poses, grid_shape

__all__ = [
    "CoverageFractions",
    "UNKNOWN",
    "FREE",
    "WALL",
    "GRID_RESOLUTION",
    "GRID_CLEARANCE",
    "Coverage",
    "build_coverage",
    "coverage_grid",
    "map_noise",
]

UNKNOWN, FREE, WALL = 0, 1, 2
#: :func:`build_coverage`'s cell size and clearance (m), explained there.
GRID_RESOLUTION, GRID_CLEARANCE = 0.05, 0.1


@dataclass(frozen=True)
class CoverageFractions:
    """The share of a coverage grid's cells in each state (:meth:`Coverage.fractions`): ``unknown`` (no mapping
    scan looked there), ``free`` (swept by a beam) and ``wall`` (hit); each in ``[0, 1]``, together 1."""

    unknown: float
    free: float
    wall: float

    def __post_init__(self):
        fraction = partial(checks.real, low=0.0, high=1.0)
        checks.record(self, unknown=fraction, free=fraction, wall=fraction)


@dataclass
class Coverage:
    """A coverage grid: ``state[i, j]`` for the cell whose lower-left corner is ``origin + resolution * (j, i)``.

    Attributes
    ----------
    origin : ndarray, shape (2,)
    resolution : float
        Cell size (m).
    state : ndarray of uint8, shape (H, W)
        :data:`UNKNOWN`, :data:`FREE` or :data:`WALL`.
    noise : float
        The map's blur (m): :func:`map_noise` of the mapping scans, 0 if not measured.
    """

    origin: np.ndarray
    resolution: float
    state: np.ndarray
    noise: float = 0.0

    def cells(self, points):
        """Row and column of the cell under each point (n, 2), and whether it lies inside the grid."""
        p = np.asarray(points, float)
        ij = np.floor((p - self.origin) / self.resolution)
        H, W = self.state.shape
        inside = (ij[..., 0] >= 0) & (ij[..., 0] < W) & (ij[..., 1] >= 0) & (ij[..., 1] < H)
        col = np.where(inside, ij[..., 0], 0).astype(np.intp)
        row = np.where(inside, ij[..., 1], 0).astype(np.intp)
        return row, col, inside

    def classify(self, points) -> np.ndarray:
        """The state under each point (any leading shape, last axis 2); ``UNKNOWN`` outside the grid.

        >>> scan = (np.array([2.0, np.inf]), np.array([0.0, np.pi]))  # a wall 2 m ahead, nothing behind
        >>> cov = build_coverage([scan], [[0.0, 0.0, 0.0]], max_range=5.0)
        >>> cov.classify([[1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [-3.0, 0.0], [0.0, 1.0]]).tolist()
        [1, 2, 0, 1, 0]
        """
        row, col, inside = self.cells(points)
        return np.where(inside, self.state[row, col], UNKNOWN)

    def fractions(self) -> CoverageFractions:
        """Share of the grid's cells in each state (:class:`CoverageFractions`)."""
        n = self.state.size
        return CoverageFractions(*(float(np.sum(self.state == k)) / n for k in (UNKNOWN, FREE, WALL)))


def build_coverage(
    scans,
    poses,
    *,
    max_range: float,
    resolution: float = GRID_RESOLUTION,
    clearance: float = GRID_CLEARANCE,
    segments=None,
) -> Coverage:
    """The coverage grid of scans ``[(ranges, angles), ...]`` taken at laser poses ``poses`` (n, 3).

    A returned beam (range below ``max_range``) sweeps ``FREE`` the cells
    along it up to ``clearance`` short of its point and marks ``WALL`` the
    cells within one cell of its point; a beam without return, or reaching
    ``max_range`` or beyond, sweeps ``FREE`` up to ``max_range`` (the laser
    would have seen a wall nearer than that).  ``WALL`` wins over ``FREE``.

    Parameters
    ----------
    max_range : float
        The reach (m) used for the map; the relocalization must use the same.
    resolution : float
        Cell size (m).  5 cm: the largest inlier distance of the line check
        (6 cm) rounded down, so a point on a wall lands in a ``WALL`` cell or
        its neighbour, and about half the beam spacing of a 1 degree laser at
        3 m (5.2 cm), so neighbouring beams rarely leave unswept gaps nearby.
    clearance : float
        A beam sweeps free only up to this (m) short of its point: two cells,
        so the ``WALL`` band stays a band even where noise (1-3 cm on the
        logs measured) puts a point in front of its wall.
    segments : array_like (M, 2, 2), optional
        The line map; when given, :attr:`Coverage.noise` is :func:`map_noise`.

    Returns
    -------
    Coverage

    Raises
    ------
    InvalidInputError
        For malformed scans, mismatched scans and poses, non-finite poses, or a non-positive ``max_range`` or
        ``resolution``.
    """
    func = "build_coverage"
    checked, poses = check_scans_at_poses(scans, poses, func)
    max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    resolution = checks.real(resolution, func, "resolution", low=0.0, strict_low=True)
    clearance = checks.real(clearance, func, "clearance", low=0.0)
    return coverage_grid(checked, poses, max_range, resolution, clearance, segments, func)


def coverage_grid(checked, poses, max_range, resolution, clearance, segments, func) -> Coverage:
    """:func:`build_coverage` of checked scans and settings, in the name of ``func``."""
    lo = poses[:, :2].min(axis=0) - max_range - 2 * resolution
    hi = poses[:, :2].max(axis=0) + max_range + 2 * resolution
    W, H = grid_shape(lo, hi, resolution, func, "max_range, resolution")
    cov = Coverage(lo, float(resolution), np.zeros((H, W), np.uint8))
    free = np.zeros(H * W, bool)
    wall = np.zeros(H * W, bool)
    steps = np.arange(0.0, max_range, resolution / 2)  # two samples a cell: no cell along a beam is skipped
    for (ranges, angles), pose in zip(checked, poses):
        r = np.where(np.isfinite(ranges), ranges, np.inf)
        hit = r < max_range
        reach = np.where(hit, r - clearance, max_range)
        phi = angles + pose[2]
        u = np.column_stack([np.cos(phi), np.sin(phi)])
        s = steps[None, :]
        on = s < reach[:, None]
        pts = pose[None, None, :2] + s[..., None] * u[:, None, :]
        row, col, inside = cov.cells(pts[on])
        free[(row * W + col)[inside]] = True
        if hit.any():
            row, col, inside = cov.cells(pose[:2] + r[hit, None] * u[hit])
            wall[(row * W + col)[inside]] = True
    wall = wall.reshape(H, W)
    grown = wall.copy()
    grown[1:] |= wall[:-1]
    grown[:-1] |= wall[1:]
    g = grown.copy()
    g[:, 1:] |= grown[:, :-1]
    g[:, :-1] |= grown[:, 1:]
    cov.state[free.reshape(H, W)] = FREE
    cov.state[g] = WALL
    if segments is not None:
        cov.noise = map_noise(checked, poses, segments, max_range=max_range)
    return cov


def map_noise(scans, poses, segments, *, max_range: float, gate: float = 0.15, step: int = 5) -> float:
    """The map's blur (m): how far the mapping scans' points lie from the nearest map wall.

    The points of every ``step``-th scan within ``gate`` of a map segment give
    the robust standard deviation ``1.4826 * median |d|`` of their distances
    ``d``.  It holds the scans' range noise and the error of the poses and of
    the fitted lines together: what a scan matched against this map must allow
    for on top of its own noise.  0 with fewer than 20 such points.

    ``gate``: 15 cm, well beyond the few centimetres of range noise and pose
    error of the corrected logs, so the spread is measured and not cut off,
    yet below the spacing of most parallel faces (a door frame, a thin wall).
    """
    segs = np.asarray(segments, float).reshape(-1, 2, 2)
    if not len(segs):
        return 0.0
    a, v = segs[:, 0], segs[:, 1] - segs[:, 0]
    vv = np.maximum(np.einsum("mi,mi->m", v, v), 1e-300)
    dists = []
    for (ranges, angles), pose in list(zip(scans, poses))[::step]:
        r = np.asarray(ranges, float)
        hit = np.isfinite(r) & (r < max_range)
        if not hit.any():
            continue
        phi = np.asarray(angles, float)[hit] + pose[2]
        p = pose[:2] + r[hit, None] * np.column_stack([np.cos(phi), np.sin(phi)])
        rel = p[:, None, :] - a[None]
        t = np.clip(np.einsum("pmi,mi->pm", rel, v) / vv, 0.0, 1.0)
        d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1)).min(axis=1)
        dists.append(d[d < gate])
    d = np.concatenate(dists) if dists else np.zeros(0)
    if len(d) < 20:
        return 0.0
    return float(1.4826 * np.median(d))
