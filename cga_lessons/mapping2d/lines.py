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

import numpy as np

from cga_lessons import checks

from .extraction import ExtractionParams, extraction_settings
from .inputs import broadcast, numbers, scan
from .segment import TWO_PI, Segment, fit_points, make_segment, point_sums

__all__ = [
    "diff_theta_as_printed",
    "split_points",
    "diff_theta",
    "extract_segments",
]


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
    p = checks.magnitude(checks.array(points, "split_points", "points", (None, 2)), "split_points", "points")
    return _split(p, checks.real(xi, "split_points", "xi", low=0.0, strict_low=True))


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
    out = diff_theta_unchecked(*_angles("diff_theta", theta_a, theta_b, theta_xi))
    return float(out) if out.ndim == 0 else out


def diff_theta_as_printed(theta_a, theta_b, theta_xi: float = 2 * np.pi / 100):
    """Eq. (3.5) exactly as printed (``+ theta_xi <= 0``), kept to show the erratum."""
    a, b, theta_xi = _angles("diff_theta_as_printed", theta_a, theta_b, theta_xi)
    d = a - b
    case1 = (a > b) & (a + theta_xi >= TWO_PI) & (b + theta_xi <= 0)
    case2 = (a < b) & (b + theta_xi >= TWO_PI) & (a + theta_xi <= 0)
    out = np.where(case1, d - TWO_PI, np.where(case2, d + TWO_PI, d))
    return float(out) if out.ndim == 0 else out


def _angles(func: str, theta_a, theta_b, theta_xi):
    """The checked arguments of :func:`diff_theta`: two finite angle arrays that broadcast, ``theta_xi >= 0``."""
    a, b = numbers(theta_a, func, "theta_a"), numbers(theta_b, func, "theta_b")
    broadcast(func, theta_a=a, theta_b=b)
    return a, b, checks.real(theta_xi, func, "theta_xi", low=0.0)


def diff_theta_unchecked(a, b, theta_xi):
    """:func:`diff_theta` of checked arrays (the correspondence search's inner loop)."""
    d = a - b
    case1 = (a > b) & (a + theta_xi >= TWO_PI) & (b - theta_xi <= 0)
    case2 = (a < b) & (b + theta_xi >= TWO_PI) & (a - theta_xi <= 0)
    return np.where(case1, d - TWO_PI, np.where(case2, d + TWO_PI, d))


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


_DEFAULT = ExtractionParams()  # extract_segments' defaults are its fields


def extract_segments(
    ranges,
    angles,
    *,
    xi: float = _DEFAULT.xi,
    phi_xi: float = _DEFAULT.phi_xi,
    min_points: int = _DEFAULT.min_points,
    min_length: float = _DEFAULT.min_length,
    max_gap: float = _DEFAULT.max_gap,
    jump_ratio: float = _DEFAULT.jump_ratio,
    max_range: float = _DEFAULT.max_range,
    edge_tolerance: float = _DEFAULT.edge_tolerance,
) -> list[Segment]:
    """Line segments of one laser scan (section 3.1.1: Eqs. 3.1-3.3 and the merge step).

    Parameters
    ----------
    ranges : array_like, shape (n,)
        Metres; ``inf`` or NaN where a beam returned nothing.
    angles : array_like, shape (n,)
        Beam angles in the laser frame (radians), increasing (counter-clockwise).
    xi, phi_xi, min_points, min_length, max_gap, jump_ratio, max_range, edge_tolerance
        The extraction's settings: their meaning (the thesis's ``xi`` of 3.2
        and ``phi_xi``, the run breaks, the reach) and their defaults are
        those of :class:`~cga_lessons.mapping2d.ExtractionParams`, where they
        are written once.

    Returns
    -------
    list of Segment
        In scan order, in the laser frame; empty when nothing line-like is seen.

    Raises
    ------
    InvalidInputError
        When ``ranges`` and ``angles`` do not match or the thresholds are invalid.
    """
    f = "extract_segments"
    r, a = scan(ranges, angles, f, increasing=True)
    settings = {"xi": xi, "phi_xi": phi_xi, "min_points": min_points, "min_length": min_length, "max_gap": max_gap,
                "jump_ratio": jump_ratio, "max_range": max_range, "edge_tolerance": edge_tolerance}  # fmt: skip
    return extract_unchecked(r, a, ExtractionParams(**extraction_settings(settings, f)))


def extract_unchecked(
    r, a, settings: ExtractionParams, *, func: str = "extract_segments", names: tuple = ("ranges", "angles")
):
    """:func:`extract_segments` of checked arguments (a scan from :func:`~cga_lessons.mapping2d.inputs.scan` with
    ``increasing=True`` and its :class:`~cga_lessons.mapping2d.extraction.ExtractionParams`); ``func`` and ``names``
    name the caller and its arguments in the error of a scan whose readings overflow."""
    xi, phi_xi, min_points, min_length = settings.xi, settings.phi_xi, settings.min_points, settings.min_length
    max_range, edge_tolerance = settings.max_range, settings.edge_tolerance
    r = r.copy()
    r[~np.isfinite(r) | (r <= 0) | (r >= max_range)] = np.inf
    ok = np.isfinite(r)
    if not ok.any():
        return []
    checks.magnitude(r[ok], func, names[0], why="squares overflow the line fits")
    checks.magnitude(a, func, names[1], why="squares overflow the line fits")
    index = np.flatnonzero(ok)
    pts = np.stack([r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok])], axis=1)
    dphi = float(np.median(np.diff(a)))

    groups = []
    moments = _prefix_moments(pts)
    for i0, i1 in _runs(pts, index, r, dphi, settings.max_gap, settings.jump_ratio):
        pieces = [(i0 + p, i0 + q) for p, q in _split(pts[i0 : i1 + 1], xi)]
        groups.append(_merge(moments, pieces, xi, phi_xi, min_points))

    out = []
    for run in groups:
        for i, j in run:
            if j - i + 1 < min_points:
                continue
            seg_pts = pts[i : j + 1]
            c, d, _ = fit_points(seg_pts, func, names[0])
            start = c + d * ((seg_pts[0] - c) @ d)
            end = c + d * ((seg_pts[-1] - c) @ d)
            if np.hypot(*(end - start)) < min_length:
                continue
            s_edge, start = _edge_end(c, d, start, index[i] - 1, -1, r, a, max_range, edge_tolerance)
            e_edge, end = _edge_end(c, d, end, index[j] + 1, 1, r, a, max_range, edge_tolerance)
            out.append(make_segment(start, end, len(seg_pts), point_sums(seg_pts), s_edge, e_edge))
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
