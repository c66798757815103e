"""Chapter 5 as printed: relocalization by voting in Hough space (Eqs. 5.1-5.6, steps 1-10).

The thesis compares the map ``M`` and the new local map ``L`` (both sets of
segments, point pairs in the conformal model) through their Hough
representations ``M_h`` and ``L_h`` (figure 5.1, Eq. 3.3: ``rho >= 0`` and
``theta`` cyclic on ``[0, 2 pi)``):

1. for one map line ``m_i`` and every local line ``l_j`` the differences
   ``Delta theta_j = diffTheta(m_i theta, l_j theta)`` (5.1) and
   ``Delta rho_j = m_i rho - l_j rho`` (5.2), the set ``phi_{m_i l}`` (5.3);
2. every local line shifted by each difference, ``psi_{h_i} = L_h + phi`` (5.4);
3. the shifted lines compared with the map, ``xi_{h_i} = M_h - psi_{h_i}`` (5.5);
4. a vote in ``V`` (``|M| x |L|``) for every comparison below ``xi_theta`` and
   ``xi_rho`` (5.6); 5. repeated for every ``m_i``;
6. the correspondence vector ``C`` from the column maxima of ``V``;
7. the mean angle ``Theta`` of the corresponding lines by diffTheta (3.5);
8. a rotor (2.96) by ``Theta`` applied to the local entities;
9. the translation by the least squares (3.12) of the closest points;
10. a translator (2.100) applied to them.

Each step is a function here.  Read literally the method cannot work in
general (measured in notebook 09 and ``DESIGN.md``): a rotation about the
laser moves every line only along ``theta`` (section 5.1, right), but a
translation moves ``rho`` by ``t . n(theta)``, a different amount for every
line direction, so shifting all of ``L_h`` by one ``Delta rho`` (5.4) puts the
lines where they are not (the erratum registered for 5.4, see
:func:`shifted_set_corrected`); and ``rho`` of the map is measured from the
map's origin while ``rho`` of the scan is measured from the laser.  The angle
part of the votes is sound, and :mod:`cga_lessons.relocalization` uses it to
propose rotations.

Reading of (5.4)-(5.6).  Elementwise, ``l_j + (m_i - l_j) = m_i`` for every
``j``, which compares nothing; the reading kept here shifts the *whole* set
``L_h`` by each difference ``phi_j`` (the hypothesis "``l_j`` is ``m_i``"), so
``psi_{h_i}`` holds ``|L|^2`` shifted lines, and ``V[i, j]`` counts the pairs
``(k, m)`` whose shifted line ``l_k + phi_j`` lands within the thresholds of
map line ``m``: the support of the hypothesis ``m_i <-> l_j``.  Every entry is
at least 1 (``k = j`` lands exactly on ``m = i``).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import TWO_PI, diff_theta

from .inputs import ndim

__all__ = [
    "THETA_XI",
    "hough_set",
    "hough_differences",
    "shifted_set",
    "shifted_set_corrected",
    "hough_comparison",
    "vote_matrix",
    "vote_matrix_indexed",
]

#: The thesis's ``theta_xi`` of diffTheta (3.5), ``2 pi / 100``.
THETA_XI = TWO_PI / 100


def endpoint_array(segments, func="hough_set", name="segments") -> np.ndarray:
    """Segments as a finite (K, 2, 2) endpoint array (no checks of length)."""
    return checks.magnitude(checks.array(segments, func, name, (None, 2, 2)), func, name)


def hough_array(value, func: str, name: str, *, lead: int = 1) -> np.ndarray:
    """Hough points ``(rho, theta)`` as a finite float array of shape (N, 2) (``lead`` leading axes: (..., 2))."""
    return checks.array(value, func, name, (None,) * lead + (2,))


def check_theta_xi(theta_xi, func: str) -> float:
    """diffTheta's threshold (3.5): a finite angle in (0, pi)."""
    return checks.real(theta_xi, func, "theta_xi", low=0.0, high=np.pi, strict_low=True, strict_high=True)


# --------------------------------------------------------------------------- figure 5.1


