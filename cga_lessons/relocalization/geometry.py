"""Geometry for the relocalization: inputs, map and scan lines as arrays, ray casting against a line map.

:func:`as_segment_array` and :func:`prepare_map` check the segments given to
:func:`cga_lessons.relocalization.relocalize` (chapter 3 Segments or (K, 2, 2)
arrays), :func:`check_scan` a raw scan; :func:`estimate_range_noise` reads the
range noise off a scan.  :class:`MapLines` and :class:`ScanLines` hold what the
search of :mod:`cga_lessons.relocalization.search` needs; :class:`Observation`
is a scan as beams; :func:`first_hits` casts every beam of a scan from many
poses into the map (the check of :mod:`cga_lessons.relocalization.verify`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import wrap_angle

from .inputs import as_segment_array, check_pose

__all__ = [
    # the checks of inputs.py, re-exported
    "ReferenceMap",
    "prepare_map",
    "reference_map",
    "pose_error",
    "pose_errors",
    "range_noise",
    "estimate_range_noise",
    "rotation_matrix",
    "transform_points",
    "MapLines",
    "ScanLines",
    "Observation",
    "segment_distances",
    "first_hits",
    "point_segment_distances",
]


@dataclass
class ReferenceMap:
    """A map prepared once for many relocalizations: :func:`prepare_map`.

    ``segments`` (K, 2, 2) and their :class:`MapLines` (with the coverage grid, if any).
    """

    segments: np.ndarray
    lines: MapLines

    def __post_init__(self):
        self.segments = as_segment_array(self.segments, "ReferenceMap", "segments")
        checks.instance(self.lines, "ReferenceMap", "lines", MapLines, "the MapLines of the segments")
        if len(self.lines) != len(self.segments):
            raise checks.fail(
                "ReferenceMap", "lines", f"hold {len(self.lines)} segments, segments {len(self.segments)}"
            )

    def __len__(self):
        return len(self.segments)

    @property
    def coverage(self):
        """The map's coverage grid (:class:`~cga_lessons.relocalization.coverage.Coverage`) or None."""
        return self.lines.coverage


def prepare_map(map_segments, coverage=None) -> ReferenceMap:
    """Check and prepare a map (Segments or a (K, 2, 2) array) for :func:`relocalize`.

    ``coverage`` (a :class:`~cga_lessons.relocalization.coverage.Coverage` of
    the scans the map was built from) makes the beam check count only beams
    that end where the map knows something; without it every beam counts.
    """
    return reference_map(map_segments, "prepare_map", coverage=coverage)


def reference_map(map_segments, func: str, name: str = "map_segments", coverage=None) -> ReferenceMap:
    """:func:`prepare_map` for the public function ``func`` (its argument ``name``): the errors name them."""
    if isinstance(map_segments, ReferenceMap) and coverage is None:
        return map_segments
    if isinstance(map_segments, ReferenceMap):
        map_segments = map_segments.segments
    if coverage is not None:
        from .coverage import Coverage  # the coverage grid reads scans with this module's check_scan

        checks.instance(coverage, func, "coverage", Coverage, "a Coverage (build_coverage) or None")
    arr = as_segment_array(map_segments, func, name)
    return ReferenceMap(arr, MapLines(arr, coverage))


def estimate_range_noise(ranges) -> float:
    """Standard deviation (m) of a scan's range noise, from the second differences of neighbouring ranges.

    On a smooth surface ``r[i-1] - 2 r[i] + r[i+1]`` is noise with standard
    deviation ``sqrt(6) sigma``; the median absolute value (times 1.4826) over
    triples without a jump (neighbours within 0.2 m) estimates it robustly.
    Returns 0 with fewer than ten such triples.  ``inf`` or NaN: no return.

    >>> r = 3.0 + np.random.default_rng(0).normal(0.0, 0.02, 2000)
    >>> round(estimate_range_noise(r), 2)
    0.02
    """
    return range_noise(checks.array(ranges, "estimate_range_noise", "ranges", (None,), finite=False))


def range_noise(r: np.ndarray) -> float:
    """:func:`estimate_range_noise` of checked ranges (n,)."""
    with np.errstate(invalid="ignore", over="ignore"):
        d1a, d1b = r[1:-1] - r[:-2], r[2:] - r[1:-1]
        d2 = d1b - d1a
        ok = np.isfinite(d2) & (np.abs(d1a) < 0.2) & (np.abs(d1b) < 0.2)
    if ok.sum() < 10:
        return 0.0
    return float(1.4826 * np.median(np.abs(d2[ok])) / np.sqrt(6.0))


def pose_error(pose, truth):
    """Position error (m) and absolute heading error (radians) of a pose against the truth."""
    p, t = check_pose(pose, "pose_error"), check_pose(truth, "pose_error", "truth")
    out = pose_errors(p, t)
    checks.finite_result(out[0], "pose_error", "pose, truth: the position error")
    return out


def pose_errors(p, t):
    """:func:`pose_error` of checked poses."""
    p, t = np.asarray(p, float), np.asarray(t, float)
    return float(np.hypot(*(p[:2] - t[:2]))), float(abs(wrap_angle(p[2] - t[2])))


