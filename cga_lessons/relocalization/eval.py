"""Measuring the relocalization: random poses in a scene, and held-out scans of a real log.

* :func:`random_free_poses`: poses drawn uniformly in the free space of a scene
  (inside the building, outside every obstacle, clear of the walls);
* :func:`evaluate_poses`: relocalize a simulated scan from each pose and
  compare with the simulator's truth; an ambiguous answer is checked for a
  *witness*: a clearly different candidate whose noise-free scan is the same
  as the one from the true pose (then no method could tell them apart);
* :func:`map_from_log` / :func:`evaluate_log`: relocalize scans of a CARMEN
  log against the line map built from the rest of the log at its logged
  poses, the logged poses as the truth.

A relocalization is a *success* when it is confident (``status == "ok"``)
and within 10 cm and 2 degrees of the truth; *confidently wrong* when it is
confident and not within them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import Scene, returns_reach, simulate_scan

from .coverage import build_coverage
from .geometry import ReferenceMap, pose_error, prepare_map
from .logmap import line_map_from_scans
from .relocalizer import relocalize

__all__ = [
    "POSITION_TOLERANCE",
    "HEADING_TOLERANCE",
    "random_free_poses",
    "scan_agreement",
    "Evaluation",
    "evaluate_poses",
    "map_from_log",
    "reference_from_log",
    "held_out_map_indices",
    "evaluate_log",
]

#: A relocalization within this distance (m) and heading (radians) of the truth is right.
POSITION_TOLERANCE = 0.10
HEADING_TOLERANCE = np.radians(2.0)


def _inside_polygon(points, poly) -> np.ndarray:
    """Even-odd rule: which points (n, 2) lie inside the closed polygon (k, 2)."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    a, b = poly, np.roll(poly, -1, axis=0)
    crosses = (a[None, :, 1] > y) != (b[None, :, 1] > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
    return np.sum(crosses & (x < xc), axis=1) % 2 == 1


def random_free_poses(scene: Scene, n: int, rng, clearance: float = 0.3) -> np.ndarray:
    """``n`` poses drawn uniformly in the free space of a scene, headings uniform.

    A position is free when it lies outside every polygon, at least
    ``clearance`` from every wall, and inside the building: rays in 16
    directions all meet a wall.

    Returns
    -------
    ndarray, shape (n, 3)
    """
    if rng is None:
        raise InvalidInputError("random_free_poses: pass rng=numpy.random.default_rng(seed)")
    walls = scene.walls
    lo, hi = walls.reshape(-1, 2).min(axis=0), walls.reshape(-1, 2).max(axis=0)
    out = []
    for _ in range(1000):
        p = rng.uniform(lo, hi, size=(4 * n, 2))
        ok = np.ones(len(p), bool)
        for poly in scene.polygons:
            ok &= ~_inside_polygon(p, poly)
        a, v = walls[:, 0], walls[:, 1] - walls[:, 0]
        rel = p[:, None, :] - a[None]
        t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.einsum("wi,wi->w", v, v), 0.0, 1.0)
        ok &= np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1)).min(axis=1) >= clearance
        for q in p[ok]:
            r, _ = simulate_scan(walls, [q[0], q[1], 0.0], n_beams=16, fov=2 * np.pi * 15 / 16, max_range=1e6)
            if np.all(np.isfinite(r)):
                out.append(q)
            if len(out) == n:
                heading = rng.uniform(-np.pi, np.pi, n)
                return np.column_stack([np.array(out), heading])
    raise InvalidInputError(f"random_free_poses: scene {scene.name!r} has too little free space")


def scan_agreement(walls, pose_a, pose_b, tolerance: float = 0.03, **scan_kw):
    """Fraction of beams on which the noise-free scans from two poses agree.

    A beam agrees when both scans have no return there or their ranges differ
    by less than ``tolerance``.  ``pose_b`` may be one pose (3,) (a float is
    returned) or several (k, 3) (a list of k fractions).
    """
    ra, _ = simulate_scan(walls, pose_a, **scan_kw)
    many = np.ndim(pose_b) == 2
    out = []
    for pb in np.atleast_2d(pose_b):
        rb, _ = simulate_scan(walls, pb, **scan_kw)
        both_none = ~np.isfinite(ra) & ~np.isfinite(rb)
        with np.errstate(invalid="ignore"):
            close = np.abs(ra - rb) < tolerance
        out.append(float(np.mean(both_none | close)))
    return out if many else out[0]


