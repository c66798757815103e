"""RANSAC with conformal planes: one plane among outliers, and the planes of a point cloud one after another.

Hypotheses are planes through three random points, ``e ^ a ^ b ^ c`` (2.77), made as a batch; the one with the
most points within a threshold wins and is refined by the least-squares :func:`cga_lessons.conformal.fit_plane`
(:mod:`cga_lessons.conformal.fitting`) of its inliers.  Used on the motorcycle cloud of the stereo notebook.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga

from .fitting import PlaneFit, checked_points, fit_plane

__all__ = ["ransac_plane", "segment_planes"]


def ransac_plane(X, rng: np.random.Generator, threshold: float, iterations: int = 200) -> tuple[PlaneFit, np.ndarray]:
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
    fit : PlaneFit
        :func:`fit_plane` of the inliers (``fit.inliers`` is their count).
    inliers : ndarray of bool, shape (N,)
    """
    func = "ransac_plane"
    X = checked_points(X, func, 3)
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
        new = np.abs(X @ fit.normal - fit.distance) < threshold
        if np.array_equal(new, inliers) or new.sum() < 3:
            break
        inliers = new
    return fit_plane(X[inliers]), inliers


def segment_planes(X, rng: np.random.Generator, n_planes=3, threshold=0.02, iterations=300, min_inliers=200):
    """Extract up to ``n_planes`` planes one after another (RANSAC, then remove the inliers).

    ``rng`` a NumPy Generator, ``n_planes`` >= 0, ``threshold`` > 0 (metres), ``iterations`` >= 1 (random triples
    per plane), ``min_inliers`` >= 0 (a plane with fewer is not kept, and the search stops).

    Returns
    -------
    fits : list of PlaneFit
        :func:`ransac_plane` results, largest first.
    labels : ndarray of int, shape (N,)
        Index of the plane each point belongs to, -1 for none.
    """
    func = "segment_planes"
    X = checked_points(X, func, 3)
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
        if fit.inliers < min_inliers:
            break
        labels[free[inl]] = i
        fits.append(fit)
    return fits, labels