def rotation_matrix(theta) -> np.ndarray:
    """The 2x2 rotation by ``theta`` (radians)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


def transform_points(points, pose) -> np.ndarray:
    """Points ``(n, 2)`` of the laser frame in the map frame: ``R(theta) p + (x, y)`` (3.4)."""
    p = checks.magnitude(checks.array(points, "transform_points", "points", (None, 2)), "transform_points", "points")
    x, y, th = check_pose(pose, "transform_points")
    out = p @ rotation_matrix(th).T + np.array([x, y])
    return checks.finite_result(out, "transform_points", "points, pose: the result")


@dataclass
class MapLines:
    """Map segments as arrays, with what the search needs.

    Attributes
    ----------
    segments : ndarray, shape (M, 2, 2)
    start, direction, normal : ndarray, shape (M, 2)
        ``normal`` is the direction turned by -90 degrees (either face).
    length, offset, angle : ndarray, shape (M,)
        ``offset = normal . start``; ``angle`` is the direction's angle modulo pi.
    coverage : Coverage or None
        What the map knows (:mod:`cga_lessons.relocalization.coverage`).
    """

    segments: np.ndarray
    coverage: object = None

    def __post_init__(self):
        s = self.segments
        v = s[:, 1] - s[:, 0]
        self.length = np.hypot(v[:, 0], v[:, 1])
        self.start = s[:, 0]
        self.direction = v / self.length[:, None]
        self.normal = np.column_stack([self.direction[:, 1], -self.direction[:, 0]])
        self.offset = np.einsum("ij,ij->i", self.normal, self.start)
        self.angle = np.mod(np.arctan2(v[:, 1], v[:, 0]), np.pi)
        self._pair_distance = None

    def __len__(self):
        return len(self.segments)

    @property
    def pair_distance(self) -> np.ndarray:
        """Smallest distance between every two map segments, shape (M, M), float32 (computed once)."""
        if self._pair_distance is None:
            self._pair_distance = segment_distances(self.segments, self.segments).astype(np.float32)
        return self._pair_distance


def segment_distances(A, B, block: int = 256) -> np.ndarray:
    """Smallest distance between every segment of ``A`` (n, 2, 2) and of ``B`` (m, 2, 2): shape (n, m).

    Zero where two segments cross; otherwise the least distance from an end
    point of one to the other.
    """
    A = np.asarray(A, float).reshape(-1, 2, 2)
    B = np.asarray(B, float).reshape(-1, 2, 2)
    out = np.empty((len(A), len(B)))

    def point_seg(p, S):  # p (k, 2), S (m, 2, 2) -> (k, m)
        a, v = S[:, 0], S[:, 1] - S[:, 0]
        rel = p[:, None, :] - a[None]
        t = np.clip(np.einsum("kmi,mi->km", rel, v) / np.maximum(np.einsum("mi,mi->m", v, v), 1e-300), 0.0, 1.0)
        return np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1))

    def cross(o, p, q):  # z of (p - o) x (q - o), broadcast
        return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (q[..., 0] - o[..., 0])

    for i in range(0, len(A), block):
        a = A[i : i + block]
        d = np.minimum(point_seg(a[:, 0], B), point_seg(a[:, 1], B))
        d = np.minimum(d, np.minimum(point_seg(B[:, 0], a), point_seg(B[:, 1], a)).T)
        a0, a1 = a[:, None, 0], a[:, None, 1]
        b0, b1 = B[None, :, 0], B[None, :, 1]
        crossing = (np.sign(cross(a0, a1, b0)) * np.sign(cross(a0, a1, b1)) < 0) & (
            np.sign(cross(b0, b1, a0)) * np.sign(cross(b0, b1, a1)) < 0
        )
        out[i : i + block] = np.where(crossing, 0.0, d)
    return out


@dataclass
class ScanLines:
    """Scan segments in the laser frame (the sensor on each segment's left, as extracted)."""

    segments: np.ndarray

    def __post_init__(self):
        s = self.segments
        v = s[:, 1] - s[:, 0]
        self.length = np.hypot(v[:, 0], v[:, 1])
        self.direction = v / self.length[:, None]
        self.midpoint = 0.5 * (s[:, 0] + s[:, 1])
        self.angle = np.mod(np.arctan2(v[:, 1], v[:, 0]), np.pi)
        self.pair_distance = segment_distances(s, s)

    def __len__(self):
        return len(self.segments)


@dataclass
class Observation:
    """What the pose is checked against: beam directions, ranges and the laser's reach.

    Attributes
    ----------
    points : ndarray, shape (n, 2)
        Returned points in the laser frame.
    ranges : ndarray, shape (n,)
    no_return : ndarray, shape (k, 2)
        Unit directions of beams that returned nothing (laser frame).
    max_range : float
    """

    points: np.ndarray
    ranges: np.ndarray
    no_return: np.ndarray
    max_range: float

    @classmethod
    def from_scan(cls, ranges, angles, max_range):
        r = np.asarray(ranges, float)
        a = np.asarray(angles, float)
        hit = np.isfinite(r) & (r > 0) & (r < max_range)
        u = np.column_stack([np.cos(a), np.sin(a)])
        return cls(u[hit] * r[hit, None], r[hit], u[~hit], float(max_range))

    @classmethod
    def from_segments(cls, segments, spacing=0.05):
        """Points every ``spacing`` metres along segments (when no raw scan is given); no beam without return."""
        pts = []
        for a, b in segments:
            n = max(2, int(np.ceil(np.hypot(*(b - a)) / spacing)) + 1)
            pts.append(a + np.linspace(0.0, 1.0, n)[:, None] * (b - a))
        p = np.concatenate(pts) if pts else np.zeros((0, 2))
        return cls(p, np.hypot(p[:, 0], p[:, 1]), np.zeros((0, 2)), float(np.inf))


def first_hits(M: MapLines, poses, dirs, reach=np.inf, budget: int = 500_000):
    """Distance along each beam to the first map segment, and that segment, for every pose.

    Only segments that come within ``reach`` of a pose's position can be hit
    (no beam is followed further), so each pose is cast against the segments
    near it alone.

    Parameters
    ----------
    poses : ndarray, shape (C, 3)
    dirs : ndarray, shape (B, 2)
        Unit beam directions in the laser frame.
    reach : float
        Hits further than this (m) may be reported as none.
    budget : int
        Largest number of (pose, beam, segment) tests done at once (memory).

    Returns
    -------
    s_hit : ndarray, shape (C, B)
        ``inf`` where the beam meets no segment (within ``reach``).
    seg : ndarray of int, shape (C, B)
        Index of the segment hit (0 where none).
    """
    poses = np.asarray(poses, float).reshape(-1, 3)
    dirs = np.asarray(dirs, float).reshape(-1, 2)
    C, B = len(poses), len(dirs)
    s_hit = np.full((C, B), np.inf)
    seg = np.zeros((C, B), int)
    if len(M) == 0 or B == 0 or C == 0:
        return s_hit, seg
    if np.isfinite(reach):
        near = point_segment_distances(poses[:, :2], M) < reach  # (C, M)
    else:
        near = np.ones((C, len(M)), bool)
    count = near.sum(axis=1)
    order = np.argsort(~near, axis=1, kind="stable")  # near segments first, in index order
    c0 = 0
    while c0 < C:
        c1, K = c0 + 1, int(count[c0])
        while c1 < C and (c1 - c0 + 1) * B * max(K, int(count[c1])) <= budget:
            K = max(K, int(count[c1]))
            c1 += 1
        if K == 0:
            c0 = c1
            continue
        idx = order[c0:c1, :K]
        valid = np.take_along_axis(near[c0:c1], idx, axis=1)
        d, k = _cast(M.segments[idx], valid, poses[c0:c1], dirs)
        s_hit[c0:c1] = d
        seg[c0:c1] = np.take_along_axis(idx, k, axis=1)
        c0 = c1
    return s_hit, seg


def point_segment_distances(points, M: MapLines) -> np.ndarray:
    """Distance of every point (n, 2) to every map segment: shape (n, M)."""
    rel = np.asarray(points, float)[:, None, :] - M.start[None]
    s = np.clip(np.einsum("pmi,mi->pm", rel, M.direction), 0.0, M.length[None])
    return np.hypot(rel[..., 0] - s * M.direction[None, :, 0], rel[..., 1] - s * M.direction[None, :, 1])


def _cast(segs, valid, poses, dirs):
    """First hits of beams (B, 2) from each pose (C, 3) on its own segments (C, K, 2, 2): (C, B) twice.

    The tests run in float32 (a quarter of the time; distances good to about
    a micrometre at 10 m), with the differences to each pose formed in float64.
    """
    f = np.float32
    c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
    ux = (c[:, None] * dirs[None, :, 0] - s[:, None] * dirs[None, :, 1]).astype(f)[..., None]  # (C, B, 1)
    uy = (s[:, None] * dirs[None, :, 0] + c[:, None] * dirs[None, :, 1]).astype(f)[..., None]
    ex = (segs[:, :, 1, 0] - segs[:, :, 0, 0]).astype(f)[:, None, :]  # (C, 1, K)
    ey = (segs[:, :, 1, 1] - segs[:, :, 0, 1]).astype(f)[:, None, :]
    wx = (segs[:, :, 0, 0] - poses[:, None, 0]).astype(f)[:, None, :]
    wy = (segs[:, :, 0, 1] - poses[:, None, 1]).astype(f)[:, None, :]
    inv = ux * ey
    inv -= uy * ex  # the denominator cross(u, e), (C, B, K)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        np.divide(f(1.0), inv, out=inv)
        dist = (wx * ey - wy * ex) * inv  # along the beam
        q = wx * uy
        q -= wy * ux
        q *= inv  # along the segment, 0..1 on it
        bad = ~np.isfinite(dist)
        bad |= dist <= 0
        bad |= q < 0
        bad |= q > 1
    bad |= ~valid[:, None, :]
    dist[bad] = np.inf
    k = np.argmin(dist, axis=2)
    return np.take_along_axis(dist, k[..., None], axis=2)[..., 0].astype(float), k
