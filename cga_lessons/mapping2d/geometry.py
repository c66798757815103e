"""Segments, their geometry and their correspondence for the 2D line map (sections 3.1.2, 3.2; Eqs. 3.3-3.5).

Segments as arrays (:class:`SegmentSet`), their rigid motion (3.4) and Hough
coordinates (3.3) with vectors and matrices (:class:`PlainGeometry`; the
conformal counterpart is :class:`cga_lessons.mapping2d.conformal_geometry.ConformalGeometry`),
the proximity matrix ``M`` and the correspondence vector ``C`` (3.5 and the
guards of 3.19).  The corrections (3.6-3.12) are in
:mod:`cga_lessons.mapping2d.corrections`, the map builder that uses both in
:mod:`cga_lessons.mapping2d.builder`; the public entry point is
:func:`cga_lessons.mapping2d.build_map`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks

from .lines import diff_theta_unchecked
from .params import CorrespondenceParams
from .poses import compose_unchecked
from .segment import TWO_PI, Segment, make_segment

__all__ = ["SegmentSet", "PlainGeometry", "proximity_matrix", "correspondences"]


# --------------------------------------------------------------------------- segment sets as arrays


@dataclass
class SegmentSet:
    """Segments as arrays: start, end (n, 2), point sums (n, 6), edge counts (n, 2) (0: not a real edge).

    The point sums are ``(n, sum x, sum y, sum x^2, sum x y, sum y^2)`` of the
    laser points behind each segment: with them a line can be refitted from
    all the points it gathered, and its centroid and spread are known.
    """

    start: np.ndarray
    end: np.ndarray
    sums: np.ndarray
    edge: np.ndarray

    def __post_init__(self):
        f = "SegmentSet"
        self.start = checks.array(self.start, f, "start", (None, 2))
        self.end = checks.array(self.end, f, "end", (None, 2))
        self.sums = checks.array(self.sums, f, "sums", (None, 6))
        edge = checks.array(self.edge, f, "edge", (None, 2))
        checks.same_length(f, start=self.start, end=self.end, sums=self.sums, edge=edge)
        if np.any(edge < 0) or np.any(edge > 2**53) or np.any(edge != np.round(edge)):
            raise checks.fail(f, "edge", "must hold whole numbers from 0 to 2**53 (how often each end was an edge)")
        self.edge = edge.astype(int)
        with np.errstate(over="ignore", invalid="ignore"):
            length = np.hypot(*(self.end - self.start).T)
        checks.finite_result(np.append(self.sums, length), f, "start, end, sums")
        if np.any(length == 0):
            raise checks.fail(f, "start, end", f"segment {int(np.argmin(length))} has coinciding ends")

    @classmethod
    def trusted(cls, start, end, sums, edge):
        """A set of arrays the caller made (finite, matching, segments of nonzero length), without the checks."""
        s = object.__new__(cls)
        s.start, s.end, s.sums, s.edge = start, end, sums, edge
        return s

    @classmethod
    def empty(cls):
        return cls.trusted(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 6)), np.zeros((0, 2), int))

    @classmethod
    def from_segments(cls, segs):
        """The set of a list of :class:`~cga_lessons.mapping2d.Segment`."""
        if isinstance(segs, (str, bytes)) or not isinstance(segs, (list, tuple)):
            raise checks.fail(
                "SegmentSet.from_segments", "segs", f"expected a list of Segment, got {type(segs).__name__}"
            )
        for s in segs:
            checks.instance(s, "SegmentSet.from_segments", "segs", Segment, "a list of Segment")
        if not segs:
            return cls.empty()
        return cls.trusted(
            np.array([s.start for s in segs]),
            np.array([s.end for s in segs]),
            np.array([s.sums for s in segs]),
            np.array([[s.start_is_edge, s.end_is_edge] for s in segs], int),
        )

    @classmethod
    def concat(cls, sets):
        """One set from several (in order)."""
        sets = list(sets)
        if not sets:
            return cls.empty()
        return cls.trusted(
            np.vstack([s.start for s in sets]),
            np.vstack([s.end for s in sets]),
            np.vstack([s.sums for s in sets]),
            np.vstack([s.edge for s in sets]),
        )

    def __len__(self):
        return len(self.start)

    def take(self, idx):
        return SegmentSet.trusted(self.start[idx], self.end[idx], self.sums[idx], self.edge[idx])

    def to_segments(self):
        return [
            make_segment(s, e, int(round(w[0])), w, bool(f[0] > 0), bool(f[1] > 0))
            for s, e, w, f in zip(self.start, self.end, self.sums, self.edge)
        ]

    @property
    def n_points(self):
        return self.sums[:, 0]

    @property
    def length(self):
        return np.hypot(*(self.end - self.start).T)

    @property
    def centroid(self):
        """Centroid of each segment's points, shape (n, 2)."""
        return self.sums[:, 1:3] / self.sums[:, :1]


