"""The workspace grid, the robot's cameras and the obstacle of the exploration document (section 3.1), and the
checks of their inputs.

The checks are thin uses of :mod:`cga_lessons.checks` (the one checking layer) for what the document's
functions read: points (N, 3), one point (3,), positive lengths, a range that may be infinite.  Errors read
``"func: argument: problem"``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

__all__ = ["MAX_NODES", "Grid", "make_grid", "CameraView", "SphereObstacle"]

#: The most nodes a grid may have (the document's grids have 162 to 1,176; 10^7 nodes are 240 MB of positions).
MAX_NODES = 10**7


# ------------------------------------------------------------------ input checks (compositions of the checks layer)
def check_points(x, func: str, name: str) -> np.ndarray:
    """Finite points of shape (N, 3) (a single point (3,) is one row), N >= 1."""
    P, _ = checks.batch(x, func, name, (3,))
    if not len(P):
        raise checks.fail(func, name, "is empty (no points)")
    return P


def check_point(x, func: str, name: str) -> np.ndarray:
    """One finite point (3,)."""
    return checks.array(x, func, name, (3,))


def check_positive(v, func: str, name: str) -> float:
    """A finite number > 0."""
    return checks.real(v, func, name, low=0.0, strict_low=True)


def check_reach(v, func: str, name: str) -> float:
    """A number > 0, or ``inf`` for no limit."""
    if isinstance(v, (float, np.floating)) and v == np.inf:
        return float(v)
    return check_positive(v, func, name)


def check_range(r, func: str, name: str) -> tuple:
    """A range ``(low, high)`` of finite numbers with low <= high."""
    a, b = (float(v) for v in checks.array(r, func, name, (2,)))
    if b < a:
        raise checks.fail(func, name, f"must have low <= high, got {(a, b)}")
    return a, b


def node_count(lo: float, hi: float, spacing: float, func: str, name: str) -> int:
    """Nodes from ``lo`` to ``hi`` in steps of ``spacing`` (3.1.1), at most :data:`MAX_NODES`."""
    n = np.floor((hi - lo) / spacing + 1e-9) + 1
    if not n <= MAX_NODES:
        raise checks.fail(func, f"{name}, spacing", f"{n:.3g} nodes along one axis; at most {MAX_NODES} in all")
    return int(n)


def check_grid_size(shape, func: str, name: str) -> tuple:
    if float(np.prod(np.asarray(shape, dtype=float))) > MAX_NODES:
        raise checks.fail(func, name, f"{' x '.join(map(str, shape))} nodes; at most {MAX_NODES} in all")
    return tuple(shape)


# -------------------------------------------------------------------------- grid
@dataclass(frozen=True)
class Grid:
    """A 3D grid of nodes; node ``(i, j, k)`` sits at ``origin + (i, j, k) * spacing``.

    Its cell is ``[Xn, Xn + spacing) x [Yn, Yn + spacing) x [Zn, Zn + spacing)``
    (exploration 3.1.3).  Flat node index ``(i * ny + j) * nz + k``.
    """

    origin: tuple
    spacing: float
    shape: tuple

    def __post_init__(self):
        f = "Grid"
        origin = tuple(float(v) for v in checks.array(self.origin, f, "origin", (3,)))
        spacing = check_positive(self.spacing, f, "spacing")
        shape = tuple(checks.integer(s, f, "shape", low=1) for s in checks.array(self.shape, f, "shape", (3,)))
        check_grid_size(shape, f, "shape")
        if not np.all(np.isfinite(np.asarray(origin) + spacing * np.asarray(shape))):
            raise checks.fail(f, "origin, spacing, shape", "the grid's far corner overflows a float")
        object.__setattr__(self, "origin", origin)
        object.__setattr__(self, "spacing", spacing)
        object.__setattr__(self, "shape", shape)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    @property
    def nodes(self) -> np.ndarray:
        """Node positions, shape (N, 3)."""
        axes = [self.origin[a] + self.spacing * np.arange(self.shape[a]) for a in range(3)]
        return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)

    def cell_of(self, points) -> np.ndarray:
        """Flat index of the node whose cell holds each point, -1 outside every cell; shape (M,)."""
        P = check_points(points, "Grid.cell_of", "points")
        return self.cells(P)

    def cells(self, P: np.ndarray) -> np.ndarray:
        """:meth:`cell_of` for checked points (N, 3)."""
        ijk = np.floor((P - np.asarray(self.origin)) / self.spacing)  # floats: no integer overflow far outside
        inside = np.all((ijk >= 0) & (ijk < np.asarray(self.shape)), axis=1)
        ijk = np.where(inside[:, None], ijk, 0).astype(int)
        flat = (ijk[:, 0] * self.shape[1] + ijk[:, 1]) * self.shape[2] + ijk[:, 2]
        return np.where(inside, flat, -1)


def make_grid(x_range=(-120.0, 120.0), y_range=(-120.0, 120.0), z_range=(0.0, 30.0), spacing=30.0) -> Grid:
    """Nodes from each range's low end in steps of ``spacing`` up to its high end (3.1.1).

    The document's workspace: x, y in [-120, 120], z in [0, 30], Delta = 30 (cm):
    9 x 9 x 2 = 162 nodes.  At most :data:`MAX_NODES` nodes.

    >>> g = make_grid()
    >>> g.shape, g.size
    ((9, 9, 2), 162)
    """
    f = "make_grid"
    d = check_positive(spacing, f, "spacing")
    lo, n = [], []
    for name, r in (("x_range", x_range), ("y_range", y_range), ("z_range", z_range)):
        a, b = check_range(r, f, name)
        lo.append(a)
        n.append(node_count(a, b, d, f, name))
    check_grid_size(n, f, "x_range, y_range, z_range, spacing")
    return Grid(tuple(lo), d, tuple(n))


# ---------------------------------------------------------------- robot, obstacle
@dataclass(frozen=True)
class CameraView:
    """The robot's cameras: position (3,), heading and total field of view (radians).

    ``max_range`` is the reconstruction range (horizontal distance; ``inf`` for none).
    The two edges ("projections of the visual range") are at heading -/+ fov/2.
    """

    position: tuple
    heading: float
    fov: float
    max_range: float = np.inf

    def __post_init__(self):
        f = "CameraView"
        object.__setattr__(self, "position", tuple(float(v) for v in check_point(self.position, f, "position")))
        object.__setattr__(self, "heading", checks.real(self.heading, f, "heading"))
        fov = checks.real(self.fov, f, "fov", low=0.0, high=2 * np.pi, strict_low=True, strict_high=True)
        object.__setattr__(self, "fov", fov)
        object.__setattr__(self, "max_range", check_reach(self.max_range, f, "max_range"))

    def edges(self) -> np.ndarray:
        """Bearings of the first (lower) and second (higher) field-of-view edge, shape (2,)."""
        return np.array([self.heading - self.fov / 2, self.heading + self.fov / 2])


@dataclass(frozen=True)
class SphereObstacle:
    """An obstacle enclosed in a sphere: centre (3,) and radius; seen in 2D as a circle."""

    center: tuple
    radius: float

    def __post_init__(self):
        f = "SphereObstacle"
        object.__setattr__(self, "center", tuple(float(v) for v in check_point(self.center, f, "center")))
        object.__setattr__(self, "radius", check_positive(self.radius, f, "radius"))

    @property
    def conformal(self):
        """The sphere as a conformal vector s = c + (c^2 - r^2) e / 2 + e0 (thesis 2.72)."""
        return cga.sphere(np.array(self.center), self.radius)
