"""The incremental line-map builder behind :func:`cga_lessons.mapping2d.build_map` (sections 3.1.2-3.1.4).

:class:`MapBuilder` keeps the thesis's global map ``G`` (:attr:`MapBuilder.lines`, a :class:`SegmentSet`) and,
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
from .fusion import fuse_segment
from .geometry import PlainGeometry, SegmentSet, correspondences_unchecked
from .index import SegmentIndex, duplicate_pairs, sphere_boxes
from .inputs import pose, reach
from .observations import Growing, Observations, PathLog, refit_lines
from .params import MapParams
from .poses import wrap_unchecked
from .support import scan_support, segment_distances

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
        what = "a PlainGeometry or a ConformalGeometry"
        self.geometry = checks.instance(geometry, f, "geometry", PlainGeometry, what)
        self.params = checks.instance(params, f, "params", MapParams, "a MapParams")
        self.mount = pose(mount, f, "mount")
        self.max_range = reach(max_range, f, "max_range")
        tol = self.REFIT_TOLERANCE if refit_tolerance is None else refit_tolerance
        self.refit_tolerance = tuple(float(t) for t in checks.array(tol, f, "refit_tolerance", (2,)))
        if min(self.refit_tolerance) < 0:
            raise checks.fail(f, "refit_tolerance", f"must be two numbers >= 0 (m, rad), got {self.refit_tolerance}")
        cell = None if index_cell is None else checks.real(index_cell, f, "index_cell", low=0.0, strict_low=True)
        self.index = SegmentIndex() if cell is None else SegmentIndex(cell)
        self._lines = SegmentSet.empty()
        self.line_ids = np.zeros(0, int)  # a stable id per map line, ascending along the rows
        self.last_seen = np.zeros(0, int)  # the last scan that saw it
        self._next_id = 0
        self._root = Growing((), int)  # line id -> id of the line it was merged into (itself while in the map)
        self.observed = Observations()  # per scan: its local segments (laser frame), and the line each went into
        self._placed = Growing((3,))  # per scan: the pose with which its observations were last placed
        self._dirty: set[int] = set()  # lines changed since the last duplicate search
        self._unfit: set[int] = set()  # lines fused or merged since the last refit
        self.path = []  # distance travelled up to each scan (m)
        self.corrector = ScanCorrector(
            geometry, params.correspondence, params.correction, params.odometry_prior, self.mount
        )

    # ------------------------------------------------------------------ the map and its index

    @property
    def lines(self) -> SegmentSet:
        """The map lines (global frame), one row per id of :attr:`line_ids`."""
        return self._lines

    @lines.setter
    def lines(self, segs: SegmentSet):
        if len(segs) != len(self.line_ids):
            raise checks.fail("MapBuilder.lines", "segs", f"{len(segs)} segments for {len(self.line_ids)} line ids")
        self._lines = segs
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
        return np.searchsorted(self.line_ids, np.asarray(ids, int))

    def rows_of(self, ids) -> np.ndarray:
        """Rows (ascending, unique) of those of the line ids ``ids`` that are in the map."""
        ids = np.unique(np.asarray(ids, int))
        rows = np.minimum(np.searchsorted(self.line_ids, ids), max(len(self.line_ids) - 1, 0))
        return rows[self.line_ids[rows] == ids] if len(self.line_ids) else np.zeros(0, int)

    def _touch(self, rows, fitted=False):
        """Lines ``rows`` changed: re-index them; the duplicate search (and, unless ``fitted``, the refit) sees them."""
        rows = np.asarray(rows, int)
        if len(rows) == 0:
            return
        ids = self.line_ids[rows]
        self.index.update(ids, *sphere_boxes(self._lines.start[rows], self._lines.end[rows], self.BOX_PAD))
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
        return self.observed.scan_counts(self.line_ids[lines])

    def segment_distance(self, centre, idx=None):
        """Distance (m) from ``centre`` to each map segment (or to those in ``idx``)."""
        return segment_distances(centre, self._lines if idx is None else self._lines.take(idx))

    def active(self, k, rows=None):
        """Mask of the map lines (or of ``rows``) seen within the last ``active_path`` metres of travel before scan
        ``k``."""
        n = len(self._lines) if rows is None else len(rows)
        if self.params.correspondence.active_path <= 0 or len(self.path) == 0:
            return np.ones(n, bool)
        path = self.path.array
        last = self.last_seen if rows is None else self.last_seen[rows]
        return path[min(k, len(path) - 1)] - path[last] <= self.params.correspondence.active_path

    def near(self, centre, k=None, radius=None, active=True):
        """Indices of map lines within ``radius`` (default ``neighbourhood``) of ``centre``, ascending.

        With ``k`` given, only the lines active at scan ``k`` (``active=True``)
        or only the others (``active=False``).  The spatial index gives the
        lines whose boxes meet the square of side ``2 radius`` about
        ``centre``; their distances are then computed exactly.
        """
        if len(self._lines) == 0:
            return np.zeros(0, int)
        radius = self.params.correspondence.neighbourhood if radius is None else radius
        centre = np.asarray(centre, float)
        if len(self._lines) < self.INDEX_MIN_LINES:
            rows = np.arange(len(self._lines))
        else:
            reach = radius + self.BOX_PAD
            rows = self._rows(self.index.query(centre - reach, centre + reach))
        ok = self.segment_distance(centre, rows) < radius
        if k is not None:
            ok &= self.active(k, rows) if active else ~self.active(k, rows)
        return rows[ok]

    def support(self, points, pose, idx):
        """How well the scan's points (laser frame) at ``pose`` lie on the map segments ``idx``
        (:func:`~cga_lessons.mapping2d.support.scan_support` with ``support_distance``)."""
        return scan_support(points, pose, self.mount, self._lines, idx, self.params.correction.support_distance)

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
        reg = self.corrector.register(self._lines.take(idx), L, predicted, prior_cov, widen, gate_cov)
        if reg is None:
            return predicted, np.asarray(prior_cov, float), None, False
        pairs = (idx[reg.gi], reg.li)
        if not test:
            return reg.pose, reg.cov, pairs, True
        carried, step_cov = step if step is not None else (np.asarray(prior_cov, float), np.zeros((3, 3)))
        new, cov, applied = self.corrector.decide(reg, predicted, carried, step_cov)
        if applied and points is not None and self.params.correction.support_distance > 0:
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
        self._lines = SegmentSet.concat([self._lines, segs])
        self.line_ids = np.concatenate([self.line_ids, ids])
        self.last_seen = np.concatenate([self.last_seen, np.full(len(segs), k, int)])
        self._touch(np.arange(len(self._lines) - len(segs), len(self._lines)))
        return ids

    def fuse(self, L, pose, k):
        """Fuse scan ``k``'s local map into the global map (section 3.1.4 / 3.2.4) and record its observations.

        The correspondences at the corrected ``pose`` among the active lines
        near the robot are merged (3.20-3.21); local lines without a partner
        become new map lines.
        """
        Lw = self.geometry.to_global(L, pose, self.mount)
        idx = self.near(pose[:2], k)
        C, _, _ = correspondences_unchecked(self._lines.take(idx), Lw, pose[:2], self.params.correspondence,
                                           self.geometry)
        gl = np.flatnonzero(C >= 0)
        pairs = (idx[gl], C[gl])
        ids = np.full(len(L), -1, int)
        for g, j in zip(*pairs):
            self._merge_into(g, Lw.start[j], Lw.end[j], Lw.sums[j], Lw.edge[j])
            self.last_seen[g] = k
            ids[j] = self.line_ids[g]
        self._touch(pairs[0])
        new = np.flatnonzero(ids < 0)
        if len(new):
            ids[new] = self.add_lines(Lw.take(new), k)
        self.observed.add(L, k, ids)
        if k >= len(self._placed):
            self._placed.extend(np.zeros((k + 1 - len(self._placed), 3)))
        self._placed.view[k] = pose

    def _merge_into(self, g, ls, le, lsums, ledge):
        """Fuse one segment into map line ``g`` (3.20-3.21: :func:`~cga_lessons.mapping2d.fusion.fuse_segment`)."""
        fuse_segment(self._lines, g, self.geometry, ls, le, lsums, ledge, self.params.correspondence.edge_match)

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
        while len(changed) and len(self._lines) > 1:
            index = self.index if len(self._lines) >= self.INDEX_MIN_LINES else None
            rows = self._rows(changed)
            a, b = duplicate_pairs(self._lines, self.line_ids, index, rows, self.geometry, self.params.cleanup,
                                   self.BOX_PAD)
            if len(a) == 0:
                break
            G = self._lines
            alive = np.ones(len(G), bool)
            into = []
            for i in np.lexsort((b, a, -G.take(a).length)):
                if alive[a[i]] and alive[b[i]]:
                    self._merge_into(a[i], G.start[b[i]], G.end[b[i]], G.sums[b[i]], G.edge[b[i]])
                    self.last_seen[a[i]] = max(self.last_seen[a[i]], self.last_seen[b[i]])
                    self._root.view[self.line_ids[b[i]]] = self.line_ids[a[i]]
                    self.observed.merge(self.line_ids[a[i]], self.line_ids[b[i]])
                    alive[b[i]] = False
                    into.append(a[i])
            gone = self.line_ids[~alive]
            self.index.remove(gone)
            self._dirty.difference_update(gone.tolist())
            self._unfit.difference_update(gone.tolist())
            changed = np.unique(self.line_ids[into])
            keep = np.flatnonzero(alive)
            self._lines, self.line_ids, self.last_seen = G.take(keep), self.line_ids[keep], self.last_seen[keep]
            self._touch(self._rows(changed))
        self._dirty.clear()

    # ------------------------------------------------------------------ refit from the observations

    def observations(self):
        """All observations: (local segments (m rows, laser frame), scan index (m,), current line id (m,))."""
        return self.observed.all(), self.observed.scan.view.copy(), self.resolve(self.observed.line.view)

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
        if len(self.observed) == 0 or len(self._lines) == 0:
            return
        n = min(len(poses), len(self._placed))
        first = max(0, min(int(first), n))
        was = self._placed.view[first:n]
        d = poses[first:n] - was
        turn = np.abs(wrap_unchecked(d[:, 2]))
        tol_xy, tol_th = self.refit_tolerance
        moved = first + np.flatnonzero((np.hypot(d[:, 0], d[:, 1]) > tol_xy) | (turn > tol_th))
        lines = np.union1d(self.observed.lines_of_scans(moved, self.resolve), np.array(sorted(self._unfit), int))
        self._placed.view[moved] = poses[moved]
        self._unfit.clear()
        if len(lines) == 0:
            return
        rows = self._rows(lines)
        obs = self.observed.rows_of_lines(lines)
        W = self.geometry.to_global_rows(self.observed.take(obs), poses[self.observed.scan.view[obs]], self.mount)
        line_of = np.searchsorted(lines, self.resolve(self.observed.line.view[obs]))
        edge_match = self.params.correspondence.edge_match
        new = refit_lines(self.geometry, self.mount, self._lines.take(rows), line_of, W, edge_match)
        G = self._lines
        self._lines = SegmentSet.trusted(G.start.copy(), G.end.copy(), G.sums.copy(), G.edge.copy())
        self._lines.start[rows], self._lines.end[rows], self._lines.sums[rows], self._lines.edge[rows] = (
            new.start, new.end, new.sums, new.edge)  # fmt: skip
        self._touch(rows, fitted=True)
