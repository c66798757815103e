"""Line maps from laser scans and odometry (thesis sections 3.1.2-3.1.4, Eqs. 3.4-3.12).

For every scan, :func:`build_map`

1. predicts the robot pose by applying the odometry *increment* to the last
   corrected pose (never the raw absolute odometry, which has drifted);
2. extracts the scan's segments (:func:`cga_lessons.lines.extract_segments`)
   and moves them into the global frame with the predicted pose (3.4): the
   local map ``L'``;
3. builds the proximity matrix ``M`` of the global map ``G`` against ``L'`` in
   Hough space, ``m = sqrt(diffTheta(theta_G, theta_L')^2 + (rho_G - rho_L')^2)``,
   and the correspondence vector ``C`` (``m < delta``, each local line given to
   at most one global line by the thesis's conflict rule);
4. corrects the heading by the mean angle difference (3.6, 3.8), recomputes
   the correspondences, corrects the position by one correspondence (3.9) or
   least squares over all (3.7, 3.10-3.12), bounded by ``T_xi``, and repeats;
5. fuses ``L'`` into ``G`` (matched lines merged, new lines ``N`` added) and
   finally removes duplicates.

What makes it work in practice (measured, see ``DESIGN.md``): ``rho`` is measured
from the robot's predicted position rather than the world origin (a small
heading error far from the origin would move ``rho`` a lot); lines are oriented
(a scan runs counter-clockwise, so the robot is on a line's left), which
identifies ``(rho, theta)`` with ``(-rho, theta + pi)`` and keeps the two faces
of a thin wall apart; corrections are weighted by each line's information
(angle: points x length^2; offset: points, less for a short face seen far off
to the side); every map line is refitted from all the points it has gathered;
where the matched lines leave a direction unobservable (all parallel, as in a
corridor) the segment ends that are real edges fix it, and otherwise that
direction is left to odometry.  Beyond the thesis, each correction is checked
against the whole scan (the lesson of chapter 5): of the corrected pose, the
heading correction alone and the prediction, the one that puts most of the
scan's points on the map is kept.  Real logs need it: a wall with a kink or
clutter can match a map line at a wrong angle.

The correspondence test is the same for this plain version and the conformal
one (:mod:`cga_lessons.mapping2d_conformal`, section 3.2): besides ``m <
delta`` a pair must overlap (the spheres on the two segments intersect or one
contains the other, cases 1-2 of 3.19, with a margin), the centre of the
global segment must lie within ``xi_d`` of the local line (2.130) and their
moments (2.128, taken about the robot) may differ by at most ``xi_m``.  Here
these are computed with vectors, there with conformal entities; both give the
same map and poses.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .algebra import InvalidInputError
from .laser import compose, relative, scan_points, wrap_angle
from .lines import TWO_PI, Segment, diff_theta, extract_segments, line_from_sums

__all__ = [
    "MapParams",
    "MapResult",
    "build_map",
    "proximity_matrix",
    "correspondences",
    "theta_correction",
    "translation_correction",
    "pose_errors",
    "map_errors",
    "map_point_errors",
    "PlainGeometry",
]


# --------------------------------------------------------------------------- parameters and result


@dataclass(frozen=True)
class MapParams:
    """Every threshold of the map builder, with the thesis's meaning.

    Attributes
    ----------
    delta : float
        ``delta``: largest proximity ``m = sqrt(diffTheta^2 + drho^2)`` (mixed
        radians and metres, as in the thesis) for two lines to correspond.
    theta_xi : float
        ``theta_xi`` of diffTheta (3.5): differences smaller than this are taken
        across the 0 / 2 pi cut the short way.  The thesis uses 2 pi / 100; it
        is set to cover ``delta`` so no candidate pair is compared the long way.
    xi_d : float
        ``xi_d``: largest distance (m) from the centre of a global segment to
        the local line (2.130), which keeps near-by thin objects apart.
    xi_m : float
        ``xi_m``: largest difference (m) of the two lines' moments (2.128) about
        the robot.
    overlap_margin : float
        The segments' spheres (2.134) are enlarged by this (m) before the
        intersection test (a continuation across a small gap still matches).
    t_xi : float
        ``T_xi``: bound (m) on each component of a position correction (3.12).
    theta_max : float
        Bound (radians) on a heading correction (3.8).
    n_iterations : int
        Rounds of correspondence, heading and position correction per scan.
    range_noise : float
        Standard deviation (m) of the laser's range noise; with the point count
        and length of a segment it gives the variance of its angle and offset.
    angle_floor, offset_floor : float
        Model error added to every line's angle (radians) and offset (m)
        standard deviation: real walls are not perfectly straight.
    weak_ratio : float
        A direction whose information is below this fraction of the largest is
        undetermined by the lines (parallel walls): matching real edges fix it,
        or else the odometry is kept there.
    edge_match : float
        Two segment ends that are real edges correspond if this close (m).
    dup_angle, dup_distance : float
        Final check: map lines closer than these (radians, m) that overlap are
        duplicates and are merged.
    cleanup_every : int
        Run the duplicate removal every so many scans (and at the end).
    support_distance : float
        The corrected pose, the heading correction alone and the prediction
        are compared by how many of the scan's points they put within this
        distance (m) of the map's segments; the best is kept (0 disables the
        check).
    neighbourhood : float
        Only map segments within this distance (m) of the robot are matched.
    """

    delta: float = 0.3
    theta_xi: float = 0.3
    xi_d: float = 0.3
    xi_m: float = 0.25
    overlap_margin: float = 0.3
    t_xi: float = 0.3
    theta_max: float = 0.2
    n_iterations: int = 3
    range_noise: float = 0.01
    angle_floor: float = 0.0
    offset_floor: float = 0.0
    weak_ratio: float = 0.02
    edge_match: float = 0.3
    dup_angle: float = 0.05
    dup_distance: float = 0.08
    cleanup_every: int = 25
    support_distance: float = 0.05
    neighbourhood: float = 8.0


@dataclass
class MapResult:
    """The result of :func:`build_map`.

    Attributes
    ----------
    segments : list of Segment
        The global line map (start and end as 2-vectors in the global frame).
    poses : ndarray, shape (T, 3)
        Corrected robot pose of every scan.
    predicted : ndarray, shape (T, 3)
        The pose predicted from the previous corrected pose and the odometry
        increment, before correction.
    n_matches : ndarray of int, shape (T,)
        Correspondences used for the last correction of each scan.
    corrected : ndarray of bool, shape (T,)
        False where no correction was possible (no segments or no
        correspondence): the pose is then the prediction.
    method : str
    history : list
        If requested, the number of map segments after each scan.
    """

    segments: list
    poses: np.ndarray
    predicted: np.ndarray
    n_matches: np.ndarray
    corrected: np.ndarray
    method: str = "plain"
    history: list = field(default_factory=list)


# --------------------------------------------------------------------------- segment sets as arrays


@dataclass
class SegmentSet:
    """Segments as arrays: start, end (n, 2), point sums (n, 6), edge counts (n, 2) (0: not a real edge)."""

    start: np.ndarray
    end: np.ndarray
    sums: np.ndarray
    edge: np.ndarray

    @classmethod
    def empty(cls):
        return cls(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 6)), np.zeros((0, 2), int))

    @classmethod
    def from_segments(cls, segs):
        if not segs:
            return cls.empty()
        return cls(
            np.array([s.start for s in segs]),
            np.array([s.end for s in segs]),
            np.array([s.sums for s in segs]),
            np.array([[s.start_is_edge, s.end_is_edge] for s in segs], int),
        )

    def __len__(self):
        return len(self.start)

    def take(self, idx):
        return SegmentSet(self.start[idx], self.end[idx], self.sums[idx], self.edge[idx])

    def to_segments(self):
        return [
            Segment(s, e, int(round(w[0])), w, bool(f[0] > 0), bool(f[1] > 0))
            for s, e, w, f in zip(self.start, self.end, self.sums, self.edge)
        ]

    @property
    def n_points(self):
        return self.sums[:, 0]

    @property
    def length(self):
        return np.hypot(*(self.end - self.start).T)


def _transform_sums(sums, R, t):
    n = sums[:, 0]
    s1 = sums[:, 1:3]
    s2 = np.stack([np.stack([sums[:, 3], sums[:, 4]], -1), np.stack([sums[:, 4], sums[:, 5]], -1)], -2)
    rs1 = s1 @ R.T
    s1n = rs1 + n[:, None] * t
    s2n = (
        np.einsum("ij,njk,lk->nil", R, s2, R)
        + rs1[:, :, None] * t[None, None, :]
        + t[None, :, None] * rs1[:, None, :]
        + n[:, None, None] * np.outer(t, t)[None]
    )
    return np.column_stack([n, s1n, s2n[:, 0, 0], s2n[:, 0, 1], s2n[:, 1, 1]])


# --------------------------------------------------------------------------- the plain geometry


class PlainGeometry:
    """The geometric operations of the map builder with vectors and matrices (section 3.1).

    :class:`cga_lessons.mapping2d_conformal.ConformalGeometry` offers the same
    operations computed with conformal entities (section 3.2).
    """

    name = "plain"

    def transform(self, segs: SegmentSet, pose) -> SegmentSet:
        """Move segments by the rigid motion of ``pose`` (3.4): ``v' = R v + T`` on the end points."""
        x, y, th = pose
        c, s = np.cos(th), np.sin(th)
        R = np.array([[c, -s], [s, c]])
        t = np.array([x, y])
        return SegmentSet(segs.start @ R.T + t, segs.end @ R.T + t, _transform_sums(segs.sums, R, t), segs.edge)

    def to_global(self, segs: SegmentSet, pose, mount) -> SegmentSet:
        """Laser-frame segments into the global frame: robot ``pose`` composed with the laser ``mount`` (3.4)."""
        return self.transform(segs, compose(pose, mount))

    def hough(self, segs: SegmentSet, centre):
        """Oriented Hough coordinates ``(rho, theta)`` seen from ``centre`` (3.3), arrays (n,)."""
        d = segs.end - segs.start
        d = d / np.hypot(*d.T)[:, None]
        n = np.column_stack([d[:, 1], -d[:, 0]])
        rho = np.einsum("ij,ij->i", n, segs.start - np.asarray(centre, float))
        theta = np.mod(np.arctan2(n[:, 1], n[:, 0]), TWO_PI)
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
    the signed angle differences (|G|, |L'|).
    """
    geometry = geometry or PlainGeometry()
    rg, tg = geometry.hough(G, centre)
    rl, tl = geometry.hough(L, centre)
    dth = diff_theta(tg[:, None], tl[None, :], theta_xi)
    drho = rg[:, None] - rl[None, :]
    return np.sqrt(dth**2 + drho**2), dth, drho


def correspondences(G: SegmentSet, L: SegmentSet, centre, params: MapParams, geometry=None):
    """The correspondence vector ``C`` of section 3.1.2 (with the guards of 3.19).

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
    geometry = geometry or PlainGeometry()
    C = np.full(len(G), -1, int)
    if len(G) == 0 or len(L) == 0:
        return C, np.zeros((len(G), len(L))), np.zeros((len(G), len(L)))
    M, dth, drho = proximity_matrix(G, L, centre, geometry, params.theta_xi)
    ok = M < params.delta
    ok &= geometry.overlap(G, L, params.overlap_margin)
    ok &= geometry.centre_line_distance(G, L) < params.xi_d
    ok &= geometry.moment_difference(G, L, centre) < params.xi_m
    Mm = np.where(ok, M, np.inf)
    best = np.argmin(Mm, axis=1)
    has = np.isfinite(Mm[np.arange(len(G)), best])
    C[has] = best[has]
    # conflict rule: a local line goes to one global line only
    for k in np.unique(C[C >= 0]):
        rivals = np.flatnonzero(C == k)
        if len(rivals) > 1:
            key = np.lexsort((np.abs(drho[rivals, k]), np.round(np.abs(dth[rivals, k]), 12)))
            C[rivals[key[1:]]] = -1
    return C, M, dth


# --------------------------------------------------------------------------- corrections (3.6-3.12)


def theta_correction(dth, weights=None) -> float:
    """Heading correction ``theta_corr`` (3.8): the (weighted) mean of diffTheta over the correspondences.

    .. math:: \\theta_{corr} = \\frac{1}{n} \\sum_{i=1}^n \\mathrm{diffTheta}(\\theta_{G_i}, \\theta_{L'_i})

    Parameters
    ----------
    dth : array_like, shape (n,)
        ``diffTheta(theta_G_i, theta_L'_i)`` for each correspondence.
    weights : array_like, shape (n,), optional
        The thesis takes the plain mean (all 1); the map builder weights each
        pair by the inverse variance of its angle difference.

    >>> theta_correction([0.01, 0.03])
    0.02
    """
    dth = np.asarray(dth, float)
    if dth.size == 0:
        raise InvalidInputError("theta_correction: no correspondences")
    w = np.ones_like(dth) if weights is None else np.asarray(weights, float)
    return float(np.sum(w * dth) / np.sum(w))


def translation_correction(rho_g, rho_l, theta_l, weights=None, weak_ratio: float = 0.0, along=None):
    """Position correction ``T_corr`` from corresponding lines (3.9-3.12).

    Each correspondence gives the constraint (3.11)
    ``rho_G - ((p_L'c + t) . (cos theta_L', sin theta_L')) = 0``, i.e.
    ``n_i . t = rho_G_i - rho_L'_i``, and ``t`` minimises the (weighted) sum of
    squares (3.12).  With one correspondence, or lines all parallel, only the
    component along their normal is determined: it is the displacement
    between the two lines' closest points (3.9); the other component is then
    taken from ``along`` if given, else zero (the odometry is kept).

    Parameters
    ----------
    rho_g, rho_l, theta_l : array_like, shape (m,)
        Hough coordinates of the global lines and of the local lines after the
        heading correction (all seen from the same point).
    weights : array_like, shape (m,), optional
        Inverse variances of ``rho_G - rho_L'`` (default all 1).
    weak_ratio : float
        A direction whose information is below this fraction of the largest
        counts as undetermined (0: only an exactly singular one).
    along : tuple (offsets (k, 2), weights (k,)), optional
        Displacements (global - local) between matching real edges; their
        weighted mean fixes the undetermined direction.

    Returns
    -------
    ndarray, shape (2,)

    >>> translation_correction([1.0, 2.0], [0.9, 2.3], [0.0, np.pi / 2]).round(12).tolist()
    [0.1, -0.3]
    >>> translation_correction([1.0], [0.9], [np.pi / 2]).round(12).tolist()  # one line: (3.9)
    [0.0, 0.1]
    """
    rho_g, rho_l, theta_l = (np.atleast_1d(np.asarray(v, float)) for v in (rho_g, rho_l, theta_l))
    if rho_g.size == 0:
        raise InvalidInputError("translation_correction: no correspondences")
    w = np.ones_like(rho_g) if weights is None else np.asarray(weights, float)
    n = np.column_stack([np.cos(theta_l), np.sin(theta_l)])
    b = rho_g - rho_l
    A = (n * w[:, None]).T @ n
    rhs = (n * w[:, None]).T @ b
    vals, vecs = np.linalg.eigh(A)
    if vals[0] > max(weak_ratio * vals[1], 1e-12 * vals[1]):
        return np.linalg.solve(A, rhs)
    strong, weak = vecs[:, 1], vecs[:, 0]
    t = strong * (strong @ rhs) / vals[1]
    if along is not None and len(along[0]):
        off, ew = np.asarray(along[0], float).reshape(-1, 2), np.asarray(along[1], float)
        t = t + weak * float(np.sum(ew * (off @ weak)) / np.sum(ew))
    return t


# --------------------------------------------------------------------------- the map builder


def _line_variances(segs: SegmentSet, centre, params: MapParams):
    """Variances of a fitted line's angle (rad^2) and of its offset ``rho`` seen from ``centre`` (m^2).

    A line fitted to ``n`` points with range noise ``sigma`` spread over length
    ``L`` has angle variance ``12 sigma^2 / (n L^2)`` and offset variance
    ``sigma^2 / n`` at its centre, which grows as ``sigma^2 (1 + 12 s^2 / L^2) / n``
    at the foot of the perpendicular from ``centre``, ``s`` along the line from
    the centre: a short face seen far off to the side says little about its
    ``rho``.  The floors model walls that are not perfectly straight.
    """
    n = segs.n_points
    L = np.maximum(segs.length, 1e-3)
    d = (segs.end - segs.start) / L[:, None]
    s = np.einsum("ij,ij->i", np.asarray(centre, float) - 0.5 * (segs.start + segs.end), d)
    var_t = 12.0 * params.range_noise**2 / (n * L**2) + params.angle_floor**2
    var_r = params.range_noise**2 / n + s**2 * var_t + params.offset_floor**2
    return var_t, var_r


class _Builder:
    def __init__(self, geometry, params: MapParams):
        self.geo = geometry
        self.p = params
        self.G = SegmentSet.empty()

    def near(self, centre):
        """Indices of map segments within the neighbourhood of the robot."""
        G = self.G
        if len(G) == 0:
            return np.zeros(0, int)
        v = G.end - G.start
        t = np.clip(np.einsum("ij,ij->i", centre - G.start, v) / np.einsum("ij,ij->i", v, v), 0, 1)
        dist = np.hypot(*(G.start + t[:, None] * v - centre).T)
        return np.flatnonzero(dist < self.p.neighbourhood)

    def match(self, Gn, Lw, centre):
        C, M, dth = correspondences(Gn, Lw, centre, self.p, self.geo)
        gi = np.flatnonzero(C >= 0)
        return gi, C[gi], dth[gi, C[gi]] if len(gi) else np.zeros(0)

    def support(self, points, pose, mount, idx):
        """How many scan points (laser frame) lie within ``support_distance`` of a map segment."""
        if len(points) == 0 or len(idx) == 0:
            return 0
        lp = compose(pose, mount)
        c, s_ = np.cos(lp[2]), np.sin(lp[2])
        q = points @ np.array([[c, s_], [-s_, c]]) + lp[:2]
        a, v = self.G.start[idx], self.G.end[idx] - self.G.start[idx]
        rel = q[:, None, :] - a[None]
        t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.einsum("wi,wi->w", v, v), 0.0, 1.0)
        d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1)).min(axis=1)
        return int(np.sum(d < self.p.support_distance))

    def correct(self, L, pose, mount, points=None):
        """Iterative heading and position correction of one scan (3.6-3.12).

        When ``points`` (the scan's points, laser frame) are given, the result
        is checked against the whole scan: of the corrected pose, the heading
        correction alone and the prediction, the one that puts most points on
        the map's segments is kept.
        """
        p = self.p
        predicted = pose.copy()
        idx = self.near(pose[:2])
        Gn = self.G.take(idx)
        n_used, corrected = 0, False
        for _ in range(p.n_iterations):
            Lw = self.geo.to_global(L, pose, mount)
            gi, li, dth = self.match(Gn, Lw, pose[:2])
            if len(gi) == 0:
                break
            # heading (3.8): weighted by the inverse variance of each angle difference
            vt_l, _ = _line_variances(Lw.take(li), pose[:2], p)
            vt_g, _ = _line_variances(Gn.take(gi), pose[:2], p)
            th = float(np.clip(theta_correction(dth, 1.0 / (vt_l + vt_g)), -p.theta_max, p.theta_max))
            pose = np.array([pose[0], pose[1], wrap_angle(pose[2] + th)])  # (3.6)
            # recompute the correspondences with the corrected heading, then the position (3.9-3.12)
            Lw = self.geo.to_global(L, pose, mount)
            gi, li, _ = self.match(Gn, Lw, pose[:2])
            if len(gi) == 0:
                break
            rg, _ = self.geo.hough(Gn.take(gi), pose[:2])
            rl, tl = self.geo.hough(Lw.take(li), pose[:2])
            _, vr_l = _line_variances(Lw.take(li), pose[:2], p)
            _, vr_g = _line_variances(Gn.take(gi), pose[:2], p)
            t = translation_correction(rg, rl, tl, 1.0 / (vr_l + vr_g), p.weak_ratio, self.edge_offsets(Gn, Lw, gi, li))
            t = np.clip(t, -p.t_xi, p.t_xi)  # bounded by T_xi
            pose = np.array([pose[0] + t[0], pose[1] + t[1], pose[2]])  # (3.7)
            n_used, corrected = len(gi), True
            if abs(th) < 1e-9 and np.hypot(*t) < 1e-7:
                break
        if corrected and points is not None and p.support_distance > 0:
            near = self.near(predicted[:2])
            heading_only = np.array([predicted[0], predicted[1], pose[2]])
            scores = [self.support(points, q, mount, near) for q in (pose, heading_only, predicted)]
            best = int(np.argmax(scores))  # the first of equals: the full correction
            if best == 1:
                return heading_only, n_used, True
            if best == 2:
                return predicted, 0, False
        return pose, n_used, corrected

    def edge_offsets(self, Gn, Lw, gi, li):
        """Displacements (global - local) between corresponding ends that are both real edges."""
        offs = []
        for g, k in zip(gi, li):
            same = (Gn.end[g] - Gn.start[g]) @ (Lw.end[k] - Lw.start[k]) >= 0
            gends = (Gn.start[g], Gn.end[g]) if same else (Gn.end[g], Gn.start[g])
            gflags = Gn.edge[g] if same else Gn.edge[g][::-1]
            for e, (lp, lf) in enumerate(((Lw.start[k], Lw.edge[k, 0]), (Lw.end[k], Lw.edge[k, 1]))):
                if lf and gflags[e] and self.geo.distance(gends[e], lp) < self.p.edge_match:
                    offs.append(gends[e] - lp)
        return np.array(offs).reshape(-1, 2), np.ones(len(offs))

    def fuse(self, Lw, centre):
        """Fuse the local map into the global map (section 3.1.4 / 3.2.4)."""
        idx = self.near(centre)
        Gn = self.G.take(idx)
        C, _, _ = correspondences(Gn, Lw, centre, self.p, self.geo)
        G = self.G
        for gi_local in np.flatnonzero(C >= 0):
            g, k = idx[gi_local], C[gi_local]
            self._merge_into(G, g, Lw.start[k], Lw.end[k], Lw.sums[k], Lw.edge[k])
        new = np.setdiff1d(np.arange(len(Lw)), C[C >= 0])
        if len(new):
            add = Lw.take(new)
            self.G = SegmentSet(
                np.vstack([G.start, add.start]),
                np.vstack([G.end, add.end]),
                np.vstack([G.sums, add.sums]),
                np.vstack([G.edge, add.edge]),
            )

    def _merge_into(self, G, g, ls, le, lsums, ledge):
        """Fuse one segment into map line ``g`` (sections 3.1.4, 3.2.4).

        The ends follow (3.20)-(3.21): the longer segment's ends, pushed out by
        any end of the shorter outside its sphere (2.118).  Ends that are real
        edges take precedence: an edge seen again is averaged with the map's
        (so the map's edge is not the most extreme of its noisy sightings), a
        map edge is not pushed out by an end that is not an edge, and an edge
        seen near a map end that was not one replaces it.  The line is
        refitted from all the points gathered.
        """
        geo = self.geo
        s, e, replaced, g_longer, same = geo.fuse_ends(G.start[g], G.end[g], ls, le)
        if (e - s) @ (G.end[g] - G.start[g]) < 0:  # back to the global segment's sense
            s, e = e, s
        union = [s, e]
        gends, gcount = [G.start[g], G.end[g]], G.edge[g]
        ledge = np.asarray(ledge)
        lends, lcount = ([ls, le], ledge) if same else ([le, ls], ledge[::-1])
        ends, counts = [None, None], np.zeros(2, int)
        for k in range(2):
            close = geo.distance(gends[k], lends[k]) < self.p.edge_match
            if gcount[k] and lcount[k] and close:
                n = gcount[k] + lcount[k]
                ends[k], counts[k] = (gcount[k] * gends[k] + lcount[k] * lends[k]) / n, n
            elif gcount[k]:
                ends[k], counts[k] = gends[k], gcount[k]
            elif lcount[k] and close:
                ends[k], counts[k] = lends[k], lcount[k]
            else:
                ends[k], counts[k] = union[k], 0
        sums = G.sums[g] + lsums
        c, d = line_from_sums(sums, ends[1] - ends[0])
        G.start[g] = c + d * ((ends[0] - c) @ d)
        G.end[g] = c + d * ((ends[1] - c) @ d)
        G.sums[g] = sums
        G.edge[g] = counts

    def remove_duplicates(self):
        """Final check: merge map lines that are the same line seen twice (section 3.1.4).

        Two map segments are duplicates when their oriented angles differ by
        less than ``dup_angle``, their spheres meet or nest, and the centre of
        the shorter lies within ``dup_distance`` of the longer's line.  Longer
        segments absorb shorter ones; repeated until nothing changes.
        """
        p = self.p
        while len(self.G) > 1:
            G = self.G
            _, th0 = self.geo.hough(G, np.zeros(2))
            close = np.abs(diff_theta(th0[:, None], th0[None, :], p.theta_xi)) < p.dup_angle
            np.fill_diagonal(close, False)
            sub = np.flatnonzero(close.any(axis=1))
            if len(sub) == 0:
                break
            S = G.take(sub)
            dup = close[np.ix_(sub, sub)] & self.geo.overlap(S, S, 0.0)
            dup &= self.geo.centre_line_distance(S, S).T < p.dup_distance  # [a, b]: centre of b to the line of a
            alive = np.ones(len(G), bool)
            changed = False
            for ia in np.argsort(-S.length, kind="stable"):
                a = sub[ia]
                if not alive[a]:
                    continue
                for ib in np.flatnonzero(dup[ia]):
                    b = sub[ib]
                    if alive[b] and S.length[ib] <= S.length[ia]:
                        self._merge_into(G, a, G.start[b], G.end[b], G.sums[b], G.edge[b])
                        alive[b] = False
                        changed = True
            self.G = G.take(np.flatnonzero(alive))
            if not changed:
                break


