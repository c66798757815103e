"""Measuring relocalization from a look around: the robot turns on the spot and scans again.

* :func:`look_around`: the scans a robot takes turning on the spot in equal
  steps from a pose, with the drifting odometry of the turn
  (:func:`cga_lessons.mapping2d.laser.simulate_odometry`);
* :func:`evaluate_look_around`: relocalize such a sequence
  (:func:`cga_lessons.relocalization.sequence.relocalize_sequence`) from each
  of many poses and compare with the simulator's truth, in the terms of
  :class:`cga_lessons.relocalization.evaluation.Evaluation` (success, confidently
  wrong, ambiguous, witness);
* :func:`evaluate_log_sequences`: the same on a real log, short runs of its
  scans with its own odometry, against the map built from the rest of it.

The witness of an ambiguous answer is the same as for one scan, over the
whole sequence: a clearly different tied candidate whose noise-free scans,
moved along the true turn, agree with the true ones on every look (the
smallest agreement over the looks is reported).
"""

from __future__ import annotations

import time

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import (
    OdometryModel,
    Scene,
    compose,
    relative,
    returns_reach,
    simulate_odometry,
    simulate_scan,
    wrap_angle,
)

from .eval import held_out, log_reference
from .evaluation import HEADING_TOLERANCE, POSITION_TOLERANCE, Evaluation, scan_agreement
from .geometry import pose_errors, reference_map
from .inputs import check_indices, check_laser, check_log, check_pose, check_scene
from .sequence import relocalize_sequence, relocalizer_for

__all__ = ["look_around", "evaluate_look_around", "evaluate_log_sequences"]


def look_around(
    scene: Scene,
    pose,
    rng,
    *,
    looks: int = 4,
    range_noise: float = 0.01,
    max_range: float = 5.0,
    n_beams: int = 361,
    fov: float = np.pi,
    odometry_model: OdometryModel | None = None,
):
    """Scans from ``pose`` turned on the spot by ``2 pi / looks`` between scans.

    Returns
    -------
    truth : ndarray, shape (looks, 3)
        The true laser poses.
    scans : list of (ranges, angles)
    odometry : ndarray, shape (looks, 3)
        What the odometer reports (its first pose is the true one; only the
        increments are used by the relocalization).
    """
    func = "look_around"
    check_scene(scene, func)
    pose = check_pose(pose, func)
    checks.generator(rng, func)
    looks = checks.integer(looks, func, "looks", low=1)
    laser = check_laser(func, range_noise=range_noise, max_range=max_range, n_beams=n_beams, fov=fov)
    check_odometry_model(odometry_model, func)
    return turn_on_the_spot(scene, pose, rng, looks, laser, odometry_model)


def check_odometry_model(model, func: str) -> None:
    """An :class:`~cga_lessons.mapping2d.laser.OdometryModel` or None."""
    if model is not None:
        checks.instance(model, func, "odometry_model", OdometryModel, "an OdometryModel or None")


def turn_on_the_spot(scene, pose, rng, looks: int, laser: dict, odometry_model):
    """:func:`look_around` of checked arguments (``laser``: the settings of the simulated scans)."""
    turns = 2 * np.pi * np.arange(looks) / looks
    truth = np.column_stack([np.full(len(turns), pose[0]), np.full(len(turns), pose[1]), pose[2] + turns])
    truth[:, 2] = wrap_angle(truth[:, 2])
    scans = [simulate_scan(scene, t, rng, **laser) for t in truth]
    odo = simulate_odometry(truth, rng, odometry_model) if len(truth) > 1 else truth.copy()
    return truth, scans, odo


def evaluate_look_around(
    scene: Scene,
    map_segments,
    poses,
    rng,
    *,
    looks: int = 4,
    stop_when_confident: bool = False,
    range_noise: float = 0.01,
    max_range: float = 5.0,
    n_beams: int = 361,
    fov: float = np.pi,
    odometry_model: OdometryModel | None = None,
    witness: bool = True,
    **relocalizer_kw,
):
    """Relocalize a look around from each pose against a map; compare the last pose with the truth.

    Returns
    -------
    evaluation : Evaluation
        ``truth`` and ``pose`` are the laser's poses at the last scan used.
    n_scans : ndarray of int
        Scans used from each pose (fewer than ``looks`` only with ``stop_when_confident``).
    """
    func = "evaluate_look_around"
    check_scene(scene, func)
    ref = reference_map(map_segments, func)
    poses, _ = checks.batch(poses, func, "poses", (3,), at_least=1)
    checks.magnitude(poses[:, :2], func, "poses")
    checks.generator(rng, func)
    looks = checks.integer(looks, func, "looks", low=1)
    stop_when_confident = checks.flag(stop_when_confident, func, "stop_when_confident")
    laser = check_laser(func, range_noise=range_noise, max_range=max_range, n_beams=n_beams, fov=fov)
    check_odometry_model(odometry_model, func)
    witness = checks.flag(witness, func, "witness")
    relocalizer_for(func, ref, laser["max_range"], relocalizer_kw)  # the keywords checked in this function's name
    ratio = relocalizer_kw.get("ambiguity_ratio", 0.98)
    scan_kw = {k: laser[k] for k in ("n_beams", "fov", "max_range")}
    rows = []
    for p in poses:
        truth, scans, odo = turn_on_the_spot(scene, p, rng, looks, laser, odometry_model)
        t0 = time.perf_counter()
        r = relocalize_sequence(
            ref, scans, odo, max_range=laser["max_range"], stop_when_confident=stop_when_confident, **relocalizer_kw
        )
        secs = time.perf_counter() - t0
        wit = np.nan
        if witness and r.status == "ambiguous":
            wit = _witness(scene.walls, truth[: r.n_scans], r, ratio, scan_kw)
        rows.append(_row(r, truth[r.n_scans - 1], wit, secs))
    return _evaluation(rows)


