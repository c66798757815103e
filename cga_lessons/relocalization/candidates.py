"""The steps of :func:`cga_lessons.relocalization.relocalize` after the hypotheses: candidates screened, verified,
ranked and decided.

* :func:`screen_hypotheses`: the hypotheses near the best quick score, checked on a subset of the beams;
* :func:`verify_hypotheses`: refined, checked, and moved along the least constrained direction while the score
  improves (beams through doors and past wall ends can fix a position the points on parallel walls leave open);
* :func:`decide`: ok, ambiguous or failed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks

from .geometry import pose_errors
from .params import RelocCheck, RelocSearch
from .verify import pose_information, refine_pose_points, score_poses

__all__ = ["Candidate", "distinct", "screen_hypotheses", "refine_if_better", "verify_hypotheses", "tie_bar", "decide"]


@dataclass
class Candidate:
    """One verified pose: ``pose`` (3,), its ``score`` and the ``inliers`` and ``violations`` behind it
    (weighted counts of beams, see :func:`score_poses`)."""

    pose: np.ndarray
    score: float
    inliers: float
    violations: float

    def __post_init__(self):
        f = "Candidate"
        self.pose = checks.array(self.pose, f, "pose", (3,))
        self.score = checks.real(self.score, f, "score")
        self.inliers = checks.real(self.inliers, f, "inliers", low=0.0)
        self.violations = checks.real(self.violations, f, "violations", low=0.0)


def distinct(p, q, check: RelocCheck) -> bool:
    """Are two poses clearly different (further apart than ``check.distinct_position`` or turned more than
    ``check.distinct_heading``)?"""
    dp, dh = pose_errors(p, q)
    return dp > check.distinct_position or dh > check.distinct_heading


def screen_hypotheses(M, obs, poses, quick, search: RelocSearch, check: RelocCheck):
    """The hypotheses near the best quick score, one per small cell of pose space, checked on a subset of
    the beams; the best of each group of poses that are not clearly different goes on: all those within
    90 % of the best screening score (up to ``4 n_verify``), at least ``n_verify``.

    The last step of the search (``search``: the quick score's ratio, how many are screened on how many beams)
    with the check's tolerances (``check``: twice its ``inlier_distance`` and ``ray_margin``, its
    ``n_verify`` and its distinctness)."""
    chosen = np.zeros((0, 3))
    if not len(poses):
        return chosen
    keep = np.flatnonzero(quick >= search.quick_ratio * quick.max())
    keep = keep[np.argsort(-quick[keep], kind="stable")]
    cells = np.column_stack([np.round(poses[keep, :2] / 0.03), np.round(poses[keep, 2] / np.radians(0.5))])
    _, first = np.unique(cells.astype(np.int64), axis=0, return_index=True)
    keep = keep[np.sort(first)][: search.n_screen]
    step = max(1, len(obs.points) // search.screen_beams)
    # twice the tolerances: a hypothesis is only as good as its voted rotation until it is refined
    sc, _, _ = score_poses(M, obs, poses[keep], 2 * check.inlier_distance, 2 * check.ray_margin, step)
    order = np.argsort(-sc, kind="stable")
    for k, score in zip(keep[order], sc[order]):
        # every clearly different pose near the best screening score goes on (twins must not be missed),
        # then the next best up to n_verify
        if len(chosen) >= check.n_verify and (score < 0.9 * sc.max() or len(chosen) >= 4 * check.n_verify):
            break
        if all(distinct(poses[k], c, check) for c in chosen):
            chosen = np.vstack([chosen, poses[k]])
    return chosen


def refine_if_better(M, obs, poses, inlier_distance: float, ray_margin: float):
    """Poses (C, 3) refined on the scan's points (:func:`refine_pose_points`) where that scores at least as
    well against the whole scan; returns the poses and their scores, inliers and violations."""
    sc, inl, vio = score_poses(M, obs, poses, inlier_distance, ray_margin)
    refined = refine_pose_points(M, obs, poses)
    sc2, inl2, vio2 = score_poses(M, obs, refined, inlier_distance, ray_margin)
    better = sc2 >= sc
    poses = np.where(better[:, None], refined, poses)
    return poses, np.where(better, sc2, sc), np.where(better, inl2, inl), np.where(better, vio2, vio)


def verify_hypotheses(M, obs, chosen, check: RelocCheck):
    """Every chosen pose refined on the scan's points, then checked against the whole scan; the refined
    pose is kept where it scores at least as well as the unrefined one."""
    chosen, sc, inl, vio = refine_if_better(M, obs, chosen, check.inlier_distance, check.ray_margin)
    # the contenders: a few steps along the direction the points leave weakest (a corridor), where beams
    # through doors and past wall ends may still decide
    for k in np.flatnonzero(sc >= 0.9 * sc.max()) if np.isfinite(sc.max()) else []:
        H, _ = pose_information(M, obs, chosen[k], check.inlier_distance)
        weak = np.linalg.eigh(H[:2, :2])[1][:, 0]
        coarse, rounds = True, 0
        while rounds < 5:
            steps = [-0.2, -0.1, -0.05, 0.05, 0.1, 0.2] if coarse else [-0.02, 0.02]
            trial = chosen[k] + np.column_stack([np.outer(steps, weak), np.zeros(len(steps))])
            s3, i3, v3 = score_poses(M, obs, trial, check.inlier_distance, check.ray_margin)
            j = int(np.argmax(s3))
            if s3[j] > sc[k]:
                chosen[k], sc[k], inl[k], vio[k] = trial[j], s3[j], i3[j], v3[j]
            elif not coarse:
                break
            else:
                coarse = False  # no better coarse step: one fine step more
            rounds += 1
    ranked = []
    for k in np.argsort(-sc, kind="stable"):
        if all(distinct(chosen[k], r.pose, check) for r in ranked):
            ranked.append(Candidate(chosen[k], float(sc[k]), inl[k].item(), vio[k].item()))
    return ranked


def tie_bar(best: float, check: RelocCheck, n_scans: int = 1) -> float:
    """The score at which a clearly different pose ties with the best one (scoring ``best``).

    ``min(ambiguity_ratio * best, best - deficit_ratio * (1 - best) / sqrt(n_scans))``: at
    least ``ambiguity_ratio`` of the best, or a *deficit* ``1 - score`` at
    most ``1 + deficit_ratio / sqrt(n_scans)`` times the best's.  The deficit is what the map
    fails to explain at the best pose (holes, clutter, a blurred wall); a
    rival that fails to explain not much more may be the true pose scored
    down by the same imperfections, so the answer is not trusted.  On a
    complete map (score about 0.99) the first term decides.

    ``n_scans``: the scores are summed over this many scans taken from different poses (a chain of
    :class:`~cga_lessons.relocalization.sequence.Relocalizer`).  The margin ``deficit_ratio`` covers how much the
    true pose's deficit varies from one look to the next (which holes and clutter the beams happen to meet); a sum
    over ``n`` looks varies ``sqrt(n)`` times less relative to its size, so the margin shrinks by that factor.
    """
    return min(check.ambiguity_ratio * best, best - check.deficit_ratio * (1.0 - best) / np.sqrt(n_scans))


def decide(M, obs, ranked, check: RelocCheck):
    """``(status, message)``: failed below ``min_score``; ambiguous when a clearly different candidate, or the
    best moved by ``distinct_position`` along its least constrained direction (or turned by
    ``distinct_heading``), ties with the best (:func:`tie_bar`)."""
    best = ranked[0]
    if best.score < check.min_score:
        return "failed", f"best score {best.score:.3f} below min_score {check.min_score}"
    bar = tie_bar(best.score, check)
    rivals = [c for c in ranked[1:] if c.score >= bar]
    if rivals:
        return "ambiguous", f"{len(rivals)} clearly different pose(s) score >= {bar:.3f}, tied with the best"
    H, _ = pose_information(M, obs, best.pose, check.inlier_distance)
    weak = np.linalg.eigh(H[:2, :2])[1][:, 0]
    d, a = check.distinct_position * 1.01, check.distinct_heading * 1.01
    probes = best.pose + np.array([[*(d * weak), 0.0], [*(-d * weak), 0.0], [0.0, 0.0, a], [0.0, 0.0, -a]])
    sc, inl, vio = score_poses(M, obs, probes, check.inlier_distance, check.ray_margin)
    if np.any(sc >= bar):
        k = int(np.argmax(sc))
        ranked.insert(1, Candidate(probes[k], float(sc[k]), inl[k].item(), vio[k].item()))  # the evidence
        return "ambiguous", (
            f"the pose moved by {check.distinct_position} m along ({weak[0]:.2f}, {weak[1]:.2f}) or turned by "
            f"{np.degrees(check.distinct_heading):.1f} deg ties with it (score >= {bar:.3f}): "
            "the scan does not fix it"
        )
    return "ok", ""