def hough_set(segments, origin=(0.0, 0.0)) -> np.ndarray:
    """The Hough representation ``M_h`` or ``L_h`` of a set of segments (figure 5.1, Eq. 3.3).

    Every segment's line ``x cos(theta) + y sin(theta) = rho`` as a point
    ``(rho, theta)`` with ``rho >= 0`` and ``theta`` in ``[0, 2 pi)``, the angle
    of the line's closest point to ``origin`` (the same numbers as
    :attr:`cga_lessons.mapping2d.segment.Segment.rho` and ``.theta``).  A rotation about
    ``origin`` moves every point along ``theta`` only, cyclically (section 5.1).

    Parameters
    ----------
    segments : array_like, shape (K, 2, 2)
        End points ``[[x0, y0], [x1, y1]]``.
    origin : array_like, shape (2,)

    Returns
    -------
    ndarray, shape (K, 2)
        Columns ``rho``, ``theta``.

    >>> hough_set([[[1.0, -1.0], [1.0, 1.0]], [[-1.0, -2.0], [1.0, -2.0]]]).round(6).tolist()
    [[1.0, 0.0], [2.0, 4.712389]]
    """
    s = endpoint_array(segments)
    origin = checks.array(origin, "hough_set", "origin", (2,))
    return checks.finite_result(hough_points(s, origin), "hough_set", "segments, origin: the result")


def hough_points(s: np.ndarray, origin=(0.0, 0.0), func: str = "hough_set", name: str = "segments") -> np.ndarray:
    """:func:`hough_set` of checked segments (K, 2, 2); a segment with coincident end points is degenerate."""
    v = s[:, 1] - s[:, 0]
    length = np.hypot(v[:, 0], v[:, 1])
    if np.any(length == 0):
        raise checks.degenerate(func, name, f"segment {int(np.argmin(length))} has coincident end points")
    n = np.column_stack([v[:, 1], -v[:, 0]]) / length[:, None]
    off = np.einsum("ij,ij->i", n, s[:, 0] - np.asarray(origin))
    n = np.where((off < 0)[:, None], -n, n)
    return np.column_stack([np.abs(off), np.mod(np.arctan2(n[:, 1], n[:, 0]), TWO_PI)])


# --------------------------------------------------------------------------- steps 1-5


def hough_differences(m, L_h, theta_xi: float = THETA_XI) -> np.ndarray:
    """The differences of one map line against every local line, Eqs. (5.1)-(5.3).

    ``Delta theta_j = diffTheta(m_theta, l_j theta)`` (5.1) and ``Delta rho_j =
    m_rho - l_j rho`` (5.2); together the set ``phi_{m l} = m - L_h`` (5.3).

    Parameters
    ----------
    m : array_like, shape (2,)
        ``(rho, theta)`` of the map line.
    L_h : array_like, shape (n, 2)
    theta_xi : float
        diffTheta's threshold (3.5).

    Returns
    -------
    ndarray, shape (n, 2)
        Rows ``(Delta rho_j, Delta theta_j)``.

    The second line lies just below ``2 pi``: diffTheta takes the short way across the cut.

    >>> hough_differences([2.0, 0.03], [[1.5, 0.01], [1.0, 6.25]]).round(6).tolist()
    [[0.5, 0.02], [1.0, 0.063185]]
    """
    func = "hough_differences"
    m = checks.array(m, func, "m", (2,))
    L_h = hough_array(L_h, func, "L_h")
    theta_xi = check_theta_xi(theta_xi, func)
    return checks.finite_result(_differences(m, L_h, theta_xi), func, "m, L_h: the result")


def _differences(m, L_h, theta_xi):
    """:func:`hough_differences` of checked arrays."""
    d_theta = np.atleast_1d(diff_theta(m[1], L_h[:, 1], theta_xi))  # (5.1)
    d_rho = m[0] - L_h[:, 0]  # (5.2)
    return np.column_stack([d_rho, d_theta])  # (5.3)


def shifted_set(L_h, phi) -> np.ndarray:
    """The local set shifted by each difference, ``psi = L_h + phi``, Eq. (5.4) as printed.

    ``psi[j, k] = (rho_k + Delta rho_j, (theta_k + Delta theta_j) mod 2 pi)``:
    the whole local map moved as if ``l_j`` were the map line of ``phi``.  As
    printed every line's ``rho`` moves by the same ``Delta rho_j``; that holds
    for a rotation about the laser (``Delta rho = 0``) but not for a
    translation (erratum, see :func:`shifted_set_corrected`).

    Parameters
    ----------
    L_h : array_like, shape (n, 2)
    phi : array_like, shape (p, 2)
        Differences ``(Delta rho, Delta theta)`` from :func:`hough_differences`.

    Returns
    -------
    ndarray, shape (p, n, 2)
    """
    L_h = hough_array(L_h, "shifted_set", "L_h")
    phi = hough_array(phi, "shifted_set", "phi")
    return checks.finite_result(_shifted(L_h, phi), "shifted_set", "L_h, phi: the result")


