"""Least-squares fits of spheres, planes and circles in the conformal model (section 4.1).

A point x lies on the sphere s exactly when ``x . s = 0`` (2.71), and for a
normalised point and sphere ``x . s = (rho^2 - |x - p|^2) / 2`` (2.66, 2.72).
Given many noisy points, minimise ``sum_i (x_i . s)^2`` over the five
coefficients of s.  In the orthonormal basis ``e1 e2 e3 e+ e-`` this is
``s^T M s`` with ``M = G D^T D G`` (D holds the points' coefficients, G =
diag(1, 1, 1, 1, -1) is the conformal metric).  Fixing the scale by the
conformal square ``s^2 = s^T G s = 1`` (so ``x . s`` is measured in units of
the radius) turns the fit into the generalised eigenvector problem

    M s = lambda G s,

whose eigenvector with the smallest non-negative lambda is the sphere (Pratt's
fit, here falling out of the metric).  The same problem restricted to vectors
without an e0 part is the plane fit (total least squares), and the two
smallest eigenvectors span the pencil of spheres through a circle, whose
outer product ``s1 ^ s2`` is the circle (2.79).

Points are first moved to their centroid and scaled to unit RMS radius (a
conformal similarity, which maps spheres to spheres): the same conditioning
step Hartley's normalisation performs for the 8-point algorithm.

The Euclidean baselines are Kasa's algebraic sphere fit (linear least squares
of ``|x|^2 = 2 p . x + c``) and the geometric (orthogonal distance) fit.  Every
fit of one kind of entity returns the same typed result (:class:`SphereFit`,
:class:`PlaneFit`, :class:`CircleFit`), the baselines' with the entity built
from their parameters.  RANSAC over these fits is in
:mod:`cga_lessons.conformal.plane_ransac`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .multivector_checks import COORD_LIMIT, COORD_WHY, multivector

__all__ = [
    "SphereFit",
    "PlaneFit",
    "CircleFit",
    "fit_sphere",
    "fit_plane",
    "fit_circle",
    "fit_sphere_kasa",
    "fit_sphere_geometric",
    "fit_plane_euclidean",
    "fit_circle_euclidean",
]


@dataclass(frozen=True)
class SphereFit:
    """A sphere fitted to points: ``center`` (3,) and ``radius`` (metres), ``rms`` (the RMS distance of the points
    from the sphere, metres) and ``blade``, the sphere s in standard form (2.75, normalised ``s . e = -1``, 2.115)."""

    center: np.ndarray
    radius: float
    rms: float
    blade: Multivector

    def __post_init__(self):
        checks.record(self, center=checks.vector3, radius=checks.length, rms=checks.length, blade=_blade)


@dataclass(frozen=True)
class PlaneFit:
    """A plane fitted to points: unit ``normal`` (3,) and ``distance`` (``normal . x = distance`` on the plane), ``rms``
    (the RMS distance of the points from it, metres), ``blade`` (standard form ``n + distance e``, 2.89), for drawing
    ``center`` (the centroid projected onto the plane) and ``radius`` (the farthest projected point from it), and
    ``inliers``, the number of points fitted (all of them, or RANSAC's inliers)."""

    normal: np.ndarray
    distance: float
    rms: float
    blade: Multivector
    center: np.ndarray
    radius: float
    inliers: int

    def __post_init__(self):
        checks.record(
            self,
            normal=checks.vector3,
            distance=checks.real,
            rms=checks.length,
            center=checks.vector3,
            radius=checks.length,
            blade=_blade,
            inliers=_count,
        )


@dataclass(frozen=True)
class CircleFit:
    """A circle fitted to points: ``center`` (3,), ``radius`` (metres), unit ``normal`` (3,) of its plane, ``rms``
    (the RMS distance of the points from it, metres) and ``blade``, the circle in dual form through three of its
    points (2.80)."""

    center: np.ndarray
    radius: float
    normal: np.ndarray
    rms: float
    blade: Multivector

    def __post_init__(self):
        checks.record(
            self, center=checks.vector3, radius=checks.length, normal=checks.vector3, rms=checks.length, blade=_blade
        )


def _blade(value, func: str, name: str) -> Multivector:
    """A fit's blade (for :func:`cga_lessons.checks.record`): one multivector of G(4,1), finite, numeric."""
    return multivector(value, func, name, single=True, numeric=True)


def _count(value, func: str, name: str) -> int:
    """A number of points (for :func:`cga_lessons.checks.record`): a whole number, at least 0."""
    return checks.integer(value, func, name, low=0)


#: The metric of G(4,1)'s vectors on (e1, e2, e3, e+, e-), and those vectors' blade indices: a fit's linear algebra
#: works on the 5 coefficients of conformal vectors.
VECTOR_METRIC = np.diag([1.0, 1.0, 1.0, 1.0, -1.0])
VECTOR_BLADES = [1, 2, 4, 8, 16]  # e1 e2 e3 e+ e-


def checked_points(X, func: str, at_least: int) -> np.ndarray:
    """The points (N, 3) through the checks layer: numbers, finite, not so large that their squares overflow."""
    X = checks.magnitude(checks.rows(X, func, "X", 3), func, "X", limit=COORD_LIMIT, why=COORD_WHY)
    if len(X) < at_least:
        raise checks.degenerate(func, "X", f"need at least {at_least} points, got {len(X)}")
    return X


def _normalise(X, func: str):
    """Centroid and RMS radius of X, and the normalised points (a similarity)."""
    c = X.mean(axis=0)
    k = np.sqrt(np.mean(np.sum((X - c) ** 2, axis=1)))
    if k == 0:
        raise checks.degenerate(func, "X", "all points coincide")
    return c, k, (X - c) / k


def _conformal_eig(Y):
    """Generalised eigenpairs of ``M s = lambda G s`` for normalised points Y.

    Returns the eigenvectors with positive conformal square (real spheres and
    planes), scaled to ``s^T G s = 1``, sorted by their residual
    ``lambda = s^T M s``, and the residuals relative to ``trace(M)``.
    """
    D = cga.up(Y).to_array(VECTOR_BLADES)  # (N, 5), conformal points (2.62)
    A = D @ VECTOR_METRIC  # row i: coefficients of the linear form s -> x_i . s
    M = A.T @ A
    # M may be singular (noise-free data); a relative ridge of 1e-13 makes it
    # positive definite without moving the answer beyond round-off.  With
    # M = L L^T the symmetric problem L^-1 G L^-T y = mu y, s = L^-T y, has
    # mu = 1/lambda: the best fits are the largest positive mu.
    L = np.linalg.cholesky(M + 1e-13 * np.trace(M) * np.eye(5))
    Li = np.linalg.inv(L)
    mu, Y_ = np.linalg.eigh(Li @ VECTOR_METRIC @ Li.T)
    V = Li.T @ Y_[:, mu > 0][:, ::-1]
    V /= np.sqrt(np.einsum("ij,ik,kj->j", V, VECTOR_METRIC, V))
    return V, np.einsum("ij,ik,kj->j", V, M, V) / np.trace(M)


def _sphere_result(X, center, radius) -> SphereFit:
    """The :class:`SphereFit` of points X for a fitted centre and radius."""
    rms = float(np.sqrt(np.mean((np.linalg.norm(X - center, axis=1) - radius) ** 2)))
    return SphereFit(center=center, radius=float(radius), rms=rms, blade=cga.sphere(center, radius))


def fit_sphere(X) -> SphereFit:
    """Least-squares sphere in the conformal model: ``min sum (x_i . s)^2`` with ``s^2 = 1`` (2.71-2.74).

    Parameters
    ----------
    X : array_like, shape (N, 3)
        At least 4 points, not all on one plane.

    Returns
    -------
    SphereFit
        The sphere s in standard form (normalised ``s . e = -1``, 2.115), its
        ``center`` and ``radius`` (2.116, 2.73) and ``rms``.
    """
    X = checked_points(X, "fit_sphere", 4)
    c, k, Y = _normalise(X, "fit_sphere")
    V, lam = _conformal_eig(Y)
    if lam[1] <= 1e-12:  # two exact fits: the pencil of spheres through a circle (noise-free: ~1e-18)
        raise checks.degenerate("fit_sphere", "X", "the points lie on a circle: every sphere through it fits them")
    s = cga.G41.from_array(V[:, 0], VECTOR_BLADES)
    weight = -(s | cga.einf).scalar()
    if abs(weight) < 1e-9 * np.linalg.norm(V[:, 0]):
        raise checks.degenerate("fit_sphere", "X", "the points lie on a plane (the best 'sphere' has infinite radius)")
    center_y, radius_y = cga.sphere_center_radius(s)  # (2.115), (2.116), (2.73)
    center, radius = c + k * center_y, k * radius_y
    return _sphere_result(X, center, radius)


def fit_plane(X) -> PlaneFit:
    """Least-squares plane in the conformal model: ``min sum (x_i . pi)^2`` with ``pi^2 = 1``, pi = n + delta e.

    The plane is the sphere problem restricted to vectors without an e0 part
    (2.77: a sphere through the point at infinity).  As e is null, its
    coefficient delta does not enter ``pi^2 = |n|^2``; it is eliminated in
    closed form and n is the eigenvector of the smallest eigenvalue of the
    remaining 3x3 problem.  This is exactly total least squares.

    Parameters
    ----------
    X : array_like, shape (N, 3)
        At least 3 points, not all on a line.

    Returns
    -------
    PlaneFit
        ``blade`` (standard form ``n + delta e``, 2.89), ``normal``,
        ``distance`` (delta: ``n . x = delta`` on the plane), ``rms``, and
        ``center`` and ``radius`` for drawing.
    """
    X = checked_points(X, "fit_plane", 3)
    c, k, Y = _normalise(X, "fit_plane")
    D = cga.up(Y).to_array(VECTOR_BLADES)
    # x . (n + delta e) = x_E . n - delta  (x . e = -1): columns for (n1, n2, n3, delta)
    A = np.column_stack([(D @ VECTOR_METRIC)[:, :3], -np.ones(len(Y))])
    M = A.T @ A
    Mnn, b, m = M[:3, :3], M[:3, 3], M[3, 3]
    reduced = Mnn - np.outer(b, b) / m  # Schur complement: delta = -b . n / m
    w, V = np.linalg.eigh(reduced)
    if w[1] <= 1e-12 * w[2]:
        raise checks.degenerate("fit_plane", "X", "the points lie on a line (the plane is not determined)")
    n = V[:, 0]
    delta_y = -b @ n / m
    delta = k * delta_y + c @ n
    return _plane_result(X, n, delta, float(np.sqrt(np.mean((X @ n - delta) ** 2))))


def _plane_result(X, n, delta, rms: float) -> PlaneFit:
    """The :class:`PlaneFit` of points X for a fitted plane ``n . x = delta``, with its centre and radius to draw."""
    c = X.mean(axis=0)
    center = c - (c @ n - delta) * n  # the centroid, projected onto the plane (for drawing)
    radius = float(np.max(np.linalg.norm((X - center) - np.outer((X - center) @ n, n), axis=1)))
    return PlaneFit(normal=n, distance=float(delta), rms=rms, blade=cga.plane(n, delta), center=center,
                    radius=radius, inliers=len(X))  # fmt: skip


def fit_circle(X) -> CircleFit:
    """Least-squares circle: the two smallest eigenvectors of the sphere problem span its pencil; z = s1 ^ s2 (2.79).

    Points on a circle satisfy ``x . s = 0`` for every sphere through it (and
    for its plane), so the eigenproblem of :func:`fit_sphere` has a
    two-dimensional (near-)null space.  Its basis s1, s2 gives the circle in
    standard form ``z = s1 ^ s2``; centre, radius and normal come from
    (2.119)-(2.124).

    Parameters
    ----------
    X : array_like, shape (N, 3)
        At least 3 points, not all on a line.

    Returns
    -------
    CircleFit
        ``blade`` (the circle z* in dual form, through three of its points),
        ``center``, ``radius``, ``normal``, ``rms``.
    """
    X = checked_points(X, "fit_circle", 3)
    c, k, Y = _normalise(X, "fit_circle")
    sv = np.linalg.svd(Y, compute_uv=False)
    if sv[1] <= 1e-9 * sv[0]:
        raise checks.degenerate("fit_circle", "X", "the points lie on a line (a circle through infinity)")
    V, _ = _conformal_eig(Y)
    s1, s2 = (cga.G41.from_array(V[:, i], VECTOR_BLADES) for i in (0, 1))
    z = s1 ^ s2  # (2.79)
    try:
        center_y, radius_y, n = cga.circle_center_radius(z)
    except cga.DegenerateGeometryError as exc:
        raise checks.degenerate("fit_circle", "X", f"no finite circle fits; points nearly on a line ({exc})") from None
    return _circle_result(X, c + k * center_y, k * radius_y, n)


def _circle_result(X, center, radius, n) -> CircleFit:
    """The :class:`CircleFit` of points X for a fitted circle, its blade through three of its points (2.80)."""
    u = np.cross(n, np.eye(3)[np.argmin(np.abs(n))])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    blade = cga.circle_from_points(center + radius * u, center + radius * v, center - radius * u)
    d_plane = (X - center) @ n
    d_axis = np.linalg.norm((X - center) - np.outer(d_plane, n), axis=1)
    rms = float(np.sqrt(np.mean(d_plane**2 + (d_axis - radius) ** 2)))
    return CircleFit(center=center, radius=float(radius), normal=n, rms=rms, blade=blade)


# ------------------------------------------------------- Euclidean baselines
def fit_sphere_kasa(X) -> SphereFit:
    """Kasa's algebraic sphere fit: linear least squares of ``|x|^2 = 2 p . x + (rho^2 - |p|^2)``.

    Returns a :class:`SphereFit`.  Biased towards small spheres when only a
    cap of the sphere is seen.
    """
    X = checked_points(X, "fit_sphere_kasa", 4)
    c, k, Y = _normalise(X, "fit_sphere_kasa")
    A = np.column_stack([2 * Y, np.ones(len(Y))])
    sol, _, rank, _ = np.linalg.lstsq(A, np.sum(Y * Y, axis=1), rcond=None)
    if rank < 4:
        raise checks.degenerate("fit_sphere_kasa", "X", "the points lie on a plane")
    p = sol[:3]
    return _sphere_result(X, c + k * p, k * np.sqrt(sol[3] + p @ p))


def fit_sphere_geometric(X, init: SphereFit | dict | None = None, iterations: int = 50) -> SphereFit:
    """Geometric sphere fit: Gauss-Newton on the distances ``|x_i - p| - rho`` (started from Kasa's fit).

    ``init``: a start, a :class:`SphereFit` or ``{"center": (3,), "radius": float}`` (default:
    :func:`fit_sphere_kasa`); ``iterations``: at most this many Gauss-Newton steps.  Returns a :class:`SphereFit`.
    """
    func = "fit_sphere_geometric"
    X = checked_points(X, func, 4)
    iterations = checks.integer(iterations, func, "iterations", low=0)
    center, radius = _start(X, init, func)
    _, k, Y = _normalise(X, func)
    if np.linalg.svd(Y, compute_uv=False)[2] <= 1e-12:
        raise checks.degenerate(func, "X", "the points lie on a plane (the best 'sphere' has infinite radius)")
    return _sphere_result(X, *_gauss_newton(X, center, radius, iterations, func))


def _start(X, init, func: str):
    """The checked start (centre, radius) of :func:`fit_sphere_geometric`: ``init``'s, or Kasa's fit's."""
    if init is None or (isinstance(init, dict) and not init):
        init = fit_sphere_kasa(X)
    if isinstance(init, SphereFit):
        return np.array(init.center, float), float(init.radius)
    checks.instance(init, func, "init", dict, "a SphereFit or a dict with 'center' and 'radius' (or None)")
    missing = [k for k in ("center", "radius") if k not in init]
    if missing:
        raise checks.fail(func, "init", f"has no {' and no '.join(map(repr, missing))}")
    checks.array(init["center"], func, "init['center']", (3,))
    checks.real(init["radius"], func, "init['radius']", low=0)
    return np.array(init["center"], float), float(init["radius"])


def _gauss_newton(P, q, r, iterations: int, func: str):
    """Centre q and radius r of the circle/sphere through the points P (N, d) nearest in distance, from (q, r)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        try:
            for _ in range(iterations):
                diff = P - q
                dist = np.linalg.norm(diff, axis=1)
                J = np.column_stack([-diff / dist[:, None], -np.ones(len(P))])
                step, *_ = np.linalg.lstsq(J, -(dist - r), rcond=None)
                q, r = q + step[:-1], r + step[-1]
                if np.linalg.norm(step) < 1e-14 * max(1.0, r):
                    break
        except np.linalg.LinAlgError:
            q = np.full_like(q, np.nan)
    if not (np.all(np.isfinite(q)) and np.isfinite(r)):
        raise checks.degenerate(func, "X", "the Gauss-Newton iteration broke down (a point at the centre?)")
    return q, r


def fit_plane_euclidean(X) -> PlaneFit:
    """Total-least-squares plane: centroid and the smallest principal direction (SVD).

    Returns a :class:`PlaneFit` with ``n . x = distance`` on the plane.
    """
    X = checked_points(X, "fit_plane_euclidean", 3)
    n, distance, rms = _tls_plane(X, "fit_plane_euclidean")
    return _plane_result(X, n, distance, rms)


def _tls_plane(X, func: str):
    """Unit normal n, distance and RMS residual of the total-least-squares plane ``n . x = distance`` of X."""
    c = X.mean(axis=0)
    _, s, vt = np.linalg.svd(X - c, full_matrices=False)
    if s[1] <= 1e-12 * s[0]:
        raise checks.degenerate(func, "X", "the points lie on a line")
    n = vt[2]
    return n, float(c @ n), float(s[2] / np.sqrt(len(X)))


def fit_circle_euclidean(X, iterations: int = 50) -> CircleFit:
    """Circle by a TLS plane, then a geometric 2D circle fit in that plane (Gauss-Newton from Kasa).

    Returns a :class:`CircleFit`.
    """
    func = "fit_circle_euclidean"
    X = checked_points(X, func, 3)
    iterations = checks.integer(iterations, func, "iterations", low=0)
    n, _, _ = _tls_plane(X, func)
    c0 = X.mean(axis=0)
    u = np.cross(n, np.eye(3)[np.argmin(np.abs(n))])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    Q = np.column_stack([(X - c0) @ u, (X - c0) @ v])
    A = np.column_stack([2 * Q, np.ones(len(Q))])
    sol, *_ = np.linalg.lstsq(A, np.sum(Q * Q, axis=1), rcond=None)
    q, r = _gauss_newton(Q, sol[:2], np.sqrt(sol[2] + sol[:2] @ sol[:2]), iterations, func)
    return _circle_result(X, c0 + q[0] * u + q[1] * v, r, n)