def build_map(
    scans,
    odometry,
    method: str = "plain",
    *,
    params: MapParams | None = None,
    mount=(0.0, 0.0, 0.0),
    max_range: float = 5.0,
    extraction: dict | None = None,
    record_history: bool = False,
    **overrides,
) -> MapResult:
    """Build a global line map and correct the robot's poses (sections 3.1.2-3.1.4 and 3.2).

    Parameters
    ----------
    scans : sequence of (ranges, angles)
        One scan per pose: arrays of shape (n,), radians in the laser frame,
        ``inf`` (or NaN) for no return.
    odometry : array_like, shape (T, 3)
        Odometry poses ``(x, y, theta)``; only their increments are used, from
        the first pose (the map's origin).
    method : {"plain", "conformal"}
        Vectors and matrices (3.1) or conformal point pairs and motors (3.2).
    params : MapParams, optional
        The thresholds; keyword ``overrides`` replace single fields.
    mount : array_like, shape (3,)
        Pose of the laser on the robot (the laser-robot motor 3.16).
    max_range : float
        Readings at or beyond this (m) are dropped (the thesis's laser: 5 m).
    extraction : dict, optional
        Keyword arguments for :func:`cga_lessons.lines.extract_segments`.
    record_history : bool
        Keep the map size after every scan in ``MapResult.history``.

    Returns
    -------
    MapResult

    Raises
    ------
    InvalidInputError
        If the inputs disagree in length or shape, or a parameter is unknown.
    """
    odometry = np.asarray(odometry, float)
    if odometry.ndim != 2 or odometry.shape[1] != 3 or not np.all(np.isfinite(odometry)):
        raise InvalidInputError(f"build_map: odometry must be a finite (T, 3) array, got shape {odometry.shape}")
    scans = list(scans)
    if len(scans) != len(odometry) or len(scans) == 0:
        raise InvalidInputError(f"build_map: {len(scans)} scans but {len(odometry)} odometry poses")
    params = params or MapParams()
    bad = set(overrides) - set(MapParams.__dataclass_fields__)
    if bad:
        raise InvalidInputError(f"build_map: unknown parameter(s) {sorted(bad)}")
    if overrides:
        params = MapParams(**{**params.__dict__, **overrides})
    if method == "plain":
        geometry = PlainGeometry()
    elif method == "conformal":
        from .mapping2d_conformal import ConformalGeometry

        geometry = ConformalGeometry()
    else:
        raise InvalidInputError(f"build_map: method must be 'plain' or 'conformal', got {method!r}")
    mount = np.asarray(mount, float).reshape(3)
    ext = {"max_range": max_range, **(extraction or {})}

    b = _Builder(geometry, params)
    T = len(scans)
    poses = np.zeros((T, 3))
    predicted = np.zeros((T, 3))
    n_matches = np.zeros(T, int)
    corrected = np.zeros(T, bool)
    history = []
    for k, (ranges, angles) in enumerate(scans):
        if k == 0:
            pose = odometry[0].copy()
        else:
            pose = compose(poses[k - 1], relative(odometry[k - 1], odometry[k]))  # odometry increment
        predicted[k] = pose
        L = SegmentSet.from_segments(extract_segments(ranges, angles, **ext))
        if k > 0 and len(L) and len(b.G):
            pts, _ = scan_points(np.where(np.asarray(ranges, float) < max_range, ranges, np.inf), angles)
            pose, n_matches[k], corrected[k] = b.correct(L, pose, mount, pts)
        poses[k] = pose
        if len(L):
            Lw = geometry.to_global(L, pose, mount)
            b.fuse(Lw, pose[:2])
        if params.cleanup_every and (k + 1) % params.cleanup_every == 0:
            b.remove_duplicates()
        if record_history:
            history.append(len(b.G))
    b.remove_duplicates()
    return MapResult(b.G.to_segments(), poses, predicted, n_matches, corrected, geometry.name, history)


