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
one (:mod:`cga_lessons.mapping2d.conformal_geometry`, section 3.2): besides ``m <
delta`` a pair must overlap (the spheres on the two segments intersect or one
contains the other, cases 1-2 of 3.19, with a margin), the centre of the
global segment must lie within ``xi_d`` of the local line (2.130) and their
moments (2.128, taken about the robot) may differ by at most ``xi_m``.  Here
these are computed with vectors, there with conformal entities; both give the
same map and poses.

The pieces live in :mod:`cga_lessons.mapping2d.geometry` (segments,
correspondence), :mod:`cga_lessons.mapping2d.corrections` (3.6-3.12),
:mod:`cga_lessons.mapping2d.builder` (correction and fusion),
:mod:`cga_lessons.mapping2d.run` (the loop over the scans),
:mod:`cga_lessons.mapping2d.loops` and :mod:`cga_lessons.mapping2d.graph`
(revisits and the pose graph), :mod:`cga_lessons.mapping2d.params` (the
thresholds, stage by stage), :mod:`cga_lessons.mapping2d.extraction` (the
extractor's settings) and :mod:`cga_lessons.mapping2d.eval` (errors against the
truth); the package's facade, :mod:`cga_lessons.mapping2d`, exports what callers
use.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from cga_lessons import checks, config

from .extraction import ExtractionParams, extraction_settings
from .geometry import PlainGeometry
from .inputs import pose, reach, scan_list
from .params import MapParams
from .run import MapRun
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
    params = config.merged(params, overrides, f, MapParams)
    ext = _extraction(extraction, reach(max_range, f, "max_range"), f)
    checks.flag(record_history, f, "record_history")
    if progress is not None and not callable(progress):
        raise checks.fail(f, "progress", f"expected a callable progress(k, T) or None, got {progress!r}")
    if method == "plain":
        geometry = PlainGeometry()
    else:
        from .conformal_geometry import ConformalGeometry

        geometry = ConformalGeometry()
    mount = checks.magnitude(pose(mount, f, "mount"), f, "mount")
    return scans, odometry, geometry, params, mount, ext.max_range, ext


def _extraction(extraction, max_range: float, f: str) -> ExtractionParams:
    """The extractor's settings: an :class:`ExtractionParams` (its ``max_range`` at most ``max_range``) or a dict of
    some of its fields over the defaults with ``max_range`` (the dict may change it)."""
    if isinstance(extraction, ExtractionParams):
        return replace(extraction, max_range=min(extraction.max_range, max_range))
    if extraction is not None and not isinstance(extraction, dict):
        raise checks.fail(f, "extraction", f"expected an ExtractionParams or a dict of its fields, got {extraction!r}")
    return replace(ExtractionParams(max_range=max_range), **extraction_settings(extraction or {}, f, "extraction: "))


def build_map(
    scans,
    odometry,
    method: str = "plain",
    *,
    params: MapParams | None = None,
    mount=(0.0, 0.0, 0.0),
    max_range: float = 5.0,
    extraction: ExtractionParams | dict | None = None,
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
        The thresholds, stage by stage.  Keyword ``overrides`` change them
        (merged by :func:`cga_lessons.config.merged`): a whole stage
        (``loops=LoopParams(...)``), a dict of some of a stage's fields
        (``loops={"loop_every": 2.0}``) or a single field by its name
        (``gate=4.0``, ``loop_closure=False``).
    mount : array_like, shape (3,)
        Pose of the laser on the robot (the laser-robot motor 3.16).
    max_range : float
        Readings at or beyond this (m) are dropped (the thesis's laser: 5 m);
        also how far old map lines are looked for when closing loops.
    extraction : ExtractionParams or dict, optional
        The settings of :func:`cga_lessons.mapping2d.extract_segments`: an
        :class:`~cga_lessons.mapping2d.extraction.ExtractionParams` (its
        ``max_range`` at most ``max_range``), or a dict of some of its fields
        over the defaults and ``max_range``.
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

    run = MapRun(scans, odometry, geometry, params, mount, max_range, ext)
    history = []
    for k in range(len(scans)):
        run.step(k)
        if record_history:
            history.append(len(run.builder.lines))
        if progress is not None:
            progress(k + 1, len(scans))
    return _result(run, run.finish(), shift, history)


def _result(run: MapRun, poses, shift, history) -> MapResult:
    """The map and poses of ``run`` moved back by ``shift`` (the multiple of 1024 m taken off the odometry)."""
    checks.finite_result(poses, "build_map", "scans, odometry")
    builder, predicted, loops = run.builder, run.predicted, run.loops.graph.loops
    segments = builder.lines.to_segments()
    if np.any(shift):
        back = np.array([shift[0], shift[1], 0.0])
        poses, predicted = poses + back, predicted + back
        segments = [s.transformed(back) for s in segments]
    return MapResult(segments, poses, predicted, run.n_matches, run.corrected, builder.geometry.name, history, loops)
