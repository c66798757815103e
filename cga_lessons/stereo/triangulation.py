"""Triangulation: the point two cameras' rays meet at (appendix A of the thesis, Eq. A.14 and figure A.4).

The rays come from :func:`cga_lessons.stereo.camera.back_project` (A.14); :func:`triangulate` returns the midpoint
of their shortest connecting segment (figure A.4) or the linear (DLT) solution.  Conventions are those of
:mod:`cga_lessons.stereo.camera`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import degenerate

from . import validate as vd
from .camera import back_project

__all__ = ["closest_points_on_rays", "triangulate"]


def closest_points_on_rays(o1, d1, o2, d2, tol: float = 1e-12):
    """Closest points of two families of lines ``o + s d`` (the segment of figure A.4).

    Parameters
    ----------
    o1, d1, o2, d2 : array_like, shape (N, 3)
        Origins and directions (need not be unit).
    tol : float
        Lines whose directions make an angle with sine below ``tol`` are
        parallel and raise.

    Returns
    -------
    p1, p2 : ndarray, shape (N, 3)
        The closest point on each line; ``|p1 - p2|`` is the rays' gap.
    """
    f = "closest_points_on_rays"
    o1, d1, o2, d2 = (vd.batch(a, f, n, (3,))[0] for a, n in ((o1, "o1"), (d1, "d1"), (o2, "o2"), (d2, "d2")))
    checks.same_length(f, o1=o1, d1=d1, o2=o2, d2=d2)
    return _closest(o1, d1, o2, d2, checks.real(tol, f, "tol", low=0.0, high=1.0), f, ("d1", "d2"))


def _closest(o1, d1, o2, d2, tol: float, func: str, names: tuple):
    """The closest points of checked rays; errors name ``func`` and the ``names`` of the two directions."""
    n1 = np.linalg.norm(d1, axis=1, keepdims=True)
    n2 = np.linalg.norm(d2, axis=1, keepdims=True)
    for n, name in ((n1, names[0]), (n2, names[1])):
        if np.any(n == 0):
            raise degenerate(func, name, f"direction {int(np.flatnonzero(n == 0)[0])} is the zero vector")
    u1, u2 = d1 / n1, d2 / n2
    cross = np.cross(u1, u2)
    denom = np.sum(cross * cross, axis=1)  # sin^2 of the angle, free of cancellation
    parallel = np.flatnonzero(denom <= tol * tol)
    if parallel.size:
        problem = f"{parallel.size} pair(s) of parallel rays (first index {parallel[0]}); the point is at infinity"
        raise degenerate(func, ", ".join(names), problem)
    w = o2 - o1
    b = np.sum(u1 * u2, axis=1)
    a1, a2 = np.sum(u1 * w, axis=1), np.sum(u2 * w, axis=1)
    s = (a1 - b * a2) / denom
    t = (b * a1 - a2) / denom
    return o1 + s[:, None] * u1, o2 + t[:, None] * u2


def triangulate(P1, P2, x1, x2, method: str = "midpoint") -> np.ndarray:
    """Triangulate corresponding image points, Eq. (A.14) and figure A.4.

    ``"midpoint"`` back-projects both rays by (A.14) and returns the midpoint
    of their shortest connecting segment (figure A.4); it needs metric
    (finite, Euclidean) cameras.  ``"dlt"`` solves the linear system
    ``x x (P X) = 0`` of both views (rows ``x p3^T - p1^T``, ``y p3^T - p2^T``)
    by SVD, as Hartley & Zisserman (the thesis's reference [13]) and OpenCV's
    ``triangulatePoints`` do; it also works with projective cameras such as
    those of :func:`cga_lessons.stereo.epipolar.cameras_from_fundamental`.

    Parameters
    ----------
    P1, P2 : array_like, shape (3, 4)
    x1, x2 : array_like, shape (N, 2)
        Pixel coordinates of the same N points in both views.
    method : {"midpoint", "dlt"}

    Returns
    -------
    X : ndarray, shape (N, 3)
        Euclidean points.

    Raises
    ------
    DegenerateGeometryError
        Parallel rays (a point at infinity) or cameras with the same centre.

    Examples
    --------
    >>> from cga_lessons.stereo.camera import calibration_matrix, project, projection_matrix
    >>> K = calibration_matrix(500.0, 500.0, 320.0, 240.0)
    >>> P1 = projection_matrix(K, np.eye(3), [0.0, 0.0, 0.0])
    >>> P2 = projection_matrix(K, np.eye(3), [0.2, 0.0, 0.0])
    >>> X = np.array([[0.1, -0.2, 3.0]])
    >>> np.round(triangulate(P1, P2, project(P1, X), project(P2, X)), 12)
    array([[ 0.1, -0.2,  3. ]])
    """
    f = "triangulate"
    P1, P2 = vd.camera(P1, f, "P1"), vd.camera(P2, f, "P2")
    (x1, _), (x2, _) = vd.batch(x1, f, "x1", (2,)), vd.batch(x2, f, "x2", (2,))
    checks.same_length(f, x1=x1, x2=x2)
    method = checks.choice(method, f, "method", ("midpoint", "dlt"))
    return checks.finite_result(_triangulate(P1, P2, x1, x2, method, f), f, "x1, x2")


def _triangulate(P1, P2, x1, x2, method: str, func: str) -> np.ndarray:
    """:func:`triangulate` of checked arguments; errors name ``func``."""
    c1, c2 = (np.linalg.svd(P)[2][-1] for P in (P1, P2))  # homogeneous centres, P C = 0
    if np.linalg.svd(np.vstack([c1, c2]), compute_uv=False)[1] <= 1e-12:
        raise degenerate(func, "P1, P2", "the cameras share their centre; there is no baseline")
    if method == "midpoint":
        with checks.relabel(func, "P1"):
            o1, d1 = back_project(P1, x1)
        with checks.relabel(func, "P2"):
            o2, d2 = back_project(P2, x2)
        q1, q2 = _closest(o1, d1, o2, d2, 1e-12, func, ("x1", "x2"))
        return 0.5 * (q1 + q2)
    else:
        A = np.stack(
            [
                x1[:, 0:1] * P1[2] - P1[0],
                x1[:, 1:2] * P1[2] - P1[1],
                x2[:, 0:1] * P2[2] - P2[0],
                x2[:, 1:2] * P2[2] - P2[1],
            ],
            axis=1,
        )  # (N, 4, 4)
        _, s, vt = np.linalg.svd(A)
        if np.any(s[:, 2] <= 1e-12 * s[:, 0]):
            raise degenerate(func, "P1, P2", "the linear system is rank deficient (cameras share their centre?)")
        Xh = vt[:, -1, :]
        w = Xh[:, 3]
        far = np.flatnonzero(np.abs(w) <= 1e-12)
        if far.size:
            raise degenerate(func, "x1, x2", f"{far.size} point(s) at infinity (parallel rays; first index {far[0]})")
        return Xh[:, :3] / w[:, None]