# --------------------------------------------------------------------------- evaluation


def pose_errors(poses, truth):
    """Root-mean-square position (m) and heading (radians) error of a trajectory.

    Parameters
    ----------
    poses, truth : array_like, shape (T, 3)

    Returns
    -------
    (float, float)
    """
    p, t = np.asarray(poses, float), np.asarray(truth, float)
    if p.shape != t.shape or p.ndim != 2 or p.shape[1] != 3:
        raise InvalidInputError(f"pose_errors: shapes {p.shape} and {t.shape} must be equal (T, 3)")
    pos = np.sqrt(np.mean(np.sum((p[:, :2] - t[:, :2]) ** 2, axis=1)))
    head = np.sqrt(np.mean(wrap_angle(p[:, 2] - t[:, 2]) ** 2))
    return float(pos), float(head)


def map_errors(segments, walls):
    """Distance (m) of every segment end point to the nearest true wall.

    Parameters
    ----------
    segments : list of Segment
    walls : array_like, shape (W, 2, 2)

    Returns
    -------
    ndarray, shape (2 * len(segments),)
    """
    walls = np.asarray(walls, float).reshape(-1, 2, 2)
    if not segments:
        return np.zeros(0)
    pts = np.array([p for s in segments for p in (s.start, s.end)])
    a, v = walls[:, 0], walls[:, 1] - walls[:, 0]
    rel = pts[:, None, :] - a[None]
    t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.maximum(np.einsum("wi,wi->w", v, v), 1e-300), 0, 1)
    d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1))
    return d.min(axis=1)


def map_point_errors(segments, points):
    """Distance (m) of every segment end point to the nearest reference point (e.g. a log's scans at the true poses).

    Parameters
    ----------
    segments : list of Segment
    points : array_like, shape (k, 2)

    Returns
    -------
    ndarray, shape (2 * len(segments),)
    """
    ref = np.asarray(points, float).reshape(-1, 2)
    if not segments or len(ref) == 0:
        return np.zeros(0)
    ends = np.array([p for s in segments for p in (s.start, s.end)])
    out = np.empty(len(ends))
    for i in range(0, len(ends), 256):
        blk = ends[i : i + 256]
        out[i : i + 256] = np.sqrt(((blk[:, None, :] - ref[None]) ** 2).sum(-1)).min(axis=1)
    return out
