"""Relocalization in a known line map (thesis chapter 5, Eqs. 5.1-5.6), made to work.

The robot has been carried somewhere in a map it built before; from one scan
it must find its pose.  :func:`relocalize` returns the pose ``(x, y, theta)``
of the laser in the map frame, the ranked candidates and whether the answer
is ambiguous.

The thesis's method (section 5.2) is in :mod:`cga_lessons.relocalization.hough`
(figure 5.1 and Eqs. 5.1-5.6) and :mod:`cga_lessons.relocalization.thesis`
(steps 6-10); its vote matrix and its pose are part of every result.  Read
literally it rarely finds the pose: a vote on angle differences cannot tell
parallel walls apart, and the ``rho`` differences (5.2) compare distances
measured from two different origins, so the shift (5.4) puts the lines where
they are not (the erratum registered for 5.4).  What :func:`relocalize` does
instead (``DESIGN.md``, measured in notebook 09):

1. the angle votes propose rotations
   (:func:`~cga_lessons.relocalization.search.propose_rotations`);
2. for each rotation, pairs of non-parallel scan lines matched to pairs of map
   lines give exact translations (3.11-3.12); the matched segments must lie
   on each other; along a corridor, positions along the walls are tried
   (:func:`~cga_lessons.relocalization.search.pose_hypotheses`);
3. the hypotheses are screened on a few beams, the best clearly different
   ones checked against the whole scan, beams without return included: a
   beam must not cross a map wall before its point, or within the laser's
   range when it returned nothing
   (:func:`~cga_lessons.relocalization.verify.score_poses`), and the
   contenders refined on the scan's points
   (:func:`~cga_lessons.relocalization.verify.refine_pose_points`);
4. the answer is *ambiguous* when a clearly different pose scores at least
   ``ambiguity_ratio`` (98 %) of the best, or fails to explain at most twice
   what the best fails to explain (``deficit_ratio``): another candidate, or the best
   itself moved along its least constrained direction (a symmetric room, a
   corridor, identical rooms, a corner whose walls run out of range).

On a map built from a robot's own scans (a real log) the map has holes: a
scan may look where no mapping scan did.  A map prepared with the coverage
grid of its scans (``prepare_map(segments, coverage)``, see
:mod:`cga_lessons.relocalization.coverage`) is judged only where it knows
something: beams ending in unknown space are left unexplained (neither for nor
against the pose), beams ending where the mapping scans looked through count
against it, beams without return count half (a laser misses glass and black
surfaces; :data:`~cga_lessons.relocalization.verify.NO_RETURN_WEIGHT`), and the distance
thresholds grow with the scan's range noise and the map's own blur together
(:func:`combined_noise`).  A rival pose that fails to explain at most twice
what the best fails to explain ties with it (``deficit_ratio``): in a
corridor of a partial map the answer is *ambiguous*, not a confident pose
slid along it.

When one scan is not enough, :class:`cga_lessons.relocalization.sequence.Relocalizer`
takes more (a turn on the spot, or driving on) with the odometry between
them and keeps every candidate until the scans tell them apart.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import extract_segments

from .candidates import Candidate, decide, screen_hypotheses, verify_hypotheses
from .geometry import Observation, ReferenceMap, ScanLines, range_noise, reference_map
from .inputs import as_segment_array, check_scan
from .params import STATUSES, RelocParams, RelocSearch, check_extraction, check_score, noise_scaled, resolve_params
from .search import pose_hypotheses, propose_rotations
from .thesis import ThesisRelocalization, thesis_relocalization
from .verify import match_lines, pose_covariance

__all__ = [
    "Relocalization",
    "relocalize",
    "combined_noise",
]


@dataclass(kw_only=True)
class Relocalization:
    """The result of :func:`relocalize` (built by keyword).

    Attributes
    ----------
    pose : ndarray, shape (3,) or None
        ``(x, y, theta)`` of the laser in the map frame (the best candidate);
        None only when no hypothesis could be made.
    score : float
        The best candidate's score (fraction of returned beams on the map,
        less the beams that would cross a wall); ``-inf`` with no candidate.
    status : str
        ``"ok"``, ``"ambiguous"`` or ``"failed"``.
    candidates : list of Candidate
        Verified poses, best first, pairwise clearly different.
    correspondences : ndarray of int, shape (k, 2)
        ``(map index, scan index)`` of the lines matched at ``pose``.
    scan_segments : ndarray, shape (L, 2, 2)
        The scan's segments in the laser frame.
    rotations : ndarray
        The rotations proposed by the angle votes.
    n_hypotheses : int
    covariance : ndarray, shape (3, 3)
        Of ``pose`` (x, y, theta), from the scan's points on the map's walls;
        ``inf`` along a direction the scan does not fix.
    range_noise : float
        The scan's range noise (m) estimated from its ranges
        (:func:`~cga_lessons.relocalization.geometry.estimate_range_noise`),
        0 without a raw scan; the distance thresholds grow with it.
    message : str
        Why the result is ambiguous or failed.
    ambiguous : bool
        Read from ``status``: True when the pose must not be trusted (another
        clearly different pose scores almost as well, the scan does not fix
        the pose, or the search failed), that is unless ``status`` is ``"ok"``.
    thesis, votes, thesis_pose, thesis_correspondences
        The literal method's result (:class:`~cga_lessons.relocalization.thesis.ThesisRelocalization`):
        the thesis's vote matrix (5.6) ``(|M|, |L|)``, its pose (steps 6-10,
        None without correspondences) and its correspondence vector ``C``
        (``-1`` for none); computed when first read.
    """

    pose: np.ndarray | None
    score: float
    status: str
    candidates: list = field(default_factory=list)
    correspondences: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), int))
    scan_segments: np.ndarray = field(default_factory=lambda: np.zeros((0, 2, 2)))
    rotations: np.ndarray = field(default_factory=lambda: np.zeros(0))
    n_hypotheses: int = 0
    covariance: np.ndarray = field(default_factory=lambda: np.full((3, 3), np.inf))
    range_noise: float = 0.0
    message: str = ""
    _thesis_input: tuple | None = field(default=None, repr=False)
    _thesis: ThesisRelocalization | None = field(default=None, repr=False)

    def __post_init__(self):
        f = "Relocalization"
        self.status = checks.choice(self.status, f, "status", STATUSES)
        if self.pose is None and self.status != "failed":
            raise checks.fail(f, "pose", f"None only for a failed result, not one with status {self.status!r}")
        self.pose = None if self.pose is None else checks.array(self.pose, f, "pose", (3,))
        self.score = check_score(self.score, f, failed=self.status == "failed")
        checks.instance(self.candidates, f, "candidates", list, "a list of Candidate")
        for c in self.candidates:
            checks.instance(c, f, "candidates", Candidate, "a list of Candidate")
        pairs = checks.array(self.correspondences, f, "correspondences", (None, 2))
        if np.any(pairs < 0) or np.any(pairs != np.round(pairs)):
            raise checks.fail(f, "correspondences", "must be whole numbers >= 0 (map index, scan index)")
        self.correspondences = pairs.astype(int)
        self.scan_segments = checks.array(self.scan_segments, f, "scan_segments", (None, 2, 2))
        self.rotations = checks.array(self.rotations, f, "rotations", (None,))
        self.n_hypotheses = checks.integer(self.n_hypotheses, f, "n_hypotheses", low=0)
        self.covariance = checks.array(self.covariance, f, "covariance", (3, 3), finite=False)
        if np.any(np.isnan(self.covariance)) or np.any(self.covariance == -np.inf):
            raise checks.fail(f, "covariance", "contains NaN or -inf (inf only along a direction not fixed)")
        self.range_noise = checks.real(self.range_noise, f, "range_noise", low=0.0)
        self.message = checks.text(self.message, f, "message", empty=True)

    @property
    def ambiguous(self) -> bool:
        """The pose must not be trusted: ``status`` is ``"ambiguous"`` or ``"failed"``."""
        return self.status != "ok"

    @property
    def thesis(self) -> ThesisRelocalization:
        """The literal method's output (:func:`~cga_lessons.relocalization.thesis.thesis_relocalization`)."""
        if self._thesis is None:
            M, L, search = self._thesis_input
            self._thesis = thesis_relocalization(M, L, xi_theta=search.xi_theta, xi_rho=search.xi_rho, entities=False)
        return self._thesis

    @property
    def votes(self) -> np.ndarray:
        return self.thesis.votes

    @property
    def thesis_pose(self):
        return self.thesis.pose

    @property
    def thesis_correspondences(self) -> np.ndarray:
        return self.thesis.C


