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

from cga_lessons import checks

from .grid import CameraView, Grid, SphereObstacle, check_point, check_points

__all__ = [
    "NOT_SEEN", "SEEN", "ANALYSED", "OCCUPIED", "LABEL_NAMES",
    "Projections", "projections",
    "seen_nodes", "ray_cast_seen", "l1_distances", "occupied_nodes_loop", "occupied_nodes",
    "cells_touched_by_sphere", "NodeLabels", "label_nodes",
]  # fmt: skip

#: Node labels, in increasing priority (an occupied node is drawn as occupied even if seen).
NOT_SEEN, SEEN, ANALYSED, OCCUPIED = 0, 1, 2, 3
LABEL_NAMES = ("not seen", "seen", "analysed", "occupied")
_EPS = 1e-12
PROJECTION_CASES = ("free", "whole", "first", "second")


# ------------------------------------------------------------------ input checks (of this module's entities)
def check_view(view, func: str, name: str = "view") -> CameraView:
    return checks.instance(view, func, name, CameraView, "a CameraView")


def check_obstacle(obstacle, func: str, name: str = "obstacle", optional: bool = True):
    if obstacle is None and optional:
        return None
    return checks.instance(obstacle, func, name, SphereObstacle, "a SphereObstacle" + (" or None" if optional else ""))


def check_grid(grid, func: str, name: str = "grid") -> Grid:
    return checks.instance(grid, func, name, Grid, "a Grid (make_grid)")


# ------------------------------------------------------------------ angles
def _wrap(a):
    """Angle(s) wrapped to [-pi, pi)."""
    return (np.asarray(a, dtype=float) + np.pi) % (2 * np.pi) - np.pi


def _between(theta, lo, hi):
    """theta lies on the counter-clockwise arc from lo to hi (angles in radians)."""
    two_pi = 2 * np.pi
    return (np.asarray(theta) - lo) % two_pi <= (hi - lo) % two_pi + _EPS


# ---------------------------------------------------------------- seen / unseen
def _optional_real(v, func: str, name: str, **limits):
    return None if v is None else checks.real(v, func, name, **limits)


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

    def __post_init__(self):
        f = "Projections"
        edges = tuple(float(v) for v in checks.array(self.edges, f, "edges", (2,)))
        tangents = self.tangents
        if tangents is not None:
            tangents = tuple(float(v) for v in checks.array(tangents, f, "tangents", (2,)))
        flags = self.tangent_in_view
        if isinstance(flags, (str, bytes)) or not hasattr(flags, "__len__") or len(flags) != 2:
            raise checks.fail(f, "tangent_in_view", f"expected two flags (True/False), got {flags!r:.40}")
        flags = tuple(checks.flag(v, f, "tangent_in_view") for v in flags)
        object.__setattr__(self, "edges", edges)
        object.__setattr__(self, "tangents", tangents)
        object.__setattr__(self, "tangent_in_view", flags)
        object.__setattr__(self, "centre_bearing", _optional_real(self.centre_bearing, f, "centre_bearing"))
        object.__setattr__(self, "centre_distance", _optional_real(self.centre_distance, f, "centre_distance", low=0))
        checks.choice(self.case, f, "case", PROJECTION_CASES)


def _horizontal(nodes, view: CameraView):
    """Bearing relative to the heading in [-pi, pi) and horizontal distance of each node."""
    d = nodes[:, :2] - np.asarray(view.position[:2])
    return _wrap(np.arctan2(d[:, 1], d[:, 0]) - view.heading), np.hypot(d[:, 0], d[:, 1])


def _in_view(theta, rho, view: CameraView):
    """Between the two field-of-view edges, within range, and not under the robot."""
    return (np.abs(theta) <= view.fov / 2 + _EPS) & (rho > _EPS) & (rho <= view.max_range)


def _projections(view: CameraView, obstacle: SphereObstacle | None, func: str) -> Projections:
    half = view.fov / 2
    if obstacle is None:
        return Projections((-half, half), None, (False, False), None, None, "free")
    v = np.asarray(obstacle.center[:2]) - np.asarray(view.position[:2])
    d = float(np.hypot(*v))
    if not np.isfinite(d):
        raise checks.fail(func, "view, obstacle", "the robot and the obstacle are too far apart for a float")
    if d <= obstacle.radius:
        raise checks.degenerate(
            func,
            "view, obstacle",
            f"the robot is inside the obstacle's circle (distance {d:.6g} <= radius {obstacle.radius:.6g})",
        )
    c = float(_wrap(np.arctan2(v[1], v[0]) - view.heading))
    a = float(np.arcsin(obstacle.radius / d))
    t = (c - a, c + a)
    in_view = tuple(bool(abs(_wrap(ti)) <= half + _EPS) for ti in t)
    case = {(False, False): "free", (True, True): "whole", (True, False): "first", (False, True): "second"}[in_view]
    return Projections((-half, half), t, in_view, c, d, case)


def projections(view: CameraView, obstacle: SphereObstacle | None = None) -> Projections:
    """Field-of-view edges and tangent projections to the obstacle's circle (3.1.2).

    Raises :class:`DegenerateGeometryError` when the robot stands inside the circle
    (no tangents exist).
    """
    f = "projections"
    return _projections(check_view(view, f), check_obstacle(obstacle, f), f)


def _seen(P: np.ndarray, view: CameraView, obstacle: SphereObstacle | None, func: str) -> np.ndarray:
    theta, rho = _horizontal(P, view)
    visible = _in_view(theta, rho, view)
    pr = _projections(view, obstacle, func)
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
    f = "seen_nodes"
    P = check_points(nodes, f, "nodes")
    return _seen(P, check_view(view, f), check_obstacle(obstacle, f), f)


