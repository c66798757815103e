"""A likelihood field of a line map, and a laser beam model on it, vectorised over particles x beams.

The probability terms that the thesis's future work (section 6.3.2) asks of the
relocalization: how likely is this scan if the laser stood at that pose?  The
answer of the *likelihood field* model (Thrun, Burgard and Fox, *Probabilistic
Robotics*, section 6.4) is cheap enough to ask for thousands of poses a scan:

* a returned beam's end point, placed in the map from the pose, is scored by
  its distance ``d`` to the nearest map segment:
  ``p = z_hit N(d; 0, sigma_hit) + z_rand / max_range``, a wall seen with
  Gaussian noise or a random reading (a person, a chair the map lacks);
* where the map knows nothing (the :class:`~cga_lessons.relocalization.coverage.Coverage`
  grid's ``UNKNOWN`` cells, farther than ``3 sigma_hit`` from every map line),
  the end point says nothing either way: ``p = 1 / max_range``, the density
  of a reading spread evenly over the laser's reach;
* a beam that returned nothing (``inf``, NaN, or at or beyond ``max_range``)
  is checked along its ray: if a map wall lies across it within
  ``max_range`` the laser should have seen it, and only a dropout explains
  the silence (``p = p_dropout``); otherwise ``p = 1 - z_rand``.

:class:`LikelihoodField` holds the distance to the nearest map segment on a
grid (the segments rasterised, :func:`scipy.ndimage.distance_transform_edt`,
exact near the walls) and the per-cell log-likelihood of an end point, so
scoring a beam is one table look-up.  With a coverage grid its ``WALL`` cells
away from every line count as walls too: surfaces the mapping scans hit that
the line map does not hold.
:meth:`LikelihoodField.log_likelihood` scores every particle against a scan's
beams at once.  The model's parameters and its closed form for one beam are in
:mod:`cga_lessons.relocalization.beam`.
"""

from __future__ import annotations

import numpy as np
from scipy import ndimage

from cga_lessons import checks

from .beam import BeamModel, beam_likelihood
from .coverage import UNKNOWN, WALL, Coverage
from .inputs import as_segment_array, check_scan, grid_shape

__all__ = ["LikelihoodField", "check_particles"]  # the model re-exported


def _point_segment(points, segments) -> np.ndarray:
    """Distance from points (..., 2) to segments (..., 2, 2) (broadcast) or to one segment (2, 2)."""
    a, v = segments[..., 0, :], segments[..., 1, :] - segments[..., 0, :]
    rel = points - a
    t = np.clip(np.sum(rel * v, axis=-1) / np.sum(v * v, axis=-1), 0.0, 1.0)
    return np.hypot(*np.moveaxis(rel - t[..., None] * v, -1, 0))


def check_particles(particles, func: str, name: str = "particles") -> np.ndarray:
    """Particles as a finite (N, 3) float array, N >= 1, or :class:`InvalidInputError`."""
    return checks.array(particles, func, name, (None, 3), at_least=1)