def combined_noise(scan_noise: float, ref: ReferenceMap) -> float:
    """The spread (m) a scan's points show about the map's walls: its range noise and the map's blur together.

    ``hypot(scan_noise, map_noise)``, the two independent; the map's blur is
    measured on its own scans (:func:`~cga_lessons.relocalization.coverage.map_noise`,
    0 without a coverage model).
    """
    scan_noise = checks.real(scan_noise, "combined_noise", "scan_noise", low=0.0)
    cov = checks.instance(ref, "combined_noise", "ref", ReferenceMap, "a ReferenceMap (prepare_map)").coverage
    return float(np.hypot(scan_noise, cov.noise if cov is not None else 0.0))


# --------------------------------------------------------------------------- the search


def relocalize(
    map_segments,
    scan_segments=None,
    *,
    scan=None,
    max_range: float = 5.0,
    params: RelocParams | None = None,
    extraction: dict | None = None,
    **overrides,
) -> Relocalization:
    """Find the laser's pose in a line map from one scan (chapter 5).

    Parameters
    ----------
    map_segments : list of Segment, array_like (M, 2, 2) or ReferenceMap
        The map ``M`` in the map frame (wall faces may run either way).
    scan_segments : list of Segment or array_like (L, 2, 2), optional
        The local map ``L`` in the laser frame, as extracted from a scan (the
        sensor on each segment's left).  Extracted from ``scan`` if omitted.
    scan : (ranges, angles), optional
        The raw scan (arrays (n,), ``inf`` or NaN for no return).  With it
        the pose is checked beam by beam, beams without return included;
        without it, against points along the scan segments.
    max_range : float
        The laser's reach (m): readings at or beyond it are no return.
    params : RelocParams, optional
        Thresholds by stage (:class:`~cga_lessons.relocalization.params.RelocSearch`,
        :class:`~cga_lessons.relocalization.params.RelocCheck`); keyword ``overrides`` replace
        single fields (``xi_theta=0.1``), a stage or some of its fields (``check={"min_score": 0.4}``).
    extraction : dict, optional
        Keyword arguments for :func:`cga_lessons.mapping2d.lines.extract_segments`
        (its ``xi`` defaults to 3 cm or three times the scan's range noise,
        whichever is larger).

    Returns
    -------
    Relocalization

    Raises
    ------
    InvalidInputError
        For an empty or malformed map, malformed segments or scan, NaN or
        inf in the geometry, an unknown parameter or a threshold of the wrong
        type or out of its range (:class:`RelocParams`).
    DegenerateGeometryError
        For a segment of zero length.

    A scan with too few lines, or without a returned beam, is not an error:
    the result says ``status="failed"`` (``score`` ``-inf``, no ``pose``).
    """
    ref, L, obs, noise, params = _inputs(map_segments, scan_segments, scan, max_range, params, extraction, overrides)
    search, check = params.search, params.check
    base = dict(scan_segments=L, range_noise=noise, _thesis_input=(ref.segments, L, search))
    if len(L) < 2:
        return _failed(f"too few lines in the scan ({len(L)}); need two non-parallel", base)
    if not len(obs.points):
        return _failed("no returned beam in the scan", base)
    S, M = ScanLines(L), ref.lines
    rotations, poses, quick = _hypotheses(M, S, search)
    base.update(rotations=rotations, n_hypotheses=len(poses))
    chosen = screen_hypotheses(M, obs, poses, quick, search, check)
    if not len(chosen):
        return _failed("no pose hypothesis (no two non-parallel lines match the map)", base)
    ranked = verify_hypotheses(M, obs, chosen, check)
    best = ranked[0]
    pairs = match_lines(
        M, S, best.pose, search.line_tolerance, search.parallel_tol, search.overlap_margin, search.min_overlap
    )
    cov = pose_covariance(M, obs, best.pose, check.inlier_distance)
    status, msg = decide(M, obs, ranked, check)
    return Relocalization(
        pose=best.pose,
        score=best.score,
        status=status,
        candidates=ranked,
        correspondences=pairs,
        covariance=cov,
        message=msg,
        **base,
    )


