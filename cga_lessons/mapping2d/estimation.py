"""The per-scan pose correction as a robust estimate with a prior, and the test that admits it (beyond 3.1.3).

The thesis corrects every scan by the mean angle difference (3.8) and the
least-squares offset (3.12) of its correspondences, and applies the result.
On real logs that is not enough (measured on the six bundled CARMEN logs: fed
their own corrected poses, the unconditional corrector moved them by 0.15-0.8 m
RMS).  Here the thesis's measurements are the rows of one estimate:

* :class:`Measurements`: every correspondence gives two linear measurements of
  the correction ``(t_x, t_y, theta)`` (its angle difference 3.8 and its offset
  3.11 taken at the segment's centroid), each real edge seen again one more,
  each with the variance of its fit plus a model floor
  (:class:`cga_lessons.mapping2d.noise.NoiseFloors`);
* :func:`estimate_correction`: iteratively reweighted least squares with a
  Huber kernel (an outlier pair is down-weighted, not obeyed) and the *a
  posteriori variance factor* ``s^2`` (how much the residuals say the stated
  variances understate the truth), giving the measurement-only estimate in
  the directions the lines fix; its covariance gets the registration's own
  error (common to every row of a scan, so not averaged away by many lines);
  the odometry's prediction then enters as a prior with its covariance;
* the test: the innovation (where the lines put the pose minus where the
  prediction put it) is compared with its covariance, prior plus
  measurement; a correction whose normalised innovation lies beyond the
  ``level`` quantile of the chi-square law is not applied: the lines and the
  odometry cannot both be right, and a wrong correction is worse than none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import stats

from cga_lessons.algebra import InvalidInputError

__all__ = ["Measurements", "Correction", "estimate_correction"]

#: Weight of the running variance factor when a scan's own is estimated, in residual degrees of freedom.  The
#: running factor averages the last ten or so scans, each with about 10-30 residual degrees of freedom; counted
#: as 20, one scan with two correspondences (dof 1) cannot move it much, one with twenty (dof 37) can.
PRIOR_DOF = 20


@dataclass(frozen=True)
class Measurements:
    """Linear measurements ``H delta = z`` of a pose correction ``delta = (t_x, t_y, theta)``.

    Attributes
    ----------
    H : ndarray, shape (m, 3)
    z : ndarray, shape (m,)
    var : ndarray, shape (m,)
        Each row's variance (its fit's, plus a model floor once :meth:`with_floors` added it).
    group : ndarray of int, shape (m,)
        Rows with the same group come from one correspondence (its angle and
        offset) and share one robust weight.
    kind : ndarray of int, shape (m,)
        0: an angle difference (3.8), 1: an offset (3.11), 2: a real edge seen again.
    """

    H: np.ndarray
    z: np.ndarray
    var: np.ndarray
    group: np.ndarray
    kind: np.ndarray

    @classmethod
    def from_pairs(cls, dth, var_theta, offset, var_offset, normal, lever, edges=None):
        """The rows of the correspondences' angle (3.8) and offset (3.11) measurements, plus real edges.

        Parameters
        ----------
        dth, var_theta, offset, var_offset : array_like, shape (n,)
        normal, lever : array_like, shape (n, 2)
            The global line's normal and the local segment's centroid relative to the robot: the offset row is
            ``offset = n . t + theta (n . J lever)``, ``J`` the quarter turn.
        edges : tuple (H (k, 3), z (k,)), optional
            Along-line measurements of real edges seen again (fit variance 0: their noise is their floor).

        >>> m = Measurements.from_pairs([0.01], [1e-4], [0.02], [1e-4], [[1.0, 0.0]], [[0.0, 2.0]])
        >>> m.H.tolist(), m.kind.tolist()
        ([[0.0, 0.0, 1.0], [1.0, 0.0, -2.0]], [0, 1])
        """
        dth, vt, off, vo = (np.atleast_1d(np.asarray(v, float)) for v in (dth, var_theta, offset, var_offset))
        normal = np.asarray(normal, float).reshape(-1, 2)
        lever = np.asarray(lever, float).reshape(-1, 2)
        n = len(dth)
        if not (len(vt) == len(off) == len(vo) == len(normal) == len(lever) == n):
            raise InvalidInputError("Measurements.from_pairs: the measurement arrays must have the same length")
        H = [np.column_stack([np.zeros((n, 2)), np.ones(n)])]
        H.append(np.column_stack([normal, normal[:, 1] * lever[:, 0] - normal[:, 0] * lever[:, 1]]))
        z, var, group, kind = [dth, off], [vt, vo], [np.arange(n)] * 2, [np.zeros(n, int), np.ones(n, int)]
        if edges is not None and len(edges[0]):
            He, ze = np.asarray(edges[0], float).reshape(-1, 3), np.asarray(edges[1], float)
            H.append(He)
            z.append(ze)
            var.append(np.zeros(len(ze)))
            group.append(n + np.arange(len(ze)))
            kind.append(np.full(len(ze), 2))
        cat = np.concatenate
        return cls(np.vstack(H), cat(z), cat(var), cat(group), cat(kind))

    def with_floors(self, floors):
        """The same rows with ``floors[kind]`` (variances, shape (3,)) added to each row's variance."""
        return Measurements(self.H, self.z, self.var + np.asarray(floors, float)[self.kind], self.group, self.kind)

    def __len__(self):
        return len(self.z)


