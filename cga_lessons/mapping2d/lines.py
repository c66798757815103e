"""Line segments from laser scans (thesis section 3.1.1, equations 3.1-3.5).

The pipeline of :func:`extract_segments`:

1. the scan's returning beams become points in the laser frame; the scan is cut
   into *runs* at beams with no return and at range jumps (two neighbouring
   points further apart than the beam spacing explains);
2. each run is split recursively (3.1-3.2): the chord from its first to its
   last point is a line ``a x + b y + c = 0``; if the farthest point is at
   least ``xi`` from it the run is split there, otherwise it is a line;
3. neighbouring pieces whose inclinations differ by less than ``phi_xi`` are
   merged (when the points of both still fit one line: RMS distance below
   ``xi / 2``; a split caused by noise at the chord's ends is undone);
4. every piece is refitted by orthogonal least squares (total least squares:
   it minimises distances *perpendicular* to the line, unlike a fit of y on x)
   and becomes a :class:`Segment`, the thesis's line structure (3.3).

:func:`diff_theta` is the thesis's difference of two Hough angles (3.5).

A segment found in a scan runs counter-clockwise around the sensor (the order
of the beams), so the sensor is on its *left*.  That orientation tells the two
faces of a thin wall apart, and it is what the thesis's remark
"``l_k . l_m = 1`` same direction, ``-1`` opposite" relies on.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons.algebra import InvalidInputError

__all__ = [
    "Segment",
    "line_through",
    "point_line_distance",
    "diff_theta_as_printed",
    "split_points",
    "fit_line",
    "diff_theta",
    "extract_segments",
    "TWO_PI",
]

TWO_PI = 2.0 * np.pi


# --------------------------------------------------------------------------- lines (3.1-3.3)


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
    p = np.asarray(p, float)
    q = np.asarray(q, float)
    return np.array([p[1] - q[1], q[0] - p[0], p[0] * q[1] - q[0] * p[1]])


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
    a, b, c = np.asarray(abc, float)
    norm = np.hypot(a, b)
    if norm == 0:
        raise InvalidInputError("point_line_distance: (a, b) is zero, not a line")
    p = np.asarray(points, float)
    return (a * p[..., 0] + b * p[..., 1] + c) / norm


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
    p = np.asarray(points, float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2:
        raise InvalidInputError(f"fit_line: need an (n >= 2, 2) array of points, got shape {p.shape}")
    c = p.mean(axis=0)
    q = p - c
    d = _principal_direction(q.T @ q, p[-1] - p[0])
    return c, d, q @ np.array([-d[1], d[0]])


def _principal_direction(scatter, hint):
    """Unit eigenvector of the largest eigenvalue of a 2x2 scatter, oriented along ``hint``."""
    sxx, sxy, syy = scatter[0, 0], scatter[0, 1], scatter[1, 1]
    angle = 0.5 * np.arctan2(2.0 * sxy, sxx - syy)
    d = np.array([np.cos(angle), np.sin(angle)])
    if d @ hint < 0:
        d = -d
    return d


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
        End points, metres; the direction runs from ``start`` to ``end``.
    n_points : int
        How many laser points support the segment.
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
        self.start = np.asarray(self.start, float).reshape(2)
        self.end = np.asarray(self.end, float).reshape(2)
        if not (np.all(np.isfinite(self.start)) and np.all(np.isfinite(self.end))):
            raise InvalidInputError("Segment: start and end must be finite 2-vectors")
        v = self.end - self.start
        length = np.hypot(*v)
        if length == 0:
            raise InvalidInputError(f"Segment: start and end coincide at {self.start.tolist()}")
        self._dir = v / length
        self.n_points = int(self.n_points)
        if self.sums is None:
            t = np.linspace(0.0, 1.0, max(self.n_points, 2))[:, None]
            self.sums = _sums(self.start + t * v)
        else:
            self.sums = np.asarray(self.sums, float).reshape(6)

    # -- construction
    @classmethod
    def from_points(cls, points, start_is_edge=False, end_is_edge=False) -> Segment:
        """Least-squares segment of ordered points: the fitted line, limited by the
        projections of the first and last points."""
        c, d, _ = fit_line(points)
        p = np.asarray(points, float)
        start = c + d * ((p[0] - c) @ d)
        end = c + d * ((p[-1] - c) @ d)
        return cls(start, end, len(p), _sums(p), bool(start_is_edge), bool(end_is_edge))

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
        n = self.normal
        return float(n @ (self.start - np.asarray(origin, float))), float(np.mod(np.arctan2(n[1], n[0]), TWO_PI))

    def transformed(self, pose) -> Segment:
        """The segment moved by the rigid motion of pose ``(x, y, theta)``, Eq. (3.4).

        ``v' = R(theta) v + T`` applied to the end points (and to the point sums).
        """
        x, y, th = np.asarray(pose, float).reshape(3)
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        t = np.array([x, y])
        return Segment(
            R @ self.start + t,
            R @ self.end + t,
            self.n_points,
            _transform_sums(self.sums, R, t),
            self.start_is_edge,
            self.end_is_edge,
        )

    def reversed(self) -> Segment:
        """The same segment run the other way (end and start swapped)."""
        return Segment(self.end, self.start, self.n_points, self.sums, self.end_is_edge, self.start_is_edge)

    def __repr__(self):
        s, e = np.round(self.start, 3).tolist(), np.round(self.end, 3).tolist()
        return f"Segment(start={s}, end={e}, rho={self.rho:.3f}, theta={self.theta:.4f}, n_points={self.n_points})"


def _sums(p):
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


# --------------------------------------------------------------------------- splitting (3.1-3.2)


def split_points(points, xi: float) -> list[tuple[int, int]]:
    """Recursive line splitting of ordered points, Eqs. (3.1)-(3.2).

    The chord from the first to the last point of a group is the line (3.1);
    if the farthest point ``v_md`` lies at distance (3.2) ``>= xi`` the group
    is split into ``v_p .. v_md`` and ``v_md+1 .. v_f`` (the thesis's step 4)
    and both halves are treated the same way.

    Parameters
    ----------
    points : array_like, shape (n, 2)
    xi : float
        The thesis's threshold ``xi``: the largest distance (m) of a point from
        a line it belongs to.

    Returns
    -------
    list of (int, int)
        Index ranges ``(first, last)``, inclusive, in order.

    >>> pts = [[0, 0], [1, 0], [2, 0], [2, 1], [2, 2]]
    >>> split_points(pts, 0.1)
    [(0, 2), (3, 4)]
    """
    p = np.asarray(points, float)
    if p.ndim != 2 or p.shape[1] != 2:
        raise InvalidInputError(f"split_points: points must have shape (n, 2), got {p.shape}")
    if not xi > 0:
        raise InvalidInputError(f"split_points: xi must be > 0, got {xi}")
    return _split(p, xi)


def _split(p, xi):
    """:func:`split_points` without the input checks (the extractor calls it on every run of every scan)."""
    out = []
    stack = [(0, len(p) - 1)] if len(p) else []
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            out.append((i, j))
            continue
        v = p[j] - p[i]
        norm = np.hypot(*v)
        q = p[i + 1 : j] - p[i]
        if norm > 0:
            d = np.abs(q[:, 0] * v[1] - q[:, 1] * v[0]) / norm  # (3.2) with the chord (3.1)
        else:
            d = np.hypot(q[:, 0], q[:, 1])
        k = int(np.argmax(d))
        if d[k] < xi:
            out.append((i, j))
        else:
            md = i + 1 + k
            stack.append((md + 1, j))  # processed second
            stack.append((i, md))  # v_p .. v_md first
    return out


# --------------------------------------------------------------------------- diffTheta (3.5)


def diff_theta(theta_a, theta_b, theta_xi: float = 2 * np.pi / 100):
    """Difference of two Hough angles in ``[0, 2 pi)``, Eq. (3.5) (corrected, see below).

    .. math::

        \\mathrm{diffTheta}(\\theta_a, \\theta_b) = \\begin{cases}
        \\theta_a - \\theta_b - 2\\pi & \\theta_a > \\theta_b,\\ \\theta_a + \\theta_\\xi \\ge 2\\pi,
            \\ \\theta_b - \\theta_\\xi \\le 0 \\\\
        \\theta_a - \\theta_b + 2\\pi & \\theta_a < \\theta_b,\\ \\theta_b + \\theta_\\xi \\ge 2\\pi,
            \\ \\theta_a - \\theta_\\xi \\le 0 \\\\
        \\theta_a - \\theta_b & \\text{otherwise}
        \\end{cases}

    Erratum: the thesis prints ``theta_b + theta_xi <= 0`` (and ``theta_a +
    theta_xi <= 0``) in the first two cases, which can never hold for angles
    in ``[0, 2 pi)`` and ``theta_xi > 0``; its own worked example
    (``diffTheta(199 pi/100, 2 pi/100) = -3 pi/100`` with ``theta_xi = 2 pi/100``)
    needs ``-``.  Near zero, the angle just below ``2 pi`` and the one just
    above ``0`` are then compared across the cut.  When both angles lie within
    ``theta_xi`` of the cut the result is the short way round.

    Parameters
    ----------
    theta_a, theta_b : float or array_like
        Angles in ``[0, 2 pi)``; arrays broadcast.
    theta_xi : float
        The thesis's threshold ``theta_xi`` "that tells whether we are near the
        angle 0" (default ``2 pi / 100`` as in the thesis).

    Returns
    -------
    float or ndarray

    >>> round(float(diff_theta(199 * np.pi / 100, 2 * np.pi / 100) / np.pi * 100), 9)
    -3.0
    """
    a = np.asarray(theta_a, float)
    b = np.asarray(theta_b, float)
    d = a - b
    case1 = (a > b) & (a + theta_xi >= TWO_PI) & (b - theta_xi <= 0)
    case2 = (a < b) & (b + theta_xi >= TWO_PI) & (a - theta_xi <= 0)
    out = np.where(case1, d - TWO_PI, np.where(case2, d + TWO_PI, d))
    return float(out) if out.ndim == 0 else out


def diff_theta_as_printed(theta_a, theta_b, theta_xi: float = 2 * np.pi / 100):
    """Eq. (3.5) exactly as printed (``+ theta_xi <= 0``), kept to show the erratum."""
    a = np.asarray(theta_a, float)
    b = np.asarray(theta_b, float)
    d = a - b
    case1 = (a > b) & (a + theta_xi >= TWO_PI) & (b + theta_xi <= 0)
    case2 = (a < b) & (b + theta_xi >= TWO_PI) & (a + theta_xi <= 0)
    out = np.where(case1, d - TWO_PI, np.where(case2, d + TWO_PI, d))
    return float(out) if out.ndim == 0 else out


# --------------------------------------------------------------------------- extraction


def _runs(points, index, ranges, dphi, max_gap, jump_ratio):
    """Cut the ordered points into runs at missing beams and range jumps: list of (first, last)."""
    if len(points) == 0:
        return []
    gap = np.hypot(*np.diff(points, axis=0).T)
    r = ranges[index]
    allowed = np.maximum(max_gap, jump_ratio * np.minimum(r[:-1], r[1:]) * dphi)
    cut = (np.diff(index) != 1) | (gap > allowed)
    starts = np.concatenate([[0], np.flatnonzero(cut) + 1])
    ends = np.concatenate([np.flatnonzero(cut), [len(points) - 1]])
    return list(zip(starts.tolist(), ends.tolist()))


def _edge_end(c, d, end, beam, step, ranges, angles, max_range, tol, look=4):
    """Is the end of a segment a real edge of the object, and where is that edge?

    Walks outward from the end over up to ``look`` beams (``beam``, ``beam +
    step``, ...).  Beams landing within ``tol`` of the segment's line (a door
    jamb's thin side, noise) are passed over; the first beam that does not
    decides: no return although the line, continued, would be within
    ``max_range`` along it, or a return from well behind the line, means the
    object ends there (an edge); a return in front of the line means it is
    hidden by something nearer (not an edge); leaving the field of view or the
    sensor's range gives no evidence (not an edge).

    The object ends somewhere between the last point and the place where the
    next beam meets the line; that gap must be below ``tol``, and the edge is
    put in its middle (the last point alone would always fall short).

    Returns
    -------
    (bool, ndarray (2,))
        Whether it is an edge, and the end point (moved to the gap's middle if so).
    """
    n = np.array([-d[1], d[0]])
    nc = n @ c
    first = None
    for _ in range(look):
        if beam < 0 or beam >= len(ranges):
            return False, end  # end of the field of view
        u = np.array([np.cos(angles[beam]), np.sin(angles[beam])])
        den = n @ u
        t_line = nc / den if abs(den) > 1e-12 else np.inf
        if not (t_line > 0 and t_line + tol < max_range):
            return False, end  # the line would leave the sensor's range: no evidence
        if first is None:
            first = t_line * u
        r = ranges[beam]
        if not np.isfinite(r) or r > t_line + tol:
            gap = np.hypot(*(first - end))
            if gap < tol:
                return True, 0.5 * (end + first)
            return False, end
        if r < t_line - tol:
            return False, end
        beam += step
    return False, end


def extract_segments(
    ranges,
    angles,
    *,
    xi: float = 0.03,
    phi_xi: float = np.radians(5.0),
    min_points: int = 6,
    min_length: float = 0.15,
    max_gap: float = 0.20,
    jump_ratio: float = 5.0,
    max_range: float = np.inf,
    edge_tolerance: float = 0.15,
) -> list[Segment]:
    """Line segments of one laser scan (section 3.1.1: Eqs. 3.1-3.3 and the merge step).

    Parameters
    ----------
    ranges : array_like, shape (n,)
        Metres; ``inf`` or NaN where a beam returned nothing.
    angles : array_like, shape (n,)
        Beam angles in the laser frame (radians), increasing (counter-clockwise).
    xi : float
        The thesis's ``xi``: largest distance (m) of a point from its line; a
        group whose farthest point is at least this far is split (3.2).
    phi_xi : float
        The thesis's ``phi_xi``: neighbouring lines whose inclinations differ
        by less than this (radians) are merged.
    min_points : int
        Fewest points a segment needs (fewer: a chair leg, a stray return).
    min_length : float
        Shortest segment kept (m).
    max_gap : float
        Neighbouring points further apart than this (m) always start a new run.
    jump_ratio : float
        ... or further apart than ``jump_ratio`` times the beam spacing at their
        range (``r * dphi``), which allows grazing walls but cuts at range jumps.
    max_range : float
        Readings at or beyond this (m) count as no return; also the range
        within which the sensor would have seen a wall that continued (edge test).
    edge_tolerance : float
        A neighbour beam landing this far (m) behind the line marks a real edge.

    Returns
    -------
    list of Segment
        In scan order, in the laser frame; empty when nothing line-like is seen.

    Raises
    ------
    InvalidInputError
        When ``ranges`` and ``angles`` do not match or the thresholds are invalid.
    """
    r = np.asarray(ranges, float).copy()
    a = np.asarray(angles, float)
    if r.ndim != 1 or r.shape != a.shape:
        raise InvalidInputError(f"extract_segments: ranges {r.shape} and angles {a.shape} must be equal 1-D shapes")
    if len(a) < 2 or np.any(~np.isfinite(a)) or np.any(np.diff(a) <= 0):
        raise InvalidInputError("extract_segments: angles must be finite and strictly increasing")
    if not (xi > 0 and phi_xi > 0 and min_points >= 2 and max_gap > 0 and max_range > 0):
        raise InvalidInputError("extract_segments: xi, phi_xi, max_gap, max_range must be > 0 and min_points >= 2")
    r[~np.isfinite(r) | (r <= 0) | (r >= max_range)] = np.inf
    ok = np.isfinite(r)
    if not ok.any():
        return []
    index = np.flatnonzero(ok)
    pts = np.stack([r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok])], axis=1)
    dphi = float(np.median(np.diff(a)))

    groups = []
    moments = _prefix_moments(pts)
    for i0, i1 in _runs(pts, index, r, dphi, max_gap, jump_ratio):
        pieces = [(i0 + p, i0 + q) for p, q in _split(pts[i0 : i1 + 1], xi)]
        groups.append(_merge(moments, pieces, xi, phi_xi, min_points))

    out = []
    for run in groups:
        for i, j in run:
            if j - i + 1 < min_points:
                continue
            seg_pts = pts[i : j + 1]
            c, d, _ = fit_line(seg_pts)
            start = c + d * ((seg_pts[0] - c) @ d)
            end = c + d * ((seg_pts[-1] - c) @ d)
            if np.hypot(*(end - start)) < min_length:
                continue
            s_edge, start = _edge_end(c, d, start, index[i] - 1, -1, r, a, max_range, edge_tolerance)
            e_edge, end = _edge_end(c, d, end, index[j] + 1, 1, r, a, max_range, edge_tolerance)
            out.append(Segment(start, end, len(seg_pts), _sums(seg_pts), s_edge, e_edge))
    return out


def _prefix_moments(pts):
    """Running sums ``(n + 1, 5)`` of x, y, x^2, xy, y^2 over ordered points (row 0 is zeros).

    The moments of any range ``i..j`` are then one subtraction, so the merge step fits a line to a range in
    constant time instead of touching its points again.
    """
    x, y = pts[:, 0], pts[:, 1]
    out = np.zeros((len(pts) + 1, 5))
    np.cumsum(np.column_stack([x, y, x * x, x * y, y * y]), axis=0, out=out[1:])
    return out


def _range_line(moments, i, j):
    """Inclination in [0, pi) and RMS perpendicular residual of the least-squares line of points ``i..j``.

    From the range's scatter matrix: the direction is its principal axis, and the mean squared
    perpendicular distance is its smaller eigenvalue over the number of points (what :func:`fit_line`'s
    residuals give, without the points).
    """
    n = j - i + 1
    sx, sy, sxx, sxy, syy = moments[j + 1] - moments[i]
    cx, cy = sx / n, sy / n
    a, b, c = sxx - n * cx * cx, sxy - n * cx * cy, syy - n * cy * cy
    small = 0.5 * (a + c - np.hypot(a - c, 2.0 * b))
    return (0.5 * np.arctan2(2.0 * b, a - c)) % np.pi, np.sqrt(max(small, 0.0) / n)


def _merge(moments, pieces, xi, phi_xi, min_points):
    """Merge neighbouring pieces of one run whose inclinations differ by less than phi_xi (and fit one line).

    ``moments`` are the scan's running sums (:func:`_prefix_moments`).  A piece too small to be a segment
    has no reliable inclination: it joins a neighbour whenever the points of both fit one line.
    """
    if len(pieces) < 2:
        return pieces
    merged = [pieces[0]]
    for p in pieces[1:]:
        q = merged[-1]
        small = min(q[1] - q[0], p[1] - p[0]) + 1 < min_points
        ok = small
        if not small:
            diff = abs(_range_line(moments, *q)[0] - _range_line(moments, *p)[0])
            ok = min(diff, np.pi - diff) < phi_xi
        if ok and _range_line(moments, q[0], p[1])[1] < xi / 2:
            merged[-1] = (q[0], p[1])
            continue
        merged.append(p)
    return merged
