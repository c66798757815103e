"""The path around an obstacle: the exploration document, section 3.2, equations (3.2)-(3.3).

In the plane of motion the robot at (x1, y1) heads straight for a goal along

    y - y1 = m (x - x1)                  exploration (3.2)

and the obstacle is the circle that encloses its points,

    (x - a)^2 + (y - b)^2 = r^2          exploration (3.3).

The document substitutes (3.2) into (3.3) to find where the path enters and
leaves the circle, removes the part inside and goes around.  Here the same two
points come also from the conformal model: the path's line meets the obstacle's
sphere in a point pair, whose endpoints are read with the thesis's (2.131).  The
detour itself follows the tangents from the robot and to the goal and the arc of
the circle between them: it never enters the circle and its heading is
continuous (the arc between the two crossing points, the literal reading, has a
corner at each).

Units: any one length unit (the document's are centimetres); angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

__all__ = ["line_circle_intersections", "line_circle_intersections_conformal", "Detour", "detour"]


def _xy(p, func: str, name: str) -> np.ndarray:
    """A point (x, y) of finite coordinates up to :data:`checks.MAX_MAGNITUDE` (their squares stay finite)."""
    return checks.magnitude(checks.array(p, func, name, (2,)), func, name)


def _check(start, goal, center, radius, func: str):
    s, g, c = _xy(start, func, "start"), _xy(goal, func, "goal"), _xy(center, func, "center")
    r = checks.real(radius, func, "radius", low=0.0, strict_low=True, high=checks.MAX_MAGNITUDE)
    if np.linalg.norm(g - s) <= 1e-12 * max(1.0, np.abs(s).max()):
        raise checks.degenerate(func, "start, goal", "start and goal coincide, the path (3.2) has no direction")
    if max(np.linalg.norm(s - c), np.linalg.norm(g - c)) > checks.MAX_MAGNITUDE * r:
        raise checks.degenerate(func, "radius", f"{r:.3g} is too small for the distances to the centre")
    return s, g, c, r


def _order_along(s, g, pts):
    """The two points ordered by their position along start -> goal (entry first)."""
    t = (pts - s) @ (g - s)
    return pts[np.argsort(t)]


def line_circle_intersections(start, goal, center, radius):
    """Where the straight path (3.2) crosses the circle (3.3), by the document's algebra.

    Substituting y = y1 + m (x - x1) of exploration (3.2) into exploration (3.3)
    gives (1 + m^2) x^2 + 2 (m k - a) x + a^2 + k^2 - r^2 = 0 with k = y1 - m x1 - b.
    For a steep path (|m| > 1) the same algebra is applied with x and y swapped,
    so the slope never exceeds 1 (a vertical path has no slope m at all).

    Parameters
    ----------
    start, goal : array, shape (2,)
        The robot (x1, y1) and the goal; they fix the slope m.
    center : array, shape (2,)
        The circle's centre (a, b).
    radius : float

    Returns
    -------
    array, shape (2, 2), or None
        Entry and exit point on the whole line, ordered along start -> goal;
        None when the line misses the circle or only touches it.

    >>> line_circle_intersections([0.0, 0.0], [10.0, 0.0], [5.0, 0.0], 2.0).tolist()
    [[3.0, 0.0], [7.0, 0.0]]
    """
    return _document(*_check(start, goal, center, radius, "line_circle_intersections"))


def _document(s, g, c, r):
    swap = abs(g[1] - s[1]) > abs(g[0] - s[0])
    order = [1, 0] if swap else [0, 1]
    (x1, y1), (x2, y2), (a, b) = s[order], g[order], c[order]
    m = (y2 - y1) / (x2 - x1)
    k = y1 - m * x1 - b
    qa, qb, qc = 1.0 + m * m, 2.0 * (m * k - a), a * a + k * k - r * r
    disc = qb * qb - 4.0 * qa * qc
    if disc <= 0 or np.sqrt(disc / qa) <= 1e-9 * r:  # the chord's length
        return None
    q = -0.5 * (qb + np.copysign(np.sqrt(disc), qb))  # stable roots: q / qa and qc / q
    xs = np.array([q / qa, qc / q])
    pts = np.stack([xs, y1 + m * (xs - x1)], axis=1)[:, order]
    return _order_along(s, g, pts)


def line_circle_intersections_conformal(start, goal, center, radius):
    """The same two points from the conformal model: a point pair and its endpoints (2.131).

    The path's line L* = e ^ S ^ G (thesis 2.81) and the obstacle's sphere
    s = c - r^2 e / 2 (2.72) both lie in standard form: X . L = 0 and X . s = 0
    for their points, so the points on both satisfy X . (s ^ L) = 0 and s ^ L is
    the point pair where the line meets the sphere; in the plane z = 0 of the
    path that sphere's equator is the circle (3.3).  Its endpoints come from
    ``point_pair_endpoints`` (2.131-2.133).  The work is done in the obstacle's
    frame (centre at the origin, radius 1: a translation and a dilation, both
    conformal), where (2.131) loses no accuracy to large coordinates.

    Returns (2, 2) ordered along start -> goal, or None when the point pair is
    imaginary (the line misses the circle) or nearly a single point (it touches).
    """
    return _conformal(*_check(start, goal, center, radius, "line_circle_intersections_conformal"))


def _conformal(s, g, c, r):
    lift = lambda p: np.array([(p[0] - c[0]) / r, (p[1] - c[1]) / r, 0.0])  # noqa: E731
    L = cga.standard_form(cga.line_from_points(lift(s), lift(g)))
    PP = cga.sphere(np.zeros(3), 1.0) ^ L  # in the obstacle's frame: the unit sphere at the origin
    B = cga.dual_form(PP)
    BB = float((B * B).scalar())  # < 0: imaginary pair, the line misses the circle
    Be = B | cga.einf
    if BB <= 0 or 2.0 * np.sqrt(BB / float((Be * Be).scalar())) <= 1e-9:  # the separation (2.131)
        return None
    p1, p2 = (c + r * p[:2] for p in cga.point_pair_endpoints(PP))
    return _order_along(s, g, np.array([p1, p2]))


@dataclass(frozen=True)
class Detour:
    """A path from start to goal around a circle.

    ``path``: polyline (M, 2).  ``crossings``: where the straight line (3.2)
    enters and leaves the circle (2, 2), or None when it misses it (the crossings
    may lie behind the robot or beyond the goal; then the path stays straight).  ``tangent_points``: where the path
    joins and leaves the circle (2, 2), or None for a straight path.
    ``direction``: +1 counter-clockwise, -1 clockwise around the centre, 0 straight.
    ``length``: exact length of the path (lines plus arc).
    """

    path: np.ndarray
    crossings: np.ndarray | None
    tangent_points: np.ndarray | None
    direction: int
    length: float


def _tangent_point(p, c, R, direction, leaving: bool):
    """The tangent point T on circle (c, R) from p such that the motion is tangent-continuous.

    Coming from p (``leaving`` False) the velocity T - p must equal the circle's
    tangent direction there; going to p (True) the velocity p - T must.
    """
    v = p - c
    d = np.linalg.norm(v)
    beta = np.arccos(R / d)
    best = None
    for sgn in (1.0, -1.0):
        ang = sgn * beta
        u = np.array([np.cos(ang) * v[0] - np.sin(ang) * v[1], np.sin(ang) * v[0] + np.cos(ang) * v[1]]) / d
        T = c + R * u
        along = direction * np.array([-u[1], u[0]])  # circle's direction of motion at T
        vel = (p - T) if leaving else (T - p)
        score = float(vel @ along)
        if best is None or score > best[0]:
            best = (score, T)
    return best[1]


def _arc(c, R, T1, T2, direction, n):
    a1 = np.arctan2(*(T1 - c)[::-1])
    sweep = (direction * (np.arctan2(*(T2 - c)[::-1]) - a1)) % (2 * np.pi)
    ang = a1 + direction * sweep * np.linspace(0.0, 1.0, n)
    return c + R * np.stack([np.cos(ang), np.sin(ang)], axis=1), R * sweep


def detour(start, goal, center, radius, clearance: float = 0.0, direction: int | None = None, n_arc: int = 64,
           method: str = "conformal") -> Detour:  # fmt: skip
    """A smooth path from start to goal around a circular obstacle, exploration (3.2)-(3.3).

    When the straight path (3.2) crosses the circle (3.3) of radius
    ``radius + clearance`` between start and goal (crossings computed by ``method``:
    "conformal" or "document"), the part inside is replaced by the tangent from the
    start, the arc of the circle and the tangent to the goal, on the side where
    that path is shorter (or ``direction`` +1/-1 to choose).  The result is the
    shortest path around the disc, with continuous heading.

    Raises :class:`DegenerateGeometryError` when start or goal lies inside the circle.
    """
    f = "detour"
    s, g, c, r = _check(start, goal, center, radius, f)
    R = r + checks.real(clearance, f, "clearance", low=0.0, high=checks.MAX_MAGNITUDE)
    if direction is not None:
        direction = checks.integer(direction, f, "direction")
        if direction not in (1, -1):
            raise checks.fail(
                f, "direction", f"must be +1 (counter-clockwise), -1 (clockwise) or None, got {direction}"
            )
    n_arc = checks.integer(n_arc, f, "n_arc", low=2, high=10**6)
    method = checks.choice(method, f, "method", ("conformal", "document"))
    for name, p in (("start", s), ("goal", g)):
        if np.linalg.norm(p - c) <= R:
            raise checks.degenerate(
                f, name, f"the {name} lies inside the obstacle's circle (radius + clearance = {R:.6g})"
            )
    find = _conformal if method == "conformal" else _document
    cross = find(s, g, c, R)
    t_entry = None if cross is None else (cross[0] - s) @ (g - s) / ((g - s) @ (g - s))
    if t_entry is None or not 0.0 <= t_entry <= 1.0:  # misses, behind the robot, or beyond the goal
        return Detour(np.array([s, g]), cross, None, 0, float(np.linalg.norm(g - s)))
    options = []
    for d in (1, -1) if direction is None else (direction,):
        T1, T2 = _tangent_point(s, c, R, d, False), _tangent_point(g, c, R, d, True)
        arc, arc_len = _arc(c, R, T1, T2, d, n_arc)
        length = np.linalg.norm(T1 - s) + arc_len + np.linalg.norm(g - T2)
        options.append((length, d, np.vstack([s, arc, g]), np.array([T1, T2])))
    length, d, path, tangents = min(options, key=lambda o: o[0])
    return Detour(path, cross, tangents, d, float(length))
