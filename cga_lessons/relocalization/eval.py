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
confident and not within them (:mod:`~cga_lessons.relocalization.evaluation`).
"""

from __future__ import annotations

import time

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import Scene, returns_reach, simulate_scan

from .coverage import GRID_CLEARANCE, GRID_RESOLUTION, coverage_grid
from .evaluation import Evaluation, record_results
from .geometry import ReferenceMap, reference_map
from .inputs import check_indices, check_laser, check_log, check_scans_at_poses, check_scene
from .logmap import line_map_from_scans
from .params import check_relocalize_kw
from .relocalizer import relocalize

__all__ = [
    "random_free_poses",
    "evaluate_poses",
    "map_from_log",
    "reference_from_log",
    "held_out_map_indices",
    "evaluate_log",
]


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
    func = "random_free_poses"
    check_scene(scene, func)
    n = checks.integer(n, func, "n", low=1)
    checks.generator(rng, func)
    clearance = checks.real(clearance, func, "clearance", low=0.0)
    walls = scene.walls
    lo, hi = walls.reshape(-1, 2).min(axis=0), walls.reshape(-1, 2).max(axis=0)
    if clearance >= np.hypot(*(hi - lo)) / 2:  # no point inside the walls is that far from all of them
        problem = f"{clearance} m: no place in scene {scene.name!r} is that far from every wall"
        raise checks.fail(func, "clearance", problem)
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
    raise checks.fail(func, "scene, clearance", f"scene {scene.name!r} has too little free space {clearance} m clear")


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
    func = "evaluate_poses"
    check_scene(scene, func)
    ref = reference_map(map_segments, func)
    poses, _ = checks.batch(poses, func, "poses", (3,))
    checks.magnitude(poses[:, :2], func, "poses")
    checks.generator(rng, func)
    laser = check_laser(func, range_noise=range_noise, max_range=max_range, n_beams=n_beams, fov=fov)
    range_noise, max_range = laser.pop("range_noise"), laser["max_range"]
    witness = checks.flag(witness, func, "witness")
    relocalize_kw = check_relocalize_kw(relocalize_kw, func)
    scan_kw = laser
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
    pose, perr, herr, wit = record_results(results, poses, scene.walls, scan_kw, witness, ratio)
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
        raise checks.fail("map_from_log", "log", "build_map moved the logged poses; the map would not match the truth")
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
    func = "reference_from_log"
    idx = check_indices(indices, func, "indices", len(check_log(log, func)))
    max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    coverage = checks.flag(coverage, func, "coverage")
    builder = checks.flag(builder, func, "builder")
    return log_reference(log, idx, max_range, coverage, builder, func)


def log_reference(log, idx, max_range: float, coverage: bool, builder: bool, func: str) -> ReferenceMap:
    """:func:`reference_from_log` of checked arguments, in the name of ``func``."""
    scans, poses = [log.scans[i] for i in idx], log.poses[idx]
    if builder:
        segs = np.array([[s.start, s.end] for s in map_from_log(log, idx, max_range=max_range)], float)
    else:
        segs = line_map_from_scans(scans, poses, max_range=max_range)
    if not len(segs):
        raise checks.fail(func, "log", f"its scans {idx.tolist()} make no map line (a wall seen twice)")
    cov = None
    if coverage:
        checked, poses = check_scans_at_poses(scans, poses, func)
        cov = coverage_grid(checked, poses, max_range, GRID_RESOLUTION, GRID_CLEARANCE, segs, func)
    return reference_map(segs.reshape(-1, 2, 2), func, "log", cov)


def held_out_map_indices(n: int, test_indices, exclude: int, map_step: int) -> np.ndarray:
    """The scans of a log of ``n`` scans the map is built from: every ``map_step``-th of those more than
    ``exclude`` scans away from every test scan."""
    func = "held_out_map_indices"
    n = checks.integer(n, func, "n", low=0)
    test = check_indices(test_indices, func, "test_indices", n, at_least=0)
    exclude = checks.integer(exclude, func, "exclude", low=0)
    return held_out(n, test, exclude, checks.integer(map_step, func, "map_step", low=1))


def held_out(n: int, test: np.ndarray, exclude: int, map_step: int) -> np.ndarray:
    """:func:`held_out_map_indices` of checked arguments."""
    keep = np.ones(n, bool)
    for k in test:
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
    func = "evaluate_log"
    test = check_indices(test_indices, func, "test_indices", len(check_log(log, func)))
    exclude = checks.integer(exclude, func, "exclude", low=0)
    map_step = checks.integer(map_step, func, "map_step", low=1)
    if max_range is not None:
        max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    coverage = checks.flag(coverage, func, "coverage")
    relocalize_kw = check_relocalize_kw(relocalize_kw, func)
    max_range = returns_reach(log.ranges) if max_range is None else max_range
    idx = held_out(len(log), test, exclude, map_step)
    if not len(idx):
        raise checks.fail(func, "test_indices, exclude", "leave no scan of the log to build the map from")
    ref = log_reference(log, idx, max_range, coverage, False, func)
    segs = ref.segments
    results, secs = [], []
    for k in test:
        t0 = time.perf_counter()
        results.append(relocalize(ref, scan=log.scans[k], max_range=max_range, **relocalize_kw))
        secs.append(time.perf_counter() - t0)
    truths = log.poses[test]
    pose, perr, herr, wit = record_results(results, truths, None, {}, False, 0.98)
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
