"""Chains of poses, one per scan, fitted to their scans and to the odometry between them at once.  (Beyond chapter 5.)

A robot relocalizing from several scans (:mod:`cga_lessons.relocalization.sequence`)
carries hypotheses that are chains of poses, one per scan.  Snapping each pose
to its own scan alone lets a chain slide: in a corridor a scan fixes the pose
across the walls and hardly along them, so each pose slides along the corridor
by whatever its scan leaves free, and the chain's steps no longer agree with
the odometry (measured on the ACES log, runs of three scans: most chains, the
right one too, ended tens of centimetres to metres off the odometry's steps).

:func:`refine_chains` estimates the poses of each chain together, by
Gauss-Newton on two kinds of residual:

* every returned point of scan ``j`` against the map wall its beam meets first
  at pose ``P_j`` (:func:`~cga_lessons.relocalization.verify.point_normal_equations`,
  the terms of :func:`~cga_lessons.relocalization.verify.refine_pose_points`), with the spread
  ``sigma_j`` the scan's points show about the map's walls;
* every step ``P_{j-1} -> P_j`` against the odometry increment ``u_j``: the
  residual ``P_j - (P_{j-1} (+) u_j)`` with the drift model's covariance of that
  increment (:meth:`~cga_lessons.mapping2d.laser.OdometryModel.step_covariance`, the same
  in every direction of the plane, so the world frame serves).

Where the scans fix the pose the points decide; along a corridor the odometry
does.  :class:`Chain` holds one hypothesis and its beam counts,
:class:`SequenceRelocalization` the relocalizer's answer.

The points of one scan are weighed as independent although the map's blur is
common to the points of one wall; the weighting is therefore optimistic across
walls, where the odometry hardly matters anyway.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import OdometryModel, wrap_angle

from .geometry import MapLines
from .verify import point_normal_equations

__all__ = ["Chain", "SequenceRelocalization", "refine_chains", "CHAIN_GATES", "STILL_VARIANCE"]

#: Association distances (m) of the Gauss-Newton rounds: wide first, so that a pose started
#: a few decimetres off (a chain carried by the odometry) finds its walls, then tight.
CHAIN_GATES = (0.3, 0.15, 0.08, 0.05)
#: Smallest variance (m^2 and rad^2) of an odometry step: the drift model gives 0 for a robot standing
#: still; 1 mm and 0.06 degrees are below any laser's registration error, so the scans still decide.
STILL_VARIANCE = 1e-6


@dataclass(kw_only=True)
class SequenceRelocalization:
    """The state of a :class:`~cga_lessons.relocalization.sequence.Relocalizer` after its latest scan (built by
    keyword).

    Attributes
    ----------
    pose : ndarray, shape (3,) or None
        The laser's pose in the map frame at the latest scan (the best chain).
    score : float
        The best chain's score over all its scans.
    status : str
        ``"ok"``, ``"ambiguous"`` or ``"failed"``.
    candidates : list of Candidate
        One per chain, best first, at the latest scan, with the chain's summed
        score, inliers and violations; pairwise clearly different.
    trajectory : ndarray, shape (n_scans, 3)
        The best chain: the laser's pose at every scan so far.
    n_scans : int
    message : str
    single : list of Relocalization
        Each scan relocalized on its own.
    ambiguous : bool
        Read from ``status``: the pose must not be trusted unless ``status`` is ``"ok"``.
    """

    pose: np.ndarray | None
    score: float
    status: str
    candidates: list = field(default_factory=list)
    trajectory: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    n_scans: int = 0
    message: str = ""
    single: list = field(default_factory=list, repr=False)

    @property
    def ambiguous(self) -> bool:
        """The pose must not be trusted: ``status`` is ``"ambiguous"`` or ``"failed"``."""
        return self.status != "ok"


@dataclass
class Chain:
    """One hypothesis of a :class:`~cga_lessons.relocalization.sequence.Relocalizer`: a pose per scan so far.

    Attributes
    ----------
    poses : list of ndarray, shape (3,)
        The laser's pose at each scan.
    inliers, violations : ndarray, shape (n_scans,)
        Each scan's beam counts at its pose (:func:`~cga_lessons.relocalization.verify.score_poses`).
    """

    poses: list
    inliers: np.ndarray
    violations: np.ndarray

    def score(self, returned: np.ndarray) -> float:
        """``(inliers - violations) / returned beams``, summed over the scans (``returned``: per scan)."""
        n = returned.sum()
        return float((self.inliers.sum() - self.violations.sum()) / n) if n else -np.inf


def refine_chains(
    M: MapLines,
    observations,
    increments,
    chains,
    sigmas,
    model: OdometryModel | None = None,
    *,
    anchor=None,
    gates=CHAIN_GATES,
) -> np.ndarray:
    """The chains' poses fitted to their scans' points and to the odometry increments together.

    Parameters
    ----------
    M : MapLines
        The map.
    observations : sequence of Observation, length n
        The scans, one per pose of a chain.
    increments : array_like, shape (n - 1, 3), or (n, 3) with ``anchor``
        The odometry increment of each step (in the frame of the earlier pose).
        With ``anchor``, the first increment leads from the anchor to the first pose.
    chains : array_like, shape (C, n, 3)
        Starting poses ``(x, y, theta)``.
    sigmas : array_like, shape (n,)
        Spread (m) of each scan's points about the walls (> 0).
    model : OdometryModel, optional
        The drift model (default :class:`~cga_lessons.mapping2d.laser.OdometryModel`).
    anchor : array_like, shape (C, 3), optional
        A fixed pose before the first (the chain's earlier poses, held).
    gates : sequence of float
        Association distances (m), one Gauss-Newton step each.

    Returns
    -------
    ndarray, shape (C, n, 3)

    A step the scans and the odometry leave free (no point, no increment)
    stays where it is (a small damping on every pose).
    """
    func = "refine_chains"
    P = checks.array(chains, func, "chains", (None, None, 3)).copy()
    C, n, _ = P.shape
    obs = list(observations)
    sig = checks.array(sigmas, func, "sigmas", (n,))
    U = checks.array(increments, func, "increments", (3,) if np.ndim(increments) == 1 else (None, 3)).reshape(-1, 3)
    if len(U) != n - (anchor is None):
        raise checks.fail(func, "increments", f"need {n - (anchor is None)} (one per step), got {len(U)}")
    A = None if anchor is None else checks.array(anchor, func, "anchor", (C, 3))
    if len(obs) != n:
        raise checks.fail(func, "observations", f"need {n} (one per pose of a chain), got {len(obs)}")
    if np.any(sig <= 0):
        raise checks.fail(func, "sigmas", f"must be > 0, got {sig.tolist()}")
    m = OdometryModel() if model is None else model
    inv_var = [1.0 / np.maximum(np.diag(m.step_covariance(u)), STILL_VARIANCE) for u in U]
    N = 3 * n
    for gate in gates:
        H = np.zeros((C, N, N))
        g = np.zeros((C, N))
        for j in range(n):
            Hj, gj, _, _ = point_normal_equations(M, obs[j], P[:, j], gate)
            H[:, 3 * j : 3 * j + 3, 3 * j : 3 * j + 3] += Hj / sig[j] ** 2
            g[:, 3 * j : 3 * j + 3] += gj / sig[j] ** 2
        for k, u in enumerate(U):
            j = k + (A is None)  # the pose this step leads to
            prev = A if j == 0 else P[:, j - 1]
            _add_step(H, g, prev, P[:, j], u, inv_var[k], None if j == 0 else j - 1, j)
        H += 1e-9 * np.eye(N) + 1e-6 * np.einsum("cii->ci", H)[:, :, None] * np.eye(N)
        step = -np.linalg.solve(H, g[..., None])[..., 0]
        P = P + step.reshape(C, n, 3)
        P[..., 2] = wrap_angle(P[..., 2])
    return P


def _add_step(H, g, a, b, u, inv_var, ia, ib):
    """The odometry residual ``b - (a (+) u)`` of one step added to ``H``, ``g`` (``ia`` None: ``a`` is held)."""
    c, s = np.cos(a[:, 2]), np.sin(a[:, 2])
    rx = b[:, 0] - a[:, 0] - (c * u[0] - s * u[1])
    ry = b[:, 1] - a[:, 1] - (s * u[0] + c * u[1])
    rt = wrap_angle(b[:, 2] - a[:, 2] - u[2])
    r = np.stack([rx, ry, rt], axis=-1)  # (C, 3)
    W = np.diag(inv_var)  # d r / d b is the identity
    bj = slice(3 * ib, 3 * ib + 3)
    H[:, bj, bj] += W
    g[:, bj] += r * inv_var
    if ia is None:
        return
    # d r / d a: -I on the position, the rotated increment's derivative on the heading
    Ja = np.zeros((len(a), 3, 3))
    Ja[:, 0, 0] = Ja[:, 1, 1] = Ja[:, 2, 2] = -1.0
    Ja[:, 0, 2] = s * u[0] + c * u[1]
    Ja[:, 1, 2] = -(c * u[0] - s * u[1])
    aj = slice(3 * ia, 3 * ia + 3)
    H[:, aj, aj] += np.einsum("cki,k,ckj->cij", Ja, inv_var, Ja)
    H[:, aj, bj] += np.einsum("cki,kj->cij", Ja, W)
    H[:, bj, aj] += np.einsum("ik,ckj->cij", W, Ja)
    g[:, aj] += np.einsum("cki,ck->ci", Ja, r * inv_var)
