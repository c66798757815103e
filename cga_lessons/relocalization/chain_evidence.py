"""What the scans taken so far say about a chain of poses: its beam counts per scan, the direction they fix least,
the chain slid along it, and the decision of a :class:`~cga_lessons.relocalization.sequence.Relocalizer`.

:class:`ScanEvidence` holds the scans (their observations, each one's check stage grown with its noise, their
returned beams); :func:`polish_chain` slides a chain along its least constrained direction while the summed score
grows; :func:`decide_chain` is the rule of a single relocalization
(:func:`~cga_lessons.relocalization.candidates.decide`) applied to all the scans together, with the odometry's
check (:func:`~cga_lessons.relocalization.odometry.odometry_misfit`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons.mapping2d import OdometryModel

from .candidates import Candidate, refine_if_better, tie_bar
from .chain import Chain
from .geometry import MapLines, Observation
from .odometry import odometry_misfit
from .params import RelocCheck
from .verify import pose_information, score_poses

__all__ = ["ScanEvidence", "polish_chain", "decide_chain", "rigid_motion"]


@dataclass
class ScanEvidence:
    """The scans of a sequence, as evidence about chains of poses (one pose per scan).

    Attributes
    ----------
    lines : MapLines
        The map.
    observations : list of Observation
        The scans, in order.
    checks : list of RelocCheck
        Each scan's check stage, its distances grown with the scan's noise
        (:func:`~cga_lessons.relocalization.params.noise_scaled`).
    sigmas : list of float
        Each scan's spread about the map's walls (m,
        :func:`~cga_lessons.relocalization.relocalizer.combined_noise`).
    returned : ndarray of int
        Each scan's returned beams.
    """

    lines: MapLines
    observations: list = field(default_factory=list)
    checks: list = field(default_factory=list)
    sigmas: list = field(default_factory=list)
    returned: np.ndarray = field(default_factory=lambda: np.zeros(0, int))

    def add(self, obs: Observation, check: RelocCheck, sigma: float) -> None:
        """One scan more."""
        self.observations.append(obs)
        self.checks.append(check)
        self.sigmas.append(sigma)
        self.returned = np.append(self.returned, len(obs.points))

    def __len__(self) -> int:
        return len(self.observations)

    def score(self, j, poses):
        """Scores, inliers and violations of poses (C, 3) against scan ``j``
        (:func:`~cga_lessons.relocalization.verify.score_poses`)."""
        c = self.checks[j]
        return score_poses(self.lines, self.observations[j], poses, c.inlier_distance, c.ray_margin)

    def fit(self, j, poses):
        """Poses (C, 3) snapped to scan ``j``'s points where that scores better; with their inliers, violations."""
        c = self.checks[j]
        poses, _, inl, vio = refine_if_better(self.lines, self.observations[j], poses, c.inlier_distance, c.ray_margin)
        return poses, inl, vio

    def per_scan(self, poses):
        """Inliers and violations (n_scans,) of one chain of poses (n_scans, 3), scan by scan."""
        out = [self.score(j, q[None]) for j, q in enumerate(poses)]
        return np.array([float(o[1][0]) for o in out]), np.array([float(o[2][0]) for o in out])

    def summed(self, poses):
        """Inliers and violations summed over the scans, for one chain of poses (n_scans, 3)."""
        inl, vio = self.per_scan(poses)
        return float(inl.sum()), float(vio.sum())

    def weak_direction(self, poses) -> np.ndarray:
        """The unit position direction (2,) that the scans constrain least, for a chain of poses (n_scans, 3).

        Every scan's information about its own pose (``J^T J`` of
        :func:`~cga_lessons.relocalization.verify.pose_information`) is carried
        to the last pose through the rigid chain: ``J_j`` maps a change of the
        last pose to the change of pose ``j``.
        """
        last = np.asarray(poses[-1])
        H = np.zeros((3, 3))
        for j, pose in enumerate(poses):
            Hj, _ = pose_information(self.lines, self.observations[j], pose, self.checks[j].inlier_distance)
            dx, dy = np.asarray(pose[:2]) - last[:2]
            J = np.array([[1.0, 0.0, -dy], [0.0, 1.0, dx], [0.0, 0.0, 1.0]])
            H += J.T @ Hj @ J
        return np.linalg.eigh(H[:2, :2])[1][:, 0]