@dataclass(frozen=True)
class Correction:
    """The result of :func:`estimate_correction`.

    Attributes
    ----------
    delta : ndarray, shape (3,)
        The fused correction (measurements and prior), from the linearisation point.
    cov : ndarray, shape (3, 3)
        Its covariance.
    valid : bool
        The innovation passed the chi-square test: apply the correction.
    nis, threshold : float
        The normalised innovation squared ``g' (S + V' P V)^-1 g`` and the chi-square quantile it was compared with.
    rank : int
        How many directions of the correction the lines fix (3; 2 in a corridor; 0: none).
    basis : ndarray, shape (3, rank)
        Those directions (orthonormal).
    innovation : ndarray, shape (rank,)
        The measurement-only estimate minus the prediction, in ``basis``.
    meas_cov : ndarray, shape (rank, rank)
        The measurement-only estimate's covariance in ``basis`` (registration error included).
    variance_factor : float
        ``s^2``: the measurement variances were scaled by this (at least 1).
    dof : int
        The scan's residual degrees of freedom.
    weights, residuals : ndarray, shape (m,)
        Each row's robust (Huber) weight and its residual at the measurement-only estimate.
    """

    delta: np.ndarray
    cov: np.ndarray
    valid: bool
    nis: float
    threshold: float
    rank: int
    basis: np.ndarray
    innovation: np.ndarray
    meas_cov: np.ndarray
    variance_factor: float
    dof: int
    weights: np.ndarray
    residuals: np.ndarray


@lru_cache(maxsize=64)
def _chi2_quantile(level, dof):
    return float(stats.chi2.ppf(level, dof))


def _huber(u, k):
    a = np.abs(u)
    return np.where(a <= k, 1.0, k / np.maximum(a, 1e-300))


def _eigen_extremes(A):
    """Smallest and largest eigenvalue of a symmetric 3 x 3 matrix, in closed form (the trigonometric solution
    of the characteristic cubic); their absolute error is a few ulps of the largest."""
    (a, b, c), (_, d, e), (_, _, f) = A.tolist()
    q = (a + d + f) / 3.0
    a0, d0, f0 = a - q, d - q, f - q
    p2 = (a0 * a0 + d0 * d0 + f0 * f0 + 2.0 * (b * b + c * c + e * e)) / 6.0
    if p2 <= 0.0:
        return q, q
    p = math.sqrt(p2)
    det = a0 * (d0 * f0 - e * e) - b * (b * f0 - e * c) + c * (b * e - d0 * c)
    phi = math.acos(min(1.0, max(-1.0, det / (2.0 * p2 * p)))) / 3.0
    return q + 2.0 * p * math.cos(phi + 2.0 * math.pi / 3.0), q + 2.0 * p * math.cos(phi)


