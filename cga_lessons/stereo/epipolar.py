"""Two-view geometry: the fundamental matrix and cameras from it (appendix A.2, Eqs. A.6-A.13).

``x2^T F x1 = 0`` (A.6) for corresponding pixels ``x1`` (view 1) and ``x2``
(view 2).  Estimates are returned with unit Frobenius norm, and the sign that
makes positive the first entry (row by row) larger than half the largest one.  Two-view geometry builds on the
one-camera model of :mod:`cga_lessons.stereo.camera` (which does not import this module).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import degenerate

from . import validate as vd
from .camera import pseudo_inverse

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


def _h(x: np.ndarray) -> np.ndarray:
    """Checked pixels (N, 2) as homogeneous (N, 3)."""
    return np.column_stack([x, np.ones(len(x))])


def _pixels(x1, x2, func: str):
    """Two checked batches of corresponding pixels (N, 2) of one length."""
    (x1, _), (x2, _) = vd.batch(x1, func, "x1", (2,)), vd.batch(x2, func, "x2", (2,))
    checks.same_length(func, x1=x1, x2=x2)
    return x1, x2


def _fundamental(F, func: str, name: str = "F") -> np.ndarray:
    """A checked (3, 3) matrix that is not zero."""
    F = vd.array(F, func, name, (3, 3))
    if not np.any(F):
        raise degenerate(func, name, "is the zero matrix")
    return F


def skew(v) -> np.ndarray:
    """Cross-product matrix ``[v]_x`` with ``[v]_x w = v x w``, Eq. (A.12).

    Parameters
    ----------
    v : array_like, shape (3,)

    Returns
    -------
    ndarray, shape (3, 3)
    """
    a, b, c = vd.array(v, "skew", "v", (3,))
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
    return _z(*_pixels(x1, x2, "eight_point_matrix"))


def _z(x1, x2) -> np.ndarray:
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
    f = "hartley_normalization"
    return _hartley(vd.batch(x, f, "x", (2,), at_least=1)[0], f, "x")


def _hartley(x, func: str, name: str):
    c = x.mean(axis=0)
    mean_dist = np.mean(np.linalg.norm(x - c, axis=1))
    if mean_dist <= 1e-12 * max(1.0, np.abs(c).max()):
        raise degenerate(func, name, "all points coincide")
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
    f = "fundamental_8point"
    x1, x2 = _pixels(x1, x2, f)
    normalize, rank2 = checks.flag(normalize, f, "normalize"), checks.flag(rank2, f, "rank2")
    if len(x1) < 8:
        raise degenerate(f, "x1, x2", f"need at least 8 correspondences, got {len(x1)}")
    T1, n1 = _hartley(x1, f, "x1")
    T2, n2 = _hartley(x2, f, "x2")
    # Degeneracy is judged on the well-conditioned (normalised) system.
    s_n = np.linalg.svd(_z(n1, n2), compute_uv=False)
    if s_n[7] <= 1e-9 * s_n[0]:
        raise degenerate(
            f,
            "x1, x2",
            f"the correspondences are degenerate (null space of Z has dimension > 1, singular values "
            f"{s_n[7]:.1e} / {s_n[0]:.1e}): points collinear, coplanar in space, or repeated",
        )
    a, b = (n1, n2) if normalize else (x1, x2)
    _, _, vt = np.linalg.svd(_z(a, b))
    F = vt[-1].reshape(3, 3)
    if rank2:
        u, s, vt = np.linalg.svd(F)
        F = u @ np.diag([s[0], s[1], 0.0]) @ vt
    if normalize:
        F = T2.T @ F @ T1
    return checks.finite_result(_canonical_sign(F), f, "x1, x2")


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
    f = "fundamental_from_cameras"
    P1, P2 = vd.camera(P1, f, "P1"), vd.camera(P2, f, "P2")
    _, s, vt = np.linalg.svd(P1)
    e2 = P2 @ vt[-1]
    if np.linalg.norm(e2) <= 1e-12 * np.linalg.norm(P2):
        raise degenerate(f, "P1, P2", "the two cameras have the same centre (no baseline)")
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
    return _epipoles(_fundamental(F, "epipoles"), "epipoles")


def _epipoles(F, func: str):
    u, s, vt = np.linalg.svd(F)
    if s[1] <= 1e-12 * s[0]:
        raise degenerate(func, "F", "has rank < 2")
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
    f = "epipolar_lines"
    return _lines(_fundamental(F, f), vd.batch(x1, f, "x1", (2,))[0], f, "x1")


def _lines(F, x, func: str, name: str) -> np.ndarray:
    lines = _h(x) @ F.T
    n = np.linalg.norm(lines[:, :2], axis=1, keepdims=True)
    if np.any(n == 0):
        raise degenerate(func, name, f"point {int(np.flatnonzero(n == 0)[0])} maps to no line (it is the epipole)")
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
    f = "epipolar_distance"
    F = _fundamental(F, f)
    x1, x2 = _pixels(x1, x2, f)
    l2, l1 = _lines(F, x1, f, "x1"), _lines(F.T, x2, f, "x2")
    d2 = np.abs(np.sum(l2 * _h(x2), axis=1))
    d1 = np.abs(np.sum(l1 * _h(x1), axis=1))
    return checks.finite_result(0.5 * (d1 + d2), f, "x1, x2")


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
    f = "cameras_from_fundamental"
    F, v = _fundamental(F, f), vd.array(v, f, "v", (3,))
    lam = checks.real(lam, f, "lam")
    if lam == 0 or abs(lam) > vd.LIMIT:
        raise checks.fail(f, "lam", f"must be a non-zero number of magnitude at most {vd.LIMIT:.0e}, got {lam}")
    s = np.linalg.svd(F, compute_uv=False)
    if s[2] > 1e-8 * s[0]:
        raise degenerate(f, "F", f"must have rank 2 (s3/s1 = {s[2] / s[0]:.1e})")
    _, e2 = _epipoles(F, f)
    P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = np.hstack([skew(e2) @ F + np.outer(e2, v), lam * e2[:, None]])
    return P1, P2
