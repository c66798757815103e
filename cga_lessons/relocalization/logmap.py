"""A line map from scans at known poses, for measuring the relocalization on real logs.

The relocalization is judged on held-out scans of a log against a map of the
rest of it, made at the logged (corrected) poses, so the map lies in the frame
of the truth.  :func:`line_map_from_scans` makes that map without the chapter 3
builder's corrections (there is nothing to correct at known poses) and without
depending on them: every scan's segments (Eqs. 3.1-3.3,
:func:`cga_lessons.mapping2d.lines.extract_segments`) are placed at the scan's pose
(3.4), and the segments that lie on one wall are merged into one map line.

Merging, longest segment first: a segment gathers the others that run within
``angle_tol`` of it with both ends within ``offset_tol`` of its line, and whose
extent along the line overlaps its own or comes within ``gap`` of it (grown
until nothing more joins); the map line is their length-weighted mean line,
between the ends its segments agree on (:func:`robust_end`).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import extract_segments

from .geometry import range_noise, transform_points
from .inputs import as_segment_array, check_scans_at_poses

__all__ = ["scan_segments_at_poses", "merge_segments", "robust_end", "line_map_from_scans"]


def scan_segments_at_poses(scans, poses, *, max_range: float) -> tuple[np.ndarray, np.ndarray]:
    """Every scan's segments in the map frame: ``(segments (N, 2, 2), n_points (N,))``.

    Each scan is cut with the extraction threshold ``xi`` of
    :func:`cga_lessons.relocalization.relocalize` (3 cm, or three times the
    scan's range noise if larger), so map and scans are made alike.
    """
    func = "scan_segments_at_poses"
    scans, poses = check_scans_at_poses(scans, poses, func)
    max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    segs, counts = [], []
    for (r, a), pose in zip(scans, poses):
        noise = range_noise(np.where(r < max_range, r, np.inf))
        for s in extract_segments(r, a, max_range=max_range, xi=max(0.03, 3 * noise)):
            segs.append(transform_points(np.array([s.start, s.end]), pose))
            counts.append(s.n_points)
    return np.array(segs, float).reshape(-1, 2, 2), np.array(counts, int)


def merge_segments(
    segments, *, angle_tol: float = np.radians(5.0), offset_tol: float = 0.05, gap: float = 0.3, support=None
):
    """Segments (N, 2, 2) that lie on one wall merged into one line each.

    Returns ``(lines (M, 2, 2), support (M,))``, M <= N: ``support`` sums the
    ``support`` of the merged segments (default 1 each: how many segments
    each line gathered).

    Parameters
    ----------
    angle_tol : float
        Largest angle (radians) between segments of one wall: 5 degrees, the
        extractor's own ``phi_xi`` for merging neighbouring pieces of a scan.
    offset_tol : float
        Largest distance (m) of a joining segment's midpoint from the line: 5 cm,
        about 2.5 times the spread of the logs' points about their walls
        (:func:`~cga_lessons.relocalization.coverage.map_noise`: 1.4 cm on
        Intel, 2.1 cm on ACES) and half the thickness of a thin wall, whose two
        faces stay apart.  The midpoint, not the ends: a segment's direction is
        only fixed to ``angle_tol``, and its ends move by half its length times
        that; a test on the ends (as before) asked a 1.5 m segment for 4 degrees
        and kept one wall's segments from two places apart (ACES, the wall at
        scans 158-168: two segments 4.4 degrees apart, each then dropped by
        ``min_support``).  Measured with ``benchmarks/bench_reloc_logs.py``
        (six logs, seeds 0-3): runs of three 1,235 -> 1,248 of 1,444 located,
        confidently wrong runs 21 -> 8; single scans 277 -> 275 of 361, wrong
        9 -> 10.
    gap : float
        Segments further apart than this (m) along the line stay apart (a
        door, 0.7 m or more, is never bridged); 0.3 m is the extractor's
        ``max_gap`` at the longest beams' spacing.
    """
    S = as_segment_array(segments, "merge_segments", allow_empty=True)
    sup = np.ones(len(S), int) if support is None else np.asarray(support, int).reshape(len(S))
    if not len(S):
        return S, sup
    v = S[:, 1] - S[:, 0]
    length = np.hypot(v[:, 0], v[:, 1])
    ang = np.mod(np.arctan2(v[:, 1], v[:, 0]), np.pi)
    mids = S.mean(axis=1)
    free = np.ones(len(S), bool)
    out, count = [], []
    for i in np.argsort(-length, kind="stable"):
        if not free[i]:
            continue
        d = np.array([np.cos(ang[i]), np.sin(ang[i])])
        n = np.array([-d[1], d[0]])
        c = n @ S[i, 0]
        dang = np.abs(np.mod(ang - ang[i] + np.pi / 2, np.pi) - np.pi / 2)
        off = np.abs(mids @ n - c)  # the midpoints' offsets
        cand = free & (dang < angle_tol) & (off < offset_tol)
        t = S @ d
        lo, hi = t.min(axis=1), t.max(axis=1)
        members = np.zeros(len(S), bool)
        members[i] = True
        a, b = lo[i], hi[i]
        while True:
            join = cand & ~members & (hi >= a - gap) & (lo <= b + gap)
            if not join.any():
                break
            members |= join
            a, b = min(a, lo[join].min()), max(b, hi[join].max())
        w = length[members]
        dm = np.angle(np.sum(w * np.exp(2j * (ang[members] - ang[i])))) / 2 + ang[i]
        d = np.array([np.cos(dm), np.sin(dm)])
        n = np.array([-d[1], d[0]])
        c = np.sum(w * (mids[members] @ n)) / w.sum()
        t = np.sort(S[members] @ d, axis=1)
        out.append([c * n + robust_end(-t[:, 0], gap) * -d, c * n + robust_end(t[:, 1], gap) * d])
        count.append(int(sup[members].sum()))
        free[members] = False
    return np.array(out), np.array(count)


def robust_end(ends, gap: float) -> float:
    """Where a wall ends, from the ends (k,) that its segments reach along it (the largest is the wall's end).

    The largest is biased outward: each segment's last point carries the
    range noise and the extraction's cut, and the largest of many such ends
    lies about two standard deviations out.  The median of the ends within
    ``gap`` of the largest (the segments that saw the end, not an occlusion
    short of it) is not; with one such segment it is its end.
    """
    ends = np.asarray(ends, float)
    near = ends[ends >= ends.max() - gap]
    return float(np.median(near))


def line_map_from_scans(scans, poses, *, max_range: float, min_support: int = 2, **merge_kw) -> np.ndarray:
    """The line map (M, 2, 2) of scans at known poses: :func:`scan_segments_at_poses`, then :func:`merge_segments`.

    Only lines gathered from at least ``min_support`` segments are kept: 2,
    a wall seen from two places (or cut in two by an occlusion); what one
    scan alone saw (a person, a door swinging, a chair) is left out.  On the
    Intel log this keeps about 600 of 900 lines, and drops mostly short ones.

    Examples
    --------
    >>> from cga_lessons.mapping2d.laser import load_scene, simulate_scan
    >>> from cga_lessons.relocalization.geometry import MapLines, point_segment_distances
    >>> room = load_scene("room")
    >>> poses = np.array([[1.0, 1.0, 0.0], [1.5, 1.5, 1.6], [2.0, 2.0, 3.1], [2.5, 1.0, -1.6]])
    >>> rng = np.random.default_rng(0)
    >>> lines = line_map_from_scans([simulate_scan(room, p, rng) for p in poses], poses, max_range=5.0)
    >>> len(lines)  # south, north and west walls, seen thrice; the far east wall only in pieces seen once
    3
    >>> ends = lines.reshape(-1, 2)  # every line lies on a wall of the room (1 cm range noise)
    >>> bool(point_segment_distances(ends, MapLines(room.walls)).min(axis=1).max() < 0.05)
    True
    """
    segs, _ = scan_segments_at_poses(scans, poses, max_range=max_range)
    lines, support = merge_segments(segs, **merge_kw)
    return lines[support >= min_support]