@dataclass
class Evaluation:
    """Per-pose results of :func:`evaluate_poses` or :func:`evaluate_log` (arrays of length n).

    Attributes
    ----------
    truth, pose : ndarray, shape (n, 3)
        ``pose`` is NaN where no pose was returned (a failure).
    status : ndarray of str
    position_error, heading_error : ndarray
        m and radians; ``inf`` without a pose.
    n_lines : ndarray of int
        Segments extracted from the scan.
    score : ndarray
    witness : ndarray
        For ambiguous results: the largest scan agreement between the true
        pose and a tied, clearly different candidate (NaN when not computed).
    seconds : ndarray
        Time of each relocalization.
    """

    truth: np.ndarray
    pose: np.ndarray
    status: np.ndarray
    position_error: np.ndarray
    heading_error: np.ndarray
    n_lines: np.ndarray
    score: np.ndarray
    witness: np.ndarray
    seconds: np.ndarray
    results: list = field(default_factory=list, repr=False)

    def take(self, index) -> Evaluation:
        """The evaluation of some of the poses only (``index``: integer array or boolean mask)."""
        idx = np.arange(len(self.status))[index]
        return Evaluation(
            self.truth[idx],
            self.pose[idx],
            self.status[idx],
            self.position_error[idx],
            self.heading_error[idx],
            self.n_lines[idx],
            self.score[idx],
            self.witness[idx],
            self.seconds[idx],
            [self.results[i] for i in idx] if self.results else [],
        )

    @property
    def right(self) -> np.ndarray:
        """The returned pose is within the tolerances (whatever the status)."""
        return (self.position_error < POSITION_TOLERANCE) & (self.heading_error < HEADING_TOLERANCE)

    @property
    def success(self) -> np.ndarray:
        """Confident and right."""
        return (self.status == "ok") & self.right

    @property
    def confidently_wrong(self) -> np.ndarray:
        return (self.status == "ok") & ~self.right

    def indistinguishable(self, agreement: float = 0.98) -> np.ndarray:
        """Ambiguous with a witness: a clearly different pose whose scan agrees on at least ``agreement`` of beams."""
        return (self.status == "ambiguous") & (np.nan_to_num(self.witness, nan=0.0) >= agreement)

    def summary(self, agreement: float = 0.98) -> dict:
        """Counts and rates: ``n``, ``success``, ``confidently_wrong``, ``ambiguous``, ``indistinguishable``,
        ``failed``, ``success_rate``, ``success_rate_distinguishable`` and ``median_ms``."""
        n = len(self.status)
        ind = int(self.indistinguishable(agreement).sum())
        ok = int(self.success.sum())
        return {
            "n": n,
            "success": ok,
            "confidently_wrong": int(self.confidently_wrong.sum()),
            "ambiguous": int((self.status == "ambiguous").sum()),
            "indistinguishable": ind,
            "failed": int((self.status == "failed").sum()),
            "success_rate": ok / n if n else float("nan"),
            "success_rate_distinguishable": ok / (n - ind) if n > ind else float("nan"),
            "median_ms": float(np.median(self.seconds) * 1000) if n else float("nan"),
        }


def _record(results, truths, walls, scan_kw, witness, ratio):
    n = len(results)
    pose = np.full((n, 3), np.nan)
    perr = np.full(n, np.inf)
    herr = np.full(n, np.inf)
    wit = np.full(n, np.nan)
    for i, (r, t) in enumerate(zip(results, truths)):
        if r.pose is not None:
            pose[i] = r.pose
            perr[i], herr[i] = pose_error(r.pose, t)
        if witness and r.status == "ambiguous" and walls is not None:
            tied = [
                c.pose
                for c in r.candidates
                if c.score >= ratio * r.score
                and (
                    pose_error(c.pose, t)[0] > 2 * POSITION_TOLERANCE
                    or pose_error(c.pose, t)[1] > 2 * HEADING_TOLERANCE
                )
            ]
            wit[i] = max(scan_agreement(walls, t, np.array(tied), **scan_kw)) if tied else 0.0
    return pose, perr, herr, wit


def evaluate_poses(
    scene: Scene,
    map_segments,
    poses,
    rng,
    *,
    range_noise: float = 0.01,
    max_range: float = 5.0,
    n_beams: int = 361,
    fov: float = np.pi,
    witness: bool = True,
    **relocalize_kw,
) -> Evaluation:
    """Relocalize a simulated scan from each pose against a map; compare with the truth.

    Parameters
    ----------
    scene : Scene
        The world the scans are simulated in.
    map_segments : Segments, (M, 2, 2) array or ReferenceMap
        The map to relocalize in (the scene's walls, or a map built from scans).
    poses : array_like, shape (n, 3)
        True laser poses.
    rng : numpy.random.Generator
        Range noise.
    range_noise, max_range, n_beams, fov
        The simulated laser (:func:`cga_lessons.mapping2d.laser.simulate_scan`).
    witness : bool
        Look for a witness of every ambiguous result (see :class:`Evaluation`).
    **relocalize_kw
        Passed to :func:`cga_lessons.relocalization.relocalize`.
    """
    poses = np.asarray(poses, float).reshape(-1, 3)
    ref = prepare_map(map_segments)
    scan_kw = dict(n_beams=n_beams, fov=fov, max_range=max_range)
    results, secs, n_lines, scores = [], [], [], []
    for p in poses:
        scan = simulate_scan(scene, p, rng, range_noise=range_noise, **scan_kw)
        t0 = time.perf_counter()
        r = relocalize(ref, scan=scan, max_range=max_range, **relocalize_kw)
        secs.append(time.perf_counter() - t0)
        results.append(r)
        n_lines.append(len(r.scan_segments))
        scores.append(r.score)
    ratio = relocalize_kw.get("ambiguity_ratio", 0.98)
    pose, perr, herr, wit = _record(results, poses, scene.walls, scan_kw, witness, ratio)
    status = np.array([r.status for r in results])
    return Evaluation(
        poses, pose, status, perr, herr, np.array(n_lines), np.array(scores), wit, np.array(secs), results
    )


