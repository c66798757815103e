"""Two-view geometry: the fundamental matrix and cameras from it (appendix A.2, Eqs. A.6-A.13).

``x2^T F x1 = 0`` (A.6) for corresponding pixels ``x1`` (view 1) and ``x2``
(view 2).  Estimates are returned with unit Frobenius norm, and the sign that
makes positive the first entry (row by row) larger than half the largest one.  The names are also available
from :mod:`cga_lessons.stereo.camera`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError

from .camera import as_batch, as_matrix, pseudo_inverse, to_homogeneous

__all__ = [
    "skew",
    "eight_point_matrix",
    "hartley_normalization",
    "fundamental_8point",
    "fundamental_from_cameras",
    "epipoles",
    "epipolar_lines",
    "epipolar_distance",
    "cameras_from_fundamental",
]


def skew(v) -> np.ndarray:
    """Cross-product matrix ``[v]_x`` with ``[v]_x w = v x w``, Eq. (A.12).

    Parameters
    ----------
    v : array_like, shape (3,)

    Returns
    -------
    ndarray, shape (3, 3)
    """
    a, b, c = as_matrix(v, (3,), "skew", "v")
    return np.array([[0.0, -c, b], [c, 0.0, -a], [-b, a, 0.0]])


def eight_point_matrix(x1, x2) -> np.ndarray:
    """The matrix Z of the linear system ``Z f = 0``, Eqs. (A.7)-(A.9).

    Row i is ``[x'x, x'y, x', y'x, y'y, y', x, y, 1]`` for the correspondence
    ``x = x1[i]``, ``x' = x2[i]``; ``f`` holds F row by row.

    Parameters
    ----------
    x1, x2 : array_like, shape (N, 2)

    Returns
    -------
    Z : ndarray, shape (N, 9)
    """
    x1 = as_batch(x1, (2,), "eight_point_matrix", "x1")
    x2 = as_batch(x2, (2,), "eight_point_matrix", "x2")
    if len(x1) != len(x2):
        raise InvalidInputError(f"eight_point_matrix: x1 has {len(x1)} points but x2 has {len(x2)}")
    x, y = x1[:, 0], x1[:, 1]
    xp, yp = x2[:, 0], x2[:, 1]
    one = np.ones_like(x)
    return np.column_stack([xp * x, xp * y, xp, yp * x, yp * y, yp, x, y, one])


def hartley_normalization(x):
    """Hartley's normalising similarity for the 8-point algorithm.

    Moves the centroid to the origin and scales so that the mean distance
    from it is sqrt(2).  Not in the thesis; it is what makes (A.9) well
    conditioned in pixel coordinates.

    Parameters
    ----------
    x : array_like, shape (N, 2)

    Returns
    -------
    T : ndarray, shape (3, 3)
        The similarity, acting on homogeneous points.
    xn : ndarray, shape (N, 2)
        The normalised points.
    """
    x = as_batch(x, (2,), "hartley_normalization", "x")
    c = x.mean(axis=0)
    mean_dist = np.mean(np.linalg.norm(x - c, axis=1))
    if mean_dist <= 1e-12 * max(1.0, np.abs(c).max()):
        raise DegenerateGeometryError("hartley_normalization: all points coincide")
    s = np.sqrt(2.0) / mean_dist
    T = np.array([[s, 0.0, -s * c[0]], [0.0, s, -s * c[1]], [0.0, 0.0, 1.0]])
    return T, (x - c) * s


def _canonical_sign(F: np.ndarray) -> np.ndarray:
    """Unit Frobenius norm; the first entry (row by row) above half the largest magnitude is positive.

    (Not simply "the largest entry positive": a parallel rig's F has two
    entries of equal size, and round-off would pick either.)
    """
    F = F / np.linalg.norm(F)
    a = np.abs(F.ravel())
    return F if F.flat[np.flatnonzero(a > 0.5 * a.max())[0]] > 0 else -F


def fundamental_8point(x1, x2, normalize: bool = True, rank2: bool = True) -> np.ndarray:
    """Fundamental matrix by the 8-point algorithm, Eqs. (A.6)-(A.9).

    Solves ``Z f = 0`` (A.9) for the right singular vector of Z with the
    smallest singular value (the least-squares null vector), optionally in
    Hartley-normalised coordinates, then enforces rank 2 by zeroing the
    smallest singular value of F (the closest rank-2 matrix in Frobenius norm).

    Parameters
    ----------
    x1, x2 : array_like, shape (N, 2)
        Corresponding pixel coordinates in view 1 and view 2, N >= 8.
    normalize : bool
        Use Hartley's normalisation (:func:`hartley_normalization`).
    rank2 : bool
        Enforce ``det F = 0`` (F of a real camera pair has rank 2).

    Returns
    -------
    F : ndarray, shape (3, 3)
        With ``x2^T F x1 = 0`` (A.6); unit Frobenius norm, sign as in the module docstring.

    Raises
    ------
    DegenerateGeometryError
        Fewer than 8 correspondences, or a configuration for which the null
        space of Z is not one-dimensional (all points on a line, all scene
        points on one plane, repeated points).
    """
    func = "fundamental_8point"
    x1 = as_batch(x1, (2,), func, "x1")
    x2 = as_batch(x2, (2,), func, "x2")
    if len(x1) != len(x2):
        raise InvalidInputError(f"{func}: x1 has {len(x1)} points but x2 has {len(x2)}")
    if len(x1) < 8:
        raise DegenerateGeometryError(f"{func}: need at least 8 correspondences, got {len(x1)}")
    T1, n1 = hartley_normalization(x1)
    T2, n2 = hartley_normalization(x2)
    # Degeneracy is judged on the well-conditioned (normalised) system.
    s_n = np.linalg.svd(eight_point_matrix(n1, n2), compute_uv=False)
    if s_n[7] <= 1e-9 * s_n[0]:
        raise DegenerateGeometryError(
            f"{func}: the correspondences are degenerate (null space of Z has dimension > 1, "
            f"singular values {s_n[7]:.1e} / {s_n[0]:.1e}): points collinear, coplanar in space, or repeated"
        )
    a, b = (n1, n2) if normalize else (x1, x2)
    _, _, vt = np.linalg.svd(eight_point_matrix(a, b))
    F = vt[-1].reshape(3, 3)
    if rank2:
        u, s, vt = np.linalg.svd(F)
        F = u @ np.diag([s[0], s[1], 0.0]) @ vt
    if normalize:
        F = T2.T @ F @ T1
    return _canonical_sign(F)


def fundamental_from_cameras(P1, P2) -> np.ndarray:
    """The fundamental matrix of two cameras, ``F = [e']_x P2 P1+`` with ``e' = P2 C1``.

    Built from the pseudo-inverse and camera centre of Eq. (A.14) and the
    cross-product matrix of Eq. (A.12); used as ground truth.

    Parameters
    ----------
    P1, P2 : array_like, shape (3, 4)

    Returns
    -------
    F : ndarray, shape (3, 3)
        Unit Frobenius norm, sign as in the module docstring.
    """
    P1 = as_matrix(P1, (3, 4), "fundamental_from_cameras", "P1")
    P2 = as_matrix(P2, (3, 4), "fundamental_from_cameras", "P2")
    _, s, vt = np.linalg.svd(P1)
    if s[2] <= 1e-12 * s[0]:
        raise DegenerateGeometryError("fundamental_from_cameras: P1 has rank < 3")
    e2 = P2 @ vt[-1]
    if np.linalg.norm(e2) <= 1e-12 * np.linalg.norm(P2):
        raise DegenerateGeometryError("fundamental_from_cameras: the two cameras have the same centre (no baseline)")
    return _canonical_sign(skew(e2) @ P2 @ pseudo_inverse(P1))


def epipoles(F):
    """Epipoles: ``F e = 0`` and ``F^T e' = 0`` (the null vectors used in Eq. A.11).

    Parameters
    ----------
    F : array_like, shape (3, 3)

    Returns
    -------
    e1, e2 : ndarray, shape (3,)
        Homogeneous unit vectors: the epipole in image 1 and in image 2.
    """
    F = as_matrix(F, (3, 3), "epipoles", "F")
    u, s, vt = np.linalg.svd(F)
    if s[1] <= 1e-12 * s[0]:
        raise DegenerateGeometryError("epipoles: F has rank < 2")
    return vt[-1], u[:, -1]


def epipolar_lines(F, x1) -> np.ndarray:
    """Epipolar lines ``l' = F x`` in image 2 of points of image 1 (Eq. A.6).

    Pass ``F.T`` and points of image 2 for the lines in image 1.

    Parameters
    ----------
    F : array_like, shape (3, 3)
    x1 : array_like, shape (N, 2)

    Returns
    -------
    lines : ndarray, shape (N, 3)
        ``(a, b, c)`` with ``a x + b y + c = 0`` and ``a^2 + b^2 = 1``, so
        ``lines @ [x, y, 1]`` is a signed distance in pixels.
    """
    F = as_matrix(F, (3, 3), "epipolar_lines", "F")
    x1 = as_batch(x1, (2,), "epipolar_lines", "x1")
    lines = to_homogeneous(x1) @ F.T
    n = np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
    if np.any(n == 0):
        raise DegenerateGeometryError("epipolar_lines: a point maps to no line (it is the epipole)")
    return lines / n


def epipolar_distance(F, x1, x2) -> np.ndarray:
    """Symmetric epipolar distance in pixels: how far (A.6) is from holding.

    Mean of the distance of ``x2`` to the line ``F x1`` and of ``x1`` to the
    line ``F^T x2``.

    Parameters
    ----------
    F : array_like, shape (3, 3)
    x1, x2 : array_like, shape (N, 2)

    Returns
    -------
    ndarray, shape (N,)
    """
    F = as_matrix(F, (3, 3), "epipolar_distance", "F")
    l2 = epipolar_lines(F, x1)
    l1 = epipolar_lines(F.T, x2)
    d2 = np.abs(np.sum(l2 * to_homogeneous(as_batch(x2, (2,), "epipolar_distance", "x2")), axis=1))
    d1 = np.abs(np.sum(l1 * to_homogeneous(as_batch(x1, (2,), "epipolar_distance", "x1")), axis=1))
    return 0.5 * (d1 + d2)


def cameras_from_fundamental(F, v=(0.0, 0.0, 0.0), lam: float = 1.0):
    """A projective camera pair for F, Eqs. (A.10)-(A.13).

    ``P = [I | 0]`` (A.10) and ``P' = [[e']_x F + e' v^T | lam e']`` (A.13),
    which is (A.11) for ``v = 0, lam = 1``.  The pair reproduces the images
    (and F) exactly; the reconstruction it gives differs from the true scene
    by a projective transformation of space.

    Parameters
    ----------
    F : array_like, shape (3, 3)
        Rank 2.
    v : array_like, shape (3,)
        Any vector.
    lam : float
        Any non-zero scalar.

    Returns
    -------
    P1, P2 : ndarray, shape (3, 4)
    """
    F = as_matrix(F, (3, 3), "cameras_from_fundamental", "F")
    v = as_matrix(v, (3,), "cameras_from_fundamental", "v")
    if lam == 0 or not np.isfinite(lam):
        raise InvalidInputError(f"cameras_from_fundamental: lam must be a non-zero number, got {lam}")
    s = np.linalg.svd(F, compute_uv=False)
    if s[2] > 1e-8 * s[0]:
        raise DegenerateGeometryError(f"cameras_from_fundamental: F must have rank 2 (s3/s1 = {s[2] / s[0]:.1e})")
    _, e2 = epipoles(F)
    P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = np.hstack([skew(e2) @ F + np.outer(e2, v), lam * e2[:, None]])
    return P1, P2