def _failed(message: str, base: dict) -> Relocalization:
    """The result of a relocalization that found no pose: ``status="failed"``, score ``-inf``, and why."""
    return Relocalization(pose=None, score=-np.inf, status="failed", message=message, **base)


def _inputs(map_segments, scan_segments, scan, max_range, params, extraction, overrides):
    """The checked inputs of :func:`relocalize`: the map, the scan's lines, the observation, the scan's range
    noise and the thresholds (grown with the noise)."""
    func = "relocalize"
    params = resolve_params(params, overrides, func)
    max_range = checks.real(max_range, func, "max_range", low=0.0, strict_low=True)
    extraction = check_extraction(extraction, func)
    ref = reference_map(map_segments, func)
    if scan is None and scan_segments is None:
        raise checks.fail(func, "scan_segments, scan", "give scan_segments, scan=(ranges, angles), or both")
    noise = 0.0
    if scan is not None:
        ranges, angles = check_scan(scan, func)
        obs = Observation.from_scan(ranges, angles, max_range)
        noise = range_noise(np.where(ranges < max_range, ranges, np.inf))
        params = noise_scaled(params, combined_noise(noise, ref))
    if scan_segments is None:
        segs = extract_segments(ranges, angles, **{"max_range": max_range, "xi": max(0.03, 3 * noise), **extraction})
        L = as_segment_array(segs, func, "scan", allow_empty=True) if segs else np.zeros((0, 2, 2))
    else:
        L = as_segment_array(scan_segments, func, "scan_segments", allow_empty=True)
    if scan is None:
        obs = Observation.from_segments(L)
    return ref, L, obs, noise, params


def _hypotheses(M, S, search: RelocSearch):
    """Rotations from the angle votes and, for each, the pose hypotheses with their quick scores."""
    rotations, rot_votes = propose_rotations(M.angle, S.angle, S.length, search.xi_theta, search.n_rotations)
    if len(rotations):
        rotations = rotations[rot_votes >= search.rotation_vote_ratio * rot_votes.max()]
    poses, quick = [np.zeros((0, 3))], [np.zeros(0)]
    for rot in rotations:
        p, q = pose_hypotheses(
            M,
            S,
            rot,
            parallel_tol=search.parallel_tol,
            n_anchor_pairs=search.n_anchor_pairs,
            min_anchor_angle=search.min_anchor_angle,
            overlap_margin=search.overlap_margin,
            min_overlap=search.min_overlap,
            line_tolerance=search.line_tolerance,
            slide_step=search.slide_step,
            slide_below=search.slide_below,
        )
        poses.append(p)
        quick.append(q)
    return rotations, np.concatenate(poses), np.concatenate(quick)