def transform_sums(sums, R, t):
    """Point sums ``(n, 6)`` moved by ``x -> R x + t``; ``R`` (2, 2) or (n, 2, 2), ``t`` (2,) or (n, 2).

    The sums are ``(n, sx, sy, sxx, sxy, syy)``; written out component by component (the map builder calls
    this thousands of times on a few dozen rows, where array-building overhead would dominate).
    """
    R = np.asarray(R, float)
    t = np.asarray(t, float)
    r00, r01, r10, r11 = R[..., 0, 0], R[..., 0, 1], R[..., 1, 0], R[..., 1, 1]
    tx, ty = t[..., 0], t[..., 1]
    n, sx, sy, sxx, sxy, syy = sums.T
    ax = r00 * sx + r01 * sy  # R s1
    ay = r10 * sx + r11 * sy
    # R S2 R^T, S2 = [[sxx, sxy], [sxy, syy]]
    m00 = r00 * (r00 * sxx + r01 * sxy) + r01 * (r00 * sxy + r01 * syy)
    m01 = r00 * (r10 * sxx + r11 * sxy) + r01 * (r10 * sxy + r11 * syy)
    m11 = r10 * (r10 * sxx + r11 * sxy) + r11 * (r10 * sxy + r11 * syy)
    out = np.empty_like(sums, dtype=float)
    out[:, 0] = n
    out[:, 1] = ax + n * tx
    out[:, 2] = ay + n * ty
    out[:, 3] = m00 + 2 * ax * tx + n * tx * tx
    out[:, 4] = m01 + ax * ty + tx * ay + n * tx * ty
    out[:, 5] = m11 + 2 * ay * ty + n * ty * ty
    return out


def _rotations(theta):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


# --------------------------------------------------------------------------- the plain geometry


