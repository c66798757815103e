"""The incremental line-map builder behind :func:`cga_lessons.mapping2d.build_map` (sections 3.1.2-3.1.4).

:class:`MapBuilder` keeps the global map ``G`` (a :class:`SegmentSet`) and,
for every map line, which scans saw it (its *observations*: the local segment
and the scan it came from).  For each scan it

* corrects the predicted pose against the map lines seen recently near the
  robot (:meth:`MapBuilder.correct`): the thesis's correspondences ``C``
  (3.5, 3.19), each pair gated by its innovation, and the heading and
  position corrections (3.8, 3.12) solved together with the odometry's
  prediction as one more measurement
  (:func:`~cga_lessons.mapping2d_corrections.pose_correction`), repeated with
  fresh correspondences; the pairs that disagree with the consensus fall out
  at the gate; the result is checked against the whole scan;
* fuses the local map into ``G`` (:meth:`MapBuilder.fuse`, 3.20-3.21) and
  records the observations;
* on request refits every map line from its observations at new poses
  (:meth:`MapBuilder.refit`, after a loop closure) and merges duplicates
  (:meth:`MapBuilder.remove_duplicates`).
"""

from __future__ import annotations

import numpy as np

from .lines import line_from_sums
from .mapping2d_correction import ScanCorrector
from .mapping2d_geometry import SegmentSet, _close_angle_pairs, _compose, correspondences

__all__ = ["MapBuilder"]


