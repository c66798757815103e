"""Line maps with conformal point pairs and motors, the map builder's side (thesis section 3.2, Eq. 3.18-3.21):
:class:`ConformalGeometry` and the five cases of figure 3.5 (:func:`sphere_case`).

:class:`ConformalGeometry` supplies the operations of :class:`~cga_lessons.mapping2d.PlainGeometry` with the
entities of G(4,1): segments as point pairs moved by the laser's motor (3.17) in a sandwich (3.18); correspondence
by the spheres through the point pairs (2.134), which intersect (theorem 2.4.1) or nest (2.118), the five cases of
figure 3.5 (3.19), with the guards ``xi_d`` (2.130) and ``xi_m`` (2.128); fusion (3.20)-(3.21).  The map builder
(``build_map(..., method="conformal")``) then produces the same map and poses as the plain version.  The entities
themselves (E2C, point pairs, motors) are in :mod:`cga_lessons.mapping2d.conformal`.

The point pairs and spheres are built plain (``frame=False``: their coefficients alone, without the local frame
that keeps entities exact far from the origin): the builder works near the origin (``build_map`` takes a multiple
of 1024 m off a log placed far away), where the coefficients hold them, and the frames would cost a third of the
method's time (office scene, 60 scans: 56 ms a scan plain, 76 with the frames).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .conformal import Z_AXIS, c2e, e2c, laser_motor, plane_points, robot_motor
from .geometry import PlainGeometry, SegmentSet, transform_sums
from .lines import diff_theta_unchecked
from .segment import TWO_PI

__all__ = ["sphere_case", "ConformalGeometry"]


def _sandwich(M: Multivector, X: Multivector) -> Multivector:
    """``X' = M X ~M`` (3.18) for a unit motor and a batch of point pairs (grade 2 kept)."""
    return (M * X * ~M).grade(2)


def _pp_from_set(segs: SegmentSet) -> Multivector:
    return cga.point_pair(plane_points(segs.start), plane_points(segs.end), frame=False)


def _ends_2d(PP: Multivector):
    p1, p2 = cga.point_pair_endpoints(PP)  # (2.131)
    return np.atleast_2d(p1)[:, :2], np.atleast_2d(p2)[:, :2]


def _spheres(PP: Multivector, margin: float):
    """Centres (n, 3), radii (n,) and enlarged spheres of point pairs (2.134)."""
    S = cga.point_pair_sphere(PP)  # (2.134)
    c, r = cga.sphere_center_radius(S)
    c = np.atleast_2d(c)
    r = np.atleast_1d(r)
    return c, r, cga.sphere(c, r + margin, frame=False)  # (2.72)