class PlainGeometry:
    """The geometric operations of the map builder with vectors and matrices (section 3.1).

    :class:`cga_lessons.mapping2d.conformal_geometry.ConformalGeometry` offers the same
    operations computed with conformal entities (section 3.2).
    """

    name = "plain"

    def transform(self, segs: SegmentSet, pose) -> SegmentSet:
        """Move segments by the rigid motion of ``pose`` (3.4): ``v' = R v + T`` on the end points."""
        x, y, th = pose
        R = _rotations(th)
        t = np.array([x, y])
        return SegmentSet.trusted(segs.start @ R.T + t, segs.end @ R.T + t, transform_sums(segs.sums, R, t), segs.edge)

    def to_global(self, segs: SegmentSet, pose, mount) -> SegmentSet:
        """Laser-frame segments into the global frame: robot ``pose`` composed with the laser ``mount`` (3.4)."""
        return self.transform(segs, compose_unchecked(pose, mount))

    def to_global_rows(self, segs: SegmentSet, poses, mount) -> SegmentSet:
        """Like :meth:`to_global`, each segment with its own robot pose (``poses`` of shape (n, 3))."""
        lp = compose_unchecked(np.asarray(poses, float), mount)
        R = _rotations(lp[:, 2])
        t = lp[:, :2]
        return SegmentSet.trusted(
            np.einsum("nij,nj->ni", R, segs.start) + t,
            np.einsum("nij,nj->ni", R, segs.end) + t,
            transform_sums(segs.sums, R, t),
            segs.edge,
        )

    def hough(self, segs: SegmentSet, centre):
        """Oriented Hough coordinates ``(rho, theta)`` seen from ``centre`` (3.3), arrays (n,)."""
        dx, dy = (segs.end - segs.start).T
        length = np.hypot(dx, dy)
        nx, ny = dy / length, -dx / length  # the normal: the direction turned by -90 degrees
        cx, cy = np.asarray(centre, float)
        rho = nx * (segs.start[:, 0] - cx) + ny * (segs.start[:, 1] - cy)
        theta = np.mod(np.arctan2(ny, nx), TWO_PI)
        return rho, theta

    def overlap(self, G: SegmentSet, L: SegmentSet, margin):
        """Do the spheres on the segments (enlarged by ``margin``) meet or nest? Cases 1-4 of (3.19), (|G|, |L|)."""
        cg, rg = 0.5 * (G.start + G.end), 0.5 * G.length + margin
        cl, rl = 0.5 * (L.start + L.end), 0.5 * L.length + margin
        dist = np.hypot(cg[:, None, 0] - cl[None, :, 0], cg[:, None, 1] - cl[None, :, 1])
        return dist <= rg[:, None] + rl[None, :]

    def centre_line_distance(self, G: SegmentSet, L: SegmentSet):
        """Distance from the centre of each global segment to each local line (2.130), (|G|, |L|)."""
        cg = 0.5 * (G.start + G.end)
        d = L.end - L.start
        d = d / np.hypot(*d.T)[:, None]
        rel = cg[:, None, :] - L.start[None, :, :]
        return np.abs(rel[..., 0] * d[None, :, 1] - rel[..., 1] * d[None, :, 0])

    def overlap_rows(self, A: SegmentSet, B: SegmentSet, margin):
        """:meth:`overlap` of ``A[i]`` and ``B[i]`` only, shape (n,)."""
        ca, cb = 0.5 * (A.start + A.end), 0.5 * (B.start + B.end)
        return np.hypot(*(ca - cb).T) <= 0.5 * (A.length + B.length) + 2 * margin

    def centre_line_distance_rows(self, A: SegmentSet, B: SegmentSet):
        """Distance from the centre of ``A[i]`` to the line of ``B[i]`` (2.130), shape (n,)."""
        d = B.end - B.start
        d = d / np.hypot(*d.T)[:, None]
        rel = 0.5 * (A.start + A.end) - B.start
        return np.abs(rel[:, 0] * d[:, 1] - rel[:, 1] * d[:, 0])

    def moment_difference(self, G: SegmentSet, L: SegmentSet, centre):
        """``|m_G - m_L|`` of the lines' moments (2.128) about ``centre``, (|G|, |L|).

        A line in the plane with unit direction ``d`` through ``p`` has the
        moment ``(p - c) x d``, whose size is the signed distance ``rho``.
        """
        rg, _ = self.hough(G, centre)
        rl, _ = self.hough(L, centre)
        return np.abs(rg[:, None] - rl[None, :])

    def distance(self, p, q) -> float:
        """Euclidean distance of two points."""
        return float(np.hypot(*(np.asarray(p) - np.asarray(q))))

    def distance_rows(self, P, Q):
        """:meth:`distance` of ``P[i]`` and ``Q[i]``, shape (n,)."""
        D = np.asarray(P, float) - np.asarray(Q, float)
        return np.hypot(D[:, 0], D[:, 1])

    def fuse_ends(self, g_start, g_end, l_start, l_end):
        """End points of the fusion of two corresponding segments (3.20-3.21).

        The longer segment's ends ``p1, p2`` are taken in the shorter's sense
        (swapped when the two run in opposite senses, 3.20-3.21); an end of the
        shorter that lies outside the sphere on ``p_e1 ^ p_e2`` (2.118) replaces
        the corresponding end.

        Returns
        -------
        start, end : ndarray, shape (2,)
            In the shorter segment's sense.
        replaced : list of bool
            Whether each end came from the shorter segment.
        g_longer, same : bool
            Whether the global segment was the longer; whether both run in the same sense.
        """
        lg, ll = np.hypot(*(g_end - g_start)), np.hypot(*(l_end - l_start))
        g_longer = bool(lg >= ll)
        big = (g_start, g_end) if g_longer else (l_start, l_end)
        small = (l_start, l_end) if g_longer else (g_start, g_end)
        same = bool((big[1] - big[0]) @ (small[1] - small[0]) >= 0)
        ends = [big[0], big[1]] if same else [big[1], big[0]]  # (3.20), (3.21)
        centre, radius = 0.5 * (ends[0] + ends[1]), 0.5 * np.hypot(*(ends[1] - ends[0]))
        replaced = [False, False]
        for k, q in enumerate(small):
            if np.hypot(*(q - centre)) > radius:  # outside the sphere (2.118)
                ends[k], replaced[k] = q, True
        return ends[0], ends[1], replaced, g_longer, same


# --------------------------------------------------------------------------- correspondence (3.5, M and C)


