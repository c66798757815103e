"""The thresholds of the 2D line-map builder (:func:`cga_lessons.mapping2d.build_map`), stage by stage, with the
thesis's meaning.

:class:`MapParams` is made of five stages, each a small frozen dataclass that checks its own fields and is read by
the code of its stage only: :class:`CorrespondenceParams` (which map lines a scan's lines correspond to, 3.5, 3.19),
:class:`CorrectionParams` (the pose correction 3.6-3.12 as an estimate, and what it learns of the sensor),
:class:`OdometryPriorParams` (the odometry's drift model: the prediction's covariance), :class:`LoopParams` (revisits
and the pose graph) and :class:`CleanupParams` (duplicate removal and the final adjustment).  Every field name is
unique across the stages, so ``build_map(..., gate=4.0)`` names one field; overrides are merged by
:func:`cga_lessons.config.merged`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from cga_lessons import checks
from cga_lessons.config import check_stages

__all__ = [
    "CorrespondenceParams",
    "CorrectionParams",
    "OdometryPriorParams",
    "LoopParams",
    "CleanupParams",
    "MapParams",
]

# The fields that are whole numbers (with their least value), flags, fractions in [0, 1], angles in [0, pi],
# and those that may be infinite (no bound); every other field is a real number >= 0.
_COUNTS = {"n_iterations": 1, "cleanup_every": 0, "loop_min_lines": 1, "learn_lag": 1, "graph_horizon": 1}
_FLAGS = {"estimate_odometry", "estimate_floors", "loop_closure", "adjust"}
_FRACTIONS = {"significance", "loop_min_support", "loop_ambiguity"}
_NO_BOUND = {"loop_max_shift"}
_SIGNED = {"odo_heading_bias"}  # a drift either way


def _check_field(value, f: str, name: str):
    """One field of a stage checked (and converted: plain ints, floats and bools) by its kind (the sets above),
    in the name ``f`` of the stage's class."""
    if name in _COUNTS:
        return checks.integer(value, f, name, low=_COUNTS[name])
    if name in _FLAGS:
        return checks.flag(value, f, name)
    if name in _FRACTIONS:
        strict = name == "significance"  # a quantile: neither 0 nor 1
        return checks.real(value, f, name, low=0.0, high=1.0, strict_low=strict, strict_high=strict)
    if name == "range_noise":  # None (estimated from each scan) is left alone by checks.record
        return checks.real(value, f, name, low=0.0, strict_low=True)
    if name in _SIGNED:
        return checks.real(value, f, name)
    if name == "loop_max_angle":
        return checks.real(value, f, name, low=0.0, high=math.pi)
    if name in _NO_BOUND and isinstance(value, (float, np.floating)) and value == math.inf:
        return float(value)
    return checks.real(value, f, name, low=0.0)


def _check_fields(stage) -> None:
    """Check and convert every field of a stage by its kind (:func:`cga_lessons.checks.record`); errors name the
    stage's class."""
    checks.record(stage, **{fld.name: _check_field for fld in fields(stage)})


@dataclass(frozen=True)
class CorrespondenceParams:
    """Which map lines a scan's lines correspond to (3.5, with the guards of 3.19), and which map lines are looked at.

    Attributes
    ----------
    delta : float
        ``delta``: largest proximity ``m = sqrt(diffTheta^2 + drho^2)`` (mixed
        radians and metres, as in the thesis) for two lines to correspond.
    theta_xi : float
        ``theta_xi`` of diffTheta (3.5): differences smaller than this are taken
        across the 0 / 2 pi cut the short way.  The thesis uses 2 pi / 100; it
        is set to cover ``delta`` so no candidate pair is compared the long way.
    xi_d : float
        ``xi_d``: largest distance (m) from the centre of a global segment to
        the local line (2.130), which keeps near-by thin objects apart.
    xi_m : float
        ``xi_m``: largest difference (m) of the two lines' moments (2.128) about
        the robot.
    overlap_margin : float
        The segments' spheres (2.134) are enlarged by this (m) before the
        intersection test (a continuation across a small gap still matches).
    edge_match : float
        Two segment ends that are real edges correspond if this close (m).
    neighbourhood : float
        Only map segments within this distance (m) of the robot are matched.
    active_path : float
        Only map lines seen within this many metres of travel are matched
        (the local map); older ones are left to loop closure (0: all lines).
    """

    delta: float = 0.3
    theta_xi: float = 0.3
    xi_d: float = 0.3
    xi_m: float = 0.25
    overlap_margin: float = 0.3
    edge_match: float = 0.3
    neighbourhood: float = 8.0
    active_path: float = 20.0

    def __post_init__(self):
        _check_fields(self)