def _fixed_directions(A, b):
    """``(rank, x)``: the least-squares solution of ``A x = b`` in the directions ``A`` fixes (eigenvalues above
    1e-9 of the largest).  A matrix clearly of full rank (ten times above that cut) is solved directly; the
    eigen-decomposition is needed only near and below it (a corridor, a single line)."""
    lo, hi = _eigen_extremes(A)
    if lo > 1e-8 * hi > 0.0:
        return 3, np.linalg.solve(A, b)
    vals, vecs = np.linalg.eigh(A)
    keep = vals > 1e-9 * max(vals[-1], 1e-300)
    return int(keep.sum()), vecs[:, keep] @ ((vecs[:, keep].T @ b) / vals[keep])


def _solve_robust(meas: Measurements, kernel, iterations, prior_factor):
    """IRLS of the measurements alone: (information A, rhs b, weights, s^2, dof, residuals at the estimate)."""
    H, z, var = meas.H, meas.z, meas.var
    Hz = np.column_stack([H, z])  # one product gives both A = H' W H and b = H' W z
    sd = np.sqrt(var)
    w = np.ones(len(z))
    s2 = prior_factor
    n_groups = meas.group.max() + 1
    for _ in range(iterations + 1):
        info = w / (s2 * var)
        Ab = (Hz * info[:, None]).T @ Hz
        rank, x = _fixed_directions(Ab[:3, :3], Ab[:3, 3])
        res = z - H @ x
        u = res / sd  # in units of the stated sigma
        dof = len(z) - rank
        # the variance factor: the scan's residuals pooled with the running factor (PRIOR_DOF of evidence)
        s2 = max((float(w @ (u * u)) + PRIOR_DOF * prior_factor) / (max(dof, 0) + PRIOR_DOF), 1.0)
        g = _huber(u / math.sqrt(s2), kernel)
        gw = np.ones(n_groups)  # one weight per correspondence: its rows stand or fall together
        np.minimum.at(gw, meas.group, g)
        if np.array_equal(gw[meas.group], w):
            break  # the weights are a fixed point: another round would repeat this one exactly
        w = gw[meas.group]
    Ab = (Hz * (w / (s2 * var))[:, None]).T @ Hz
    return Ab[:3, :3], Ab[:3, 3], w, s2, dof, res


def estimate_correction(
    meas: Measurements,
    prior_cov,
    prior_offset=None,
    *,
    level: float = 0.999,
    kernel: float = 2.0,
    iterations: int = 2,
    prior_factor: float = 1.0,
    model_cov=None,
) -> Correction:
    """Robust weighted least squares of a pose correction, the prediction as prior, and the innovation's test.

    Parameters
    ----------
    meas : Measurements
        The rows, linearised at the current pose, their variances including the floors.
    prior_cov : array_like, shape (3, 3)
        The prediction's covariance.
    prior_offset : array_like, shape (3,), optional
        The correction that returns to the prediction (predicted pose minus the current one), default zero.
    level : float
        The correction is applied only if its normalised innovation lies within this quantile of the
        chi-square law of ``rank`` degrees of freedom (0.999: a right correction is refused once in a
        thousand scans).
    kernel : float
        Huber constant in units of the scaled sigma: rows within it count fully, beyond it with weight
        ``kernel / |u|``.  2 rather than the textbook 1.345 (95 % efficiency under a normal law): measured on
        the logs, most rows are good and the heavy tail is a few wrong pairs, so fewer good rows are
        down-weighted.
    iterations : int
        Reweighting rounds.
    prior_factor : float
        The variance factor of earlier scans (a running estimate kept by the caller), pooled with this scan's
        residuals as ``PRIOR_DOF`` degrees of freedom; the pooled factor is never below 1.
    model_cov : array_like, shape (3, 3), optional
        The registration's own error, common to all rows of a scan: added to the measurement-only estimate's
        covariance, in the test and in the fusion.

    Returns
    -------
    Correction

    >>> m = Measurements.from_pairs([0.0, 0.0], [1e-6, 1e-6], [0.05, 0.0], [1e-6, 1e-6],
    ...                             [[1.0, 0.0], [0.0, 1.0]], [[0.0, 0.0], [0.0, 0.0]])
    >>> c = estimate_correction(m, np.eye(3))
    >>> np.round(c.delta, 3).tolist(), c.rank, c.valid  # the lines move the robot 5 cm along x
    ([0.05, 0.0, 0.0], 3, True)
    >>> estimate_correction(m, np.eye(3) * 1e-6).valid  # ... which a 1 mm odometry cannot have missed
    False
    """
    prior_cov = np.asarray(prior_cov, float)
    if prior_cov.shape != (3, 3) or not np.all(np.isfinite(prior_cov)):
        raise InvalidInputError(f"estimate_correction: prior_cov must be a finite (3, 3) matrix, got {prior_cov.shape}")
    p = np.zeros(3) if prior_offset is None else np.asarray(prior_offset, float).reshape(3)
    model_cov = np.zeros((3, 3)) if model_cov is None else np.asarray(model_cov, float).reshape(3, 3)
    if not (0.5 < level < 1 and kernel > 0 and prior_factor > 0 and iterations >= 0):
        raise InvalidInputError("estimate_correction: need 0.5 < level < 1, kernel > 0, prior_factor > 0")
    if len(meas) == 0 or not np.all(meas.var > 0):
        raise InvalidInputError("estimate_correction: need at least one measurement, each with a variance > 0")
    A, b, w, s2, dof, res = _solve_robust(meas, kernel, iterations, prior_factor)
    lo, hi = _eigen_extremes(A)
    if lo > 1e-8 * hi > 0.0:
        return _full_rank(A, b, p, prior_cov, model_cov, level, (s2, dof, w, res))
    return _partial_rank(A, b, p, prior_cov, model_cov, level, (s2, dof, w, res))


