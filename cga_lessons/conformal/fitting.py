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
of ``|x|^2 = 2 p . x + c``) and the geometric (orthogonal distance) fit.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

from .multivector_checks import COORD_LIMIT, COORD_WHY

__all__ = [
    "fit_sphere",
    "fit_plane",
    "fit_circle",
    "fit_sphere_kasa",
    "fit_sphere_geometric",
    "fit_plane_euclidean",
    "fit_circle_euclidean",
    "ransac_plane",
    "segment_planes",
]

_G = np.diag([1.0, 1.0, 1.0, 1.0, -1.0])
_BLADES = [1, 2, 4, 8, 16]  # e1 e2 e3 e+ e-


def _points(X, func: str, at_least: int) -> np.ndarray:
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
    D = cga.up(Y).to_array(_BLADES)  # (N, 5), conformal points (2.62)
    A = D @ _G  # row i: coefficients of the linear form s -> x_i . s
    M = A.T @ A
    # M may be singular (noise-free data); a relative ridge of 1e-13 makes it
    # positive definite without moving the answer beyond round-off.  With
    # M = L L^T the symmetric problem L^-1 G L^-T y = mu y, s = L^-T y, has
    # mu = 1/lambda: the best fits are the largest positive mu.
    L = np.linalg.cholesky(M + 1e-13 * np.trace(M) * np.eye(5))
    Li = np.linalg.inv(L)
    mu, Y_ = np.linalg.eigh(Li @ _G @ Li.T)
    V = Li.T @ Y_[:, mu > 0][:, ::-1]
    V /= np.sqrt(np.einsum("ij,ik,kj->j", V, _G, V))
    return V, np.einsum("ij,ik,kj->j", V, M, V) / np.trace(M)


def _sphere_rms(X, center, radius):
    return float(np.sqrt(np.mean((np.linalg.norm(X - center, axis=1) - radius) ** 2)))


def fit_sphere(X) -> dict:
    """Least-squares sphere in the conformal model: ``min sum (x_i . s)^2`` with ``s^2 = 1`` (2.71-2.74).

    Parameters
    ----------
    X : array_like, shape (N, 3)
        At least 4 points, not all on one plane.

    Returns
    -------
    dict
        ``blade`` (the sphere s in standard form, normalised ``s . e = -1``,
        2.115), ``center`` (3,) and ``radius`` (2.116, 2.73), ``rms`` (RMS
        distance of the points from the sphere, metres).
    """
    X = _points(X, "fit_sphere", 4)
    c, k, Y = _normalise(X, "fit_sphere")
    V, lam = _conformal_eig(Y)
    if lam[1] <= 1e-12:  # two exact fits: the pencil of spheres through a circle (noise-free: ~1e-18)
        raise checks.degenerate("fit_sphere", "X", "the points lie on a circle: every sphere through it fits them")
    s = cga.G41.from_array(V[:, 0], _BLADES)
    weight = -(s | cga.einf).scalar()
    if abs(weight) < 1e-9 * np.linalg.norm(V[:, 0]):
        raise checks.degenerate("fit_sphere", "X", "the points lie on a plane (the best 'sphere' has infinite radius)")
    center_y, radius_y = cga.sphere_center_radius(s)  # (2.115), (2.116), (2.73)
    center, radius = c + k * center_y, k * radius_y
    rms = _sphere_rms(X, center, radius)
    return {"blade": cga.sphere(center, radius), "center": center, "radius": radius, "rms": rms}