def _shifted(L_h, phi):
    """:func:`shifted_set` of checked arrays."""
    rho = L_h[None, :, 0] + phi[:, None, 0]
    theta = np.mod(L_h[None, :, 1] + phi[:, None, 1], TWO_PI)
    return np.stack([rho, theta], axis=-1)


def shifted_set_corrected(L_h, rotation, translation) -> np.ndarray:
    """Where the local lines really go under the motion ``(rotation, translation)``: Eq. (5.4) corrected.

    A line ``(rho, theta)`` of the laser frame, moved by ``x -> R x + t``, is the
    line with normal angle ``theta + Theta`` and offset ``rho + t . n(theta +
    Theta)``: the shift of ``rho`` depends on each line's direction, so it is
    not one ``Delta rho`` for the whole set.  The result is brought back to the
    thesis's form (``rho >= 0``, ``theta`` in ``[0, 2 pi)``).

    Parameters
    ----------
    L_h : array_like, shape (n, 2)
    rotation : float
        ``Theta`` (radians).
    translation : array_like, shape (2,)

    Returns
    -------
    ndarray, shape (n, 2)

    >>> shifted_set_corrected([[1.0, 0.0], [1.0, np.pi / 2]], 0.0, [0.5, 0.0]).round(6).tolist()
    [[1.5, 0.0], [1.0, 1.570796]]
    """
    func = "shifted_set_corrected"
    L_h = hough_array(L_h, func, "L_h")
    t = checks.array(translation, func, "translation", (2,))
    theta = L_h[:, 1] + checks.real(rotation, func, "rotation")
    rho = L_h[:, 0] + t[0] * np.cos(theta) + t[1] * np.sin(theta)
    theta = np.where(rho < 0, theta + np.pi, theta)
    out = np.column_stack([np.abs(rho), np.mod(theta, TWO_PI)])
    return checks.finite_result(out, func, "L_h, rotation, translation: the result")


def hough_comparison(M_h, psi, theta_xi: float = THETA_XI) -> np.ndarray:
    """The comparison ``xi = M_h - psi`` of every shifted line with every map line, Eq. (5.5).

    Parameters
    ----------
    M_h : array_like, shape (M, 2)
    psi : array_like, shape (..., 2)
        Shifted lines (5.4).
    theta_xi : float
        diffTheta's threshold (3.5): angle differences are taken with diffTheta.

    Returns
    -------
    ndarray, shape (..., M, 2)
        ``(M_rho - psi_rho, diffTheta(M_theta, psi_theta))``.
    """
    func = "hough_comparison"
    M_h = hough_array(M_h, func, "M_h")
    psi = hough_array(psi, func, "psi", lead=max(ndim(psi) - 1, 1))
    theta_xi = check_theta_xi(theta_xi, func)
    return checks.finite_result(_comparison(M_h, psi, theta_xi), func, "M_h, psi: the comparison")


def _comparison(M_h, psi, theta_xi):
    """:func:`hough_comparison` of checked arrays."""
    d_rho = M_h[:, 0] - psi[..., None, 0]
    d_theta = diff_theta(M_h[:, 1], psi[..., None, 1], theta_xi)
    return np.stack([d_rho, np.asarray(d_theta, float)], axis=-1)


def check_votes(M_h, L_h, xi_theta, xi_rho, theta_xi, func):
    """The checked arguments of the vote matrix (5.6): Hough sets (N, 2), ``xi_theta`` in (0, pi],
    ``xi_rho`` > 0 (``inf``: the angles alone), ``theta_xi`` in (0, pi)."""
    M_h = hough_array(M_h, func, "M_h")
    L_h = hough_array(L_h, func, "L_h")
    xi_theta = checks.real(xi_theta, func, "xi_theta", low=0.0, high=np.pi, strict_low=True)
    if not (isinstance(xi_rho, (float, np.floating)) and xi_rho == np.inf):
        xi_rho = checks.real(xi_rho, func, "xi_rho", low=0.0, strict_low=True)
    return M_h, L_h, xi_theta, float(xi_rho), check_theta_xi(theta_xi, func)