def _full_rank(A, b, p, prior_cov, model_cov, level, rest) -> Correction:
    """:func:`estimate_correction` when the lines fix every direction (the usual case): the estimate in the standard
    basis, no eigen-decomposition (the innovation's law is the same in any orthonormal basis).  ``rest``: the
    robust solve's ``(s2, dof, weights, residuals)``."""
    P_inv = np.linalg.inv(prior_cov)
    V = np.eye(3)
    A_inv = np.linalg.inv(A)
    y = A_inv @ b
    S = A_inv + model_cov
    g = y - p
    nis = float(g @ np.linalg.solve(S + prior_cov, g))
    S_inv = np.linalg.inv(S)
    cov = np.linalg.inv(S_inv + P_inv)
    delta = cov @ (S_inv @ y + P_inv @ p)
    threshold = _chi2_quantile(level, 3)
    return Correction(delta, cov, nis <= threshold, nis, threshold, 3, V, g, S, *rest)


def _partial_rank(A, b, p, prior_cov, model_cov, level, rest) -> Correction:
    """:func:`estimate_correction` in the directions the lines fix (eigenvectors V of A), with covariance
    diag(1 / lambda) plus the registration's own error V' model_cov V; the rest is left to the prior."""
    P_inv = np.linalg.inv(prior_cov)
    vals, vecs = np.linalg.eigh(A)
    keep = vals > 1e-9 * max(vals[-1], 1e-300)
    V, lam = vecs[:, keep], vals[keep]
    rank = int(keep.sum())
    if rank == 0:
        return Correction(np.zeros(3), prior_cov, False, 0.0, 0.0, 0, V, np.zeros(0), np.zeros((0, 0)), *rest)
    y = (V.T @ b) / lam
    S = np.diag(1.0 / lam) + V.T @ model_cov @ V
    g = y - V.T @ p  # the innovation
    nis = float(g @ np.linalg.solve(S + V.T @ prior_cov @ V, g))
    threshold = _chi2_quantile(level, rank)
    S_inv = np.linalg.inv(S)
    cov = np.linalg.inv(V @ S_inv @ V.T + P_inv)
    delta = cov @ (V @ S_inv @ y + P_inv @ p)
    return Correction(delta, cov, nis <= threshold, nis, threshold, rank, V, g, S, *rest)