def _row(r, last, wit, secs):
    est = np.full(3, np.nan) if r.pose is None else r.pose
    perr, herr = pose_errors(r.pose, last) if r.pose is not None else (np.inf, np.inf)
    n_lines = int(np.mean([len(s.scan_segments) for s in r.single]))
    return (last, est, r.status, perr, herr, n_lines, r.score, wit, secs, r)


def _evaluation(rows):
    cols = list(zip(*rows))
    ev = Evaluation(
        np.array(cols[0]),
        np.array(cols[1]),
        np.array(cols[2]),
        np.array(cols[3]),
        np.array(cols[4]),
        np.array(cols[5]),
        np.array(cols[6]),
        np.array(cols[7], float),
        np.array(cols[8]),
        list(cols[9]),
    )
    return ev, np.array([r.n_scans for r in cols[9]])


def _witness(walls, truth, result, ratio, scan_kw) -> float:
    """The largest, over tied clearly different candidates, of the smallest agreement over the looks."""
    last = truth[-1]
    best = 0.0
    for c in result.candidates:
        if c.score < ratio * result.score:
            continue
        pe, he = pose_errors(c.pose, last)
        if pe <= 2 * POSITION_TOLERANCE and he <= 2 * HEADING_TOLERANCE:
            continue
        # the candidate's chain moved along the true turn
        chain = compose(c.pose, relative(last, truth))
        agree = min(scan_agreement(walls, t, q, **scan_kw) for t, q in zip(truth, chain))
        best = max(best, agree)
    return best


def evaluate_log_sequences(
    log,
    starts,
    *,
    length: int = 3,
    stride: int = 3,
    exclude: int = 2,
    map_step: int = 2,
    max_range: float | None = None,
    odometry=None,
    coverage: bool = True,
    **relocalizer_kw,
):
    """Relocalize short runs of a log's scans, with its odometry, against the map of the rest of it.

    Run ``i`` uses the scans ``starts[i] + stride * (0, 1, ..., length - 1)``
    (the robot driving on, not turning); the map is built as in
    :func:`cga_lessons.relocalization.eval.evaluate_log` from every
    ``map_step``-th scan more than ``exclude`` scans away from every scan of
    every run (with its coverage grid when ``coverage``, see
    :func:`cga_lessons.relocalization.eval.reference_from_log`); the truth is
    the logged (corrected) pose of each run's last scan.  ``odometry`` (T, 3)
    replaces the logged odometry (the corrected logs log the poses there: pass
    :func:`cga_lessons.mapping2d.laser.simulate_odometry` of the truth).  ``max_range``
    (m) is the laser's reach for the map and the scans; None: the log's own
    (:func:`cga_lessons.mapping2d.laser_facts.returns_reach`).

    Returns
    -------
    evaluation : Evaluation
        (``witness`` is not computed: there is no simulator.)
    n_scans : ndarray of int
    map_segments : ndarray, shape (M, 2, 2)
    """
    func = "evaluate_log_sequences"
    starts = check_indices(starts, func, "starts", len(check_log(log, func)))
    length = checks.integer(length, func, "length", low=1)
    stride = checks.integer(stride, func, "stride", low=1)
    runs = starts[:, None] + stride * np.arange(length)[None, :]
    if runs.max() >= len(log):
        raise checks.fail(
            func, "starts, length, stride", f"runs reach scan {runs.max()}, past the log (0..{len(log) - 1})"
        )
    odo = log.odometry if odometry is None else checks.array(odometry, func, "odometry", (len(log), 3))
    exclude = checks.integer(exclude, func, "exclude", low=0)
    map_step = checks.integer(map_step, func, "map_step", low=1)
    coverage = checks.flag(coverage, func, "coverage")
    if max_range is not None:
        max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    max_range = returns_reach(log.ranges) if max_range is None else max_range
    idx = held_out(len(log), runs.ravel(), exclude, map_step)
    if not len(idx):
        raise checks.fail(func, "starts, exclude", "leave no scan of the log to build the map from")
    ref = log_reference(log, idx, max_range, coverage, False, func)
    relocalizer_for(func, ref, max_range, relocalizer_kw)  # the keywords checked
    segs = ref.segments
    rows = []
    for run in runs:
        t0 = time.perf_counter()
        r = relocalize_sequence(ref, [log.scans[k] for k in run], odo[run], max_range=max_range, **relocalizer_kw)
        rows.append(_row(r, log.poses[run[r.n_scans - 1]], np.nan, time.perf_counter() - t0))
    ev, n = _evaluation(rows)
    return ev, n, segs