def proximity_matrix(G: SegmentSet, L: SegmentSet, centre, geometry=None, theta_xi: float = 0.3):
    """The proximity matrix ``M`` of section 3.1.2, shape (|G|, |L'|).

    ``m_{g,l} = sqrt(diffTheta(theta_G, theta_L')^2 + (rho_G - rho_L')^2)`` with
    oriented Hough coordinates seen from ``centre`` (the robot).  Also returns
    the signed angle differences and the ``rho`` differences (|G|, |L'|).
    """
    f = "proximity_matrix"
    G, L, centre, geometry = _inputs(f, G, L, centre, geometry)
    theta_xi = checks.real(theta_xi, f, "theta_xi", low=0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        out = proximity_unchecked(G, L, centre, geometry, theta_xi)
    return checks.finite_result(out, f, "G, L, centre")


def _inputs(func: str, G, L, centre, geometry):
    """The checked segment sets, centre and geometry of :func:`proximity_matrix` and :func:`correspondences`."""
    G = checks.instance(G, func, "G", SegmentSet, "a SegmentSet (SegmentSet.from_segments(list of Segment))")
    L = checks.instance(L, func, "L", SegmentSet, "a SegmentSet (SegmentSet.from_segments(list of Segment))")
    centre = checks.magnitude(checks.array(centre, func, "centre", (2,)), func, "centre")
    if geometry is None:
        geometry = PlainGeometry()
    what = "a PlainGeometry or a ConformalGeometry (or None)"
    return G, L, centre, checks.instance(geometry, func, "geometry", PlainGeometry, what)


def proximity_unchecked(G: SegmentSet, L: SegmentSet, centre, geometry, theta_xi: float):
    """:func:`proximity_matrix` of checked arguments (the correspondence search's inner loop)."""
    rg, tg = geometry.hough(G, centre)
    rl, tl = geometry.hough(L, centre)
    dth = diff_theta_unchecked(tg[:, None], tl[None, :], theta_xi)
    drho = rg[:, None] - rl[None, :]
    return np.sqrt(dth**2 + drho**2), dth, drho


def correspondences(G: SegmentSet, L: SegmentSet, centre, params=None, geometry=None):
    """The correspondence vector ``C`` of section 3.1.2 (with the guards of 3.19).

    Parameters
    ----------
    G, L : SegmentSet
        The global map and the local map ``L'`` (both in the global frame).
    centre : array_like, shape (2,)
        The robot's position, from which ``rho`` is measured.
    params : CorrespondenceParams, optional
        ``delta``, ``theta_xi``, ``overlap_margin``, ``xi_d`` and ``xi_m`` are used (default: the defaults).
    geometry : PlainGeometry or ConformalGeometry, optional

    Returns
    -------
    C : ndarray of int, shape (|G|,)
        ``C[i] = k`` if global line ``i`` corresponds to local line ``k``, else ``-1``
        (the thesis counts from 1 and writes 0 for none).
    M : ndarray, shape (|G|, |L'|)
    dth : ndarray, shape (|G|, |L'|)
        diffTheta of each pair.

    Conflict rule: when two global lines pick the same local line, the one
    with the smaller angle difference keeps it (then the smaller ``rho``
    difference); the other gets none.
    """
    f = "correspondences"
    G, L, centre, geometry = _inputs(f, G, L, centre, geometry)
    if params is None:
        params = CorrespondenceParams()
    params = checks.instance(params, f, "params", CorrespondenceParams, "a CorrespondenceParams (or None)")
    with np.errstate(over="ignore", invalid="ignore"):
        C, M, dth = correspondences_unchecked(G, L, centre, params, geometry)
    return C, checks.finite_result(M, f, "G, L, centre"), dth


def correspondences_unchecked(G: SegmentSet, L: SegmentSet, centre, params: CorrespondenceParams, geometry):
    """:func:`correspondences` of checked arguments (the map builder's inner loop)."""
    C = np.full(len(G), -1, int)
    if len(G) == 0 or len(L) == 0:
        return C, np.zeros((len(G), len(L))), np.zeros((len(G), len(L)))
    M, dth, drho = proximity_unchecked(G, L, centre, geometry, params.theta_xi)
    ok = M < params.delta
    if ok.any():
        ok &= geometry.overlap(G, L, params.overlap_margin)
        ok &= geometry.centre_line_distance(G, L) < params.xi_d
        ok &= geometry.moment_difference(G, L, centre) < params.xi_m
    Mm = np.where(ok, M, np.inf)
    best = np.argmin(Mm, axis=1)
    has = np.isfinite(Mm[np.arange(len(G)), best])
    C[has] = best[has]
    # conflict rule: a local line goes to one global line only
    taken = np.bincount(C[has], minlength=len(L))
    for k in np.flatnonzero(taken > 1):
        rivals = np.flatnonzero(C == k)
        if len(rivals) > 1:
            key = np.lexsort((np.abs(drho[rivals, k]), np.round(np.abs(dth[rivals, k]), 12)))
            C[rivals[key[1:]]] = -1
    return C, M, dth


def close_angle_pairs(theta, tol):
    """Pairs ``(i, j)`` of angles in [0, 2 pi) closer than ``tol`` across the circle, as two index arrays."""
    n = len(theta)
    order = np.argsort(theta, kind="stable")
    ext = np.concatenate([theta[order], theta[order] + 2 * np.pi])
    hi = np.minimum(np.searchsorted(ext, ext[:n] + tol, side="left"), np.arange(n) + n)
    count = np.maximum(hi - np.arange(n) - 1, 0)
    first = np.repeat(np.arange(n), count)
    offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    second = first + 1 + offset
    return order[first], order[second % n]
