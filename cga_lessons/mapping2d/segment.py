"""Lines and line segments of the 2D map (thesis section 3.1.1, equations 3.1-3.3): the :class:`Segment` structure.

The line through two points (3.1), the distance of a point to a line (3.2), the orthogonal least-squares line of
points (the refit of section 3.1.1) and the thesis's segment structure ``l_k`` (3.3) with the point sums that let a
map line be refitted from every point it gathered.  :mod:`cga_lessons.mapping2d.lines` cuts scans into these
segments and re-exports the names here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks

from .inputs import numbers

__all__ = [
    "TWO_PI",
    "Segment",
    "line_through",
    "point_line_distance",
    "fit_line",
    "line_from_sums",
    "point_sums",
    "make_segment",
]

TWO_PI = 2.0 * np.pi


def line_through(p, q) -> np.ndarray:
    """The line ``a x + b y + c = 0`` through two points, Eq. (3.1).

    Parameters
    ----------
    p, q : array_like, shape (2,)

    Returns
    -------
    ndarray, shape (3,)
        ``(a, b, c)`` with ``(a, b)`` normal to ``q - p`` (not normalised).

    >>> line_through([0.0, 1.0], [2.0, 1.0]).tolist() == [0.0, 2.0, -2.0]  # y = 1 (signs of zero aside)
    True
    """
    p = checks.array(p, "line_through", "p", (2,))
    q = checks.array(q, "line_through", "q", (2,))
    out = np.array([p[1] - q[1], q[0] - p[0], p[0] * q[1] - q[0] * p[1]])
    return checks.finite_result(out, "line_through", "p, q")


def point_line_distance(abc, points) -> np.ndarray:
    """Signed distance of points to the line ``(a, b, c)``, Eq. (3.2).

    ``d(l, p) = (a p_x + b p_y + c) / sqrt(a^2 + b^2)``.

    Parameters
    ----------
    abc : array_like, shape (3,)
    points : array_like, shape (..., 2)

    Returns
    -------
    ndarray, shape (...)

    >>> float(point_line_distance([0.0, 1.0, -1.0], [3.0, 4.0]))
    3.0
    """
    a, b, c = checks.array(abc, "point_line_distance", "abc", (3,))
    norm = np.hypot(a, b)
    if norm == 0:
        raise checks.fail("point_line_distance", "abc", "(a, b) is zero, not a line")
    p = numbers(points, "point_line_distance", "points")
    if p.ndim == 0 or p.shape[-1] != 2:
        raise checks.fail("point_line_distance", "points", f"expected shape (2,) or (..., 2), got {p.shape}")
    return checks.finite_result((a * p[..., 0] + b * p[..., 1] + c) / norm, "point_line_distance", "abc, points")


def fit_line(points):
    """Orthogonal least-squares line through points (the refit of section 3.1.1).

    Minimises the sum of squared perpendicular distances: the line passes
    through the centroid along the principal axis of the scatter matrix.

    Parameters
    ----------
    points : array_like, shape (n, 2), n >= 2

    Returns
    -------
    centroid : ndarray, shape (2,)
    direction : ndarray, shape (2,)
        Unit vector, oriented from the first point towards the last.
    residuals : ndarray, shape (n,)
        Signed perpendicular distances of the points to the line.
    """
    return fit_points(checks.array(points, "fit_line", "points", (None, 2), at_least=2), "fit_line")


def fit_points(p: np.ndarray, func: str, name: str = "points"):
    """:func:`fit_line` of a checked (n >= 2, 2) array; an overflow of the scatter is an error of ``func``."""
    c = p.mean(axis=0)
    q = p - c
    with np.errstate(over="ignore", invalid="ignore"):
        scatter = q.T @ q
    checks.finite_result(scatter, func, name)
    d = _principal_direction(scatter, p[-1] - p[0])
    return c, d, q @ np.array([-d[1], d[0]])


def _principal_direction(scatter, hint):
    """Unit eigenvector of the largest eigenvalue of a 2x2 scatter, oriented along ``hint``."""
    sxx, sxy, syy = scatter[0, 0], scatter[0, 1], scatter[1, 1]
    angle = 0.5 * np.arctan2(2.0 * sxy, sxx - syy)
    d = np.array([np.cos(angle), np.sin(angle)])
    if d @ hint < 0:
        d = -d
    return d


def _end(value, func: str, name: str) -> np.ndarray:
    p = numbers(value, func, name)
    if p.size != 2:
        raise checks.fail(func, name, f"expected a point (x, y), got shape {p.shape}")
    return p.reshape(2)


@dataclass(eq=False)
class Segment:
    """A line segment, the thesis's structure for ``l_k`` (section 3.1.1, Eq. 3.3).

    The thesis's members are the initial point ``(x_i, y_i)`` (:attr:`start`),
    the final point ``(x_f, y_f)`` (:attr:`end`), the Hesse distance
    :attr:`rho`, the polar angle :attr:`theta` in ``[0, 2 pi)`` of the closest
    point to the origin, the :attr:`closest_point` itself and the line
    parameters :attr:`abc` with ``a x + b y + c = 0``; the normal form (3.3) is
    ``x cos(theta) + y sin(theta) = rho``.  Beside them a segment keeps the
    point count and the sums of its points (so a map line can be refitted from
    all the points it gathered) and whether each end is a real *edge* of the
    object (the next beam missed, or passed behind the line) rather than a cut
    by an occlusion or the field of view.

    Parameters
    ----------
    start, end : array_like, shape (2,)
        End points, metres; the direction runs from ``start`` to ``end``.  Their coordinates, and the sums of
        their squares, must be finite floats.
    n_points : int
        How many laser points support the segment (>= 0).
    sums : array_like, shape (6,), optional
        ``(n, sum x, sum y, sum x^2, sum x y, sum y^2)`` of the points; by
        default those of ``n_points`` points spread evenly from start to end.
    start_is_edge, end_is_edge : bool
    """

    start: np.ndarray
    end: np.ndarray
    n_points: int = 2
    sums: np.ndarray | None = None
    start_is_edge: bool = False
    end_is_edge: bool = False
    _dir: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        f = "Segment"
        self.start, self.end = _end(self.start, f, "start"), _end(self.end, f, "end")
        self.n_points = checks.integer(self.n_points, f, "n_points", low=0)
        self.start_is_edge = checks.flag(self.start_is_edge, f, "start_is_edge")
        self.end_is_edge = checks.flag(self.end_is_edge, f, "end_is_edge")
        v = self.end - self.start
        with np.errstate(over="ignore", invalid="ignore"):
            length = np.hypot(*v)
            if self.sums is None:
                t = np.linspace(0.0, 1.0, max(self.n_points, 2))[:, None]
                sums = point_sums(self.start + t * v)
            else:
                sums = checks.array(self.sums, f, "sums", (6,))
        checks.finite_result(np.append(sums, length), f, "start, end")
        if length == 0:
            raise checks.fail(f, "start, end", f"start and end coincide at {self.start.tolist()}")
        self.sums = sums
        self._dir = v / length

    # -- construction
    @classmethod
    def from_points(cls, points, start_is_edge=False, end_is_edge=False) -> Segment:
        """Least-squares segment of ordered points: the fitted line, limited by the
        projections of the first and last points."""
        f = "Segment.from_points"
        p = checks.array(points, f, "points", (None, 2), at_least=2)
        edges = checks.flag(start_is_edge, f, "start_is_edge"), checks.flag(end_is_edge, f, "end_is_edge")
        with np.errstate(over="ignore", invalid="ignore"):
            sums = point_sums(p)
        checks.finite_result(sums, f, "points")
        c, d, _ = fit_points(p, f)
        start = c + d * ((p[0] - c) @ d)
        end = c + d * ((p[-1] - c) @ d)
        if np.hypot(*(end - start)) == 0:
            raise checks.fail(f, "points", "the points span no length (the first and last coincide on the line)")
        return make_segment(start, end, len(p), sums, *edges)

    # -- the thesis's members
    @property
    def direction(self) -> np.ndarray:
        """Unit direction from start to end, shape (2,)."""
        return self._dir

    @property
    def normal(self) -> np.ndarray:
        """Unit normal to the right of the direction (away from the sensor that saw it), shape (2,)."""
        return np.array([self._dir[1], -self._dir[0]])

    @property
    def rho(self) -> float:
        """Hesse distance: distance from the origin to the (infinite) line, >= 0 (3.3)."""
        return float(abs(self.normal @ self.start))

    @property
    def theta(self) -> float:
        """Polar angle of the closest point of the line to the origin, in [0, 2 pi) (3.3).

        When the line passes through the origin the angle of :attr:`normal` is used.
        """
        n = self.normal
        s = n @ self.start
        if s < 0:
            n = -n
        return float(np.mod(np.arctan2(n[1], n[0]), TWO_PI))

    @property
    def closest_point(self) -> np.ndarray:
        """Point of the line closest to the origin, ``rho (cos theta, sin theta)``, shape (2,)."""
        n = self.normal
        return n * (n @ self.start)

    @property
    def abc(self) -> np.ndarray:
        """``(a, b, c) = (cos theta, sin theta, -rho)``: the line ``a x + b y + c = 0`` (3.1, 3.3)."""
        t = self.theta
        return np.array([np.cos(t), np.sin(t), -self.rho])

    @property
    def length(self) -> float:
        return float(np.hypot(*(self.end - self.start)))

    @property
    def midpoint(self) -> np.ndarray:
        return 0.5 * (self.start + self.end)

    @property
    def inclination(self) -> float:
        """Inclination angle of the line in [0, pi) (used by the merge step)."""
        return float(np.mod(np.arctan2(self._dir[1], self._dir[0]), np.pi))

    def hough(self, origin=(0.0, 0.0)):
        """Oriented Hough coordinates ``(rho, theta)`` of the line seen from ``origin``.

        ``theta`` is the angle of :attr:`normal` in ``[0, 2 pi)`` and ``rho`` the
        signed distance ``normal . (p - origin)``.  For a segment in the frame
        of the sensor that saw it this equals ``(rho, theta)`` of (3.3); the
        orientation keeps ``(rho, theta)`` and ``(-rho, theta + pi)`` from
        being told apart as two lines, and the two faces of a wall distinct.
        """
        o = checks.array(origin, "Segment.hough", "origin", (2,))
        n = self.normal
        rho = checks.finite_result(float(n @ (self.start - o)), "Segment.hough", "origin")
        return rho, float(np.mod(np.arctan2(n[1], n[0]), TWO_PI))

    def transformed(self, pose) -> Segment:
        """The segment moved by the rigid motion of pose ``(x, y, theta)``, Eq. (3.4).

        ``v' = R(theta) v + T`` applied to the end points (and to the point sums).
        """
        x, y, th = checks.array(pose, "Segment.transformed", "pose", (3,))
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        t = np.array([x, y])
        with np.errstate(over="ignore", invalid="ignore"):
            start, end, sums = R @ self.start + t, R @ self.end + t, _transform_sums(self.sums, R, t)
        checks.finite_result(np.concatenate([start, end, sums]), "Segment.transformed", "pose")
        if np.array_equal(start, end):  # the motion's translation swamps the segment in rounding
            raise checks.fail("Segment.transformed", "pose", "the translation is too large for the segment's length")
        return make_segment(start, end, self.n_points, sums, self.start_is_edge, self.end_is_edge)

    def reversed(self) -> Segment:
        """The same segment run the other way (end and start swapped)."""
        return make_segment(self.end, self.start, self.n_points, self.sums, self.end_is_edge, self.start_is_edge)

    def __repr__(self):
        s, e = np.round(self.start, 3).tolist(), np.round(self.end, 3).tolist()
        return f"Segment(start={s}, end={e}, rho={self.rho:.3f}, theta={self.theta:.4f}, n_points={self.n_points})"


def make_segment(start, end, n_points, sums, start_is_edge=False, end_is_edge=False) -> Segment:
    """A :class:`Segment` of values the caller has checked (finite 2-vectors apart, a count, finite sums):
    the map builder's and the extractor's constructor, without the checks of ``Segment(...)``."""
    s = object.__new__(Segment)
    s.start, s.end = np.asarray(start, float), np.asarray(end, float)
    s.n_points, s.sums = int(n_points), np.asarray(sums, float)
    s.start_is_edge, s.end_is_edge = bool(start_is_edge), bool(end_is_edge)
    v = s.end - s.start
    s._dir = v / np.hypot(*v)
    return s


def point_sums(p):
    """The point sums ``(n, sum x, sum y, sum x^2, sum x y, sum y^2)`` of points (n, 2)."""
    p = np.asarray(p, float)
    x, y = p[:, 0], p[:, 1]
    return np.array([len(p), x.sum(), y.sum(), x @ x, x @ y, y @ y])


def _transform_sums(s, R, t):
    n = s[0]
    s1 = s[1:3]
    s2 = np.array([[s[3], s[4]], [s[4], s[5]]])
    s1n = R @ s1 + n * t
    s2n = R @ s2 @ R.T + np.outer(R @ s1, t) + np.outer(t, R @ s1) + n * np.outer(t, t)
    return np.array([n, s1n[0], s1n[1], s2n[0, 0], s2n[0, 1], s2n[1, 1]])


def line_from_sums(sums, hint):
    """Orthogonal least-squares line from point sums: ``(centroid, direction)``.

    Parameters
    ----------
    sums : array_like, shape (6,)
        ``(n, sum x, sum y, sum x^2, sum x y, sum y^2)``.
    hint : array_like, shape (2,)
        The direction is oriented to have a positive component along it.
    """
    s = np.asarray(sums, float)
    n = s[0]
    c = s[1:3] / n
    scatter = np.array([[s[3], s[4]], [s[4], s[5]]]) - n * np.outer(c, c)
    return c, _principal_direction(scatter, np.asarray(hint, float))