@dataclass(frozen=True)
class CorrectionParams:
    """The correction of a scan's pose against the map (3.6-3.12) as a robust estimate with a prior, and what the
    corrector learns of the sensor and the odometry while the map is built.

    Attributes
    ----------
    t_xi : float
        ``T_xi``: bound (m) on each component of a position correction (3.12).
    theta_max : float
        Bound (radians) on a heading correction (3.8).
    n_iterations : int
        Rounds of correspondence and correction per scan.
    range_noise : float or None
        Standard deviation (m) of the laser's range noise; with the point count
        and length of a segment it gives the variance of its angle and offset.
        None (default): estimated from each scan, the median scatter of its
        segments' points about their lines
        (:func:`~cga_lessons.mapping2d.noise.scan_range_noise`; the logs
        differ, 0.7 cm median on Intel, 1.4 cm on ACES).
    significance : float
        A correction is applied only when its normalised innovation (the
        lines' estimate against the prediction, with both covariances) lies
        within this quantile of the chi-square law
        (:func:`~cga_lessons.mapping2d.estimation.estimate_correction`): 0.999
        refuses a right correction once in a thousand scans.  Also the level of
        the likelihood-ratio test that lets the learnt odometry scale leave
        "exact" (:class:`~cga_lessons.mapping2d.noise.InnovationModel`).
    estimate_odometry : bool
        Learn how good the odometry is, relative to its drift model, from the
        registration of each scan on the one before
        (:class:`~cga_lessons.mapping2d.noise.InnovationModel`: a running
        scale for the corrections, one for the whole run in the final
        adjustment); False: the model's covariance as stated.
    robust_kernel : float
        Huber constant (in scaled standard deviations) of the robust least
        squares of each correction.
    registration_xy, registration_theta : float
        Shape (m, rad) of the registration error common to all the lines of a
        scan, whose scale the same model learns: the robust spread of the
        registration of each scan on the map built at the logs' own poses,
        measured on Intel, ACES and CSAIL (2-3 cm and 0.4-0.6 degrees, where a
        simulated scan at its exact pose gives 0.3-0.6 cm and 0.06 degrees).
    angle_floor, offset_floor : float
        Model error added to every line's angle (radians) and offset (m)
        standard deviation (walls that are not perfectly straight), until
        enough residuals are in to estimate it (``estimate_floors``).
    estimate_floors : bool
        Estimate those floors, and the edges', from the residuals of recent
        corrections (:class:`~cga_lessons.mapping2d.noise.NoiseFloors`).
    gate : float
        A correspondence whose angle or offset innovation exceeds this many
        standard deviations is not used (also the scale of the robust weight of
        loop edges in the pose graph).
    consensus_angle : float
        Two correspondences agree on the heading when their angle differences
        are within this (radians; or ``gate`` standard deviations, if more);
        only the largest agreeing set (weighted by length) is used.
    edge_sigma : float
        Standard deviation (m) of a real edge's position along its line.
    support_distance : float
        Each of the scan's points within this distance ``D`` (m) of a map
        segment scores ``1 - (d / D)^2``; a correction is refused when the
        prediction scores more by over 1 % of the points (0 disables the check).
    learn_lag : int
        Besides each scan on the one before, every ``learn_lag``-th scan is
        registered on the scan ``learn_lag`` before it to learn how good the
        odometry is (its error grows with the steps, the registration's does
        not).  Four: scans a few metres apart still share most of their
        walls on the bundled logs (steps of about a metre); 1 turns it off.
    """

    t_xi: float = 0.3
    theta_max: float = 0.2
    n_iterations: int = 3
    range_noise: float | None = None
    significance: float = 0.999
    estimate_odometry: bool = True
    robust_kernel: float = 2.0
    registration_xy: float = 0.025
    registration_theta: float = 0.009
    angle_floor: float = 0.0
    offset_floor: float = 0.003
    estimate_floors: bool = True
    gate: float = 3.0
    consensus_angle: float = 0.02
    edge_sigma: float = 0.03
    support_distance: float = 0.05
    learn_lag: int = 4

    def __post_init__(self):
        _check_fields(self)


@dataclass(frozen=True)
class OdometryPriorParams:
    """The odometry's drift model, which gives the prediction's covariance (as
    :class:`cga_lessons.mapping2d.laser.OdometryModel`).

    Attributes
    ----------
    odo_sigma_xy, odo_sigma_heading, odo_sigma_turn, odo_heading_bias : float
        m per sqrt(m), rad per sqrt(m), rad per sqrt(rad) turned, rad per m
        (the bias a drift either way: it may be negative).
    """

    odo_sigma_xy: float = 0.02
    odo_sigma_heading: float = 0.01
    odo_sigma_turn: float = 0.03
    odo_heading_bias: float = 0.005

    def __post_init__(self):
        _check_fields(self)


