"""Chapter 5 as printed, steps 6-10: correspondences from the votes, rotor, least squares, translator.

After the vote matrix ``V`` (5.6, :mod:`cga_lessons.relocalization.hough`):

6. the correspondence vector ``C`` from the column maxima of ``V``
   (:func:`correspondences_from_votes`);
7. the mean angle ``Theta`` of the corresponding lines by diffTheta (3.5)
   (:func:`mean_angle`);
8. a rotor (2.96) by ``Theta`` applied to the local point pairs
   (:func:`rotate_entities`);
9. the translation from the closest points of the corresponding lines by the
   least squares (3.12) (:func:`translation_from_lines`);
10. a translator (2.100) applied to them (:func:`translate_entities`).

:func:`thesis_relocalization` runs steps 1-10.  The pose it finds is the
laser's pose in the map, ``x -> R(Theta) x + t``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, GeometryError
from cga_lessons.mapping2d import TWO_PI, diff_theta, theta_correction, translation_correction

from .hough import THETA_XI, check_votes, endpoint_array, hough_points, votes_indexed

__all__ = [
    "correspondences_from_votes",
    "mean_angle",
    "segments_from_point_pairs",
    "rotate_entities",
    "translation_from_lines",
    "translate_entities",
    "thesis_relocalization",
    "ThesisRelocalization",
]


@dataclass(frozen=True)
class ThesisRelocalization:
    """What :func:`thesis_relocalization` finds by steps 1-10 of section 5.2.

    Attributes
    ----------
    votes : ndarray of int, shape (M, L)
        The vote matrix ``V`` (5.6).
    C : ndarray of int, shape (M,)
        The correspondence vector of step 6 (``-1``: none).
    M_h, L_h : ndarray, shape (M, 2) and (L, 2)
        The Hough sets ``(rho, theta)`` of the map and of the local map (figure 5.1).
    pose : ndarray, shape (3,) or None
        The laser's pose ``(x, y, Theta)`` in the map (steps 7 and 9); None when no correspondence was found.
    rotated, placed : ndarray, shape (L, 2, 2) or None
        The local segments after the rotor (step 8) and after the translator too (step 10); None without
        ``entities`` or without a pose.
    Theta : float or None
        The mean angle of step 7 (3.8), None without a pose.
    translation : ndarray, shape (2,) or None
        The least-squares translation of step 9 (3.12), None without a pose.
    """

    votes: np.ndarray
    C: np.ndarray
    M_h: np.ndarray
    L_h: np.ndarray
    pose: np.ndarray | None = None
    rotated: np.ndarray | None = None
    placed: np.ndarray | None = None
    Theta: float | None = None
    translation: np.ndarray | None = None

    def __post_init__(self):
        f = "ThesisRelocalization"
        n_map = len(checks.array(self.M_h, f, "M_h", (None, 2)))
        n_scan = len(checks.array(self.L_h, f, "L_h", (None, 2)))
        votes = checks.array(self.votes, f, "votes", (None, None))
        if votes.shape != (n_map, n_scan):
            raise checks.fail(f, "votes", f"expected shape ({n_map}, {n_scan}) (M_h's lines, L_h's), got {votes.shape}")
        if np.any(votes < 0) or np.any(votes != np.round(votes)):
            raise checks.fail(f, "votes", "must be whole numbers >= 0")
        C = checks.array(self.C, f, "C", (None,))
        if len(C) != n_map:
            raise checks.fail(f, "C", f"expected one entry per line of M_h ({n_map}), got {len(C)}")
        if np.any(C < -1) or np.any(C >= n_scan) or np.any(C != np.round(C)):
            raise checks.fail(f, "C", f"must be indices of scan lines (0 to {n_scan - 1}) or -1")
        for name in ("votes", "C", "M_h", "L_h"):  # checked, kept as given (the votes and C stay integers)
            object.__setattr__(self, name, np.asarray(getattr(self, name)))
        if (self.pose is None) != (self.Theta is None) or (self.pose is None) != (self.translation is None):
            raise checks.fail(f, "pose, Theta, translation", "give all three (a pose found) or none")
        if self.pose is not None:
            object.__setattr__(self, "pose", checks.array(self.pose, f, "pose", (3,)))
            object.__setattr__(self, "Theta", checks.real(self.Theta, f, "Theta"))
            object.__setattr__(self, "translation", checks.array(self.translation, f, "translation", (2,)))
        for name in ("rotated", "placed"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, checks.array(getattr(self, name), f, name, (n_scan, 2, 2)))


def correspondences_from_votes(V, min_votes: int = 2) -> np.ndarray:
    """The correspondence vector ``C`` of step 6 from the column maxima of ``V``.

    For every local line (column) the map line (row) with most votes is its
    correspondence; ``C`` has one entry per map line, the index of its local
    line or ``-1`` (the thesis's "null").  When several columns pick the same
    row the one with more votes keeps it (then the first).  A column whose
    maximum is below ``min_votes`` gets no correspondence: every entry is at
    least 1 (each hypothesis votes for itself), so 1 means no support.

    Parameters
    ----------
    V : array_like of int, shape (M, L)
    min_votes : int

    Returns
    -------
    ndarray of int, shape (M,)

    >>> correspondences_from_votes([[1, 5], [3, 1], [1, 1]]).tolist()
    [1, 0, -1]
    """
    func = "correspondences_from_votes"
    V = checks.array(V, func, "V", (None, None))
    return correspondences(V, checks.integer(min_votes, func, "min_votes", low=0))


def correspondences(V: np.ndarray, min_votes: int) -> np.ndarray:
    """:func:`correspondences_from_votes` of a checked vote matrix."""
    C = np.full(V.shape[0], -1, int)
    if V.size == 0:
        return C
    rows = np.argmax(V, axis=0)
    best = V[rows, np.arange(V.shape[1])]
    for j in np.argsort(-best, kind="stable"):
        if best[j] >= min_votes and C[rows[j]] < 0:
            C[rows[j]] = j
    return C


def mean_angle(M_h, L_h, C, theta_xi: float = THETA_XI) -> float:
    """``Theta``: the mean angle difference of the corresponding lines by diffTheta (3.5), step 7.

    ``Theta = mean_i diffTheta(m_i theta, l_C[i] theta)`` (the mean of 3.8).
    """
    M_h = np.asarray(M_h, float).reshape(-1, 2)
    L_h = np.asarray(L_h, float).reshape(-1, 2)
    i = np.flatnonzero(np.asarray(C) >= 0)
    if len(i) == 0:
        raise checks.fail("mean_angle", "C", "holds no correspondence")
    d = np.atleast_1d(diff_theta(M_h[i, 1], L_h[np.asarray(C)[i], 1], theta_xi))
    return theta_correction(d)


def _xyz(p):
    p = np.asarray(p, float)
    return np.concatenate([p, np.zeros(p.shape[:-1] + (1,))], axis=-1)


def segments_from_point_pairs(PP) -> np.ndarray:
    """End points (K, 2, 2) of a batch of point pairs in the z = 0 plane, by (2.131)."""
    p1, p2 = cga.point_pair_endpoints(PP)
    return np.stack([np.atleast_2d(p1)[:, :2], np.atleast_2d(p2)[:, :2]], axis=1)


def _move_point_pairs(V, s, func, name):
    """``V PP* ~V`` for the point pairs of segments ``s`` (K, 2, 2), end points read back by (2.131).

    (2.131) loses accuracy when the points are far from the origin compared
    with their separation (``DESIGN.md``); a wildly wrong pose can put them
    there.  Then the same versor moves the two conformal points that span the
    pair (``V (P1 ^ P2) ~V = (V P1 ~V) ^ (V P2 ~V)``), which is exact.
    """
    try:
        PP = cga.point_pair(_xyz(s[:, 0]), _xyz(s[:, 1]))  # (2.68)
        try:
            out = segments_from_point_pairs(cga.apply(V, PP))
        except DegenerateGeometryError:
            out = cga.apply_to_points(V, _xyz(s.reshape(-1, 2)))[:, :2].reshape(-1, 2, 2)
    except GeometryError as exc:  # finite, but too large for the conformal model's squares
        raise checks.fail(func, name, f"cannot be moved as point pairs ({exc})") from None
    return checks.finite_result(out, func, f"{name}: the result")


def rotate_entities(segments, angle) -> np.ndarray:
    """Step 8: the rotor (2.96) of ``angle`` about ``e3`` applied to the local point pairs.

    Each segment becomes its point pair ``PP* = E2C(p_i) ^ E2C(p_f)`` (2.68,
    3.13), is turned by ``R PP* ~R`` and read back by (2.131).

    Returns
    -------
    ndarray, shape (K, 2, 2)
    """
    s = endpoint_array(segments, "rotate_entities")
    return rotated(s, checks.real(angle, "rotate_entities", "angle"), "rotate_entities", "segments")


def rotated(s: np.ndarray, angle: float, func: str, name: str) -> np.ndarray:
    """:func:`rotate_entities` of checked segments, in the name of ``func`` and its argument ``name``."""
    if len(s) == 0:
        return s.copy()
    R = cga.rotor([0.0, 0.0, 1.0], angle)  # (2.96)
    return _move_point_pairs(R, s, func, name)


def translate_entities(segments, translation) -> np.ndarray:
    """Step 10: the translator (2.100) of ``translation`` applied to the local point pairs.

    Returns
    -------
    ndarray, shape (K, 2, 2)
    """
    s = endpoint_array(segments, "translate_entities")
    t = checks.array(translation, "translate_entities", "translation", (2,))
    return translated(s, t, "translate_entities", "segments, translation")


def translated(s: np.ndarray, t: np.ndarray, func: str, name: str) -> np.ndarray:
    """:func:`translate_entities` of checked segments and translation (2,), in the name of ``func``."""
    if len(s) == 0:
        return s.copy()
    T = cga.translator([t[0], t[1], 0.0])  # (2.100)
    return _move_point_pairs(T, s, func, name)


def translation_from_lines(M_h, L_h_rotated, C) -> np.ndarray:
    """Step 9: the translation from the closest points of corresponding lines, least squares (3.12).

    Each pair gives ``rho_G = (p_L'c + t) . (cos theta_L', sin theta_L')``
    (3.11); :func:`cga_lessons.mapping2d.translation_correction` solves them
    in the least-squares sense (3.12).  With one correspondence, or parallel
    lines only, the component along the lines stays 0.
    """
    M_h = np.asarray(M_h, float).reshape(-1, 2)
    L_h_rotated = np.asarray(L_h_rotated, float).reshape(-1, 2)
    i = np.flatnonzero(np.asarray(C) >= 0)
    if len(i) == 0:
        raise checks.fail("translation_from_lines", "C", "holds no correspondence")
    j = np.asarray(C)[i]
    return translation_correction(M_h[i, 0], L_h_rotated[j, 0], L_h_rotated[j, 1])


def thesis_relocalization(
    map_segments,
    scan_segments,
    *,
    xi_theta: float = np.radians(3.0),
    xi_rho: float = 0.2,
    theta_xi: float = THETA_XI,
    min_votes: int = 2,
    entities: bool = True,
) -> ThesisRelocalization:
    """Steps 1-10 of section 5.2 as printed: votes, correspondences, rotor, least squares, translator.

    Parameters
    ----------
    map_segments : array_like, shape (M, 2, 2)
        The map ``M`` in the map frame.
    scan_segments : array_like, shape (L, 2, 2)
        The local map ``L`` in the laser frame.
    xi_theta, xi_rho : float
        Vote thresholds of (5.6) (the thesis gives no values).
    theta_xi : float
        diffTheta's threshold (3.5).
    min_votes : int
        See :func:`correspondences_from_votes`.
    entities : bool
        Move the local point pairs with the rotor and the translator (steps 8
        and 10).  Without them only the pose is computed: a rotation about
        the origin keeps ``rho`` and adds ``Theta`` to ``theta``, which is all
        step 9 needs (the same numbers, faster).

    Returns
    -------
    ThesisRelocalization
        ``votes`` (M, L), ``C`` (M,), ``pose`` ``(x, y, Theta)`` or None when
        no correspondence was found, ``rotated`` and ``placed`` local segments
        (L, 2, 2) after steps 8 and 10 (None without ``entities``), ``M_h`` and ``L_h``.
    """
    func = "thesis_relocalization"
    M = endpoint_array(map_segments, func, "map_segments")
    L = endpoint_array(scan_segments, func, "scan_segments")
    M_h, L_h = hough_points(M, func=func, name="map_segments"), hough_points(L, func=func, name="scan_segments")
    checks.finite_result(M_h, func, "map_segments: the Hough set")
    checks.finite_result(L_h, func, "scan_segments: the Hough set")
    M_h, L_h, xi_theta, xi_rho, theta_xi = check_votes(M_h, L_h, xi_theta, xi_rho, theta_xi, func)
    min_votes = checks.integer(min_votes, func, "min_votes", low=0)
    entities = checks.flag(entities, func, "entities")
    V = votes_indexed(M_h, L_h, xi_theta, xi_rho, theta_xi)  # steps 1-5, (5.1)-(5.6)
    C = correspondences(V, min_votes)  # step 6
    if not np.any(C >= 0):
        return ThesisRelocalization(votes=V, C=C, M_h=M_h, L_h=L_h)
    Theta = mean_angle(M_h, L_h, C, theta_xi)  # step 7
    if entities:
        turned = rotated(L, Theta, func, "scan_segments")  # step 8
        t = translation_from_lines(M_h, hough_points(turned, func=func, name="scan_segments"), C)  # step 9, (3.12)
        checks.finite_result(t, func, "map_segments, scan_segments: the translation")
        placed = translated(turned, t, func, "scan_segments")  # step 10
    else:
        turned = placed = None
        t = translation_from_lines(M_h, np.column_stack([L_h[:, 0], np.mod(L_h[:, 1] + Theta, TWO_PI)]), C)
        checks.finite_result(t, func, "map_segments, scan_segments: the translation")
    theta = float(np.mod(Theta + np.pi, TWO_PI) - np.pi)
    pose = np.array([t[0], t[1], theta])
    return ThesisRelocalization(
        votes=V, C=C, M_h=M_h, L_h=L_h, pose=pose, rotated=turned, placed=placed, Theta=Theta, translation=t
    )
