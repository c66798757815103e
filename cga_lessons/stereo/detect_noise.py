"""The noise model of entity detection: per-point covariances, chi-square gates, Mahalanobis residuals.

A detected entity is only as good as the test "does this point lie on it?".
Every residual of :mod:`cga_lessons.stereo.detect_models` is a vector r of
``codim`` distances (1 for a sphere or plane, 2 for a circle or line) whose
first-order dependence on the point is ``r ~ B^T dx`` (B holds unit
directions: the surface normal, or two directions across a curve).  With the
point's covariance Sigma the squared Mahalanobis distance

    m = r^T (B^T Sigma B)^-1 r

is chi-square with ``codim`` degrees of freedom for points on the entity, so
the gate ``m < chi2_codim(confidence)`` keeps the stated fraction of them
whatever the noise level: every distance threshold of the detector comes from
here, never from a number in metres.

Where the covariances come from:

* a **sensor fact**: the stereo rig's pixel noise sigma, propagated through
  triangulation (A.14) to first order by :func:`triangulation_covariance`
  (depth noise grows as Z^2 / (f b), lateral noise as Z / f);
* a given isotropic 3D noise sigma (metres);
* **estimated from the data** by :func:`estimate_noise` when nothing is known.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail

from . import validate as vd
from .triangulation import triangulate

__all__ = ["NoiseModel", "as_noise_model", "estimate_noise", "triangulation_covariance", "chi2_gate"]


@dataclass(frozen=True, eq=False)
class NoiseModel:
    """Covariances of the points of a cloud: isotropic ``sigma`` (metres) or one (3, 3) matrix per point.

    Attributes
    ----------
    sigma : float or None
        Isotropic standard deviation (used when ``cov`` is None).
    cov : ndarray, shape (N, 3, 3), or None
        Per-point covariances (m^2), e.g. from :func:`triangulation_covariance`.
    source : str
        ``"given"``, ``"estimated"`` or ``"covariances"``: where the numbers came from.
    """

    sigma: float | None = None
    cov: np.ndarray | None = None
    source: str = "given"

    def __post_init__(self):
        if self.cov is not None:  # the six distinct entries, each contiguous: fast products in quad
            c = self.cov
            six = np.stack([c[:, 0, 0], c[:, 1, 1], c[:, 2, 2], c[:, 0, 1], c[:, 0, 2], c[:, 1, 2]])
            object.__setattr__(self, "_six", six)

    def quad(self, idx, g, h) -> np.ndarray:
        """``g^T Sigma_i h`` for the points ``idx`` (n,); g and h have shape (..., n, 3)."""
        if self.cov is None:
            return self.sigma**2 * np.sum(g * h, axis=-1)
        xx, yy, zz, xy, xz, yz = self._six[:, idx]
        gx, gy, gz, hx, hy, hz = g[..., 0], g[..., 1], g[..., 2], h[..., 0], h[..., 1], h[..., 2]
        return (gx * hx * xx + gy * hy * yy + gz * hz * zz + (gx * hy + gy * hx) * xy + (gx * hz + gz * hx) * xz
                + (gy * hz + gz * hy) * yz)  # fmt: skip

    def apply(self, idx, g) -> np.ndarray:
        """``Sigma_i g_i`` for the points ``idx`` (n,); g has shape (n, 3)."""
        if self.cov is None:
            return self.sigma**2 * g
        xx, yy, zz, xy, xz, yz = self._six[:, idx]
        gx, gy, gz = g[..., 0], g[..., 1], g[..., 2]
        return np.stack([xx * gx + xy * gy + xz * gz, xy * gx + yy * gy + yz * gz, xz * gx + yz * gy + zz * gz], -1)

    def trace(self, idx) -> np.ndarray:
        """``tr Sigma_i`` for the points ``idx`` (n,)."""
        if self.cov is None:
            return np.full(len(idx), 3 * self.sigma**2)
        return self._six[0, idx] + self._six[1, idx] + self._six[2, idx]

    def subset(self, idx) -> NoiseModel:
        """The noise model of the points ``idx`` only."""
        return self if self.cov is None else NoiseModel(None, self.cov[idx], self.source)

    def max_std(self) -> float:
        """The largest standard deviation along any direction, over all points (metres)."""
        if self.cov is None:
            return float(self.sigma)
        return float(np.sqrt(np.max(np.linalg.eigvalsh(self.cov))))

    def mahalanobis2(self, idx, r, B) -> np.ndarray:
        """Squared Mahalanobis distances of residuals r (..., n, c) with directions B (..., n, 3, c).

        The residual covariance is ``B^T Sigma B`` (c = 1 or 2: closed-form inverse).
        """
        c = r.shape[-1]
        b0 = B[..., 0]
        s00 = self.quad(idx, b0, b0)
        if c == 1:
            return r[..., 0] ** 2 / s00
        b1 = B[..., 1]
        s01, s11 = self.quad(idx, b0, b1), self.quad(idx, b1, b1)
        det = s00 * s11 - s01 * s01
        r0, r1 = r[..., 0], r[..., 1]
        return (s11 * r0 * r0 - 2.0 * s01 * r0 * r1 + s00 * r1 * r1) / det

    def residual_cov(self, idx, B) -> np.ndarray:
        """Covariance (n, c, c) of the residuals with directions B (n, 3, c): ``B^T Sigma B``."""
        c = B.shape[-1]
        out = np.empty(B.shape[:-2] + (c, c))
        for a in range(c):
            for b in range(a, c):
                out[..., a, b] = out[..., b, a] = self.quad(idx, B[..., a], B[..., b])
        return out


def as_noise_model(noise, X: np.ndarray, func: str) -> NoiseModel:
    """The noise model for the cloud X (N, 3) from what the caller gave.

    ``None``: estimate an isotropic sigma from the data (:func:`estimate_noise`);
    a positive number: isotropic sigma in metres (a sensor fact); an array
    (N, 3, 3): per-point covariances (symmetric, positive definite); a
    :class:`NoiseModel` is checked and returned.
    """
    if isinstance(noise, NoiseModel):
        if noise.cov is not None:
            return as_noise_model(noise.cov, X, func)
        return as_noise_model(noise.sigma, X, func) if noise.source != "estimated" else noise
    if noise is None:
        try:
            return NoiseModel(estimate_noise(X), None, "estimated")
        except GeometryError as exc:
            raise degenerate(func, "noise", f"cannot be estimated from the cloud: {exc}") from None
    if not isinstance(noise, (list, tuple)) and np.ndim(noise) == 0:
        return NoiseModel(checks.real(noise, func, "noise", low=0.0, strict_low=True, high=vd.LIMIT), None, "given")
    arr = vd.array(noise, func, "noise", (len(X), 3, 3))
    if not np.allclose(arr, np.swapaxes(arr, 1, 2), rtol=1e-9, atol=1e-18):
        raise fail(func, "noise", "covariances must be symmetric")
    if np.any(np.linalg.eigvalsh(arr)[:, 0] <= 0):
        raise fail(func, "noise", "covariances must be positive definite")
    return NoiseModel(None, arr, "covariances")


def estimate_noise(X, k: int = 16) -> float:
    """Isotropic noise sigma (metres) estimated from the cloud itself by local principal components.

    For each point, the smallest eigenvalue of the covariance of its ``k``
    nearest neighbours measures the spread across the local surface (or
    curve); the median over all points, corrected by ``k / (k - 3)`` for the
    three fitted degrees of freedom of a local plane, is sigma^2.  The median
    ignores clutter as long as most points lie on smooth objects; curvature
    inflates the estimate slightly (by ``~ (k-neighbourhood size)^2 / radius``),
    which errs on the side of wider gates.
    """
    from scipy.spatial import cKDTree

    f = "estimate_noise"
    k = checks.integer(k, f, "k", low=4)
    X = vd.array(X, f, "X", (None, 3), at_least=k + 1)
    _, nb = cKDTree(X).query(X, k=k)
    P = X[nb] - X[nb].mean(axis=1, keepdims=True)
    lam = np.linalg.eigvalsh(np.einsum("nki,nkj->nij", P, P) / k)[:, 0]
    s = float(np.sqrt(np.median(lam) * k / (k - 3)))
    if not s > 0:
        raise degenerate(f, "X", "the points are noise-free (sigma = 0); give noise explicitly")
    return s


def triangulation_covariance(P1, P2, x1, x2, sigma_px: float, method: str = "midpoint") -> np.ndarray:
    """First-order covariance (N, 3, 3) of triangulated points (A.14) under pixel noise ``sigma_px``.

    The Jacobian J (3 x 4) of the triangulated point with respect to its four
    pixel coordinates is taken by central differences of
    :func:`cga_lessons.stereo.triangulation.triangulate` (the same estimator the cloud came
    from); then ``Sigma = sigma_px^2 J J^T``.  For a parallel rig this is the
    familiar depth noise ``sigma_Z = sqrt(2) Z^2 sigma_px / (f b)`` along the
    ray and ``Z sigma_px / f`` across it.

    Parameters
    ----------
    P1, P2 : array_like, shape (3, 4)
    x1, x2 : array_like, shape (N, 2)
        The observed pixels (the linearisation point).
    sigma_px : float
        Pixel noise (standard deviation per coordinate), > 0.
    """
    f = "triangulation_covariance"
    P1, P2 = vd.camera(P1, f, "P1"), vd.camera(P2, f, "P2")
    (x1, _), (x2, _) = vd.batch(x1, f, "x1", (2,)), vd.batch(x2, f, "x2", (2,))
    checks.same_length(f, x1=x1, x2=x2)
    s = checks.real(sigma_px, f, "sigma_px", low=0.0, strict_low=True, high=vd.LIMIT)
    method = checks.choice(method, f, "method", ("midpoint", "dlt"))
    try:
        return checks.finite_result(_covariance(P1, P2, x1, x2, s, method), f, "sigma_px")
    except GeometryError as exc:
        raise degenerate(f, "P1, P2, x1, x2", f"the points cannot be triangulated: {exc}") from None


def _covariance(P1, P2, x1, x2, s: float, method: str) -> np.ndarray:
    h = 1e-3  # pixels: the triangulation is smooth, central differences are exact to ~h^2
    cols = []
    for view in (0, 1):
        for c in (0, 1):
            plus, minus = [x1.copy(), x2.copy()], [x1.copy(), x2.copy()]
            plus[view][:, c] += h
            minus[view][:, c] -= h
            Xp = triangulate(P1, P2, plus[0], plus[1], method=method)
            Xm = triangulate(P1, P2, minus[0], minus[1], method=method)
            cols.append((Xp - Xm) / (2 * h))
    J = np.stack(cols, axis=2)  # (N, 3, 4)
    return s * s * np.einsum("nik,njk->nij", J, J)


def chi2_gate(dof: int, confidence: float) -> float:
    """The ``confidence`` quantile of chi-square with ``dof`` degrees of freedom (the inlier gate on m)."""
    from scipy.special import chdtri  # inverse survival function of chi-square

    dof = checks.integer(dof, "chi2_gate", "dof", low=1)
    confidence = checks.real(
        confidence, "chi2_gate", "confidence", low=0.0, high=1.0, strict_low=True, strict_high=True
    )
    return float(chdtri(dof, 1.0 - confidence))
