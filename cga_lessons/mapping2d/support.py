"""How points lie on map segments: their distances, and the score that checks a correction and verifies a revisit."""

from __future__ import annotations

import numpy as np

from .geometry import SegmentSet
from .poses import compose_unchecked

__all__ = ["scan_support", "segment_distances"]


def scan_support(points, pose, mount, lines: SegmentSet, idx, distance: float) -> float:
    """How well the scan's points (laser frame) at ``pose`` lie on the map segments ``lines[idx]``.

    The laser is at ``mount`` on the robot.  Each point within ``D = distance``
    (m) of a segment counts ``1 - (d / D)^2`` (``d`` its distance): a point on
    the line counts one, the score falls smoothly to zero at ``D``, so of two
    poses the better aligned scores higher even when both put every point
    within ``D``.
    """
    if len(points) == 0 or len(idx) == 0:
        return 0.0
    lp = compose_unchecked(pose, mount)
    c, s_ = np.cos(lp[2]), np.sin(lp[2])
    q = points @ np.array([[c, s_], [-s_, c]]) + lp[:2]
    a, v = lines.start[idx], lines.end[idx] - lines.start[idx]
    rx, ry = q[:, 0, None] - a[None, :, 0], q[:, 1, None] - a[None, :, 1]  # (points, lines)
    t = np.clip((rx * v[:, 0] + ry * v[:, 1]) / (v[:, 0] ** 2 + v[:, 1] ** 2), 0.0, 1.0)
    rx -= t * v[:, 0]
    ry -= t * v[:, 1]
    d2 = (rx * rx + ry * ry).min(axis=1)  # squared distance to the nearest segment
    return float(np.sum(np.maximum(0.0, 1.0 - d2 / distance**2)))


def segment_distances(centre, lines: SegmentSet) -> np.ndarray:
    """Distance (m) from the point ``centre`` (2,) to each segment of ``lines``."""
    if len(lines) == 0:
        return np.zeros(0)
    v = lines.end - lines.start
    t = np.clip(np.einsum("ij,ij->i", centre - lines.start, v) / np.einsum("ij,ij->i", v, v), 0, 1)
    return np.hypot(*(lines.start + t[:, None] * v - centre).T)
