"""Pinhole cameras and triangulation (appendix A of the thesis, Eqs. A.1-A.5 and A.14).

Two-view geometry (A.6-A.13: the fundamental matrix, the 8-point algorithm,
cameras from F) lives in :mod:`cga_lessons.stereo.epipolar` and is re-exported here,
so ``from cga_lessons.stereo.camera import fundamental_8point`` works.

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

from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError

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


# Two-view geometry is defined in :mod:`cga_lessons.stereo.epipolar` (A.6-A.13) and
# reachable from here as ``camera.fundamental_8point`` etc.
def __getattr__(name):
    """Lazy re-export of :mod:`cga_lessons.stereo.epipolar` (which imports this module)."""
    from . import epipolar

    if name in epipolar.__all__:
        return getattr(epipolar, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ----------------------------------------------------------------- validation
def as_batch(a, shape_tail: tuple, func: str, name: str) -> np.ndarray:
    """``a`` as a float array of shape ``(N,) + shape_tail`` (a single item is promoted)."""
    try:
        arr = np.asarray(a, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"{func}: {name} is not numeric ({exc})") from None
    if arr.shape == shape_tail:
        arr = arr[None]
    if arr.ndim != len(shape_tail) + 1 or arr.shape[1:] != shape_tail:
        want = "(N, " + ", ".join(map(str, shape_tail)) + ")"
        raise InvalidInputError(f"{func}: {name} must have shape {want}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidInputError(f"{func}: {name} contains NaN or inf")
    return arr


def as_matrix(a, shape: tuple, func: str, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.shape != shape:
        raise InvalidInputError(f"{func}: {name} must have shape {shape}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidInputError(f"{func}: {name} contains NaN or inf")
    return arr


def _check_rotation(R, func: str) -> np.ndarray:
    R = as_matrix(R, (3, 3), func, "R")
    if not np.allclose(R @ R.T, np.eye(3), atol=1e-9) or np.linalg.det(R) < 0:
        raise InvalidInputError(f"{func}: R is not a rotation matrix (R R^T != I or det R < 0)")
    return R


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
    vals = np.array([alpha_x, alpha_y, x0, y0, skew], dtype=float)
    if not np.all(np.isfinite(vals)):
        raise InvalidInputError("calibration_matrix: parameters contain NaN or inf")
    if alpha_x <= 0 or alpha_y <= 0:
        raise InvalidInputError(f"calibration_matrix: focal lengths must be positive, got {alpha_x}, {alpha_y}")
    return np.array([[alpha_x, skew, x0], [0.0, alpha_y, y0], [0.0, 0.0, 1.0]])


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
    K = as_matrix(K, (3, 3), "projection_matrix", "K")
    R = _check_rotation(R, "projection_matrix")
    C = as_matrix(C, (3,), "projection_matrix", "C")
    if abs(np.linalg.det(K)) < 1e-300:
        raise DegenerateGeometryError("projection_matrix: K is singular")
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
    K = as_matrix(K, (3, 3), "projection_matrix_rt", "K")
    R = _check_rotation(R, "projection_matrix_rt")
    t = as_matrix(t, (3,), "projection_matrix_rt", "t")
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
    P = as_matrix(P, (3, 4), "decompose_projection", "P")
    M = P[:, :3]
    if abs(np.linalg.det(M)) < 1e-12 * np.linalg.norm(M) ** 3:
        raise DegenerateGeometryError("decompose_projection: the left 3x3 block of P is singular (camera at infinity)")
    if np.linalg.det(M) < 0:  # P is defined up to scale: pick the sign that gives det R = +1
        P, M = -P, -M
    # RQ via QR of the flipped, transposed matrix
    flip = np.eye(3)[::-1]
    q, r = np.linalg.qr((flip @ M).T)
    K = flip @ r.T @ flip
    R = flip @ q.T
    D = np.diag(np.sign(np.diag(K)))
    K, R = K @ D, D @ R
    C = camera_center(P)
    return K / K[2, 2], R, C


# ------------------------------------------------------------- projection
def to_homogeneous(X) -> np.ndarray:
    """Homogeneous coordinates ``[X, Y, Z, 1]`` of Euclidean points, Eq. (A.4).

    Parameters
    ----------
    X : array_like, shape (N, D)

    Returns
    -------
    ndarray, shape (N, D + 1)
    """
    X = np.asarray(X, dtype=float)
    return np.concatenate([X, np.ones(X.shape[:-1] + (1,))], axis=-1)


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
    Xh = np.asarray(Xh, dtype=float)
    w = Xh[..., -1:]
    bad = np.abs(w[..., 0]) <= tol * np.linalg.norm(Xh, axis=-1)
    if np.any(bad):
        raise DegenerateGeometryError(f"from_homogeneous: {int(np.sum(bad))} point(s) at infinity (W = 0)")
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
    P = as_matrix(P, (3, 4), "project", "P")
    X = as_batch(X, (3,), "project", "X")
    lam_x = to_homogeneous(X) @ P.T
    lam = lam_x[:, 2]
    if np.any(np.abs(lam) <= 1e-14 * np.linalg.norm(lam_x, axis=1)):
        raise DegenerateGeometryError("project: a point lies on the camera's principal plane (projective depth 0)")
    x = lam_x[:, :2] / lam[:, None]
    if not return_depth:
        return x
    M = P[:, :3]
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
    P = as_matrix(P, (3, 4), "camera_center", "P")
    _, s, vt = np.linalg.svd(P)
    if s[2] <= 1e-12 * s[0]:
        raise DegenerateGeometryError("camera_center: P has rank < 3")
    c = vt[-1]
    if abs(c[3]) <= 1e-12 * np.linalg.norm(c):
        raise DegenerateGeometryError("camera_center: the camera centre is at infinity (affine camera)")
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
    P = as_matrix(P, (3, 4), "optical_planes", "P")
    norms = np.linalg.norm(P[:, :3], axis=1)
    if np.any(norms == 0):
        raise DegenerateGeometryError("optical_planes: a row of P has a zero normal")
    return np.sign(np.linalg.det(P[:, :3])) * P / norms[:, None]


def pseudo_inverse(P) -> np.ndarray:
    """Pseudo-inverse ``P+ = P^T (P P^T)^-1`` (footnote to Eq. A.14), so ``P P+ = I``.

    Parameters
    ----------
    P : array_like, shape (3, 4)

    Returns
    -------
    ndarray, shape (4, 3)
    """
    P = as_matrix(P, (3, 4), "pseudo_inverse", "P")
    PPt = P @ P.T
    if np.linalg.cond(PPt) > 1e14:
        raise DegenerateGeometryError("pseudo_inverse: P P^T is singular (rank of P < 3)")
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
    P = as_matrix(P, (3, 4), "back_project", "P")
    x = as_batch(x, (2,), "back_project", "x")
    C = camera_center(P)
    Ch = np.append(C, 1.0)
    A = to_homogeneous(x) @ pseudo_inverse(P).T  # P+ x, homogeneous 4-vectors
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
    func = "closest_points_on_rays"
    o1, d1, o2, d2 = (as_batch(a, (3,), func, n) for a, n in ((o1, "o1"), (d1, "d1"), (o2, "o2"), (d2, "d2")))
    if not len(o1) == len(d1) == len(o2) == len(d2):
        raise InvalidInputError(f"{func}: inputs have different numbers of rows")
    n1 = np.linalg.norm(d1, axis=1, keepdims=True)
    n2 = np.linalg.norm(d2, axis=1, keepdims=True)
    if np.any(n1 == 0) or np.any(n2 == 0):
        raise DegenerateGeometryError(f"{func}: a direction is the zero vector")
    u1, u2 = d1 / n1, d2 / n2
    cross = np.cross(u1, u2)
    denom = np.sum(cross * cross, axis=1)  # sin^2 of the angle, free of cancellation
    parallel = np.flatnonzero(denom <= tol * tol)
    if parallel.size:
        raise DegenerateGeometryError(
            f"{func}: {parallel.size} pair(s) of parallel rays (first index {parallel[0]}); the point is at infinity"
        )
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
    func = "triangulate"
    P1 = as_matrix(P1, (3, 4), func, "P1")
    P2 = as_matrix(P2, (3, 4), func, "P2")
    x1 = as_batch(x1, (2,), func, "x1")
    x2 = as_batch(x2, (2,), func, "x2")
    if len(x1) != len(x2):
        raise InvalidInputError(f"{func}: x1 has {len(x1)} points but x2 has {len(x2)}")
    if method not in ("midpoint", "dlt"):
        raise InvalidInputError(f"{func}: method must be 'midpoint' or 'dlt', got {method!r}")
    c1, c2 = (np.linalg.svd(P)[2][-1] for P in (P1, P2))  # homogeneous centres, P C = 0
    if np.linalg.svd(np.vstack([c1, c2]), compute_uv=False)[1] <= 1e-12:
        raise DegenerateGeometryError(f"{func}: the cameras share their centre; there is no baseline")
    if method == "midpoint":
        o1, d1 = back_project(P1, x1)
        o2, d2 = back_project(P2, x2)
        q1, q2 = closest_points_on_rays(o1, d1, o2, d2)
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
            raise DegenerateGeometryError(f"{func}: the linear system is rank deficient (cameras share their centre?)")
        Xh = vt[:, -1, :]
        w = Xh[:, 3]
        far = np.flatnonzero(np.abs(w) <= 1e-12)
        if far.size:
            raise DegenerateGeometryError(
                f"{func}: {far.size} point(s) at infinity (parallel rays; first index {far[0]})"
            )
        return Xh[:, :3] / w[:, None]