class LikelihoodField:
    """The distance to the nearest map segment and the log-likelihood of an end point, on a grid.

    Parameters
    ----------
    map_segments : array_like (M, 2, 2), list of Segment, or ReferenceMap
        The map; a :class:`~cga_lessons.relocalization.geometry.ReferenceMap`
        brings its coverage grid along.
    coverage : Coverage, optional
        What the map knows (:func:`~cga_lessons.relocalization.coverage.build_coverage`).
    model : BeamModel, optional

    Attributes
    ----------
    origin : ndarray, shape (2,)
        Lower-left corner of cell ``[0, 0]``; cell ``[i, j]`` covers
        ``origin + resolution * ([j, j + 1], [i, i + 1])``.
    distance : ndarray of float32, shape (H, W)
        Distance (m) from each cell's centre to the nearest map segment.
    log_hit : ndarray of float32, shape (H, W)
        Log-likelihood of a returned beam ending in each cell.
    known : ndarray of bool, shape (H, W)
        Where the map knows something (everywhere without a coverage grid).
    """

    def __init__(self, map_segments, coverage=None, model: BeamModel | None = None, *, func: str = "LikelihoodField"):
        if coverage is None and hasattr(map_segments, "coverage"):
            coverage = map_segments.coverage
        if hasattr(map_segments, "segments") and not isinstance(map_segments, np.ndarray):
            map_segments = map_segments.segments
        self.segments = as_segment_array(map_segments, func, "map_segments")
        if coverage is not None:
            checks.instance(coverage, func, "coverage", Coverage, "a Coverage or None")
        if model is not None:
            checks.instance(model, func, "model", BeamModel, "a BeamModel or None")
        self.model = m = model or BeamModel()
        self.coverage = coverage
        res = m.resolution
        pts = self.segments.reshape(-1, 2)
        margin = 3 * m.sigma_hit + 3 * res  # beyond it the Gaussian has died: a far cell's value
        self.origin = pts.min(axis=0) - margin
        W, H = grid_shape(self.origin, pts.max(axis=0) + margin, res, func, "map_segments")
        self.shape = (H, W)
        self.distance = self._distances()
        centres = self.centres()
        if coverage is not None:
            self.distance = np.minimum(self.distance, self._clutter_distances(coverage, centres))
        self.distance = self.distance.astype(np.float32)
        if coverage is None:
            self.known = np.ones(self.shape, bool)
        else:
            self.known = (coverage.classify(centres) != UNKNOWN) | (self.distance < 3 * m.sigma_hit)
        log_p = np.log(beam_likelihood(self.distance, m))
        self.log_hit = np.where(self.known, log_p, m.log_unknown).astype(np.float32)
        self.blocked = self.distance <= m.ray_step / 2
        # the outermost ring of cells stands for everything outside the grid (look-ups are clipped onto it):
        # far from every wall, known only without a coverage grid
        ring = np.ones(self.shape, bool)
        ring[1:-1, 1:-1] = False
        self.distance[ring] = np.inf
        self.known[ring] = coverage is None
        self.log_hit[ring] = m.log_miss if coverage is None else m.log_unknown
        self.blocked[ring] = False
        self._flat = (self.log_hit.ravel(), self.blocked.ravel(), self.distance.ravel(), self.known.ravel())

    # ----------------------------------------------------------------- the grid

    def centres(self) -> np.ndarray:
        """Centres of all cells, shape (H, W, 2)."""
        H, W = self.shape
        res = self.model.resolution
        x = self.origin[0] + res * (np.arange(W) + 0.5)
        y = self.origin[1] + res * (np.arange(H) + 0.5)
        return np.stack(np.meshgrid(x, y), axis=-1)

    def cells(self, points):
        """Flat cell index under each point (any leading shape, last axis 2) and whether it is inside the grid.

        A point outside the grid gets the index of the nearest cell of its outermost ring, which stands for
        the outside (far from every wall, no wall across a ray).
        """
        q = (np.asarray(points, float) - self.origin) / self.model.resolution
        return self._flat_index(q[..., 0], q[..., 1]), self._inside(q[..., 0], q[..., 1])

    def _inside(self, col, row):
        H, W = self.shape
        return (col >= 1) & (col < W - 1) & (row >= 1) & (row < H - 1)

    def _flat_index(self, col, row) -> np.ndarray:
        """Flat index of the cell at fractional grid coordinates (column, row), clipped onto the outer ring."""
        H, W = self.shape
        c = np.clip(col, 0, W - 1).astype(np.intp)
        r = np.clip(row, 0, H - 1).astype(np.intp)
        r *= W
        r += c
        return r

    def _distances(self) -> np.ndarray:
        """Distance from every cell centre to the nearest map segment: exact within ``band`` of a segment.

        Everywhere: the exact distance to the segment behind the nearest
        rasterised wall cell (:func:`scipy.ndimage.distance_transform_edt`),
        an upper bound that is off where one cell holds two segments (a thin
        wall's two faces, a corner); within ``band`` (``4 sigma_hit`` or
        ``ray_step``, whichever is larger, and two cells) of a segment: the
        exact distance to the nearest segment, all that the beam model reads
        finely (the Gaussian is dead beyond ``3 sigma_hit``; silent rays and
        the free space ask whether a point is within 10 or 20 cm of a wall).
        """
        H, W = self.shape
        m = self.model
        res = m.resolution
        S = self.segments
        owner = np.full(H * W, -1, np.int64)
        for k, (a, b) in enumerate(S):  # sample each segment at a quarter cell: no cell it crosses is skipped
            n = int(np.ceil(np.hypot(*(b - a)) / (res / 4))) + 1
            flat, inside = self.cells(a + np.linspace(0.0, 1.0, n)[:, None] * (b - a))
            owner[flat[inside]] = k
        wall = (owner >= 0).reshape(H, W)
        _, (ri, ci) = ndimage.distance_transform_edt(~wall, return_indices=True)
        c = self.centres()
        D = _point_segment(c, S[owner.reshape(H, W)[ri, ci]])
        band = max(4 * m.sigma_hit, m.ray_step) + 2 * res
        for a, b in S:
            lo = np.floor((np.minimum(a, b) - band - self.origin) / res).astype(int)
            hi = np.ceil((np.maximum(a, b) + band - self.origin) / res).astype(int) + 1
            c0, r0 = np.maximum(lo, 0)
            c1, r1 = np.minimum(hi, [W, H])
            block = D[r0:r1, c0:c1]
            np.minimum(block, _point_segment(c[r0:r1, c0:c1], np.array([a, b])), out=block)
        return D

    def _clutter_distances(self, coverage, centres) -> np.ndarray:
        """Distance (m) to the coverage grid's ``WALL`` cells more than two of its cells from every map line.

        Surfaces the mapping scans hit that the line map does not hold
        (furniture, clutter): measured at the logged poses of the six CARMEN
        logs, 4-19 % of a scan's returned beams end in such cells, where the
        lines alone would call them misses.  The two cells leave alone the
        ``WALL`` band of a mapped wall (one cell either side of its points).
        """
        clutter = (coverage.classify(centres) == WALL) & (self.distance > 2 * coverage.resolution)
        if not clutter.any():
            return np.full(self.shape, np.inf)
        return ndimage.distance_transform_edt(~clutter) * self.model.resolution

    def free_space(self, clearance: float) -> np.ndarray:
        """Cells where the laser can stand: at least ``clearance`` (m) from every map wall, inside the map.

        With a coverage grid, cells its scans swept (not ``UNKNOWN``);
        without one, cells not connected to the grid's border by such free
        cells (the outside of a closed building), unless that leaves nothing
        (a map with gaps in its outer wall: then all of them).
        """
        free = self.distance >= clearance
        free[[0, -1]] = False
        free[:, [0, -1]] = False
        if self.coverage is not None:
            return free & (self.coverage.classify(self.centres()) != UNKNOWN)
        labels, _ = ndimage.label(free)
        border = np.unique(np.concatenate([labels[1], labels[-2], labels[:, 1], labels[:, -2]]))
        inside = free & ~np.isin(labels, border[border > 0])
        return inside if inside.any() else free

    # ----------------------------------------------------------------- scoring

    def select_beams(self, scan, func: str = "LikelihoodField.log_likelihood"):
        """The beams scored of a scan: ``(hit_ranges, hit_angles, silent_angles)``.

        ``max_beams`` beams evenly spread over the scan; of those, the ones that
        returned a range below ``max_range`` are scored at their end points,
        at most ``max_silent_beams`` of the others along their rays.
        """
        r, a = check_scan(scan, func)
        m = self.model
        idx = np.unique(np.round(np.linspace(0, len(r) - 1, min(m.max_beams, len(r)))).astype(int))
        r, a = r[idx], a[idx]
        hit = np.isfinite(r) & (r < m.max_range)
        silent = a[~hit]
        if len(silent) > m.max_silent_beams:
            silent = silent[np.round(np.linspace(0, len(silent) - 1, m.max_silent_beams)).astype(int)]
        return r[hit], a[hit], silent

    def log_likelihood(self, particles, scan) -> tuple[np.ndarray, np.ndarray]:
        """The log-likelihood of a scan from every particle (laser poses).

        Parameters
        ----------
        particles : array_like, shape (N, 3)
            Laser poses ``(x, y, theta)`` in the map frame.
        scan : (ranges, angles)
            Arrays (n,); ``inf``, NaN or ``>= max_range`` for no return; or the
            beams :meth:`select_beams` chose of a scan.

        Returns
        -------
        log_weight : ndarray, shape (N,)
            ``beam_weight`` times the sum over the scored beams of each beam's
            log-likelihood: the particle's log-weight.
        per_beam : ndarray, shape (N,)
            The mean log-likelihood per beam the map can judge (silent beams,
            and returned beams ending in known space; 0 without any): the
            measure of fit the augmented filter averages over time.  Beams
            ending where the map knows nothing are left out: a scan looking
            into unmapped space is not a worse fit (on ACES, held-out blocks
            driving into space only they saw put 50-75 % of the beams at the
            logged pose into unknown space, and each such scan looked like a
            kidnapping to the filter).
        """
        p = check_particles(particles, "LikelihoodField.log_likelihood")
        r_hit, a_hit, a_silent = scan if len(scan) == 3 else self.select_beams(scan)
        total = np.zeros(len(p))
        judged = np.full(len(p), float(len(a_silent)))
        if len(r_hit):
            hits, known = self._hit_terms(p, r_hit, a_hit)
            total += hits
            judged += known
        if len(a_silent):
            total += self._silent_terms(p, a_silent)
        # the fit per beam counts the beams the map can judge: an end point in unknown space is no worse a fit
        unknown = len(r_hit) - (judged - len(a_silent))
        per_beam = (total - unknown * self.model.log_unknown) / np.maximum(judged, 1.0)
        return self.model.beam_weight * total, per_beam

    def fit(self, pose, scan) -> float:
        """Share of the scan's beams that the map explains at one pose, among those it can judge.

        A returned beam is explained when its end point lies within
        ``3 sigma_hit`` of a map wall, contradicted when it ends farther in
        mapped space; a silent beam is contradicted when a map wall lies across
        its ray within reach.  End points where the map knows nothing, and
        silent beams with a clear ray, do not count.  NaN when no beam counts.
        """
        p = check_particles(np.reshape(np.asarray(pose, float), (1, -1)), "LikelihoodField.fit", "pose")[0]
        r, a = check_scan(scan, "LikelihoodField.fit")
        m = self.model
        hit = np.isfinite(r) & (r < m.max_range)
        phi = p[2] + a
        ends = p[:2] + r[hit, None] * np.column_stack([np.cos(phi[hit]), np.sin(phi[hit])])
        flat, _ = self.cells(ends)
        _, _, dist, known = self._flat
        near = dist[flat] < 3 * m.sigma_hit
        explained = int(near.sum())
        contradicted = int((known[flat] & ~near).sum())
        if (~hit).any():
            contradicted += int(self._blocked_rays(p[None], a[~hit]).sum())
        total = explained + contradicted
        return explained / total if total else float("nan")

    def _hit_terms(self, p, r, a) -> tuple[np.ndarray, np.ndarray]:
        """Sum over the returned beams of the end points' log-likelihoods, and how many end in known space,
        per particle (N,), (N,)."""
        res = self.model.resolution
        phi = (p[:, 2:3] + a[None, :]).astype(np.float32)
        rr = (r / res).astype(np.float32)
        col = np.cos(phi)
        col *= rr
        col += ((p[:, 0:1] - self.origin[0]) / res).astype(np.float32)
        row = np.sin(phi)
        row *= rr
        row += ((p[:, 1:2] - self.origin[1]) / res).astype(np.float32)
        idx = self._flat_index(col, row)
        return self._flat[0][idx].sum(axis=1, dtype=float), self._flat[3][idx].sum(axis=1, dtype=float)

    def _blocked_rays(self, p, a) -> np.ndarray:
        """Whether a map wall lies across each silent beam's ray within reach, (N, B) for particles (N, 3)."""
        m = self.model
        res = m.resolution
        s = (np.arange(m.ray_step / 2, m.max_range, m.ray_step) / res).astype(np.float32)
        phi = (p[:, 2:3] + a[None, :]).astype(np.float32)  # (N, B)
        col = np.cos(phi)[..., None] * s
        col += ((p[:, 0] - self.origin[0]) / res).astype(np.float32)[:, None, None]
        row = np.sin(phi)[..., None] * s
        row += ((p[:, 1] - self.origin[1]) / res).astype(np.float32)[:, None, None]
        return self._flat[1][self._flat_index(col, row)].any(axis=2)

    def _silent_terms(self, p, a) -> np.ndarray:
        """Per particle: the sum over silent beams of ``log p_dropout`` (wall across the ray) or ``log(1 - z_rand)``."""
        m = self.model
        blocked = self._blocked_rays(p, a)
        return np.where(blocked, np.log(m.p_dropout), np.log(1 - m.z_rand)).sum(axis=1)