def map_from_log(log, indices, *, max_range: float = 8.0) -> list:
    """The line map of the scans ``indices`` of a log placed at their logged poses (no correction).

    Uses :func:`cga_lessons.mapping2d.build_map` with the logged poses as the
    odometry and every correction switched off, so the map lies in the frame
    of the logged poses (checked).

    Returns
    -------
    list of Segment
    """
    from cga_lessons.mapping2d import build_map

    idx = np.asarray(indices, int)
    res = build_map(
        [log.scans[i] for i in idx],
        log.poses[idx],
        max_range=max_range,
        t_xi=0.0,
        theta_max=0.0,
        loop_closure=False,
        adjust=False,
    )
    if not np.allclose(res.poses, log.poses[idx], atol=1e-6):
        raise InvalidInputError("map_from_log: build_map moved the logged poses; the map would not match the truth")
    return res.segments


def reference_from_log(
    log, indices, *, max_range: float = 8.0, coverage: bool = True, builder: bool = False
) -> ReferenceMap:
    """The map of the scans ``indices`` of a log at their logged poses, prepared for relocalization.

    The lines come from :func:`cga_lessons.relocalization.logmap.line_map_from_scans`
    (each scan's segments at its pose, merged per wall), or with ``builder``
    from :func:`map_from_log` (chapter 3's builder with its corrections off).
    With ``coverage`` the map also carries the coverage grid of the same scans
    (:func:`cga_lessons.relocalization.coverage.build_coverage`), so that
    beams ending where those scans never looked do not count.
    """
    idx = np.asarray(indices, int)
    if idx.size == 0 or idx.min() < 0 or idx.max() >= len(log):
        raise InvalidInputError(f"reference_from_log: indices must be non-empty and within 0..{len(log) - 1}")
    scans, poses = [log.scans[i] for i in idx], log.poses[idx]
    if builder:
        segs = np.array([[s.start, s.end] for s in map_from_log(log, idx, max_range=max_range)], float)
    else:
        segs = line_map_from_scans(scans, poses, max_range=max_range)
    cov = build_coverage(scans, poses, max_range=max_range, segments=segs) if coverage else None
    return prepare_map(segs.reshape(-1, 2, 2), cov)


def held_out_map_indices(n: int, test_indices, exclude: int, map_step: int) -> np.ndarray:
    """The scans of a log of ``n`` scans the map is built from: every ``map_step``-th of those more than
    ``exclude`` scans away from every test scan."""
    keep = np.ones(n, bool)
    for k in np.asarray(test_indices, int).ravel():
        keep[max(0, k - exclude) : k + exclude + 1] = False
    return np.flatnonzero(keep)[::map_step]


def evaluate_log(
    log,
    test_indices,
    *,
    exclude: int = 2,
    map_step: int = 2,
    max_range: float | None = None,
    coverage: bool = True,
    **relocalize_kw,
):
    """Relocalize held-out scans of a log against the map built from the rest of it.

    The map uses every ``map_step``-th scan that is more than ``exclude``
    scans away from every test scan; the truth is the logged pose.  With
    ``coverage`` the map carries the coverage grid of its scans
    (:func:`reference_from_log`).  ``max_range`` (m) is the laser's reach for
    the map and the scans; None: the log's own
    (:func:`cga_lessons.mapping2d.laser_facts.returns_reach`, the distance within which
    99 % of its returns fall).

    Returns
    -------
    evaluation : Evaluation
        (``witness`` is not computed: there is no simulator.)
    map_segments : ndarray, shape (M, 2, 2)
    """
    test = np.asarray(test_indices, int)
    if test.size == 0 or test.min() < 0 or test.max() >= len(log):
        raise InvalidInputError(f"evaluate_log: test_indices must be non-empty and within 0..{len(log) - 1}")
    max_range = returns_reach(log.ranges) if max_range is None else max_range
    ref = reference_from_log(
        log, held_out_map_indices(len(log), test, exclude, map_step), max_range=max_range, coverage=coverage
    )
    segs = ref.segments
    results, secs = [], []
    for k in test:
        t0 = time.perf_counter()
        results.append(relocalize(ref, scan=log.scans[k], max_range=max_range, **relocalize_kw))
        secs.append(time.perf_counter() - t0)
    truths = log.poses[test]
    pose, perr, herr, wit = _record(results, truths, None, {}, False, 0.98)
    ev = Evaluation(
        truths,
        pose,
        np.array([r.status for r in results]),
        perr,
        herr,
        np.array([len(r.scan_segments) for r in results]),
        np.array([r.score for r in results]),
        wit,
        np.array(secs),
        results,
    )
    return ev, segs