class MapBuilder:
    """Global line map with its observations, correction of poses against it, fusion (sections 3.1.2-3.1.4).

    Parameters
    ----------
    geometry : PlainGeometry or ConformalGeometry
    params : MapParams
    mount : ndarray, shape (3,)
        Laser pose on the robot.
    max_range : float
        The laser's reach (m): how far old lines are looked for when closing loops.
    """

    def __init__(self, geometry, params, mount=(0.0, 0.0, 0.0), max_range=np.inf):
        self.geo = geometry
        self.p = params
        self.mount = np.asarray(mount, float).reshape(3)
        self.max_range = float(max_range)
        self.G = SegmentSet.empty()
        self.gid = np.zeros(0, int)  # a stable id per map line
        self.last = np.zeros(0, int)  # the last scan that saw it
        self._next_id = 0
        self._root = np.zeros(0, int)  # line id -> id of the line it now belongs to (after merges)
        self._obs = []  # per scan: its local segments (laser frame)
        self._obs_scan = np.zeros(0, int)  # per observation: the scan ...
        self._obs_id = np.zeros(0, int)  # ... and the id of the line it was fused into
        self.path = []  # distance travelled up to each scan (m)
        self.corrector = ScanCorrector(geometry, params, self.mount)

    # ------------------------------------------------------------------ map queries

    def resolve(self, ids):
        """Current ids of lines, following merges."""
        return self._root[np.asarray(ids, int)]

    def observers(self, lines):
        """How many of the map lines ``lines`` (indices) each scan observed, shape (scans,)."""
        mine = np.isin(self._root[self._obs_id], self.gid[lines])
        return np.bincount(self._obs_scan[mine], minlength=len(self._obs))

    def segment_distance(self, centre, idx=None):
        """Distance (m) from ``centre`` to each map segment (or to those in ``idx``)."""
        G = self.G if idx is None else self.G.take(idx)
        if len(G) == 0:
            return np.zeros(0)
        v = G.end - G.start
        t = np.clip(np.einsum("ij,ij->i", centre - G.start, v) / np.einsum("ij,ij->i", v, v), 0, 1)
        return np.hypot(*(G.start + t[:, None] * v - centre).T)

    def active(self, k):
        """Mask of the map lines seen within the last ``active_path`` metres of travel before scan ``k``."""
        if self.p.active_path <= 0 or len(self.path) == 0:
            return np.ones(len(self.G), bool)
        path = np.asarray(self.path)
        return path[min(k, len(path) - 1)] - path[self.last] <= self.p.active_path

    def near(self, centre, k=None, radius=None, active=True):
        """Indices of map lines within ``radius`` (default ``neighbourhood``) of ``centre``.

        With ``k`` given, only the lines active at scan ``k`` (``active=True``)
        or only the others (``active=False``).
        """
        if len(self.G) == 0:
            return np.zeros(0, int)
        radius = self.p.neighbourhood if radius is None else radius
        ok = self.segment_distance(np.asarray(centre, float)) < radius
        if k is not None:
            ok &= self.active(k) if active else ~self.active(k)
        return np.flatnonzero(ok)

    def support(self, points, pose, idx):
        """How well the scan's points (laser frame) at ``pose`` lie on the map segments ``idx``.

        Each point within ``D = support_distance`` of a segment counts
        ``1 - (d / D)^2`` (``d`` its distance): a point on the line counts one,
        the score falls smoothly to zero at ``D``, so of two poses the better
        aligned scores higher even when both put every point within ``D``.
        """
        if len(points) == 0 or len(idx) == 0:
            return 0.0
        lp = _compose(pose, self.mount)
        c, s_ = np.cos(lp[2]), np.sin(lp[2])
        q = points @ np.array([[c, s_], [-s_, c]]) + lp[:2]
        a, v = self.G.start[idx], self.G.end[idx] - self.G.start[idx]
        rel = q[:, None, :] - a[None]
        t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.einsum("wi,wi->w", v, v), 0.0, 1.0)
        d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1)).min(axis=1)
        return float(np.sum(np.maximum(0.0, 1.0 - (d / self.p.support_distance) ** 2)))

    # ------------------------------------------------------------------ correction (3.6-3.12)

    def correct(self, L, pose, prior_cov, idx, points=None, widen=True, test=True, step=None):
        """Correct one scan's predicted pose against the map lines ``idx`` (3.6-3.12).

        The registration is :meth:`ScanCorrector.register
        <cga_lessons.mapping2d_correction.ScanCorrector.register>`.  With
        ``test`` (and ``step = (carried, step_cov)``, the prediction's
        covariance split into the part carried from the last pose and the
        odometry step's model covariance) the correction is applied only if
        :meth:`~cga_lessons.mapping2d_correction.ScanCorrector.decide` admits
        it and, when ``points`` (the scan's points, laser frame) are given, if
        the prediction does not put them on the map clearly better
        (:meth:`support`, by more than 1 % of the points).  Without ``test``
        the refined pose is returned as it is (a revisit's hypothesis is
        refined, not tested against its start).

        Returns
        -------
        pose : ndarray, shape (3,)
        cov : ndarray, shape (3, 3)
            Its covariance (the prediction's if the correction was not applied).
        pairs : tuple (map line indices, local indices) or None
            The correspondences of the last round; None if no line was matched.
        applied : bool
        """
        predicted = np.array(pose, float)
        gate_cov = None if step is None else step[0] + max(self.corrector.odometry_scale, 1.0) * step[1]
        reg = self.corrector.register(self.G.take(idx), L, predicted, prior_cov, widen, gate_cov)
        if reg is None:
            return predicted, np.asarray(prior_cov, float), None, False
        pairs = (idx[reg.gi], reg.li)
        if not test:
            return reg.pose, reg.cov, pairs, True
        carried, step_cov = step if step is not None else (np.asarray(prior_cov, float), np.zeros((3, 3)))
        new, cov, applied = self.corrector.decide(reg, predicted, carried, step_cov)
        if applied and points is not None and self.p.support_distance > 0:
            margin = 0.01 * len(points)  # refused only if clearly worse than the prediction
            if self.support(points, predicted, idx) > self.support(points, new, idx) + margin:
                return predicted, np.asarray(prior_cov, float), pairs, False
        return new, cov, pairs, applied

    # ------------------------------------------------------------------ fusion (3.1.4, 3.20-3.21)

    def add_lines(self, segs: SegmentSet, k):
        """Append segments (global frame) to the map as new lines last seen at scan ``k``; returns their ids."""
        ids = np.arange(self._next_id, self._next_id + len(segs))
        self._next_id += len(segs)
        self._root = np.concatenate([self._root, ids])
        self.G = SegmentSet.concat([self.G, segs])
        self.gid = np.concatenate([self.gid, ids])
        self.last = np.concatenate([self.last, np.full(len(segs), k, int)])
        return ids

    def fuse(self, L, pose, k):
        """Fuse scan ``k``'s local map into the global map (section 3.1.4 / 3.2.4) and record its observations.

        The correspondences at the corrected ``pose`` among the active lines
        near the robot are merged (3.20-3.21); local lines without a partner
        become new map lines.
        """
        Lw = self.geo.to_global(L, pose, self.mount)
        idx = self.near(pose[:2], k)
        C, _, _ = correspondences(self.G.take(idx), Lw, pose[:2], self.p, self.geo)
        gl = np.flatnonzero(C >= 0)
        pairs = (idx[gl], C[gl])
        ids = np.full(len(L), -1, int)
        for g, j in zip(*pairs):
            self._merge_into(g, Lw.start[j], Lw.end[j], Lw.sums[j], Lw.edge[j])
            self.last[g] = k
            ids[j] = self.gid[g]
        new = np.flatnonzero(ids < 0)
        if len(new):
            ids[new] = self.add_lines(Lw.take(new), k)
        self._obs.append(L)
        self._obs_scan = np.concatenate([self._obs_scan, np.full(len(L), k, int)])
        self._obs_id = np.concatenate([self._obs_id, ids])

    def _merge_into(self, g, ls, le, lsums, ledge):
        """Fuse one segment into map line ``g`` (sections 3.1.4, 3.2.4).

        The ends follow (3.20)-(3.21): the longer segment's ends, pushed out by
        any end of the shorter outside its sphere (2.118).  Ends that are real
        edges take precedence: an edge seen again is averaged with the map's
        (so the map's edge is not the most extreme of its noisy sightings), a
        map edge is not pushed out by an end that is not an edge, and an edge
        seen near a map end that was not one replaces it.  The line is
        refitted from all the points gathered.
        """
        G, geo = self.G, self.geo
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
        less than ``dup_angle``, their spheres meet or nest (3.19), and the
        centre of the shorter lies within ``dup_distance`` of the longer's line
        (2.130).  Longer segments absorb shorter ones; repeated until nothing
        changes.
        """
        p = self.p
        while len(self.G) > 1:
            G = self.G
            _, th = self.geo.hough(G, np.zeros(2))
            a, b = _close_angle_pairs(th, p.dup_angle)
            length = G.length
            swap = (length[b] > length[a]) | ((length[b] == length[a]) & (b < a))
            a, b = np.where(swap, b, a), np.where(swap, a, b)  # a: the longer
            A, B = G.take(a), G.take(b)
            dup = self.geo.overlap_rows(A, B, 0.0) & (self.geo.centre_line_distance_rows(B, A) < p.dup_distance)
            a, b = a[dup], b[dup]
            if len(a) == 0:
                break
            alive = np.ones(len(G), bool)
            for i in np.lexsort((b, a, -length[a])):
                if alive[a[i]] and alive[b[i]]:
                    self._merge_into(a[i], G.start[b[i]], G.end[b[i]], G.sums[b[i]], G.edge[b[i]])
                    self.last[a[i]] = max(self.last[a[i]], self.last[b[i]])
                    self._root[self._root == self.gid[b[i]]] = self.gid[a[i]]
                    alive[b[i]] = False
            keep = np.flatnonzero(alive)
            self.G, self.gid, self.last = G.take(keep), self.gid[keep], self.last[keep]

    # ------------------------------------------------------------------ refit from the observations

    def observations(self):
        """All observations: (local segments (m rows, laser frame), scan index (m,), current line id (m,))."""
        return SegmentSet.concat(self._obs), self._obs_scan, self.resolve(self._obs_id)

    def refit(self, poses):
        """Rebuild every map line from its observations placed with ``poses`` (T, 3).

        The sums of all the points a line gathered give its least-squares line;
        its ends are the outermost ends of its observations along it, except
        where observations saw a real edge: then the mean of the edge
        sightings near the outermost one (section 3.1.4's fusion, done at once).
        """
        L, scan, ids = self.observations()
        if len(L) == 0 or len(self.G) == 0:
            return
        W = self.geo.to_global_rows(L, np.asarray(poses, float)[scan], self.mount)
        order = np.argsort(self.gid)
        row = order[np.searchsorted(self.gid, ids, sorter=order)]
        n = len(self.G)
        sums = np.zeros((n, 6))
        np.add.at(sums, row, W.sums)
        c = sums[:, 1:3] / sums[:, :1]
        sxx = sums[:, 3] - sums[:, 0] * c[:, 0] ** 2
        sxy = sums[:, 4] - sums[:, 0] * c[:, 0] * c[:, 1]
        syy = sums[:, 5] - sums[:, 0] * c[:, 1] ** 2
        ang = 0.5 * np.arctan2(2 * sxy, sxx - syy)
        d = np.column_stack([np.cos(ang), np.sin(ang)])
        flip = np.einsum("ij,ij->i", d, self.G.end - self.G.start) < 0
        d[flip] *= -1
        same = np.einsum("ij,ij->i", W.end - W.start, d[row]) >= 0
        ps = np.einsum("ij,ij->i", W.start - c[row], d[row])
        pe = np.einsum("ij,ij->i", W.end - c[row], d[row])
        lo, hi = np.where(same, ps, pe), np.where(same, pe, ps)
        e_lo = np.where(same, W.edge[:, 0], W.edge[:, 1]) > 0
        e_hi = np.where(same, W.edge[:, 1], W.edge[:, 0]) > 0
        ends = np.zeros((n, 2))
        counts = np.zeros((n, 2), int)
        for side, (pos, edge, sign) in enumerate(((lo, e_lo, -1.0), (hi, e_hi, 1.0))):
            extreme = np.full(n, -np.inf)
            np.maximum.at(extreme, row, sign * pos)
            outer_edge = np.full(n, -np.inf)
            np.maximum.at(outer_edge, row[edge], sign * pos[edge])
            near = edge & (sign * pos > outer_edge[row] - self.p.edge_match)
            cnt = np.bincount(row[near], minlength=n)
            tot = np.bincount(row[near], weights=pos[near], minlength=n)
            has = cnt > 0
            ends[:, side] = sign * extreme
            ends[has, side] = tot[has] / cnt[has]
            counts[:, side] = cnt
        self.G = SegmentSet(c + d * ends[:, :1], c + d * ends[:, 1:], sums, counts)

