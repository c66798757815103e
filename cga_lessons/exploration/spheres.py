"""The sphere that encloses an obstacle (exploration document, section 3.1.2) and points on spheres and boxes.

Any obstacle is enclosed in a sphere: a conformal sphere fitted to its points (thesis 2.118), or the sphere
about the points' bounding box, whichever is smaller; the document samples the sphere's surface on a
latitude-longitude grid (:func:`sphere_points`).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError

from .grid import check_point, check_points, check_positive

__all__ = ["fit_sphere", "enclosing_sphere", "sphere_points", "box_surface_points"]

_MAX_SAMPLES = 10**7  # the most points box_surface_points makes


# ------------------------------------------------------------ enclosing sphere
def _sphere_fit(P: np.ndarray, func: str):
    """The conformal least-squares sphere of checked points P (N, 3), or a degenerate-geometry error."""
    if len(P) < 4:
        raise checks.degenerate(func, "points", f"need at least 4 points, got {len(P)}")
    sv = np.linalg.svd(P - P.mean(axis=0), compute_uv=False)
    if sv[0] == 0 or sv[-1] <= 1e-9 * sv[0]:
        raise checks.degenerate(func, "points", "the points are coplanar (or coincide): no unique sphere")
    fit = cga.fit_sphere(P)
    return fit.center, float(fit.radius)


def fit_sphere(points):
    """Least-squares sphere through points in the conformal model.

    A point X lies on the sphere s when X . s = 0 (thesis 2.118); the sphere
    minimising sum (X_i . s)^2 under s^2 = 1 is an eigenvector problem in the
    conformal metric.  The solve is :func:`cga_lessons.conformal.fitting.fit_sphere`
    (the same fit serves the stereo chapter); this wrapper adds the checks the
    exploration needs and returns plain centre and radius.

    Parameters
    ----------
    points : array, shape (N, 3), N >= 4, not coplanar, coordinates up to 1e150

    Returns
    -------
    center : array, shape (3,)
    radius : float
    """
    P = checks.magnitude(check_points(points, "fit_sphere", "points"), "fit_sphere", "points")
    return _sphere_fit(P, "fit_sphere")


def enclosing_sphere(points):
    """Sphere that encloses every point of an object, whatever its shape (3.1.2).

    Two candidate centres: the conformal least-squares sphere's (:func:`fit_sphere`;
    best for round objects and partial scans of them) and the centre of the points'
    bounding box (best for boxy or flat objects); the radius is the largest distance
    of a point from the centre, so no point is left outside.  The smaller sphere wins.

    Returns (center (3,), radius).
    """
    f = "enclosing_sphere"
    P = checks.magnitude(check_points(points, f, "points"), f, "points")
    centers = [0.5 * (P.min(axis=0) + P.max(axis=0))]
    try:
        centers.append(_sphere_fit(P, f)[0])
    except DegenerateGeometryError:
        pass  # flat or too few points: the box centre alone
    radii = [float(np.max(np.linalg.norm(P - c, axis=1))) for c in centers]
    k = int(np.argmin(radii))
    if radii[k] == 0:
        raise checks.degenerate(f, "points", "all points coincide, the sphere has zero radius")
    return centers[k], radii[k]


def sphere_points(center, radius, n: int = 20) -> np.ndarray:
    """Points on a sphere on a latitude-longitude grid, like MATLAB's ``sphere(n)``.

    The document stores "the points of the sphere" in a vector; (n + 1)^2 grid
    points with the repeated poles and seam removed: shape (n * (n - 1) + 2, 3).
    ``n`` from 3 to 3000.
    """
    f = "sphere_points"
    c = check_point(center, f, "center")
    r = check_positive(radius, f, "radius")
    n = checks.integer(n, f, "n", low=3, high=3000)
    theta = np.linspace(-np.pi, np.pi, n + 1)[:-1]
    phi = np.linspace(-np.pi / 2, np.pi / 2, n + 1)[1:-1]
    ph, th = np.meshgrid(phi, theta, indexing="ij")
    unit = np.stack([np.cos(ph) * np.cos(th), np.cos(ph) * np.sin(th), np.sin(ph)], axis=-1).reshape(-1, 3)
    unit = np.vstack([[0.0, 0.0, -1.0], unit, [0.0, 0.0, 1.0]])
    return checks.finite_result(c + r * unit, f, "center, radius: the points")


def box_surface_points(rng, center, size, n: int = 300) -> np.ndarray:
    """``n`` random points on the surface of an axis-aligned box (a stand-in object), shape (n, 3)."""
    f = "box_surface_points"
    checks.generator(rng, f)
    c = check_point(center, f, "center")
    size = check_point(size, f, "size")
    if np.any(size < 0):
        raise checks.fail(f, "size", f"must not be negative, got {tuple(size)}")
    half = 0.5 * size
    n = checks.integer(n, f, "n", low=0, high=_MAX_SAMPLES)
    u = rng.uniform(-1.0, 1.0, size=(n, 3))
    face = rng.integers(0, 3, size=n)
    u[np.arange(n), face] = rng.choice([-1.0, 1.0], size=n)
    return checks.finite_result(c + u * half, f, "center, size: the points")
