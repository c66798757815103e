"""Pinhole cameras and their rays (appendix A of the thesis, Eqs. A.1-A.5 and A.14).

Triangulation (A.14, figure A.4) is in :mod:`cga_lessons.stereo.triangulation`.  Two-view geometry (A.6-A.13:
the fundamental matrix, the 8-point algorithm, cameras from F) lives in :mod:`cga_lessons.stereo.epipolar`, which
builds on this module (this one does not import it).

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
    alpha_x, alpha_y = (
        checks.real(a, f, n, low=0.0, strict_low=True) for a, n in ((alpha_x, "alpha_x"), (alpha_y, "alpha_y"))
    )
    x0, y0, skew = (checks.real(a, f, n) for a, n in ((x0, "x0"), (y0, "y0"), (skew, "skew")))
    K = np.array([[alpha_x, skew, x0], [0.0, alpha_y, y0], [0.0, 0.0, 1.0]])
    return checks.magnitude(K, f, "alpha_x, alpha_y, x0, y0, skew", limit=vd.LIMIT, why=vd.WHY)


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
