"""A scan's returns as points: in the laser frame, and a sequence of scans placed in the world with their poses
(chapter 3, section 3.1; a pose composed with the laser's mount, the rigid motion 3.4)."""

from __future__ import annotations

import numpy as np

from cga_lessons import checks

from .inputs import pose, reach, scan, scan_list
from .poses import compose_unchecked

__all__ = ["scan_points", "scan_points_unchecked", "scans_to_world"]


def scan_points(ranges, angles):
    """Cartesian points of the returning beams in the laser frame.

    Returns
    -------
    points : ndarray, shape (k, 2)
    index : ndarray of int, shape (k,)
        Beam index of each point (beams with no return, inf or NaN, are dropped).
    """
    r, a = scan(ranges, angles, "scan_points")
    return scan_points_unchecked(r, a)


def scan_points_unchecked(r, a):
    """:func:`scan_points` of checked arrays."""
    ok = np.isfinite(r) & (r > 0)
    idx = np.flatnonzero(ok)
    return np.stack([r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok])], axis=1), idx


def scans_to_world(scans, poses, max_range: float = np.inf, mount=(0.0, 0.0, 0.0), step: int = 1) -> np.ndarray:
    """All the points of a sequence of scans placed in the world with the given robot poses.

    Parameters
    ----------
    scans : sequence of (ranges, angles)
    poses : array_like, shape (T, 3)
    max_range : float
        Readings at or beyond this (m) are left out.
    mount : array_like, shape (3,)
        The laser's pose on the robot.
    step : int
        Use every ``step``-th scan.

    Returns
    -------
    ndarray, shape (k, 2)
    """
    f = "scans_to_world"
    scans = scan_list(scans, f)
    poses = checks.batch(poses, f, "poses", (3,))[0]
    checks.same_length(f, scans=scans, poses=poses)
    max_range = reach(max_range, f, "max_range")
    mount = pose(mount, f, "mount")
    step = checks.integer(step, f, "step", low=1)
    out = []
    for (r, a), where in list(zip(scans, poses))[::step]:
        pts, _ = scan_points_unchecked(np.where(r < max_range, r, np.inf), a)
        lp = compose_unchecked(where, mount)
        c, s = np.cos(lp[2]), np.sin(lp[2])
        out.append(pts @ np.array([[c, s], [-s, c]]) + lp[:2])
    return checks.finite_result(np.concatenate(out) if out else np.zeros((0, 2)), f, "scans, poses")
