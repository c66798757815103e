"""Pinhole cameras and triangulation (appendix A of the thesis, Eqs. A.1-A.5 and A.14).

Two-view geometry (A.6-A.13: the fundamental matrix, the 8-point algorithm,
cameras from F) lives in :mod:`cga_lessons.stereo.epipolar`, which builds on this
module (this one does not import it).

Conventions
-----------
* World points are Euclidean, shape ``(N, 3)`` in metres; their homogeneous
  form (A.4) is ``(N, 4)`` with ``W = 1``.
* Image points are pixel coordinates ``(x, y)``, shape ``(N, 2)``; ``x`` grows
  to the right and ``y`` downwards (the OpenCV convention).
* A camera is its 3x4 projection matrix ``P = K R [I | -C]`` (A.1), with ``R``
  the rotation *from world to camera* coordinates (camera axes: x right, y down,
  z forward) and ``C`` the camera centre in the world.

Bad input (wrong shapes, NaN, too few points) raises
:class:`~cga_lessons.algebra.InvalidInputError`; degenerate configurations
(collinear or coplanar correspondences, parallel rays, points at infinity)
raise :class:`~cga_lessons.algebra.DegenerateGeometryError`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import degenerate

from . import validate as vd

__all__ = [
    "calibration_matrix",
    "projection_matrix",
    "projection_matrix_rt",
    "decompose_projection",
    "to_homogeneous",
    "from_homogeneous",
    "project",
    "camera_center",
    "optical_planes",
    "pseudo_inverse",
    "back_project",
    "closest_points_on_rays",
    "triangulate",
]


# ------------------------------------------------------------ camera model
def calibration_matrix(alpha_x: float, alpha_y: float, x0: float, y0: float, skew: float = 0.0) -> np.ndarray:
    """Camera calibration matrix K, Eq. (A.2).

    Parameters
    ----------
    alpha_x, alpha_y : float
        Focal length in pixels along x and y (``f m_x``, ``f m_y``); positive.
    x0, y0 : float
        Principal point in pixels.
    skew : float, optional
        The skew ``s`` (0 for rectangular pixels).

    Returns
    -------
    K : ndarray, shape (3, 3)

    Examples
    --------
    >>> calibration_matrix(500.0, 500.0, 320.0, 240.0)
    array([[500.,   0., 320.],
           [  0., 500., 240.],
           [  0.,   0.,   1.]])
    """
    f = "calibration_matrix"
    alpha_x, alpha_y = (vd.positive(a, f, n) for a, n in ((alpha_x, "alpha_x"), (alpha_y, "alpha_y")))
    x0, y0, skew = (checks.real(a, f, n) for a, n in ((x0, "x0"), (y0, "y0"), (skew, "skew")))
    K = np.array([[alpha_x, skew, x0], [0.0, alpha_y, y0], [0.0, 0.0, 1.0]])
    return vd.bounded(K, f, "alpha_x, alpha_y, x0, y0, skew")


def projection_matrix(K, R, C) -> np.ndarray:
    """Projection matrix ``P = K R [I | -C]``, Eq. (A.1).

    Parameters
    ----------
    K : array_like, shape (3, 3)
        Calibration matrix (A.2).
    R : array_like, shape (3, 3)
        Rotation from world to camera coordinates.
    C : array_like, shape (3,)
        Camera centre in world coordinates (metres).

    Returns
    -------
    P : ndarray, shape (3, 4)
    """
    f = "projection_matrix"
    K, R, C = vd.calibration(K, f), vd.rotation(R, f), vd.array(C, f, "C", (3,))
    return K @ R @ np.hstack([np.eye(3), -C[:, None]])


def projection_matrix_rt(K, R, t) -> np.ndarray:
    """Projection matrix ``P = K [R | t]`` with ``t = -R C``, Eq. (A.3).

    Parameters
    ----------
    K, R : array_like, shape (3, 3)
    t : array_like, shape (3,)
        Translation: the world origin in camera coordinates.

    Returns
    -------
    P : ndarray, shape (3, 4)
    """
    f = "projection_matrix_rt"
    K, R, t = vd.calibration(K, f), vd.rotation(R, f), vd.array(t, f, "t", (3,))
    return K @ np.hstack([R, t[:, None]])


def decompose_projection(P):
    """Split a finite camera into ``K, R, C`` with ``P ~ K R [I | -C]``, inverting Eq. (A.1).

    ``K`` is returned with positive diagonal and ``K[2, 2] = 1`` (RQ
    decomposition of the left 3x3 block).

    Parameters
    ----------
    P : array_like, shape (3, 4)

    Returns
    -------
    K : ndarray, shape (3, 3)
    R : ndarray, shape (3, 3)
    C : ndarray, shape (3,)
    """
    f = "decompose_projection"
    P = vd.camera(P, f)
    M = P[:, :3]
    if abs(np.linalg.det(M)) < 1e-12 * np.linalg.norm(M) ** 3:
        raise degenerate(f, "P", "the left 3x3 block is singular (a camera at infinity)")
    if np.linalg.det(M) < 0:  # P is defined up to scale: pick the sign that gives det R = +1
        P, M = -P, -M
    # RQ via QR of the flipped, transposed matrix
    flip = np.eye(3)[::-1]
    q, r = np.linalg.qr((flip @ M).T)
    K = flip @ r.T @ flip
    R = flip @ q.T
    D = np.diag(np.sign(np.diag(K)))
    K, R = K @ D, D @ R
    return K / K[2, 2], R, _centre(P, f, "P")


# ------------------------------------------------------------- projection
def _homogeneous(x: np.ndarray) -> np.ndarray:
    """Checked points (N, D) with a column of ones appended."""
    return np.concatenate([x, np.ones(x.shape[:-1] + (1,))], axis=-1)


def to_homogeneous(X) -> np.ndarray:
    """Homogeneous coordinates ``[X, Y, Z, 1]`` of Euclidean points, Eq. (A.4).

    Parameters
    ----------
    X : array_like, shape (N, D)

    Returns
    -------
    ndarray, shape (N, D + 1)
    """
    return _homogeneous(vd.numbers(X, "to_homogeneous", "X"))


def from_homogeneous(Xh, tol: float = 1e-12) -> np.ndarray:
    """Euclidean points ``(X/W, Y/W, Z/W)`` from homogeneous ones, Eq. (A.4).

    Parameters
    ----------
    Xh : array_like, shape (N, D + 1)
    tol : float
        A point whose ``|W|`` is below ``tol`` times its norm is at infinity.

    Returns
    -------
    ndarray, shape (N, D)
    """
    f = "from_homogeneous"
    Xh, tol = vd.numbers(Xh, f, "Xh"), checks.real(tol, f, "tol", low=0.0)
    w = Xh[..., -1:]
    bad = np.abs(w[..., 0]) <= tol * np.linalg.norm(Xh, axis=-1)
    if np.any(bad):
        raise degenerate(f, "Xh", f"{int(np.sum(bad))} point(s) at infinity (W = 0)")
    return Xh[..., :-1] / w


def project(P, X, return_depth: bool = False):
    """Project world points into the image, ``lambda x = P X``, Eq. (A.5).

    Parameters
    ----------
    P : array_like, shape (3, 4)
    X : array_like, shape (N, 3) or (3,)
        Euclidean world points.
    return_depth : bool
        Also return the depth of each point in front of the camera (metres
        along the principal axis; negative behind the camera).

    Returns
    -------
    x : ndarray, shape (N, 2)
        Pixel coordinates.
    depth : ndarray, shape (N,)
        Only when ``return_depth``.
    """
    f = "project"
    P, (X, _) = vd.camera(P, f), vd.batch(X, f, "X", (3,))
    return_depth = checks.flag(return_depth, f, "return_depth")
    lam_x = _homogeneous(X) @ P.T
    lam = lam_x[:, 2]
    if np.any(np.abs(lam) <= 1e-14 * np.linalg.norm(lam_x, axis=1)):
        raise degenerate(f, "X", "a point lies on the camera's principal plane (projective depth 0)")
    x = lam_x[:, :2] / lam[:, None]
    if not return_depth:
        return x
    M = P[:, :3]
    if abs(np.linalg.det(M)) < 1e-12 * np.linalg.norm(M) ** 3:
        raise degenerate(f, "P", "is a camera at infinity (singular left 3x3 block): its points have no depth")
    depth = np.sign(np.linalg.det(M)) * lam / np.linalg.norm(M[2])
    return x, depth


def camera_center(P) -> np.ndarray:
    """Camera centre: the null vector ``P C = 0`` of Eqs. (A.1) and (A.14).

    Parameters
    ----------
    P : array_like, shape (3, 4)

    Returns
    -------
    C : ndarray, shape (3,)
        Euclidean centre (raises for a camera at infinity).
    """
    return _centre(vd.camera(P, "camera_center"), "camera_center", "P")


def _centre(P, func: str, name: str) -> np.ndarray:
    """The Euclidean centre of a checked camera P; errors name ``func`` and ``name``."""
    _, s, vt = np.linalg.svd(P)
    if s[2] <= 1e-12 * s[0]:
        raise degenerate(func, name, "has rank < 3: it is not a camera")
    c = vt[-1]
    if abs(c[3]) <= 1e-12 * np.linalg.norm(c):
        raise degenerate(func, name, "the camera centre is at infinity (affine camera)")
    return c[:3] / c[3]


def optical_planes(P) -> np.ndarray:
    """The three optical planes: the rows ``p_i^T`` of P, Eq. (A.5) and figure A.2.

    Plane ``p1`` holds the points that project onto the image column
    ``x = 0``, ``p2`` onto the row ``y = 0``, and ``p3`` is the principal
    plane (depth 0).  All three pass through the camera centre.  They are
    scaled to unit normals and oriented so that ``p3 . [X, 1]`` is the depth
    of X in metres.

    Parameters
    ----------
    P : array_like, shape (3, 4)

    Returns
    -------
    planes : ndarray, shape (3, 4)
        Row ``i`` is ``(n_x, n_y, n_z, d)`` with ``n . X + d = 0`` on plane i.
    """
    f = "optical_planes"
    P = vd.camera(P, f)
    norms = np.linalg.norm(P[:, :3], axis=1)
    if np.any(norms == 0):
        raise degenerate(f, "P", "a row has a zero normal (1:3)")
    det = np.linalg.det(P[:, :3] / norms[:, None])
    if abs(det) <= 1e-12:
        raise degenerate(f, "P", "the left 3x3 block is singular (a camera at infinity): the planes have no front")
    return np.sign(det) * P / norms[:, None]


def pseudo_inverse(P) -> np.ndarray:
    """Pseudo-inverse ``P+ = P^T (P P^T)^-1`` (footnote to Eq. A.14), so ``P P+ = I``.

    Parameters
    ----------
    P : array_like, shape (3, 4)

    Returns
    -------
    ndarray, shape (4, 3)
    """
    return _pinv(vd.camera(P, "pseudo_inverse"), "pseudo_inverse", "P")


def _pinv(P, func: str, name: str) -> np.ndarray:
    PPt = P @ P.T
    if np.linalg.cond(PPt) > 1e14:
        raise degenerate(func, name, "P P^T is singular (rank of P < 3)")
    return P.T @ np.linalg.inv(PPt)


def back_project(P, x):
    """Rays ``X(lambda) = P+ x + lambda C`` through image points, Eq. (A.14).

    Parameters
    ----------
    P : array_like, shape (3, 4)
        A finite camera.
    x : array_like, shape (N, 2)
        Pixel coordinates.

    Returns
    -------
    origins : ndarray, shape (N, 3)
        The camera centre C, once per ray.
    directions : ndarray, shape (N, 3)
        Unit directions, pointing in front of the camera.
    """
    f = "back_project"
    return _back_project(vd.camera(P, f), vd.batch(x, f, "x", (2,))[0], f, "P")


def _back_project(P, x, func: str, name: str):
    C = _centre(P, func, name)
    Ch = np.append(C, 1.0)
    A = _homogeneous(x) @ _pinv(P, func, name).T  # P+ x, homogeneous 4-vectors
    # Point at infinity of the pencil A + lambda C: W_A C - W_C A has W = 0.
    d = A[:, 3:4] * Ch[None, :3] - A[:, :3]
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    M = P[:, :3]
    front = np.sign(np.linalg.det(M)) * (d @ M[2]) > 0
    d[~front] *= -1.0
    return np.repeat(C[None], len(x), axis=0), d


# ---------------------------------------------------------- triangulation
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
    those of :func:`cameras_from_fundamental`.

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
    return vd.overflow(_triangulate(P1, P2, x1, x2, method, f), f, "x1, x2")


def _triangulate(P1, P2, x1, x2, method: str, func: str) -> np.ndarray:
    """:func:`triangulate` of checked arguments; errors name ``func``."""
    c1, c2 = (np.linalg.svd(P)[2][-1] for P in (P1, P2))  # homogeneous centres, P C = 0
    if np.linalg.svd(np.vstack([c1, c2]), compute_uv=False)[1] <= 1e-12:
        raise degenerate(func, "P1, P2", "the cameras share their centre; there is no baseline")
    if method == "midpoint":
        o1, d1 = _back_project(P1, x1, func, "P1")
        o2, d2 = _back_project(P2, x2, func, "P2")
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
