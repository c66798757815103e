"""The laser's part of the fused 3D map: virtual walls (figures 4.5, 4.6) and posts (section 4.2.3).

A line of the laser map becomes a *virtual wall*: the vertical plane through
it (2.77), drawn from the floor to a stated height.  The laser cannot tell a
wall from furniture at its height; the thesis uses these walls to visualise,
and relies on the cameras for what lies outside the laser's plane.

Posts are thin and round: a few returns that stand free of what is behind
them.  Their centres come from a circle fit of known radius.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

__all__ = ["VirtualWall", "virtual_wall", "fit_post_center", "laser_posts", "group_detections"]

_UP = np.array([0.0, 0.0, 1.0])


@dataclass
class VirtualWall:
    """A laser line of the map shown as a wall: its trace at laser height and the vertical plane through it.

    Attributes
    ----------
    start, end : ndarray (3,)
        The segment's ends at the laser's height (unified frame).
    pair : Multivector
        ``a ^ b`` (2.68) of the ends.
    plane : Multivector
        The vertical plane ``e ^ a ^ b ^ a_up`` (2.77), dual form.
    corners : ndarray (4, 3)
        The drawn wall: the segment from the floor to ``height``.
    height : float
    """

    start: np.ndarray
    end: np.ndarray
    pair: object
    plane: object
    corners: np.ndarray
    height: float


def virtual_wall(start_xy, end_xy, laser_height: float, height: float = 1.0) -> VirtualWall:
    """The virtual wall of a laser segment (figure 4.6): a vertical plane through it, ``height`` metres tall.

    The laser cannot tell a wall from a box at its height (section 4.2.3); the
    height is a drawing choice (default 1 m: tall enough to read the room,
    low enough not to hide the objects in a view from above).

    >>> w = virtual_wall([0, 0], [2, 0], 0.35)
    >>> n, d = cga.plane_normal_distance(w.plane); (abs(n) + 0.0).round(12).tolist(), round(abs(d), 12)
    ([0.0, 1.0, 0.0], 0.0)
    """
    f = "virtual_wall"
    laser_height = checks.real(laser_height, f, "laser_height")
    a = np.array([*checks.array(start_xy, f, "start_xy", (2,)), laser_height])
    b = np.array([*checks.array(end_xy, f, "end_xy", (2,)), laser_height])
    height = checks.real(height, f, "height", low=0.0, strict_low=True)
    P = cga.plane_from_points(a, b, a + _UP)  # (2.77): e ^ a ^ b ^ a_up
    lo, hi = np.array([0.0, 0.0, -laser_height]), np.array([0.0, 0.0, height - laser_height])
    corners = np.array([a + lo, b + lo, b + hi, a + hi])
    return VirtualWall(a, b, cga.point_pair(a, b), P, corners, float(height))


def fit_post_center(points, origin, radius: float, iterations: int = 10) -> np.ndarray:
    """Centre (2,) of a circle of known ``radius`` through laser points (k, 2) seen from ``origin``.

    Least squares of ``|p_i - c| - radius`` by Gauss-Newton, started behind the
    points' centroid (the laser sees the near side).
    """
    p = checks.rows(points, "fit_post_center", "points", 2)
    if len(p) < 2:
        raise checks.degenerate("fit_post_center", "points", f"need at least 2 points, got {len(p)}")
    m = p.mean(axis=0)
    away = m - np.asarray(origin, float)
    c = m + radius * away / max(np.linalg.norm(away), 1e-12)
    for _ in range(iterations):
        v = c - p
        dist = np.linalg.norm(v, axis=1)
        J = v / np.maximum(dist, 1e-12)[:, None]
        step, *_ = np.linalg.lstsq(J, -(dist - radius), rcond=None)
        c = c + step
        if np.linalg.norm(step) < 1e-9:
            break
    return c


def laser_posts(ranges, angles, radius: float = 0.05, max_width: float = 0.25, jump: float = 0.15, min_points=3):
    """Post candidates in one scan (laser frame): short runs of returns that stand free of what is behind.

    A run is a maximal sequence of returns whose neighbours differ by less
    than ``jump`` metres in range; it is a post when it spans at most
    ``max_width``, has at least ``min_points`` returns and the beams on both
    sides reach at least ``jump`` farther (or nothing).  Each centre comes from
    :func:`fit_post_center` with the posts' known ``radius``.

    Returns
    -------
    centres : ndarray (k, 2)
    counts : ndarray (k,)
    """
    f = "laser_posts"
    r = checks.array(ranges, f, "ranges", (None,), finite=False)  # inf: no return
    a = checks.array(angles, f, "angles", (None,))
    checks.same_length(f, ranges=r, angles=a)
    fin = np.isfinite(r)
    out, counts = [], []
    i, n = 0, len(r)
    while i < n:
        if not fin[i]:
            i += 1
            continue
        j = i
        while j + 1 < n and fin[j + 1] and abs(r[j + 1] - r[j]) < jump:
            j += 1
        pts = np.column_stack([r[i : j + 1] * np.cos(a[i : j + 1]), r[i : j + 1] * np.sin(a[i : j + 1])])
        free = all(k < 0 or k >= n or not fin[k] or r[k] > r[i if k < i else j] + jump for k in (i - 1, j + 1))
        if free and len(pts) >= min_points and np.linalg.norm(pts[-1] - pts[0]) <= max_width:
            out.append(fit_post_center(pts, (0.0, 0.0), radius))
            counts.append(len(pts))
        i = j + 1
    return np.array(out).reshape(-1, 2), np.array(counts, int)


def group_detections(points, radius: float):
    """Greedy grouping of points (k, 3) within ``radius`` of a group's running mean: list of index arrays."""
    groups, means = [], []
    for i, p in enumerate(points):
        d = [np.linalg.norm(p[:2] - m[:2]) for m in means]
        if d and min(d) < radius:
            g = int(np.argmin(d))
            groups[g].append(i)
            means[g] = points[groups[g]].mean(axis=0)
        else:
            groups.append([i])
            means.append(p.copy())
    return [np.array(g) for g in groups]