def sphere_case(
    g_start, g_end, l_start, l_end, *, angle_gate: float = 0.3, xi_d: float = 0.3, margin: float = 0.0
) -> int:
    """Which of the five cases of figure 3.5 a global and a local segment are in (3.19).

    The spheres through the two point pairs (2.134) intersect (theorem 2.4.1:
    ``(s_1 ^ s_2)^2 < 0``) or not; if not, one may lie inside the other (the
    centre of the local sphere inside the global one, or the reverse, by
    2.118).  "The same segment" means the same oriented line: angle difference
    (3.5) below ``angle_gate`` and the centre of the global sphere within
    ``xi_d`` of the local line (2.130).

    Returns
    -------
    int
        1 intersect, same segment; 2 nested, same; 3 intersect, not the same;
        4 nested, not the same; 5 apart (and not the same).
    """
    f = "sphere_case"
    ends = {k: v for k, v in (("g_start", g_start), ("g_end", g_end), ("l_start", l_start), ("l_end", l_end))}
    ends = {k: checks.magnitude(checks.array(v, f, k, (2,)), f, k) for k, v in ends.items()}
    angle_gate = checks.real(angle_gate, f, "angle_gate", low=0.0)
    xi_d = checks.real(xi_d, f, "xi_d", low=0.0)
    margin = checks.real(margin, f, "margin", low=0.0, high=checks.MAX_MAGNITUDE)
    for a, b in (("g_start", "g_end"), ("l_start", "l_end")):
        if np.array_equal(ends[a], ends[b]):
            raise checks.degenerate(f, f"{a}, {b}", "the segment's ends coincide")
    PPg = cga.point_pair(plane_points(ends["g_start"]), plane_points(ends["g_end"]), frame=False)
    PPl = cga.point_pair(plane_points(ends["l_start"]), plane_points(ends["l_end"]), frame=False)
    cg, _, Sg = _spheres(PPg, margin)
    cl, _, Sl = _spheres(PPl, margin)
    wedge2 = float(np.squeeze(((Sg ^ Sl) * (Sg ^ Sl)).scalar()))
    intersect = wedge2 <= 0.0  # theorem 2.4.1 (tangent counts as touching)
    nested = (not intersect) and (
        np.squeeze(cga.point_sphere_side(cl[0], Sg)) > 0 or np.squeeze(cga.point_sphere_side(cg[0], Sl)) > 0
    )
    rg = np.asarray(cga.line_direction(PPg ^ cga.einf), float)
    rl = np.asarray(cga.line_direction(PPl ^ cga.einf), float)
    tg = np.mod(np.arctan2(-rg[0], rg[1]), TWO_PI)
    tl = np.mod(np.arctan2(-rl[0], rl[1]), TWO_PI)
    same = (
        abs(diff_theta_unchecked(tg, tl, angle_gate)) < angle_gate
        and cga.point_line_distance(cg[0], PPl ^ cga.einf) < xi_d
    )
    if intersect:
        return 1 if same else 3
    if nested:
        return 2 if same else 4
    return 5