def polish_chain(evidence: ScanEvidence, ch: Chain, rounds: int = 5) -> None:
    """Slide the whole chain along its least constrained direction while the summed score grows (in place).

    The points fix a pose across walls but hardly along a corridor; there
    the beams through doors and past wall ends decide, and they only count
    in the beam score.  Coarse steps (5 to 20 cm), then 2 cm steps.
    """
    weak = evidence.weak_direction(ch.poses)
    poses = np.array(ch.poses)
    cur = float(ch.inliers.sum() - ch.violations.sum())
    coarse = True
    for _ in range(rounds):
        steps = [-0.2, -0.1, -0.05, 0.05, 0.1, 0.2] if coarse else [-0.02, 0.02]
        trials = [(poses + np.array([st * weak[0], st * weak[1], 0.0])) for st in steps]
        per_scan = [evidence.per_scan(t) for t in trials]
        net = [float(i.sum() - v.sum()) for i, v in per_scan]
        k = int(np.argmax(net))
        if net[k] > cur:
            poses, cur = trials[k], net[k]
            ch.poses = list(poses)
            ch.inliers, ch.violations = per_scan[k]
        elif coarse:
            coarse = False
        else:
            break


def decide_chain(
    evidence: ScanEvidence, best: Chain, cands: list, check: RelocCheck, odometry: list, model: OdometryModel
):
    """``(status, message, probe)``: the rule of :func:`~cga_lessons.relocalization.candidates.decide` on the
    summed scores; the probe is the chain moved rigidly along its weakest direction when it ties.

    ``cands``: one :class:`~cga_lessons.relocalization.candidates.Candidate` per chain, best first;
    ``odometry``: the odometry pose of every scan; ``model``: its drift model.
    """
    p = check
    if cands[0].score < p.min_score:
        return "failed", f"best score {cands[0].score:.3f} below min_score {p.min_score}", None
    bad = odometry_misfit(best.poses, odometry, model)
    if bad is not None:
        return "ambiguous", f"the best chain of poses moves against the odometry at scan {bad}", None
    bar = tie_bar(cands[0].score, p, len(evidence))
    rivals = [c for c in cands[1:] if c.score >= bar]
    if rivals:
        return (
            "ambiguous",
            f"{len(rivals)} clearly different pose(s) score >= {bar:.3f}, tied with the best "
            f"after {len(evidence)} scan(s)",
            None,
        )
    last = np.asarray(best.poses[-1])
    weak = evidence.weak_direction(best.poses)
    d, a = p.distinct_position * 1.01, p.distinct_heading * 1.01
    motions = [(d * weak[0], d * weak[1], 0.0), (-d * weak[0], -d * weak[1], 0.0), (0.0, 0.0, a), (0.0, 0.0, -a)]
    scores, details = [], []
    for mx, my, ma in motions:
        moved = np.array([rigid_motion(np.asarray(q), last[:2], mx, my, ma) for q in best.poses])
        inl, vio = evidence.summed(moved)
        scores.append((inl - vio) / evidence.returned.sum())
        details.append((rigid_motion(last, last[:2], mx, my, ma), inl, vio))
    kbest = int(np.argmax(scores))
    if scores[kbest] >= bar:
        pose, inl, vio = details[kbest]
        return (
            "ambiguous",
            f"the poses moved by {p.distinct_position} m along ({weak[0]:.2f}, {weak[1]:.2f}) or turned by "
            f"{np.degrees(p.distinct_heading):.1f} deg tie with them (score >= {bar:.3f}): "
            f"{len(evidence)} scan(s) do not fix the pose",
            Candidate(pose, float(scores[kbest]), inl, vio),
        )
    return "ok", "", None


def rigid_motion(pose, centre, mx, my, ma):
    """A pose moved by the rigid motion: turn by ``ma`` about ``centre``, then shift by ``(mx, my)``."""
    c, s = np.cos(ma), np.sin(ma)
    d = pose[:2] - centre
    return np.array([centre[0] + c * d[0] - s * d[1] + mx, centre[1] + s * d[0] + c * d[1] + my, pose[2] + ma])