def vote_matrix(M_h, L_h, xi_theta: float, xi_rho: float, theta_xi: float = THETA_XI) -> np.ndarray:
    """The vote matrix ``V`` of Eq. (5.6), step by step as printed (steps 1-5).

    For every map line ``m_i``: the differences (5.1)-(5.3), the shifted set
    (5.4), the comparison (5.5), and ``V[i, j] += 1`` for every pair ``(k, m)``
    whose comparison ``xi`` is below ``xi_rho`` and ``xi_theta`` under the
    shift ``phi_j`` (5.6).  Every map line compares ``|L|^2`` shifted lines with
    the whole map here: ``|M|^2 |L|^2`` comparisons in all.
    :func:`vote_matrix_indexed` gives the same matrix with ``|M| |L|^2`` binary
    searches.

    Parameters
    ----------
    M_h : array_like, shape (M, 2)
    L_h : array_like, shape (L, 2)
    xi_theta, xi_rho : float
        The thesis's thresholds (radians, metres); ``numpy.inf`` for ``xi_rho``
        votes on angles alone.
    theta_xi : float
        diffTheta's threshold (3.5).

    Returns
    -------
    ndarray of int, shape (M, L)
    """
    M_h, L_h, xi_theta, xi_rho, theta_xi = check_votes(M_h, L_h, xi_theta, xi_rho, theta_xi, "vote_matrix")
    V = np.zeros((len(M_h), len(L_h)), int)
    for i, m in enumerate(M_h):
        phi = _differences(m, L_h, theta_xi)  # (5.1)-(5.3)
        psi = _shifted(L_h, phi)  # (5.4): (j, k)
        xi = _comparison(M_h, psi, theta_xi)  # (5.5): (j, k, m)
        close = (np.abs(xi[..., 0]) < xi_rho) & (np.abs(xi[..., 1]) < xi_theta)
        V[i] += close.sum(axis=(1, 2))  # (5.6)
    return V


def vote_matrix_indexed(M_h, L_h, xi_theta: float, xi_rho: float, theta_xi: float = THETA_XI) -> np.ndarray:
    """The vote matrix (5.6) with the map sorted by ``rho``: the same numbers as :func:`vote_matrix`.

    The ``|M| |L|^2`` shifted lines are the queries; each finds the map lines
    within ``xi_rho`` by binary search in the map sorted by ``rho`` and checks
    only those for the angle.  Cost ``O(|M| |L|^2 (log |M| + h))`` with ``h``
    the map lines in a ``rho`` window (few when ``xi_rho`` is small; all of
    them for ``xi_rho = inf``, which is then the dense count again).
    """
    M_h, L_h, xi_theta, xi_rho, theta_xi = check_votes(M_h, L_h, xi_theta, xi_rho, theta_xi, "vote_matrix_indexed")
    return votes_indexed(M_h, L_h, xi_theta, xi_rho, theta_xi)


def votes_indexed(M_h, L_h, xi_theta: float, xi_rho: float, theta_xi: float) -> np.ndarray:
    """:func:`vote_matrix_indexed` of checked arguments."""
    nM, nL = len(M_h), len(L_h)
    V = np.zeros((nM, nL), int)
    if nM == 0 or nL == 0:
        return V
    order = np.argsort(M_h[:, 0], kind="stable")
    rho_sorted = M_h[order, 0]
    theta_sorted = M_h[order, 1]
    block = max(1, 20000 // (nL * nL))
    for i0 in range(0, nM, block):
        rows = np.arange(i0, min(nM, i0 + block))
        # (5.1)-(5.4) for a block of map lines at once: psi[i, j, k] = l_k + (m_i - l_j)
        d_rho = M_h[rows, None, 0] - L_h[None, :, 0]
        d_theta = np.asarray(diff_theta(M_h[rows, None, 1], L_h[None, :, 1], theta_xi), float)
        psi_rho = (L_h[None, None, :, 0] + d_rho[..., None]).ravel()
        psi_theta = np.mod(L_h[None, None, :, 1] + d_theta[..., None], TWO_PI).ravel()
        if np.isfinite(xi_rho):
            pad = 1e-9 * (1.0 + abs(xi_rho))
            lo = np.searchsorted(rho_sorted, psi_rho - xi_rho - pad, side="left")
            hi = np.searchsorted(rho_sorted, psi_rho + xi_rho + pad, side="right")
        else:
            lo = np.zeros(len(psi_rho), int)
            hi = np.full(len(psi_rho), nM)
        counts = hi - lo
        total = int(counts.sum())
        if total == 0:
            continue
        q = np.repeat(np.arange(len(psi_rho)), counts)
        hit = np.repeat(lo - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts) + np.arange(total)
        d_r = rho_sorted[hit] - psi_rho[q]  # (5.5)
        d_t = np.asarray(diff_theta(theta_sorted[hit], psi_theta[q], theta_xi), float)
        ok = (np.abs(d_r) < xi_rho) & (np.abs(d_t) < xi_theta)  # (5.6)
        V[rows] += np.bincount(q[ok] // nL, minlength=len(rows) * nL).reshape(len(rows), nL)
    return V