class ConformalGeometry(PlainGeometry):
    """The map builder's geometric operations with conformal entities (section 3.2).

    Every operation the map builder needs is computed here from point pairs,
    lines, spheres and motors of G(4,1); the bookkeeping (the correspondence
    vector, the weighted means, the refit from point sums) is shared with
    :class:`~cga_lessons.mapping2d.PlainGeometry`.
    """

    name = "conformal"

    def __init__(self):
        self._cache = {}

    def _cached(self, kind, segs: SegmentSet, extra, make):
        """Reuse an entity built from the same segment arrays within one correspondence pass."""
        key = (kind, id(segs.start), id(segs.end), extra)
        hit = self._cache.get(key)
        if hit is not None and hit[0] is segs.start and hit[1] is segs.end:
            return hit[2]
        if len(self._cache) > 64:
            self._cache.clear()
        value = make()
        self._cache[key] = (segs.start, segs.end, value)
        return value

    def _pp(self, segs: SegmentSet) -> Multivector:
        return self._cached("pp", segs, None, lambda: _pp_from_set(segs))

    def to_global(self, segs: SegmentSet, pose, mount) -> SegmentSet:
        """Point pairs moved by the laser motor (3.17) with the sandwich (3.18), ends by (2.131)."""
        if len(segs) == 0:
            return segs
        M = laser_motor(pose, mount)
        PP = _sandwich(M, _pp_from_set(segs))  # (3.18)
        p1, p2 = _ends_2d(PP)
        H = np.asarray(cga.motor_to_matrix(M))  # the point sums follow the same rigid motion
        return SegmentSet.trusted(p1, p2, transform_sums(segs.sums, H[:2, :2], H[:2, 3]), segs.edge)

    def transform(self, segs: SegmentSet, pose) -> SegmentSet:
        return self.to_global(segs, pose, (0.0, 0.0, 0.0))

    def to_global_rows(self, segs: SegmentSet, poses, mount) -> SegmentSet:
        """Each segment moved by its own laser motor (3.17), all in one batch of sandwiches (3.18).

        The point sums follow the rigid motion read off the motor's action on
        the points E2C(0, 0) and E2C(1, 0) (3.13).
        """
        if len(segs) == 0:
            return segs
        poses = np.asarray(poses, float).reshape(-1, 3)
        n = len(poses)
        # (3.16)-(3.17): the robot motors of the poses times the laser's on the robot
        M = cga.translator(plane_points(poses[:, :2])) * cga.rotor(Z_AXIS, poses[:, 2]) * robot_motor(mount)
        p1, p2 = _ends_2d(_sandwich(M, _pp_from_set(segs)))  # (3.18), (2.131)
        o = c2e(M * e2c(np.zeros((n, 2))) * ~M)
        ex = c2e(M * e2c(np.tile([1.0, 0.0], (n, 1))) * ~M) - o
        R = np.stack([np.stack([ex[:, 0], -ex[:, 1]], -1), np.stack([ex[:, 1], ex[:, 0]], -1)], -2)
        return SegmentSet.trusted(p1, p2, transform_sums(segs.sums, R, o), segs.edge)

    def _lines_about(self, segs: SegmentSet, centre):
        """Lines ``L* = PP* ^ e`` of the segments, moved so that ``centre`` is the origin (a translator)."""
        c = tuple(np.asarray(centre, float).tolist())

        def make():
            T = cga.translator(-plane_points(np.asarray(c)))
            return _sandwich(T, self._pp(segs)) ^ cga.einf

        return self._cached("lines", segs, c, make)

    def hough(self, segs: SegmentSet, centre):
        """Oriented ``(rho, theta)`` from ``centre``: (3.14) for rho, (3.15) closest point, (2.127) direction."""
        if len(segs) == 0:
            return np.zeros(0), np.zeros(0)
        L = self._lines_about(segs, centre)
        r = np.atleast_2d(cga.line_direction(L))[:, :2]  # (2.127)
        p = np.atleast_2d(cga.line_closest_point(L))[:, :2]  # (3.15)
        rho = np.atleast_1d(cga.point_line_distance(np.zeros(3), L))  # (3.14)
        n = np.column_stack([r[:, 1], -r[:, 0]])  # the scan runs counter-clockwise: normal on the right
        sign = np.sign(np.einsum("ij,ij->i", n, p))
        return sign * rho, np.mod(np.arctan2(n[:, 1], n[:, 0]), TWO_PI)

    def overlap(self, G: SegmentSet, L: SegmentSet, margin):
        """Cases 1-2 (or 3-4) of (3.19): the enlarged spheres (2.134) intersect (theorem 2.4.1) or nest (2.118)."""
        out = np.zeros((len(G), len(L)), bool)
        if len(G) == 0 or len(L) == 0:
            return out
        cg, _, Sg = self._cached("spheres", G, margin, lambda: _spheres(self._pp(G), margin))
        cl, _, Sl = self._cached("spheres", L, margin, lambda: _spheres(self._pp(L), margin))
        for k in range(len(L)):
            s = Sl.batch_item(k)
            w = np.atleast_1d(((Sg ^ s) * (Sg ^ s)).scalar())  # theorem 2.4.1
            inside = (np.atleast_1d(cga.point_sphere_side(cl[k], Sg)) > 0) | (
                np.atleast_1d(cga.point_sphere_side(cg, s)) > 0
            )  # (2.118)
            out[:, k] = (w <= 0.0) | inside
        return out

    def centre_line_distance(self, G: SegmentSet, L: SegmentSet):
        """Distance from the centre of each global sphere to each local line, (2.130), shape (|G|, |L|)."""
        out = np.zeros((len(G), len(L)))
        if len(G) == 0 or len(L) == 0:
            return out
        cg, _, _ = self._cached("spheres", G, 0.0, lambda: _spheres(self._pp(G), 0.0))
        lines = self._pp(L) ^ cga.einf
        for k in range(len(L)):
            out[:, k] = np.atleast_1d(cga.point_line_distance(cg, lines.batch_item(k)))
        return out

    def overlap_rows(self, A: SegmentSet, B: SegmentSet, margin):
        """Cases 1-4 of (3.19) for the pairs ``A[i]``, ``B[i]``: theorem 2.4.1 and (2.118), shape (n,)."""
        if len(A) == 0:
            return np.zeros(0, bool)
        ca, _, Sa = _spheres(_pp_from_set(A), margin)
        cb, _, Sb = _spheres(_pp_from_set(B), margin)
        w = np.atleast_1d(((Sa ^ Sb) * (Sa ^ Sb)).scalar())
        inside = (np.atleast_1d(cga.point_sphere_side(cb, Sa)) > 0) | (np.atleast_1d(cga.point_sphere_side(ca, Sb)) > 0)
        return (w <= 0.0) | inside

    def centre_line_distance_rows(self, A: SegmentSet, B: SegmentSet):
        """Distance from the centre of the sphere of ``A[i]`` to the line of ``B[i]`` (2.130), shape (n,)."""
        if len(A) == 0:
            return np.zeros(0)
        ca, _, _ = _spheres(_pp_from_set(A), 0.0)
        return np.atleast_1d(cga.point_line_distance(ca, _pp_from_set(B) ^ cga.einf))

    def moment_difference(self, G: SegmentSet, L: SegmentSet, centre):
        """``|m_G - m_L|`` of the line moments (2.128) about ``centre``, shape (|G|, |L|)."""
        if len(G) == 0 or len(L) == 0:
            return np.zeros((len(G), len(L)))
        mg = np.atleast_2d(cga.line_moment(self._lines_about(G, centre)))
        ml = np.atleast_2d(cga.line_moment(self._lines_about(L, centre)))
        return np.linalg.norm(mg[:, None, :] - ml[None, :, :], axis=-1)

    def distance(self, p, q) -> float:
        """Distance of two points from the inner product of their conformal points: ``-2 X . Y = |x - y|^2``."""
        d2 = -2.0 * float((e2c(p) | e2c(q)).scalar())
        return float(np.sqrt(max(d2, 0.0)))

    def distance_rows(self, P, Q):
        """:meth:`distance` of ``P[i]`` and ``Q[i]`` (each from its conformal points), shape (n,)."""
        return np.array([self.distance(p, q) for p, q in zip(P, Q)], float).reshape(-1)

    def fuse_ends(self, g_start, g_end, l_start, l_end):
        """End points of the fusion of two point pairs, Eqs. (3.20)-(3.21).

        Lengths from (2.125), directions from (2.127), ends from (2.131), the
        sphere of ``pp_e = p_e1 ^ p_e2`` from (2.134) and the side of each end
        of the shorter pair from (2.118).
        """
        PPg = cga.point_pair(plane_points(g_start), plane_points(g_end), frame=False)
        PPl = cga.point_pair(plane_points(l_start), plane_points(l_end), frame=False)
        Lg, Ll = PPg ^ cga.einf, PPl ^ cga.einf
        len_g = float((Lg * Lg).scalar())  # (2.125): the squared length (up to the sign convention of L*^2)
        len_l = float((Ll * Ll).scalar())
        g_longer = bool(abs(len_g) >= abs(len_l))
        big, small = (PPg, PPl) if g_longer else (PPl, PPg)
        Lb, Ls = (Lg, Ll) if g_longer else (Ll, Lg)
        same = bool(np.dot(cga.line_direction(Lb), cga.line_direction(Ls)) >= 0)  # (2.127)
        p1, p2 = cga.point_pair_endpoints(big)  # (2.131)
        pe = [p1, p2] if same else [p2, p1]  # (3.20), (3.21)
        S = cga.point_pair_sphere(cga.point_pair(pe[0], pe[1], frame=False))  # (2.134)
        q = cga.point_pair_endpoints(small)
        replaced = [False, False]
        for k in range(2):
            if cga.point_sphere_side(q[k], S) < 0:  # outside (2.118)
                pe[k], replaced[k] = q[k], True
        return np.asarray(pe[0], float)[:2], np.asarray(pe[1], float)[:2], replaced, g_longer, same
