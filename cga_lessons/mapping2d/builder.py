"""The incremental line-map builder behind :func:`cga_lessons.mapping2d.build_map` (sections 3.1.2-3.1.4).

:class:`MapBuilder` keeps the global map ``G`` (a :class:`SegmentSet`) and,
for every map line, which scans saw it (its *observations*: the local segment
and the scan it came from).  For each scan it

* corrects the predicted pose against the map lines seen recently near the
  robot (:meth:`MapBuilder.correct`): the thesis's correspondences ``C``
  (3.5, 3.19), each pair gated by its innovation, and the heading and
  position corrections (3.8, 3.12) solved together with the odometry's
  prediction as one more measurement
  (:func:`~cga_lessons.mapping2d.corrections.pose_correction`), repeated with
  fresh correspondences; the pairs that disagree with the consensus fall out
  at the gate; the result is checked against the whole scan;
* fuses the local map into ``G`` (:meth:`MapBuilder.fuse`, 3.20-3.21) and
  records the observations;
* on request refits the map lines from their observations at new poses
  (:meth:`MapBuilder.refit`, after a loop closure) and merges duplicates
  (:meth:`MapBuilder.remove_duplicates`).

None of this scans the whole map or the whole log per scan: the lines are
kept in a spatial index (:class:`~cga_lessons.mapping2d.index.SegmentIndex`)
that :meth:`MapBuilder.near` and the duplicate search query, the duplicate
search looks only at the lines changed since its last run, and a refit reads
only the observations of the lines whose observing poses moved
(:class:`~cga_lessons.mapping2d.observations.Observations`).  The index and
the duplicate search are exact (the map is the one a search of every line
gives, to the last bit); the refit is exact with ``refit_tolerance`` 0.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks

from .correction import ScanCorrector
from .geometry import PlainGeometry, SegmentSet, correspondences_unchecked
from .index import SegmentIndex, duplicate_pairs, sphere_boxes
from .inputs import pose, reach
from .observations import Growing, Observations, PathLog, refit_lines
from .params import MapParams
from .poses import compose_unchecked, wrap_unchecked
from .segment import line_from_sums

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
    index_cell : float, optional
        Cell side (m) of the spatial index of the lines
        (:class:`~cga_lessons.mapping2d.index.SegmentIndex`; default there).
    refit_tolerance : (float, float), optional
        ``(m, rad)``: a refit after a loop closure (:meth:`refit`) refits the
        lines seen from the poses that moved by more than this since those
        lines were last placed, and the lines fused or merged since the last
        refit; each map line thus stays within this of its refit from every
        observation.  ``(0, 0)``: every line whose poses moved at all, the
        map of a refit of every line to the last bit.  Default: the class
        attribute :attr:`REFIT_TOLERANCE`.

    Attributes
    ----------
    REFIT_TOLERANCE : (float, float)
        ``(0.005, 0.001)``: 5 mm and 1 mrad (8 mm at the 8 m reach of the
        logs' readings), well below the maps' median error (3-6 cm on Intel,
        ACES and CSAIL).  A chosen bound, not a tuned one: its effect on the
        poses and maps is measured by ``benchmarks/bench_growth.py`` and
        ``benchmarks/bench_logs.py`` against ``(0, 0)``.
    INDEX_MIN_LINES : int
        Below this many lines :meth:`near` and the duplicate search look at
        every line (vectorised): on the Intel map tiled 1, 4, 16 and 64
        times (1,111 to 71,104 lines) a neighbourhood query through the index
        took about the same time at every size, the search of every line
        grew with the map and cost the same at about 3,000 lines.
    """

    REFIT_TOLERANCE = (0.005, 0.001)
    INDEX_MIN_LINES = 2000
    BOX_PAD = 1e-6  # (m) the index's boxes are this much larger: rounding never hides a line at a box's edge

    def __init__(self, geometry, params, mount=(0.0, 0.0, 0.0), max_range=np.inf, *, index_cell=None,
                 refit_tolerance=None):  # fmt: skip
        f = "MapBuilder"
        self.geo = checks.instance(geometry, f, "geometry", PlainGeometry, "a PlainGeometry or a ConformalGeometry")
        self.p = checks.instance(params, f, "params", MapParams, "a MapParams")
        self.mount = pose(mount, f, "mount")
        self.max_range = reach(max_range, f, "max_range")
        tol = self.REFIT_TOLERANCE if refit_tolerance is None else refit_tolerance
        self.refit_tolerance = tuple(float(t) for t in checks.array(tol, f, "refit_tolerance", (2,)))
        if min(self.refit_tolerance) < 0:
            raise checks.fail(f, "refit_tolerance", f"must be two numbers >= 0 (m, rad), got {self.refit_tolerance}")
        cell = None if index_cell is None else checks.real(index_cell, f, "index_cell", low=0.0, strict_low=True)
        self.index = SegmentIndex() if cell is None else SegmentIndex(cell)
        self._G = SegmentSet.empty()
        self.gid = np.zeros(0, int)  # a stable id per map line, ascending along the rows
        self.last = np.zeros(0, int)  # the last scan that saw it
        self._next_id = 0
        self._root = Growing((), int)  # line id -> id of the line it was merged into (itself while in the map)
        self.obs = Observations()  # per scan: its local segments (laser frame), and the line each went into
        self._placed = Growing((3,))  # per scan: the pose with which its observations were last placed
        self._dirty: set[int] = set()  # lines changed since the last duplicate search
        self._unfit: set[int] = set()  # lines fused or merged since the last refit
        self.path = []  # distance travelled up to each scan (m)
        self.corrector = ScanCorrector(geometry, params, self.mount)

    # ------------------------------------------------------------------ the map and its index

    @property
    def G(self) -> SegmentSet:
        """The map lines (global frame), one row per id of :attr:`gid`."""
        return self._G

    @G.setter
    def G(self, segs: SegmentSet):
        if len(segs) != len(self.gid):
            raise checks.fail("MapBuilder.G", "segs", f"{len(segs)} segments for {len(self.gid)} line ids")
        self._G = segs
        self.index.clear()
        self._touch(np.arange(len(segs)))

    @property
    def path(self) -> PathLog:
        """Distance travelled (m) up to each scan: append one value per scan."""
        return self._path

    @path.setter
    def path(self, values):
        self._path = PathLog(values)

    def _rows(self, ids) -> np.ndarray:
        """Rows of the lines ``ids`` (current ids, ascending in, ascending out)."""
        return np.searchsorted(self.gid, np.asarray(ids, int))

    def rows_of(self, ids) -> np.ndarray:
        """Rows (ascending, unique) of those of the line ids ``ids`` that are in the map."""
        ids = np.unique(np.asarray(ids, int))
        rows = np.minimum(np.searchsorted(self.gid, ids), max(len(self.gid) - 1, 0))
        return rows[self.gid[rows] == ids] if len(self.gid) else np.zeros(0, int)

    def _touch(self, rows, fitted=False):
        """Lines ``rows`` changed: re-index them; the duplicate search (and, unless ``fitted``, the refit) sees them."""
        rows = np.asarray(rows, int)
        if len(rows) == 0:
            return
        ids = self.gid[rows]
        self.index.update(ids, *sphere_boxes(self._G.start[rows], self._G.end[rows], self.BOX_PAD))
        self._dirty.update(ids.tolist())
        if not fitted:
            self._unfit.update(ids.tolist())

    # ------------------------------------------------------------------ map queries

    def resolve(self, ids):
        """Current ids of lines, following merges."""
        root = self._root.view
        ids = np.asarray(ids, int)
        r = root[ids]
        while True:
            nxt = root[r]
            if np.array_equal(nxt, r):
                root[ids] = r  # shortcut the chains of merges
                return r
            r = nxt

    def observers(self, lines):
        """The scans that observed the map lines ``lines`` (indices) and how many of them each saw: two arrays."""
        return self.obs.scan_counts(self.gid[lines])

    def segment_distance(self, centre, idx=None):
        """Distance (m) from ``centre`` to each map segment (or to those in ``idx``)."""
        G = self._G if idx is None else self._G.take(idx)
        if len(G) == 0:
            return np.zeros(0)
        v = G.end - G.start
        t = np.clip(np.einsum("ij,ij->i", centre - G.start, v) / np.einsum("ij,ij->i", v, v), 0, 1)
        return np.hypot(*(G.start + t[:, None] * v - centre).T)

    def active(self, k, rows=None):
        """Mask of the map lines (or of ``rows``) seen within the last ``active_path`` metres of travel before scan
        ``k``."""
        n = len(self._G) if rows is None else len(rows)
        if self.p.active_path <= 0 or len(self.path) == 0:
            return np.ones(n, bool)
        path = self.path.array
        last = self.last if rows is None else self.last[rows]
        return path[min(k, len(path) - 1)] - path[last] <= self.p.active_path

    def near(self, centre, k=None, radius=None, active=True):
        """Indices of map lines within ``radius`` (default ``neighbourhood``) of ``centre``, ascending.

        With ``k`` given, only the lines active at scan ``k`` (``active=True``)
        or only the others (``active=False``).  The spatial index gives the
        lines whose boxes meet the square of side ``2 radius`` about
        ``centre``; their distances are then computed exactly.
        """
        if len(self._G) == 0:
            return np.zeros(0, int)
        radius = self.p.neighbourhood if radius is None else radius
        centre = np.asarray(centre, float)
        if len(self._G) < self.INDEX_MIN_LINES:
            rows = np.arange(len(self._G))
        else:
            reach = radius + self.BOX_PAD
            rows = self._rows(self.index.query(centre - reach, centre + reach))
        ok = self.segment_distance(centre, rows) < radius
        if k is not None:
            ok &= self.active(k, rows) if active else ~self.active(k, rows)
        return rows[ok]

    def support(self, points, pose, idx):
        """How well the scan's points (laser frame) at ``pose`` lie on the map segments ``idx``.

        Each point within ``D = support_distance`` of a segment counts
        ``1 - (d / D)^2`` (``d`` its distance): a point on the line counts one,
        the score falls smoothly to zero at ``D``, so of two poses the better
        aligned scores higher even when both put every point within ``D``.
        """
        if len(points) == 0 or len(idx) == 0:
            return 0.0
        lp = compose_unchecked(pose, self.mount)
        c, s_ = np.cos(lp[2]), np.sin(lp[2])
        q = points @ np.array([[c, s_], [-s_, c]]) + lp[:2]
        a, v = self._G.start[idx], self._G.end[idx] - self._G.start[idx]
        rx, ry = q[:, 0, None] - a[None, :, 0], q[:, 1, None] - a[None, :, 1]  # (points, lines)
        t = np.clip((rx * v[:, 0] + ry * v[:, 1]) / (v[:, 0] ** 2 + v[:, 1] ** 2), 0.0, 1.0)
        rx -= t * v[:, 0]
        ry -= t * v[:, 1]
        d2 = (rx * rx + ry * ry).min(axis=1)  # squared distance to the nearest segment
        return float(np.sum(np.maximum(0.0, 1.0 - d2 / self.p.support_distance**2)))

    # ------------------------------------------------------------------ correction (3.6-3.12)

    def correct(self, L, pose, prior_cov, idx, points=None, widen=True, test=True, step=None):
        """Correct one scan's predicted pose against the map lines ``idx`` (3.6-3.12).

        The registration is :meth:`ScanCorrector.register
        <cga_lessons.mapping2d.correction.ScanCorrector.register>`.  With
        ``test`` (and ``step = (carried, step_cov)``, the prediction's
        covariance split into the part carried from the last pose and the
        odometry step's model covariance) the correction is applied only if
        :meth:`~cga_lessons.mapping2d.correction.ScanCorrector.decide` admits
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
        reg = self.corrector.register(self._G.take(idx), L, predicted, prior_cov, widen, gate_cov)
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
        self._root.extend(ids)
        self._G = SegmentSet.concat([self._G, segs])
        self.gid = np.concatenate([self.gid, ids])
        self.last = np.concatenate([self.last, np.full(len(segs), k, int)])
        self._touch(np.arange(len(self._G) - len(segs), len(self._G)))
        return ids

    def fuse(self, L, pose, k):
        """Fuse scan ``k``'s local map into the global map (section 3.1.4 / 3.2.4) and record its observations.

        The correspondences at the corrected ``pose`` among the active lines
        near the robot are merged (3.20-3.21); local lines without a partner
        become new map lines.
        """
        Lw = self.geo.to_global(L, pose, self.mount)
        idx = self.near(pose[:2], k)
        C, _, _ = correspondences_unchecked(self._G.take(idx), Lw, pose[:2], self.p, self.geo)
        gl = np.flatnonzero(C >= 0)
        pairs = (idx[gl], C[gl])
        ids = np.full(len(L), -1, int)
        for g, j in zip(*pairs):
            self._merge_into(g, Lw.start[j], Lw.end[j], Lw.sums[j], Lw.edge[j])
            self.last[g] = k
            ids[j] = self.gid[g]
        self._touch(pairs[0])
        new = np.flatnonzero(ids < 0)
        if len(new):
            ids[new] = self.add_lines(Lw.take(new), k)
        self.obs.add(L, k, ids)
        if k >= len(self._placed):
            self._placed.extend(np.zeros((k + 1 - len(self._placed), 3)))
        self._placed.view[k] = pose

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
        G, geo = self._G, self.geo
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
        (2.130).  Longer segments absorb shorter ones (the longest first);
        repeated until nothing changes.  Lines that did not change since the
        last check cannot have become duplicates of each other, so only the
        pairs with a changed line are tested, found in the spatial index
        (spheres that meet have boxes that meet): the pairs, and so the
        merges, of a test of every pair.
        """
        changed = np.array(sorted(self._dirty), int)
        while len(changed) and len(self._G) > 1:
            index = self.index if len(self._G) >= self.INDEX_MIN_LINES else None
            a, b = duplicate_pairs(self._G, self.gid, index, self._rows(changed), self.geo, self.p, self.BOX_PAD)
            if len(a) == 0:
                break
            G = self._G
            alive = np.ones(len(G), bool)
            into = []
            for i in np.lexsort((b, a, -G.take(a).length)):
                if alive[a[i]] and alive[b[i]]:
                    self._merge_into(a[i], G.start[b[i]], G.end[b[i]], G.sums[b[i]], G.edge[b[i]])
                    self.last[a[i]] = max(self.last[a[i]], self.last[b[i]])
                    self._root.view[self.gid[b[i]]] = self.gid[a[i]]
                    self.obs.merge(self.gid[a[i]], self.gid[b[i]])
                    alive[b[i]] = False
                    into.append(a[i])
            gone = self.gid[~alive]
            self.index.remove(gone)
            self._dirty.difference_update(gone.tolist())
            self._unfit.difference_update(gone.tolist())
            changed = np.unique(self.gid[into])
            keep = np.flatnonzero(alive)
            self._G, self.gid, self.last = G.take(keep), self.gid[keep], self.last[keep]
            self._touch(self._rows(changed))
        self._dirty.clear()

    # ------------------------------------------------------------------ refit from the observations

    def observations(self):
        """All observations: (local segments (m rows, laser frame), scan index (m,), current line id (m,))."""
        return self.obs.all(), self.obs.scan.view.copy(), self.resolve(self.obs.line.view)

    def refit(self, poses, first=0):
        """Rebuild the map lines from their observations placed with ``poses`` (T, 3).

        The sums of all the points a line gathered give its least-squares line;
        its ends are the outermost ends of its observations along it, except
        where observations saw a real edge: then the mean of the edge
        sightings near the outermost one (section 3.1.4's fusion, done at
        once: :func:`~cga_lessons.mapping2d.observations.refit_lines`).

        Only the lines it would change are refitted: those seen from a pose
        that moved by more than ``refit_tolerance`` since they were last
        placed, and those fused or merged since the last refit.  ``first``:
        the poses before it are known not to have moved (they are not
        compared).
        """
        poses = np.asarray(poses, float)
        if len(self.obs) == 0 or len(self._G) == 0:
            return
        n = min(len(poses), len(self._placed))
        first = max(0, min(int(first), n))
        was = self._placed.view[first:n]
        d = poses[first:n] - was
        turn = np.abs(wrap_unchecked(d[:, 2]))
        tol_xy, tol_th = self.refit_tolerance
        moved = first + np.flatnonzero((np.hypot(d[:, 0], d[:, 1]) > tol_xy) | (turn > tol_th))
        lines = np.union1d(self.obs.lines_of_scans(moved, self.resolve), np.array(sorted(self._unfit), int))
        self._placed.view[moved] = poses[moved]
        self._unfit.clear()
        if len(lines) == 0:
            return
        rows = self._rows(lines)
        obs = self.obs.rows_of_lines(lines)
        W = self.geo.to_global_rows(self.obs.take(obs), poses[self.obs.scan.view[obs]], self.mount)
        line_of = np.searchsorted(lines, self.resolve(self.obs.line.view[obs]))
        new = refit_lines(self.geo, self.mount, self._G.take(rows), line_of, W, self.p.edge_match)
        G = self._G
        self._G = SegmentSet.trusted(G.start.copy(), G.end.copy(), G.sums.copy(), G.edge.copy())
        self._G.start[rows], self._G.end[rows], self._G.sums[rows], self._G.edge[rows] = (
            new.start, new.end, new.sums, new.edge)  # fmt: skip
        self._touch(rows, fitted=True)
