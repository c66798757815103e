"""Seen, unseen and occupied nodes around an obstacle: the exploration document, section 3.1.

The second document (a thesis on exploration with a mobile robot and two webcams)
labels the nodes of a 3D grid over the workspace:

* **seen / not seen** (3.1.1-3.1.2): a node is seen when its bearing from the robot
  lies between the two projections (edges) of the cameras' field of view and,
  when an obstacle is in view, it is not hidden behind the obstacle's circle;
* **occupied** (3.1.3): a node is occupied when a point of the obstacle lies in its
  cell ``[Xn, Xn + Delta) x [Yn, Yn + Delta) x [Zn, Zn + Delta)``; the document
  finds them with a nearest-node loop on the L1 distance, exploration (3.1).

Any obstacle is enclosed in a sphere (a conformal sphere fitted to its points) and
seen in the plane as a circle.  The document calls the angle of a projection in
the x-y plane its *elevation angle* ("angulo de elevacion"); in code it is the
bearing, measured from the x axis, and every rule works with bearings relative to
the robot's heading, so that "first" (lower) and "second" (higher) projections
are the clockwise and counter-clockwise ones as the robot sees them.

The document's test cases (3.1.4) are in :mod:`cga_lessons.exploration.cases`, the
path around an obstacle (section 3.2, equations 3.2-3.3) in
:mod:`cga_lessons.exploration.path`.

Units: the functions are unit-agnostic (lengths in any one unit, angles in
radians); the document's cases (:mod:`cga_lessons.exploration.cases`) are in centimetres.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError

__all__ = [
    "NOT_SEEN", "SEEN", "ANALYSED", "OCCUPIED", "LABEL_NAMES",
    "Grid", "make_grid", "CameraView", "SphereObstacle", "Projections", "projections",
    "fit_sphere", "enclosing_sphere", "sphere_points", "box_surface_points",
    "seen_nodes", "ray_cast_seen", "l1_distances", "occupied_nodes_loop", "occupied_nodes",
    "cells_touched_by_sphere", "NodeLabels", "label_nodes",
]  # fmt: skip

#: Node labels, in increasing priority (an occupied node is drawn as occupied even if seen).
NOT_SEEN, SEEN, ANALYSED, OCCUPIED = 0, 1, 2, 3
LABEL_NAMES = ("not seen", "seen", "analysed", "occupied")
_EPS = 1e-12


# ------------------------------------------------------------------ input checks
def _points(x, func: str, name: str) -> np.ndarray:
    """Validated (N, 3) float array; raises for empty, NaN/inf or the wrong shape."""
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"{func}: {name} must be numbers of shape (N, 3)") from exc
    if arr.ndim == 1 and arr.shape == (3,):
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InvalidInputError(f"{func}: {name} must have shape (N, 3), got {arr.shape}")
    if arr.shape[0] == 0:
        raise InvalidInputError(f"{func}: {name} is empty")
    if not np.all(np.isfinite(arr)):
        raise InvalidInputError(f"{func}: {name} contains NaN or inf")
    return arr


def _positive(v, func: str, name: str, allow_inf: bool = False) -> float:
    v = float(v)
    if np.isnan(v) or v <= 0 or (np.isinf(v) and not allow_inf):
        raise InvalidInputError(
            f"{func}: {name} must be a positive {'number' if allow_inf else 'finite number'}, got {v}"
        )
    return v


def _wrap(a):
    """Angle(s) wrapped to [-pi, pi)."""
    return (np.asarray(a, dtype=float) + np.pi) % (2 * np.pi) - np.pi


def _between(theta, lo, hi):
    """theta lies on the counter-clockwise arc from lo to hi (angles in radians)."""
    two_pi = 2 * np.pi
    return (np.asarray(theta) - lo) % two_pi <= (hi - lo) % two_pi + _EPS


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
        P = _points(points, "Grid.cell_of", "points")
        ijk = np.floor((P - np.asarray(self.origin)) / self.spacing).astype(int)
        inside = np.all((ijk >= 0) & (ijk < np.asarray(self.shape)), axis=1)
        flat = (ijk[:, 0] * self.shape[1] + ijk[:, 1]) * self.shape[2] + ijk[:, 2]
        return np.where(inside, flat, -1)


def make_grid(x_range=(-120.0, 120.0), y_range=(-120.0, 120.0), z_range=(0.0, 30.0), spacing=30.0) -> Grid:
    """Nodes from each range's low end in steps of ``spacing`` up to its high end (3.1.1).

    The document's workspace: x, y in [-120, 120], z in [0, 30], Delta = 30 (cm):
    9 x 9 x 2 = 162 nodes.

    >>> g = make_grid()
    >>> g.shape, g.size
    ((9, 9, 2), 162)
    """
    d = _positive(spacing, "make_grid", "spacing")
    lo, n = [], []
    for name, (a, b) in zip("xyz", (x_range, y_range, z_range)):
        a, b = float(a), float(b)
        if not (np.isfinite(a) and np.isfinite(b)) or b < a:
            raise InvalidInputError(f"make_grid: {name}_range must be finite with low <= high, got {(a, b)}")
        lo.append(a)
        n.append(int(np.floor((b - a) / d + 1e-9)) + 1)
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
        p = _points(self.position, "CameraView", "position")[0]
        object.__setattr__(self, "position", tuple(float(v) for v in p))
        if not np.isfinite(self.heading):
            raise InvalidInputError(f"CameraView: heading must be finite, got {self.heading}")
        f = float(self.fov)
        if not (0 < f < 2 * np.pi):
            raise InvalidInputError(
                f"CameraView: fov must lie in (0, 2 pi) radians, got {f} (a zero field of view sees nothing)"
            )
        _positive(self.max_range, "CameraView", "max_range", allow_inf=True)

    def edges(self) -> np.ndarray:
        """Bearings of the first (lower) and second (higher) field-of-view edge, shape (2,)."""
        return np.array([self.heading - self.fov / 2, self.heading + self.fov / 2])


@dataclass(frozen=True)
class SphereObstacle:
    """An obstacle enclosed in a sphere: centre (3,) and radius; seen in 2D as a circle."""

    center: tuple
    radius: float

    def __post_init__(self):
        c = _points(self.center, "SphereObstacle", "center")[0]
        object.__setattr__(self, "center", tuple(float(v) for v in c))
        object.__setattr__(self, "radius", _positive(self.radius, "SphereObstacle", "radius"))

    @property
    def conformal(self):
        """The sphere as a conformal vector s = c + (c^2 - r^2) e / 2 + e0 (thesis 2.72)."""
        return cga.sphere(np.array(self.center), self.radius)


# ------------------------------------------------------------ enclosing sphere
def fit_sphere(points):
    """Least-squares sphere through points in the conformal model.

    A point X lies on the sphere s when X . s = 0 (thesis 2.118); the sphere
    minimising sum (X_i . s)^2 under s^2 = 1 is an eigenvector problem in the
    conformal metric.  The solve is :func:`cga_lessons.conformal.fitting.fit_sphere`
    (the same fit serves the stereo chapter); this wrapper adds the checks the
    exploration needs and returns plain centre and radius.

    Parameters
    ----------
    points : array, shape (N, 3), N >= 4, not coplanar

    Returns
    -------
    center : array, shape (3,)
    radius : float
    """
    from cga_lessons.conformal import fit_sphere as _conformal_sphere_fit

    P = _points(points, "fit_sphere", "points")
    if len(P) < 4:
        raise DegenerateGeometryError(f"fit_sphere: need at least 4 points, got {len(P)}")
    sv = np.linalg.svd(P - P.mean(axis=0), compute_uv=False)
    if sv[0] == 0 or sv[-1] <= 1e-9 * sv[0]:
        raise DegenerateGeometryError("fit_sphere: the points are coplanar (or coincide): no unique sphere")
    fit = _conformal_sphere_fit(P)
    return fit["center"], float(fit["radius"])


def enclosing_sphere(points):
    """Sphere that encloses every point of an object, whatever its shape (3.1.2).

    Two candidate centres: the conformal least-squares sphere's (:func:`fit_sphere`;
    best for round objects and partial scans of them) and the centre of the points'
    bounding box (best for boxy or flat objects); the radius is the largest distance
    of a point from the centre, so no point is left outside.  The smaller sphere wins.

    Returns (center (3,), radius).
    """
    P = _points(points, "enclosing_sphere", "points")
    centers = [0.5 * (P.min(axis=0) + P.max(axis=0))]
    try:
        centers.append(fit_sphere(P)[0])
    except DegenerateGeometryError:
        pass  # flat or too few points: the box centre alone
    radii = [float(np.max(np.linalg.norm(P - c, axis=1))) for c in centers]
    k = int(np.argmin(radii))
    if radii[k] == 0:
        raise DegenerateGeometryError("enclosing_sphere: all points coincide, the sphere has zero radius")
    return centers[k], radii[k]


def sphere_points(center, radius, n: int = 20) -> np.ndarray:
    """Points on a sphere on a latitude-longitude grid, like MATLAB's ``sphere(n)``.

    The document stores "the points of the sphere" in a vector; (n + 1)^2 grid
    points with the repeated poles and seam removed: shape (n * (n - 1) + 2, 3).
    """
    c = _points(center, "sphere_points", "center")[0]
    r = _positive(radius, "sphere_points", "radius")
    if int(n) < 3:
        raise InvalidInputError(f"sphere_points: n must be >= 3, got {n}")
    n = int(n)
    theta = np.linspace(-np.pi, np.pi, n + 1)[:-1]
    phi = np.linspace(-np.pi / 2, np.pi / 2, n + 1)[1:-1]
    ph, th = np.meshgrid(phi, theta, indexing="ij")
    unit = np.stack([np.cos(ph) * np.cos(th), np.cos(ph) * np.sin(th), np.sin(ph)], axis=-1).reshape(-1, 3)
    unit = np.vstack([[0.0, 0.0, -1.0], unit, [0.0, 0.0, 1.0]])
    return c + r * unit


def box_surface_points(rng, center, size, n: int = 300) -> np.ndarray:
    """``n`` random points on the surface of an axis-aligned box (a stand-in object), shape (n, 3)."""
    c = _points(center, "box_surface_points", "center")[0]
    half = 0.5 * _points(size, "box_surface_points", "size")[0]
    u = rng.uniform(-1.0, 1.0, size=(int(n), 3))
    face = rng.integers(0, 3, size=int(n))
    u[np.arange(int(n)), face] = rng.choice([-1.0, 1.0], size=int(n))
    return c + u * half


# ---------------------------------------------------------------- seen / unseen
@dataclass(frozen=True)
class Projections:
    """Bearings (radians, relative to the heading) of the lines the rules of 3.1.2 use.

    ``edges``: first and second field-of-view edge, (-fov/2, fov/2).  ``tangents``:
    first (lower) and second projection to the obstacle, ``centre - a`` and
    ``centre + a`` with ``sin a = r / d`` (may pass +-pi), or None.  ``case``: "free"
    (no projection to the obstacle in view, 3.1.1 and figure 3.7a), "whole" (both,
    figure 3.4), "first" or "second" (only that one, figure 3.5 a/b).
    """

    edges: tuple
    tangents: tuple | None
    tangent_in_view: tuple
    centre_bearing: float | None
    centre_distance: float | None
    case: str


def _horizontal(nodes, view: CameraView):
    """Bearing relative to the heading in [-pi, pi) and horizontal distance of each node."""
    d = nodes[:, :2] - np.asarray(view.position[:2])
    return _wrap(np.arctan2(d[:, 1], d[:, 0]) - view.heading), np.hypot(d[:, 0], d[:, 1])


def _in_view(theta, rho, view: CameraView):
    """Between the two field-of-view edges, within range, and not under the robot."""
    return (np.abs(theta) <= view.fov / 2 + _EPS) & (rho > _EPS) & (rho <= view.max_range)


def projections(view: CameraView, obstacle: SphereObstacle | None = None) -> Projections:
    """Field-of-view edges and tangent projections to the obstacle's circle (3.1.2).

    Raises :class:`DegenerateGeometryError` when the robot stands inside the circle
    (no tangents exist).
    """
    half = view.fov / 2
    if obstacle is None:
        return Projections((-half, half), None, (False, False), None, None, "free")
    v = np.asarray(obstacle.center[:2]) - np.asarray(view.position[:2])
    d = float(np.hypot(*v))
    if d <= obstacle.radius:
        raise DegenerateGeometryError(
            f"projections: the robot is inside the obstacle's circle (distance {d:.6g} <= radius {obstacle.radius:.6g})"
        )
    c = float(_wrap(np.arctan2(v[1], v[0]) - view.heading))
    a = float(np.arcsin(obstacle.radius / d))
    t = (c - a, c + a)
    in_view = tuple(bool(abs(_wrap(ti)) <= half + _EPS) for ti in t)
    case = {(False, False): "free", (True, True): "whole", (True, False): "first", (False, True): "second"}[in_view]
    return Projections((-half, half), t, in_view, c, d, case)


def seen_nodes(nodes, view: CameraView, obstacle: SphereObstacle | None = None) -> np.ndarray:
    """Seen nodes by the rules of exploration 3.1.1-3.1.2, as written; bool (N,).

    A node is seen when it is in view (bearing between the edges, within range;
    3.1.1) and, by the case of :func:`projections`:

    * "whole": between the first edge and the first tangent, or between the second
      tangent and the second edge, or between the tangents and nearer (horizontally)
      than the obstacle's centre;
    * "first" / "second" (figure 3.5): between the first (second) edge and the tangent
      in view, or on the obstacle's side of it and nearer than the centre (the
      printed second condition repeats the first interval; we read it as the other
      side of the tangent, which is what figure 3.5 draws);
    * "free": every node in view (also when the obstacle fills the whole view, which
      the document does not consider).

    Nodes at zero horizontal distance (under the robot) have no bearing: not seen.
    """
    P = _points(nodes, "seen_nodes", "nodes")
    theta, rho = _horizontal(P, view)
    visible = _in_view(theta, rho, view)
    pr = projections(view, obstacle)
    if pr.case == "free":
        return visible
    lo, hi = pr.edges
    t1, t2 = pr.tangents
    nearer = rho < pr.centre_distance
    if pr.case == "whole":
        rule = _between(theta, lo, t1) | _between(theta, t2, hi) | (_between(theta, t1, t2) & nearer)
    elif pr.case == "first":
        rule = _between(theta, lo, t1) | (_between(theta, t1, hi) & nearer)
    else:
        rule = _between(theta, t2, hi) | (_between(theta, lo, t2) & nearer)
    return visible & rule


def ray_cast_seen(nodes, view: CameraView, obstacle: SphereObstacle | None = None) -> np.ndarray:
    """3D visibility: in view (as :func:`seen_nodes`) and the segment camera -> node misses the ball; bool (N,)."""
    P = _points(nodes, "ray_cast_seen", "nodes")
    theta, rho = _horizontal(P, view)
    visible = _in_view(theta, rho, view)
    if obstacle is None:
        return visible
    o, c = np.asarray(view.position), np.asarray(obstacle.center)
    if np.linalg.norm(o - c) <= obstacle.radius:
        raise DegenerateGeometryError("ray_cast_seen: the camera is inside the obstacle's sphere")
    d = P - o
    t = np.clip(((c - o) @ d.T) / np.maximum(np.sum(d * d, axis=1), 1e-300), 0.0, 1.0)
    closest = o + t[:, None] * d
    return visible & (np.linalg.norm(closest - c, axis=1) > obstacle.radius)


# --------------------------------------------------------------------- occupied
def l1_distances(nodes, point) -> np.ndarray:
    """B = |Xn - x| + |Yn - y| + |Zn - z| for every node, exploration (3.1); shape (N,).

    >>> l1_distances([[0.0, 0.0, 0.0], [30.0, 0.0, 30.0]], [10.0, -5.0, 2.0])
    array([17., 53.])
    """
    return np.abs(np.asarray(nodes) - np.asarray(point)).sum(axis=1)


@dataclass(frozen=True)
class OccupancyLoop:
    """Result of :func:`occupied_nodes_loop`: bool masks (N,), the steps, and points left out.

    ``steps``: one ``(point_index, node_index, occupied?)`` per node examined, in order.
    ``outside``: indices of the points that lie in no node's cell (not searched).
    """

    occupied: np.ndarray
    analysed: np.ndarray
    steps: list = field(repr=False)
    outside: np.ndarray = field(repr=False)


def occupied_nodes_loop(grid: Grid, points) -> OccupancyLoop:
    """Occupied nodes by the document's nearest-node elimination loop, exploration (3.1).

    While points remain: take the first; rank the remaining nodes by the L1 distance
    B of (3.1) and take the nearest; if the point lies in its cell the node is
    occupied, and it and every point in its cell are removed; otherwise the node is
    *analysed* and the next nearest is tried for the same point.  Analysed nodes are
    skipped for that point only (removing them for good can lose an occupied node
    whose cell holds a later point).  Points in no cell are left out first (the loop
    would never find their node); see :attr:`OccupancyLoop.outside`.
    """
    P = _points(points, "occupied_nodes_loop", "points")
    nodes = grid.nodes
    node_alive = np.ones(len(nodes), bool)
    point_alive = grid.cell_of(P) >= 0
    outside = list(np.flatnonzero(~point_alive))
    occupied, analysed = np.zeros(len(nodes), bool), np.zeros(len(nodes), bool)
    steps = []
    while point_alive.any():
        p = int(np.flatnonzero(point_alive)[0])
        candidates = node_alive.copy()
        while candidates.any():
            idx = np.flatnonzero(candidates)
            n = int(idx[np.argmin(l1_distances(nodes[idx], P[p]))])
            # the three conditions of 3.1.3: Xn <= x < Xn + Delta, and the same for y and z
            in_cell = np.all((P >= nodes[n]) & (P < nodes[n] + grid.spacing), axis=1)
            steps.append((p, n, bool(in_cell[p])))
            if in_cell[p]:
                occupied[n], node_alive[n] = True, False
                point_alive &= ~in_cell
                break
            analysed[n], candidates[n] = True, False
        else:  # a float tie on a cell face: no node claims the point
            outside.append(p)
            point_alive[p] = False
    return OccupancyLoop(occupied, analysed & ~occupied, steps, np.array(sorted(outside), dtype=int))


def occupied_nodes(grid: Grid, points) -> np.ndarray:
    """Occupied nodes in one pass: each point's cell index floor((x - origin) / Delta) (3.1.3); bool (N,).

    Gives the same labels as the loop of exploration (3.1); points in no cell are ignored.
    """
    cells = grid.cell_of(_points(points, "occupied_nodes", "points"))
    out = np.zeros(grid.size, bool)
    out[cells[cells >= 0]] = True
    return out


def cells_touched_by_sphere(grid: Grid, obstacle: SphereObstacle) -> np.ndarray:
    """Cells whose box meets the sphere's surface (exact, not sampled); bool (N,).

    The surface meets a box when the nearest point of the box is within the radius
    and the farthest corner beyond it.  An upper bound for any sampling of the sphere.
    """
    lo = grid.nodes
    hi = lo + grid.spacing
    c = np.asarray(obstacle.center)
    near = np.linalg.norm(np.clip(c, lo, hi) - c, axis=1)
    far = np.linalg.norm(np.maximum(np.abs(c - lo), np.abs(c - hi)), axis=1)
    return (near <= obstacle.radius) & (far >= obstacle.radius)


# ----------------------------------------------------------------------- labels
@dataclass(frozen=True)
class NodeLabels:
    """Boolean masks (N,) per label and the combined label array (priority occupied > analysed > seen)."""

    seen: np.ndarray
    occupied: np.ndarray
    analysed: np.ndarray

    @property
    def labels(self) -> np.ndarray:
        out = np.where(self.seen, SEEN, NOT_SEEN)
        out[self.analysed] = ANALYSED
        out[self.occupied] = OCCUPIED
        return out

    def counts(self) -> dict:
        """Number of nodes per label name (in the order of :data:`LABEL_NAMES`)."""
        lab = self.labels
        return {name: int(np.sum(lab == i)) for i, name in enumerate(LABEL_NAMES)}


def label_nodes(grid: Grid, view: CameraView, obstacle: SphereObstacle | None, points=None) -> NodeLabels:
    """Seen (3.1.1-3.1.2), occupied and analysed (3.1.3, loop of exploration (3.1)) labels of every node."""
    seen = seen_nodes(grid.nodes, view, obstacle)
    if points is None:
        z = np.zeros(grid.size, bool)
        return NodeLabels(seen, z, z.copy())
    loop = occupied_nodes_loop(grid, points)
    return NodeLabels(seen, loop.occupied, loop.analysed)