@dataclass(frozen=True)
class LoopParams:
    """Loop closure: the search for revisits of old parts of the map, and the pose graph that relaxes the poses.

    Attributes
    ----------
    loop_closure : bool
        Look for revisits of old parts of the map and relax the poses.
    loop_every : float
        Travel (m) between two searches for a revisit.
    loop_angle_tol, loop_shift_tol : float
        Resolution of the revisit search: angle (rad) and offset (m) within
        which a line pair agrees with a hypothesis.
    loop_max_angle, loop_max_shift : float
        Largest rotation (rad) and translation (m) a revisit may correct, on
        top of the search window, which is three standard deviations of the
        pose's uncertainty relative to the old lines, propagated along the
        chain of poses (it grows with the distance travelled since they were
        seen).  No bound by default (pi, inf): a fixed bound of 3 m missed the
        revisits of the ACES log's 170 m loops, whose drift reached 5-10 m.
    loop_min_lines : int
        Fewest old lines a revisit must match.
    loop_min_support : float
        Fraction of the scan's points that must lie on the old lines (by the
        score of :attr:`CorrectionParams.support_distance`).
    loop_max_sigma : float
        Largest standard deviation (m) of the revisit's position in any
        direction (parallel corridor walls alone do not close a loop).
    loop_ambiguity : float
        A revisit is refused when a clearly different one puts more than this
        fraction of the points on the old lines.
    graph_sigma_xy, graph_sigma_theta : float
        Model error (m, rad) added to each corrected step and revisit in the
        pose graph.
    graph_horizon : int
        Scans over which a revisit is handled along the chain alone, as on a
        single lap of a building: the search window is the chain's drift since
        the old lines were seen, and the relaxation frees every pose since the
        revisit's anchor.  Beyond it (a long log that comes back to its map
        again and again) the window is also bounded by the drift the revisits
        made on the way leave, and the relaxation is windowed
        (:mod:`cga_lessons.mapping2d.drift`), so that a scan's cost does not
        grow with the log.  1,000: a cost budget, not a tuned threshold; an
        exact relaxation of 1,000 poses takes 20-35 ms (measured on the Intel
        log six laps over), about 1.5 ms a scan at its one revisit every 20
        scans, a tenth of a 15 ms budget per scan; the whole Intel log
        (910 scans) and every bundled log are within it, and the six logs'
        maps are those of the chain alone.
    """

    loop_closure: bool = True
    loop_every: float = 1.0
    loop_angle_tol: float = 0.02
    loop_shift_tol: float = 0.1
    loop_max_angle: float = np.pi
    loop_max_shift: float = np.inf
    loop_min_lines: int = 3
    loop_min_support: float = 0.3
    loop_max_sigma: float = 0.1
    loop_ambiguity: float = 0.8
    graph_sigma_xy: float = 0.01
    graph_sigma_theta: float = 0.005
    graph_horizon: int = 1000

    def __post_init__(self):
        _check_fields(self)


@dataclass(frozen=True)
class CleanupParams:
    """The map's clean-up (duplicate lines merged) and the final adjustment.

    Attributes
    ----------
    dup_angle, dup_distance : float
        Map lines closer than these (radians, m) that overlap are duplicates
        and are merged.
    cleanup_every : int
        Run the duplicate removal every so many scans (and at the end; 0: only
        at the end).
    adjust : bool
        When the last scan is in, estimate all poses and lines together from
        every observation and odometry step
        (:func:`~cga_lessons.mapping2d.adjust.adjust_map`).
    """

    dup_angle: float = 0.05
    dup_distance: float = 0.08
    cleanup_every: int = 25
    adjust: bool = True

    def __post_init__(self):
        _check_fields(self)


@dataclass(frozen=True)
class MapParams:
    """Every threshold of the map builder, stage by stage, with the thesis's meaning.

    One set of defaults serves the synthetic scenes and real logs; only the
    sensor's reach (``max_range`` of :func:`~cga_lessons.mapping2d.build_map`) differs.
    :func:`~cga_lessons.mapping2d.build_map` takes overrides as a whole stage
    (``loops=LoopParams(loop_every=2.0)``), a dict of some of a stage's fields
    (``loops={"loop_every": 2.0}``) or a single field by its name
    (``loop_every=2.0``): field names are unique across the stages.

    Attributes
    ----------
    correspondence : CorrespondenceParams
        Which map lines correspond to a scan's lines (3.5, 3.19), and which are looked at.
    correction : CorrectionParams
        The pose correction (3.6-3.12) as a robust estimate, and what it learns of the sensor.
    odometry_prior : OdometryPriorParams
        The odometry's drift model (the prediction's covariance).
    loops : LoopParams
        Loop closure: revisits and the pose graph.
    cleanup : CleanupParams
        Duplicate removal and the final adjustment.
    """

    correspondence: CorrespondenceParams = field(default_factory=CorrespondenceParams)
    correction: CorrectionParams = field(default_factory=CorrectionParams)
    odometry_prior: OdometryPriorParams = field(default_factory=OdometryPriorParams)
    loops: LoopParams = field(default_factory=LoopParams)
    cleanup: CleanupParams = field(default_factory=CleanupParams)

    def __post_init__(self):
        check_stages(self)
