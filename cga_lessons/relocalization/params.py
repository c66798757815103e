"""The thresholds of :func:`~cga_lessons.relocalization.relocalize`, by stage, each field checked where it is set.

:class:`RelocParams` holds two stages: :class:`RelocSearch` (the pose
hypotheses and their screening) and :class:`RelocCheck` (verification and the
decision); :func:`resolve_params` merges a user's overrides into them (through
:func:`cga_lessons.config.merged`), checked in the name of the function the
user called; :func:`noise_scaled` grows the distance thresholds with a scan's
noise.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, replace

import numpy as np

from cga_lessons import checks, config
from cga_lessons.config import check_stages
from cga_lessons.mapping2d import ExtractionParams

__all__ = [
    "STATUSES",
    "RelocSearch",
    "RelocCheck",
    "RelocParams",
    "check_param",
    "check_fields",
    "check_score",
    "resolve_params",
    "check_extraction",
    "check_relocalize_kw",
    "noise_scaled",
]

#: The statuses of a relocalization.
STATUSES = ("ok", "ambiguous", "failed")


@dataclass(frozen=True)
class RelocSearch:
    """The search stage of :func:`~cga_lessons.relocalization.relocalize`: the hypotheses (votes, rotations,
    anchor pairs, slides), their quick score and their screening (read by
    :mod:`~cga_lessons.relocalization.search` and :func:`~cga_lessons.relocalization.candidates.screen_hypotheses`).

    Attributes
    ----------
    xi_theta : float
        Angle threshold (radians) of the votes (5.6) and of the rotation votes.
    xi_rho : float
        Offset threshold (m) of the votes (5.6) (the literal method only).
    n_rotations : int
        Rotation proposals taken from the angle votes (each gives two rotations).
    parallel_tol : float
        A scan line and a map line are parallel under a rotation within this (radians).
    n_anchor_pairs : int
        Pairs of non-parallel scan lines used to make translation hypotheses, per rotation.
    min_anchor_angle : float
        Smallest angle (radians) between the two lines of an anchor pair.
    overlap_margin : float
        A map segment's extent is widened by this (m) when a scan segment must lie on it.
    min_overlap : float
        Fraction of a scan segment that must lie within its map segment's extent.
    line_tolerance : float
        Midpoint-to-line distance (m) for a scan line to count as on a map line
        (quick score, correspondences; grows to 5 times the scan's range noise).
    slide_step, slide_below : float
        When the scan lines across the longest one add up to less than
        ``slide_below`` (m), positions ``slide_step`` (m) apart along its map
        partners are tried as well (``slide_step`` 0 disables).  ``inf``: always.
        The lines across may be there and still fix nothing: door frames,
        cupboards and people that the map does not hold.  Measured on held-out
        scans of the six CARMEN logs (every 7th, map from the rest): in
        corridors no hypothesis came within 30 cm of the true pose because
        every scan line matching the map there was parallel to the corridor
        (ACES, the run ending at scan 276: 9 such lines, and 2.9 m of lines
        across without any map partner, so the 1 m bar of old kept the slide
        off); always sliding located 5 more of the 361 scans (ACES 3, CSAIL 1,
        Orebro 1) and made none more confidently wrong.
    rotation_vote_ratio : float
        Rotations whose vote is below this fraction of the best are dropped.
    quick_ratio : float
        Hypotheses whose quick score (scan length on map segments) is below
        this fraction of the best are dropped before the screening.
    n_screen : int
        At most this many hypotheses (one per 3 cm x 0.5 degree cell) are
        screened against a subset of the beams.
    screen_beams : int
        About this many returned beams are used in the screening.
    """

    xi_theta: float = np.radians(3.0)
    xi_rho: float = 0.2
    n_rotations: int = 8
    parallel_tol: float = np.radians(4.0)
    n_anchor_pairs: int = 4
    min_anchor_angle: float = np.radians(30.0)
    overlap_margin: float = 0.3
    min_overlap: float = 0.5
    line_tolerance: float = 0.1
    slide_step: float = 0.2
    slide_below: float = np.inf
    rotation_vote_ratio: float = 0.25
    quick_ratio: float = 0.8
    n_screen: int = 600
    screen_beams: int = 24

    def __post_init__(self):
        check_fields(self)


@dataclass(frozen=True)
class RelocCheck:
    """The check stage of :func:`~cga_lessons.relocalization.relocalize`: how the screened hypotheses are
    verified against the whole scan, and when the answer is ok, ambiguous or failed (read by
    :mod:`~cga_lessons.relocalization.candidates`, and by the sequence's chains).

    Attributes
    ----------
    n_verify : int
        Clearly different hypotheses refined and checked against the whole
        scan: all within 90 % of the best screening score (up to four times
        this), at least this many.
    inlier_distance : float
        A returned beam whose point lies within this (m) of the first map wall
        along it supports the pose (grows to 4 times the scan's range noise).
    ray_margin : float
        A beam may end this far (m) behind a map wall before it counts against
        the pose (grows to 5 times the scan's range noise).
    ambiguity_ratio : float
        A clearly different pose scoring at least this fraction of the best makes the answer ambiguous.
    deficit_ratio : float
        ... or one whose deficit ``1 - score`` is at most ``1 + deficit_ratio``
        times the best's (:func:`~cga_lessons.relocalization.candidates.tie_bar`).
        1: measured on held-out scans of the Intel and ACES logs (every 7th,
        map from the rest by chapter 3's builder, with its coverage grid), the
        second-best pose of a confident wrong answer scored 0.43-0.96 of the
        best (18 of 22 above 0.7), of a confident right one mostly below 0.7
        (112 of 131); a rival failing to explain at most twice what the best
        fails to explain (a deficit of 10 % against 5 %) is too close to call
        on a map with holes.  0 gives the ratio rule alone.  A chain of
        ``n`` scans (:class:`~cga_lessons.relocalization.sequence.Relocalizer`)
        is held to ``deficit_ratio / sqrt(n)``: its deficit is summed over
        ``n`` looks.  Measured with ``benchmarks/bench_reloc_logs.py`` (runs of
        three, six CARMEN logs, seeds 0-3, the map's lines then merged by
        their ends): 1,235 of 1,444 runs located
        against 1,133 with the single scan's margin, confidently wrong 21
        against 18; on the four logs the margin was not measured on (CSAIL,
        Freiburg, Seattle, Orebro) 586 of 672 against 543, none more wrong.
    distinct_position, distinct_heading : float
        Poses further apart than this (m) or turned more than this (radians)
        are clearly different; the best pose moved by these along its least
        constrained direction is checked as a rival too.
    min_score : float
        Below this score (see :func:`~cga_lessons.relocalization.verify.score_poses`)
        the result is a failure.  0: a pose that contradicts more beams than it
        explains is no answer; above that the tie rule decides (a best pose
        scoring ``s`` must leave its rivals below ``2 s - 1``).  A fixed bar of
        0.5 refused right poses with no rival near them whose beams mostly
        returned nothing (Freiburg: up to 78 % of the beams, a fifth of those
        crossing a map wall), and scans of cluttered rooms: with 0, 3 more
        of the 361 held-out scans and 5 more runs of three were located, none
        more confidently wrong.
    """

    n_verify: int = 12
    inlier_distance: float = 0.06
    ray_margin: float = 0.08
    ambiguity_ratio: float = 0.98
    deficit_ratio: float = 1.0
    distinct_position: float = 0.2
    distinct_heading: float = np.radians(4.0)
    min_score: float = 0.0

    def __post_init__(self):
        check_fields(self)


@dataclass(frozen=True)
class RelocParams:
    """Every threshold of :func:`~cga_lessons.relocalization.relocalize`, by stage: ``search``
    (:class:`RelocSearch`) makes and screens the pose hypotheses, ``check`` (:class:`RelocCheck`) verifies them
    and decides.

    Each field name belongs to one stage only, so a single threshold may be given by its name
    (``relocalize(..., xi_theta=0.1)``), a stage as a whole or as a dict of some of its fields
    (``relocalize(..., check={"min_score": 0.4})``); :func:`cga_lessons.config.merged` merges them.
    """

    search: RelocSearch = field(default_factory=RelocSearch)
    check: RelocCheck = field(default_factory=RelocCheck)

    def __post_init__(self):
        check_stages(self)


#: The ranges of RelocParams' real fields (keywords of :func:`cga_lessons.checks.real`).
_PARAM_RANGES = {
    "xi_theta": dict(low=0.0, high=np.pi, strict_low=True),
    "xi_rho": dict(low=0.0, strict_low=True, high=checks.MAX_MAGNITUDE),
    "parallel_tol": dict(low=0.0, high=np.pi / 2, strict_low=True),
    "min_anchor_angle": dict(low=0.0, high=np.pi / 2),
    "overlap_margin": dict(low=0.0, high=checks.MAX_MAGNITUDE),
    "min_overlap": dict(low=0.0, high=1.0),
    "line_tolerance": dict(low=0.0, strict_low=True, high=checks.MAX_MAGNITUDE),
    "slide_step": dict(low=0.0, high=checks.MAX_MAGNITUDE),
    "slide_below": dict(low=0.0, high=checks.MAX_MAGNITUDE),
    "rotation_vote_ratio": dict(low=0.0, high=1.0),
    "quick_ratio": dict(low=0.0, high=1.0),
    "inlier_distance": dict(low=0.0, strict_low=True, high=checks.MAX_MAGNITUDE),
    "ray_margin": dict(low=0.0, high=checks.MAX_MAGNITUDE),
    "ambiguity_ratio": dict(low=0.0, high=1.0, strict_low=True),
    "deficit_ratio": dict(low=0.0),
    "distinct_position": dict(low=0.0, strict_low=True, high=checks.MAX_MAGNITUDE),
    "distinct_heading": dict(low=0.0, high=np.pi, strict_low=True),
    "min_score": dict(high=1.0),
}
#: RelocParams' counts.
_PARAM_COUNTS = ("n_rotations", "n_anchor_pairs", "n_screen", "screen_beams", "n_verify")


def check_param(name: str, value, func: str):
    """One field of a stage of :class:`RelocParams` checked in the name of ``func``: its counts are whole numbers
    >= 1, its thresholds finite numbers in their ranges, distances (m) within
    :data:`~cga_lessons.checks.MAX_MAGNITUDE` (``slide_below`` may be ``inf``: always slide)."""
    if name in _PARAM_COUNTS:
        return checks.integer(value, func, name, low=1)
    if name == "slide_below" and isinstance(value, (float, np.floating)) and value == np.inf:
        return float(value)
    return checks.real(value, func, name, **_PARAM_RANGES[name])


def check_fields(stage) -> None:
    """Check (and convert) every field of a stage (:class:`RelocSearch`, :class:`RelocCheck`) in its own name."""
    checks.record(stage, **{f.name: _as_field for f in dataclasses.fields(stage)})


def _as_field(value, func: str, name: str):
    """:func:`check_param` as a checker of :func:`cga_lessons.checks.record`."""
    return check_param(name, value, func)


def check_score(value, func: str, name: str = "score", *, failed: bool = False) -> float:
    """A score: a finite number, or ``-inf`` when ``failed`` (no candidate, no returned beam)."""
    if failed and isinstance(value, (float, np.floating)) and value == -np.inf:
        return float(value)
    return checks.real(value, func, name)


def noise_scaled(params: RelocParams, noise: float) -> RelocParams:
    """The thresholds that are distances grown with the noise (they are set for about 1 cm): the search's
    ``line_tolerance``, the check's ``inlier_distance`` and ``ray_margin``.

    ``noise``: the scan's range noise, or :func:`combined_noise` with the map's blur.
    """
    search, check = params.search, params.check
    return replace(
        params,
        search=replace(search, line_tolerance=max(search.line_tolerance, 5 * noise)),
        check=replace(
            check, inlier_distance=max(check.inlier_distance, 4 * noise), ray_margin=max(check.ray_margin, 5 * noise)
        ),
    )


def resolve_params(params: RelocParams | None, overrides: dict, func: str = "relocalize") -> RelocParams:
    """``params`` (default :class:`RelocParams`) with ``overrides`` merged in by :func:`cga_lessons.config.merged`
    (single fields by name, a stage, or a dict of a stage's fields), checked in the name of ``func``; unknown
    names raise."""
    return config.merged(params, overrides, func, RelocParams)


def check_extraction(extraction, func: str) -> dict:
    """Keyword arguments for :func:`~cga_lessons.mapping2d.lines.extract_segments` (a dict of its settings)."""
    if extraction is None:
        return {}
    checks.instance(extraction, func, "extraction", dict, "a dict of extract_segments' settings or None")
    known = {f.name for f in dataclasses.fields(ExtractionParams)}  # extract_segments' settings
    bad = sorted(map(str, set(extraction) - known))
    if bad:
        raise checks.fail(func, "extraction", f"unknown setting(s) of extract_segments: {', '.join(bad)}")
    return extraction


def check_relocalize_kw(kw: dict, func: str) -> dict:
    """Keywords for :func:`~cga_lessons.relocalization.relocalize` (``params``, ``extraction``, stages and single
    thresholds), checked in the name of ``func``."""
    if kw.get("extraction") is not None:
        checks.instance(kw["extraction"], func, "extraction", dict, "a dict of extract_segments' settings")
    resolve_params(kw.get("params"), {k: v for k, v in kw.items() if k not in ("params", "extraction")}, func)
    return kw