def fit_plane(X) -> dict:
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
    dict
        ``blade`` (standard form ``n + delta e``, 2.89), ``normal`` (3,),
        ``distance`` (delta: ``n . x = delta`` on the plane), ``rms``; for
        drawing, ``center`` (the centroid projected onto the plane) and
        ``radius`` (the farthest projected point from it).
    """
    X = _points(X, "fit_plane", 3)
    c, k, Y = _normalise(X, "fit_plane")
    D = cga.up(Y).to_array(_BLADES)
    # x . (n + delta e) = x_E . n - delta  (x . e = -1): columns for (n1, n2, n3, delta)
    A = np.column_stack([(D @ _G)[:, :3], -np.ones(len(Y))])
    M = A.T @ A
    Mnn, b, m = M[:3, :3], M[:3, 3], M[3, 3]
    reduced = Mnn - np.outer(b, b) / m  # Schur complement: delta = -b . n / m
    w, V = np.linalg.eigh(reduced)
    if w[1] <= 1e-12 * w[2]:
        raise checks.degenerate("fit_plane", "X", "the points lie on a line (the plane is not determined)")
    n = V[:, 0]
    delta_y = -b @ n / m
    delta = k * delta_y + c @ n
    rms = float(np.sqrt(np.mean((X @ n - delta) ** 2)))
    center = c - (c @ n - delta) * n  # the centroid, projected onto the plane (for drawing)
    radius = float(np.max(np.linalg.norm((X - center) - np.outer((X - center) @ n, n), axis=1)))
    return {
        "blade": cga.plane(n, delta),
        "normal": n,
        "distance": float(delta),
        "rms": rms,
        "center": center,
        "radius": radius,
    }


def fit_circle(X) -> dict:
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
    dict
        ``blade`` (the circle z* in dual form, through three of its points),
        ``center``, ``radius``, ``normal``, ``rms``.
    """
    X = _points(X, "fit_circle", 3)
    c, k, Y = _normalise(X, "fit_circle")
    sv = np.linalg.svd(Y, compute_uv=False)
    if sv[1] <= 1e-9 * sv[0]:
        raise checks.degenerate("fit_circle", "X", "the points lie on a line (a circle through infinity)")
    V, _ = _conformal_eig(Y)
    s1, s2 = (cga.G41.from_array(V[:, i], _BLADES) for i in (0, 1))
    z = s1 ^ s2  # (2.79)
    try:
        center_y, radius_y, n = cga.circle_center_radius(z)
    except cga.DegenerateGeometryError as exc:
        raise checks.degenerate("fit_circle", "X", f"no finite circle fits; points nearly on a line ({exc})") from None
    center, radius = c + k * center_y, k * radius_y
    u = np.cross(n, np.eye(3)[np.argmin(np.abs(n))])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    blade = cga.circle_from_points(center + radius * u, center + radius * v, center - radius * u)
    d_plane = (X - center) @ n
    d_axis = np.linalg.norm((X - center) - np.outer(d_plane, n), axis=1)
    rms = float(np.sqrt(np.mean(d_plane**2 + (d_axis - radius) ** 2)))
    return {"blade": blade, "center": center, "radius": float(radius), "normal": n, "rms": rms}


# ------------------------------------------------------- Euclidean baselines
def fit_sphere_kasa(X) -> dict:
    """Kasa's algebraic sphere fit: linear least squares of ``|x|^2 = 2 p . x + (rho^2 - |p|^2)``.

    Returns ``{"center", "radius", "rms"}``.  Biased towards small spheres
    when only a cap of the sphere is seen.
    """
    X = _points(X, "fit_sphere_kasa", 4)
    c, k, Y = _normalise(X, "fit_sphere_kasa")
    A = np.column_stack([2 * Y, np.ones(len(Y))])
    sol, _, rank, _ = np.linalg.lstsq(A, np.sum(Y * Y, axis=1), rcond=None)
    if rank < 4:
        raise checks.degenerate("fit_sphere_kasa", "X", "the points lie on a plane")
    p = sol[:3]
    center, radius = c + k * p, k * np.sqrt(sol[3] + p @ p)
    return {"center": center, "radius": float(radius), "rms": _sphere_rms(X, center, radius)}


def fit_sphere_geometric(X, init: dict | None = None, iterations: int = 50) -> dict:
    """Geometric sphere fit: Gauss-Newton on the distances ``|x_i - p| - rho`` (started from Kasa's fit).

    ``init``: a start ``{"center": (3,), "radius": float}`` (default: :func:`fit_sphere_kasa`); ``iterations``:
    at most this many Gauss-Newton steps.  Returns ``{"center", "radius", "rms"}``.
    """
    func = "fit_sphere_geometric"
    X = _points(X, func, 4)
    iterations = checks.integer(iterations, func, "iterations", low=0)
    if init is None or (isinstance(init, dict) and not init):
        init = fit_sphere_kasa(X)
    else:
        checks.instance(init, func, "init", dict, "a dict with 'center' and 'radius' (or None)")
        missing = [k for k in ("center", "radius") if k not in init]
        if missing:
            raise checks.fail(func, "init", f"has no {' and no '.join(map(repr, missing))}")
        checks.array(init["center"], func, "init['center']", (3,))
        checks.real(init["radius"], func, "init['radius']", low=0)
    _, k, Y = _normalise(X, func)
    if np.linalg.svd(Y, compute_uv=False)[2] <= 1e-12:
        raise checks.degenerate(func, "X", "the points lie on a plane (the best 'sphere' has infinite radius)")
    p, r = _gauss_newton(X, np.array(init["center"], float), float(init["radius"]), iterations, func)
    return {"center": p, "radius": float(r), "rms": _sphere_rms(X, p, r)}


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


def fit_plane_euclidean(X) -> dict:
    """Total-least-squares plane: centroid and the smallest principal direction (SVD).

    Returns ``{"normal", "distance", "rms"}`` with ``n . x = distance`` on the plane.
    """
    return _tls_plane(_points(X, "fit_plane_euclidean", 3), "fit_plane_euclidean")


def _tls_plane(X, func: str) -> dict:
    c = X.mean(axis=0)
    _, s, vt = np.linalg.svd(X - c, full_matrices=False)
    if s[1] <= 1e-12 * s[0]:
        raise checks.degenerate(func, "X", "the points lie on a line")
    n = vt[2]
    return {"normal": n, "distance": float(c @ n), "rms": float(s[2] / np.sqrt(len(X)))}