def ray_cast_seen(nodes, view: CameraView, obstacle: SphereObstacle | None = None) -> np.ndarray:
    """3D visibility: in view (as :func:`seen_nodes`) and the segment camera -> node misses the ball; bool (N,)."""
    f = "ray_cast_seen"
    P = check_points(nodes, f, "nodes")
    view, obstacle = check_view(view, f), check_obstacle(obstacle, f)
    theta, rho = _horizontal(P, view)
    visible = _in_view(theta, rho, view)
    if obstacle is None:
        return visible
    o, c = np.asarray(view.position), np.asarray(obstacle.center)
    if np.linalg.norm(o - c) <= obstacle.radius:
        raise checks.degenerate(f, "view, obstacle", "the camera is inside the obstacle's sphere")
    d = P - o
    t = ((c - o) @ d.T) / np.maximum(np.sum(d * d, axis=1), 1e-300)
    if not np.all(np.isfinite(t)):
        raise checks.fail(
            f, "nodes", f"coordinates too large: beyond about {checks.MAX_MAGNITUDE:.0e} the ray test overflows"
        )
    closest = o + np.clip(t, 0.0, 1.0)[:, None] * d
    return visible & (np.linalg.norm(closest - c, axis=1) > obstacle.radius)


# --------------------------------------------------------------------- occupied
def l1_distances(nodes, point) -> np.ndarray:
    """B = |Xn - x| + |Yn - y| + |Zn - z| for every node, exploration (3.1); shape (N,).

    >>> l1_distances([[0.0, 0.0, 0.0], [30.0, 0.0, 30.0]], [10.0, -5.0, 2.0])
    array([17., 53.])
    """
    f = "l1_distances"
    B = _l1(check_points(nodes, f, "nodes"), check_point(point, f, "point"))
    return checks.finite_result(B, f, "nodes, point: the distances")


def _l1(nodes: np.ndarray, point: np.ndarray) -> np.ndarray:
    return np.abs(nodes - point).sum(axis=1)


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
    f = "occupied_nodes_loop"
    grid = check_grid(grid, f)
    return _loop(grid, check_points(points, f, "points"))


def _loop(grid: Grid, P: np.ndarray) -> OccupancyLoop:
    nodes = grid.nodes
    node_alive = np.ones(len(nodes), bool)
    point_alive = grid.cells(P) >= 0
    outside = list(np.flatnonzero(~point_alive))
    occupied, analysed = np.zeros(len(nodes), bool), np.zeros(len(nodes), bool)
    steps = []
    while point_alive.any():
        p = int(np.flatnonzero(point_alive)[0])
        candidates = node_alive.copy()
        while candidates.any():
            idx = np.flatnonzero(candidates)
            n = int(idx[np.argmin(_l1(nodes[idx], P[p]))])
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
    f = "occupied_nodes"
    grid = check_grid(grid, f)
    cells = grid.cells(check_points(points, f, "points"))
    out = np.zeros(grid.size, bool)
    out[cells[cells >= 0]] = True
    return out


def cells_touched_by_sphere(grid: Grid, obstacle: SphereObstacle) -> np.ndarray:
    """Cells whose box meets the sphere's surface (exact, not sampled); bool (N,).

    The surface meets a box when the nearest point of the box is within the radius
    and the farthest corner beyond it.  An upper bound for any sampling of the sphere.
    """
    f = "cells_touched_by_sphere"
    grid, obstacle = check_grid(grid, f), check_obstacle(obstacle, f, optional=False)
    lo = grid.nodes
    hi = lo + grid.spacing
    c = np.asarray(obstacle.center)
    near = np.linalg.norm(np.clip(c, lo, hi) - c, axis=1)
    far = np.linalg.norm(np.maximum(np.abs(c - lo), np.abs(c - hi)), axis=1)
    return (near <= obstacle.radius) & (far >= obstacle.radius)


# ----------------------------------------------------------------------- labels
def _mask(v, func: str, name: str) -> np.ndarray:
    """A 1-D array of bools (one per node); 0/1 numbers are refused (they would index nodes, not mask them)."""
    a = v if isinstance(v, np.ndarray) else np.asarray(v) if isinstance(v, (list, tuple)) else None
    if a is None or a.dtype != bool or a.ndim != 1:
        got = f"{a.dtype} array of shape {a.shape}" if a is not None else type(v).__name__
        raise checks.fail(func, name, f"expected a 1-D array of bools (one per node), got {got}")
    return a


@dataclass(frozen=True)
class NodeLabels:
    """Boolean masks (N,) per label and the combined label array (priority occupied > analysed > seen)."""

    seen: np.ndarray
    occupied: np.ndarray
    analysed: np.ndarray

    def __post_init__(self):
        f = "NodeLabels"
        for name in ("seen", "occupied", "analysed"):
            object.__setattr__(self, name, _mask(getattr(self, name), f, name))
        checks.same_length(f, seen=self.seen, occupied=self.occupied, analysed=self.analysed)

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
    f = "label_nodes"
    grid, view, obstacle = check_grid(grid, f), check_view(view, f), check_obstacle(obstacle, f)
    P = None if points is None else check_points(points, f, "points")
    seen = _seen(grid.nodes, view, obstacle, f)
    if P is None:
        z = np.zeros(grid.size, bool)
        return NodeLabels(seen, z, z.copy())
    loop = _loop(grid, P)
    return NodeLabels(seen, loop.occupied, loop.analysed)
