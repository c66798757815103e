"""Line maps from laser scans and odometry (thesis sections 3.1.2-3.1.4, Eqs. 3.4-3.12), with loop closure.

For every scan, :func:`build_map`

1. predicts the robot pose by applying the odometry *increment* to the last
   corrected pose (never the raw absolute odometry, which has drifted), with
   the covariance the stated drift model gives that step;
2. extracts the scan's segments (:func:`cga_lessons.mapping2d.lines.extract_segments`)
   and moves them into the global frame with the predicted pose (3.4): the
   local map ``L'``;
3. builds the proximity matrix ``M`` of the global map ``G`` against ``L'`` in
   Hough space, ``m = sqrt(diffTheta(theta_G, theta_L')^2 + (rho_G - rho_L')^2)``,
   and the correspondence vector ``C`` (``m < delta``, each local line given to
   at most one global line by the thesis's conflict rule), with the guards of
   (3.19);
4. corrects the heading by the angle differences (3.6, 3.8) and the position
   by the lines' offsets (3.7, 3.9-3.12), bounded by ``T_xi``, recomputes the
   correspondences and repeats;
5. fuses ``L'`` into ``G`` (matched lines merged, new lines ``N`` added) and
   finally removes duplicates.

What makes it work in practice (measured, see ``DESIGN.md``): ``rho`` is measured
from the robot's predicted position rather than the world origin (a small
heading error far from the origin would move ``rho`` a lot); lines are oriented
(a scan runs counter-clockwise, so the robot is on a line's left), which
identifies ``(rho, theta)`` with ``(-rho, theta + pi)`` and keeps the two faces
of a thin wall apart; every map line is refitted from all the points it has
gathered.  Beyond the thesis, as a robotics engineer would:

* **statistics** (:mod:`cga_lessons.mapping2d.correction`,
  :mod:`cga_lessons.mapping2d.estimation`, :mod:`cga_lessons.mapping2d.noise`):
  each pair's angle (3.8) and offset (3.11) are measurements with the
  variance of a line fitted to its points, the range noise read from the
  scan itself, plus model floors learnt from the residuals; heading and
  position are estimated together by robust (Huber) least squares with the
  odometry's prediction as a prior; the correction is applied only when its
  innovation passes a chi-square test (a wrong correction is worse than
  none); how good the odometry really is, relative to its drift model, is
  learnt by registering each scan on the one before and comparing with the
  odometry increment, so a perfect odometry is barely moved and a drifting
  one corrected; a short face of furniture cannot turn the robot, and a
  direction the lines leave open (all parallel, as in a corridor) keeps the
  odometry, or is fixed by segment ends that are real edges;
* **gating and consensus**: a pair whose angle and offset innovation lies
  beyond ``gate`` standard deviations (its variance plus the pose's) is
  dropped; in the first round only the largest set of pairs that agree on
  the heading is kept (one long wrong line cannot drag the rest), and each
  later round gates with the new, smaller covariance; the correction is
  refused if the prediction puts the scan's points on the map clearly better
  (the lesson of chapter 5);
* **local map and loop closure**: scans are matched against the lines seen in
  the last ``active_path`` metres; when old lines come into view, a revisit
  is searched for within three standard deviations of the pose's
  uncertainty propagated along the chain since the old lines were seen (no
  fixed bound), verified against the whole scan, checked against the drift
  the chain allows (:mod:`cga_lessons.mapping2d.loops`); the poses are
  relaxed in a pose graph with a robust cost on revisits
  (:mod:`cga_lessons.mapping2d.graph`) and the map is refitted from its
  observations, so the two copies of a place merge.

The correspondence test is the same for this plain version and the conformal
one (:mod:`cga_lessons.mapping2d.conformal`, section 3.2): besides ``m <
delta`` a pair must overlap (the spheres on the two segments intersect or one
contains the other, cases 1-2 of 3.19, with a margin), the centre of the
global segment must lie within ``xi_d`` of the local line (2.130) and their
moments (2.128, taken about the robot) may differ by at most ``xi_m``.  Here
these are computed with vectors, there with conformal entities; both give the
same map and poses.

The pieces live in :mod:`cga_lessons.mapping2d.geometry` (segments,
correspondence), :mod:`cga_lessons.mapping2d.corrections` (3.6-3.12),
:mod:`cga_lessons.mapping2d.builder` (correction and fusion),
:mod:`cga_lessons.mapping2d.loops` and :mod:`cga_lessons.mapping2d.graph`
(revisits and the pose graph), :mod:`cga_lessons.mapping2d.params` (the
thresholds) and :mod:`cga_lessons.mapping2d.eval` (errors against the truth);
the package's facade, :mod:`cga_lessons.mapping2d`, exports what callers use.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks

from .adjust import adjust_built_map
from .builder import MapBuilder
from .corrections import odometry_covariance
from .geometry import PlainGeometry, SegmentSet
from .inputs import pose, reach, scan_list
from .laser import scan_points_unchecked
from .lines import extract_unchecked, extraction_defaults, extraction_settings
from .loops import LoopCloser
from .params import MapParams
from .poses import compose_unchecked, relative_unchecked
from .segment import Segment

__all__ = [
    "MapResult",
    "build_map",
]


# --------------------------------------------------------------------------- parameters and result


@dataclass
class MapResult:
    """The result of :func:`build_map`.

    Attributes
    ----------
    segments : list of Segment
        The global line map (start and end as 2-vectors in the global frame).
    poses : ndarray, shape (T, 3)
        Corrected robot pose of every scan (after the last loop closure).
    predicted : ndarray, shape (T, 3)
        The pose predicted from the previous corrected pose and the odometry
        increment, before correction.
    n_matches : ndarray of int, shape (T,)
        Correspondences used for the last correction of each scan.
    corrected : ndarray of bool, shape (T,)
        False where no correction was possible (no segments, no
        correspondence, or the correction was refused): the pose is then the
        prediction.
    method : str
    history : list
        If requested, the number of map segments after each scan.
    loops : list of (int, int)
        The revisits closed: (earlier scan, scan).
    """

    segments: list
    poses: np.ndarray
    predicted: np.ndarray
    n_matches: np.ndarray
    corrected: np.ndarray
    method: str = "plain"
    history: list = field(default_factory=list)
    loops: list = field(default_factory=list)

    def __post_init__(self):
        f = "MapResult"
        if not isinstance(self.segments, list):
            raise checks.fail(f, "segments", f"expected a list of Segment, got {type(self.segments).__name__}")
        for s in self.segments:
            checks.instance(s, f, "segments", Segment, "a list of Segment")
        self.poses = checks.array(self.poses, f, "poses", (None, 3))
        self.predicted = checks.array(self.predicted, f, "predicted", (None, 3))
        n_matches = checks.array(self.n_matches, f, "n_matches", (None,))
        self.n_matches = _whole(n_matches, f, "n_matches", 0, None)
        corrected = checks.array(self.corrected, f, "corrected", (None,))
        self.corrected = _whole(corrected, f, "corrected", 0, 1).astype(bool)
        names = ("poses", "predicted", "n_matches", "corrected")
        checks.same_length(f, **{k: getattr(self, k) for k in names})
        self.method = checks.choice(self.method, f, "method", ("plain", "conformal"))
        for name in ("history", "loops"):
            if not isinstance(getattr(self, name), list):
                raise checks.fail(f, name, f"expected a list, got {type(getattr(self, name)).__name__}")
        self.history = [checks.integer(n, f, "history", low=0) for n in self.history]
        self.loops = [_scan_pair(p, f) for p in self.loops]


def _whole(a, func: str, name: str, low, high) -> np.ndarray:
    """A float array of whole numbers within ``[low, high]`` (``None``: up to 2**53), as ints."""
    high = 2**53 if high is None else high
    if np.any(a != np.round(a)) or np.any(a < low) or np.any(a > high):
        raise checks.fail(func, name, f"must hold whole numbers from {low} to {high}")
    return a.astype(int)


def _scan_pair(pair, func: str) -> tuple:
    if not isinstance(pair, (tuple, list)) or len(pair) != 2:
        raise checks.fail(func, "loops", f"expected (earlier scan, scan) pairs, got {pair!r}")
    return tuple(checks.integer(k, func, "loops", low=0) for k in pair)


# --------------------------------------------------------------------------- the map


def _inputs(scans, odometry, method, params, mount, max_range, extraction, record_history, progress, overrides):
    """The checked arguments of :func:`build_map`: scans, odometry, geometry, params, mount, extraction settings."""
    f = "build_map"
    scans = scan_list(scans, f, "scans", increasing=True)
    odometry = checks.array(odometry, f, "odometry", (None, 3))
    if len(scans) != len(odometry) or len(scans) == 0:
        raise checks.fail(f, "scans, odometry", f"{len(scans)} scans but {len(odometry)} odometry poses")
    checks.magnitude(odometry[:, :2] - odometry[0, :2], f, "odometry")  # the steps' covariances square them
    method = checks.choice(method, f, "method", ("plain", "conformal"))
    if params is None:
        params = MapParams()
    params = checks.instance(params, f, "params", MapParams, "a MapParams (or None)")
    bad = set(overrides) - set(MapParams.__dataclass_fields__)
    if bad:
        raise checks.fail(f, ", ".join(sorted(bad)), f"unknown parameter(s) {sorted(bad)} (see MapParams)")
    if overrides:
        params = MapParams(**{**params.__dict__, **overrides})
    ext = {**extraction_defaults(), "max_range": reach(max_range, f, "max_range")}
    if extraction is not None:
        if not isinstance(extraction, dict):
            raise checks.fail(f, "extraction", f"expected a dict of extract_segments settings, got {extraction!r}")
        ext.update(extraction_settings(extraction, f, "extraction: "))
    ext["func"] = f
    checks.flag(record_history, f, "record_history")
    if progress is not None and not callable(progress):
        raise checks.fail(f, "progress", f"expected a callable progress(k, T) or None, got {progress!r}")
    if method == "plain":
        geometry = PlainGeometry()
    else:
        from .conformal import ConformalGeometry

        geometry = ConformalGeometry()
    mount = checks.magnitude(pose(mount, f, "mount"), f, "mount")
    return scans, odometry, geometry, params, mount, ext["max_range"], ext


def _warm_up(corrector, scans, odometry, ext, params):
    """Learn how good the odometry is from the first scans, each registered on the one before, before any
    correction (so that the first corrections already use it); returns their segments (laser frame)."""
    n = min(len(scans), corrector.innovations.min_count + 1) if params.estimate_odometry else 0
    local = [
        SegmentSet.from_segments(extract_unchecked(r, a, **ext, names=_names(k))) for k, (r, a) in enumerate(scans[:n])
    ]
    for k in range(1, n):
        if len(local[k]) and len(local[k - 1]):
            inc = relative_unchecked(odometry[k - 1], odometry[k])
            corrector.learn_odometry(local[k - 1], local[k], inc, odometry_covariance(inc, params))
        if params.learn_lag > 1 and k >= params.learn_lag and k % params.learn_lag == 0:
            corrector.learn_lagged(local[k - params.learn_lag], local[k], odometry, k - params.learn_lag, k)
    return local


def build_map(
    scans,
    odometry,
    method: str = "plain",
    *,
    params: MapParams | None = None,
    mount=(0.0, 0.0, 0.0),
    max_range: float = 5.0,
    extraction: dict | None = None,
    record_history: bool = False,
    progress=None,
    **overrides,
) -> MapResult:
    """Build a global line map and correct the robot's poses (sections 3.1.2-3.1.4 and 3.2).

    Parameters
    ----------
    scans : sequence of (ranges, angles)
        One scan per pose: arrays of shape (n,), radians in the laser frame,
        ``inf`` (or NaN) for no return.
    odometry : array_like, shape (T, 3)
        Odometry poses ``(x, y, theta)``; only their increments are used, from
        the first pose (the map's origin).
    method : {"plain", "conformal"}
        Vectors and matrices (3.1) or conformal point pairs and motors (3.2).
    params : MapParams, optional
        The thresholds; keyword ``overrides`` replace single fields.
    mount : array_like, shape (3,)
        Pose of the laser on the robot (the laser-robot motor 3.16).
    max_range : float
        Readings at or beyond this (m) are dropped (the thesis's laser: 5 m);
        also how far old map lines are looked for when closing loops.
    extraction : dict, optional
        Keyword arguments for :func:`cga_lessons.mapping2d.lines.extract_segments`.
    record_history : bool
        Keep the map size after every scan in ``MapResult.history``.
    progress : callable, optional
        Called as ``progress(k, T)`` after scan ``k`` (a count from 1) of the
        ``T`` scans has been fused; for progress bars.

    Returns
    -------
    MapResult

    Raises
    ------
    InvalidInputError
        If the inputs disagree in length or shape, or a parameter is unknown.
    """
    scans, odometry, geometry, params, mount, max_range, ext = _inputs(
        scans, odometry, method, params, mount, max_range, extraction, record_history, progress, overrides
    )
    # Work near the origin: a log placed far away (map coordinates of 1e6 m) would leave the conformal entities
    # of table 2.1 with ~eps |x|^2 of accuracy.  A multiple of 1024 m is subtracted exactly and added back
    # exactly, so a log near the origin is computed bit for bit as before.
    shift = np.round(odometry[0, :2] / 1024.0) * 1024.0
    odometry = odometry - np.array([shift[0], shift[1], 0.0])

    b = MapBuilder(geometry, params, mount, max_range)
    T = len(scans)
    loops = LoopCloser(params, T)
    poses = np.zeros((T, 3))
    predicted = np.zeros((T, 3))
    n_matches = np.zeros(T, int)
    corrected = np.zeros(T, bool)
    history = []
    P = np.zeros((3, 3))
    local = _warm_up(b.corrector, scans, odometry, ext, params)
    increments, step_covs = np.zeros((max(T - 1, 0), 3)), np.zeros((max(T - 1, 0), 3, 3))
    previous = SegmentSet.empty()
    recent = deque(local[-(params.learn_lag + 1) :], maxlen=params.learn_lag + 1)  # the last scans' segments
    for k, (ranges, angles) in enumerate(scans):
        if k == 0:
            pose = odometry[0].copy()
            b.path.append(0.0)
        else:
            inc = relative_unchecked(odometry[k - 1], odometry[k])  # odometry increment
            pose = compose_unchecked(poses[k - 1], inc)
            b.path.append(b.path[-1] + float(np.hypot(inc[0], inc[1])))
            Q = odometry_covariance(inc, params)
            d = pose[:2] - poses[k - 1, :2]
            J = np.array([[1.0, 0.0, -d[1]], [0.0, 1.0, d[0]], [0.0, 0.0, 1.0]])
            carried = J @ P @ J.T
        predicted[k] = pose
        L = (
            local[k]
            if k < len(local)
            else SegmentSet.from_segments(extract_unchecked(ranges, angles, **ext, names=_names(k)))
        )
        if k >= len(local) and len(L) and len(previous):
            b.corrector.learn_odometry(previous, L, inc, Q)  # how good the odometry is, scan against scan
        previous = L
        if k >= len(local):
            recent.append(L)
            if params.learn_lag > 1 and k % params.learn_lag == 0 and len(recent) == params.learn_lag + 1:
                b.corrector.learn_lagged(recent[0], L, odometry, k - params.learn_lag, k)
        if k > 0:
            P = carried + b.corrector.odometry_scale * Q  # the step scaled by what the data say of the odometry
            increments[k - 1], step_covs[k - 1] = inc, b.corrector.odometry_scale * Q
        pts = np.zeros((0, 2))
        if len(L):
            pts, _ = scan_points_unchecked(np.where(ranges < max_range, ranges, np.inf), angles)
        if k > 0 and len(L) and len(b.G):
            pose, P, pairs, corrected[k] = b.correct(L, pose, P, b.near(pose[:2], k), pts, step=(carried, Q))
            n_matches[k] = 0 if pairs is None else len(pairs[0])
        poses[k] = pose
        if k > 0:
            loops.add_step(k, poses, P if n_matches[k] else b.corrector.odometry_scale * Q)
        b.fuse(L, pose, k)
        closed = loops.search(b, k, poses, L, pts, (angles.min(), angles.max()))
        if closed is not None:
            poses[: k + 1], P = closed
        if params.cleanup_every and (k + 1) % params.cleanup_every == 0:
            b.remove_duplicates()
        if record_history:
            history.append(len(b.G))
        if progress is not None:
            progress(k + 1, T)
    b.remove_duplicates()
    if params.adjust and T > 1:
        poses = adjust_built_map(b, poses, increments, step_covs).poses
    return _result(b, shift, poses, predicted, n_matches, corrected, history, loops.graph.loops)


def _names(k: int) -> tuple:
    return f"scans[{k}] ranges", f"scans[{k}] angles"


def _result(b, shift, poses, predicted, n_matches, corrected, history, loops) -> MapResult:
    """The map and poses moved back by ``shift`` (the multiple of 1024 m taken off the odometry)."""
    checks.finite_result(poses, "build_map", "scans, odometry")
    segments = b.G.to_segments()
    if np.any(shift):
        back = np.array([shift[0], shift[1], 0.0])
        poses, predicted = poses + back, predicted + back
        segments = [s.transformed(back) for s in segments]
    return MapResult(segments, poses, predicted, n_matches, corrected, b.geo.name, history, loops)