def fit_circle_euclidean(X, iterations: int = 50) -> dict:
    """Circle by a TLS plane, then a geometric 2D circle fit in that plane (Gauss-Newton from Kasa).

    Returns ``{"center", "radius", "normal", "rms"}``.
    """
    func = "fit_circle_euclidean"
    X = _points(X, func, 3)
    iterations = checks.integer(iterations, func, "iterations", low=0)
    pl = _tls_plane(X, func)
    n = pl["normal"]
    c0 = X.mean(axis=0)
    u = np.cross(n, np.eye(3)[np.argmin(np.abs(n))])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    Q = np.column_stack([(X - c0) @ u, (X - c0) @ v])
    A = np.column_stack([2 * Q, np.ones(len(Q))])
    sol, *_ = np.linalg.lstsq(A, np.sum(Q * Q, axis=1), rcond=None)
    q, r = _gauss_newton(Q, sol[:2], np.sqrt(sol[2] + sol[:2] @ sol[:2]), iterations, func)
    center = c0 + q[0] * u + q[1] * v
    d_plane = (X - center) @ n
    d_axis = np.linalg.norm((X - center) - np.outer(d_plane, n), axis=1)
    rms = float(np.sqrt(np.mean(d_plane**2 + (d_axis - r) ** 2)))
    return {"center": center, "radius": float(r), "normal": n, "rms": rms}


# ------------------------------------------------------------------- RANSAC
def ransac_plane(X, rng: np.random.Generator, threshold: float, iterations: int = 200) -> tuple[dict, np.ndarray]:
    """RANSAC with conformal planes: hypotheses ``e ^ a ^ b ^ c`` (2.77), refined by :func:`fit_plane`.

    Parameters
    ----------
    X : array_like, shape (N, 3)
    rng : numpy.random.Generator
    threshold : float
        Inlier distance (metres), > 0.
    iterations : int
        Number of random triples, >= 1.

    Returns
    -------
    fit : dict
        :func:`fit_plane` of the inliers, plus ``"inliers"`` (their count).
    inliers : ndarray of bool, shape (N,)
    """
    func = "ransac_plane"
    X = _points(X, func, 3)
    rng, threshold, iterations = _ransac_settings(rng, threshold, iterations, func)
    return _ransac(X, rng, threshold, iterations, func)


def _ransac_settings(rng, threshold, iterations, func: str):
    rng = checks.generator(rng, func)
    threshold = checks.real(threshold, func, "threshold", low=0, strict_low=True)
    return rng, threshold, checks.integer(iterations, func, "iterations", low=1)


def _ransac(X, rng, threshold: float, iterations: int, func: str):
    idx = rng.integers(0, len(X), size=(iterations, 3))
    a, b, c = X[idx[:, 0]], X[idx[:, 1]], X[idx[:, 2]]
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    span = np.maximum(np.linalg.norm(b - a, axis=1), np.linalg.norm(c - a, axis=1))
    ok = area > 1e-6 * np.maximum(span, 1e-12) ** 2
    if not np.any(ok):
        raise checks.degenerate(func, "X", "every sampled triple is collinear")
    P = cga.plane_from_points(a[ok], b[ok], c[ok])  # a batch of planes (2.77)
    n, d = cga.plane_normal_distance(P)
    counts = np.sum(np.abs(X @ n.T - d) < threshold, axis=0)
    best = int(np.argmax(counts))
    inliers = np.abs(X @ n[best] - d[best]) < threshold
    for _ in range(3):  # refine on the inliers, re-select
        fit = fit_plane(X[inliers])
        new = np.abs(X @ fit["normal"] - fit["distance"]) < threshold
        if np.array_equal(new, inliers) or new.sum() < 3:
            break
        inliers = new
    fit = fit_plane(X[inliers])
    fit["inliers"] = int(inliers.sum())
    return fit, inliers


def segment_planes(X, rng: np.random.Generator, n_planes=3, threshold=0.02, iterations=300, min_inliers=200):
    """Extract up to ``n_planes`` planes one after another (RANSAC, then remove the inliers).

    ``rng`` a NumPy Generator, ``n_planes`` >= 0, ``threshold`` > 0 (metres), ``iterations`` >= 1 (random triples
    per plane), ``min_inliers`` >= 0 (a plane with fewer is not kept, and the search stops).

    Returns
    -------
    fits : list of dict
        :func:`ransac_plane` results, largest first.
    labels : ndarray of int, shape (N,)
        Index of the plane each point belongs to, -1 for none.
    """
    func = "segment_planes"
    X = _points(X, func, 3)
    rng, threshold, iterations = _ransac_settings(rng, threshold, iterations, func)
    n_planes = checks.integer(n_planes, func, "n_planes", low=0)
    min_inliers = checks.integer(min_inliers, func, "min_inliers", low=0)
    labels = np.full(len(X), -1)
    fits = []
    for i in range(n_planes):
        free = np.flatnonzero(labels < 0)
        if len(free) < max(3, min_inliers):
            break
        fit, inl = _ransac(X[free], rng, threshold, iterations, func)
        if fit["inliers"] < min_inliers:
            break
        labels[free[inl]] = i
        fits.append(fit)
    return fits, labels
