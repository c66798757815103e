"""A spatial index of the 2D line map: a uniform grid of buckets over the boxes of the map's segments.

The map builder asks, for every scan, which map lines lie near the robot
(:meth:`~cga_lessons.mapping2d.builder.MapBuilder.near`), and every
``cleanup_every`` scans which lines may be duplicates of the lines that
changed.  Scanning every line answers both in time proportional to the map's
size; :class:`SegmentIndex` answers with the lines registered in the grid cells
a query box covers, a superset of the answer that the caller then tests exactly
on those few lines, so the result is the brute force's, in time proportional
to the lines in the neighbourhood (plus ``O(log |M|)`` to turn ids into rows).

Each line is registered under the box of the sphere on its segment (2.134):
its centre plus or minus half its length on both axes.  The box holds the
segment and the whole sphere, so

* a segment within ``r`` of a point ``p`` has its box meeting the box
  ``p +- r`` (the nearest point of the segment is in both), and
* two segments whose spheres meet or nest (the overlap test of 3.19) have
  boxes that meet.

The index keeps one set of ids per occupied cell (a dictionary: an
unbounded map costs memory only where there are lines) and each id's cell
range, so a line that grows within its cells costs one comparison to update.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks

from .geometry import close_angle_pairs

__all__ = ["SegmentIndex", "sphere_boxes", "duplicate_pairs"]


def sphere_boxes(start, end, pad: float = 0.0):
    """Boxes ``(lo, hi)``, each (n, 2), of the spheres on the segments ``start -> end``: centre +- (half length
    + ``pad``)."""
    start = np.asarray(start, float).reshape(-1, 2)
    end = np.asarray(end, float).reshape(-1, 2)
    centre = 0.5 * (start + end)
    half = 0.5 * np.hypot(*(end - start).T)[:, None] + pad
    return centre - half, centre + half


class SegmentIndex:
    """Grid buckets of integer ids (the map lines' stable ids), each registered under an axis-aligned box.

    Parameters
    ----------
    cell : float
        Side (m) of a grid cell.  The default, 4 m, is half the builder's
        8 m neighbourhood: a neighbourhood query covers 25 cells at most, a
        typical indoor segment (median 0.5 m, 95 % under 3.5 m on the map of
        the Intel log three laps over) one to four.  On that map (1,111
        lines), 8 m queries about points of the trajectory took 1.0, 0.8,
        0.5, 0.5 and 0.6 (relative) with cells of 1, 2, 4, 8 and 16 m, with
        338, 360, 404, 493 and 690 candidates.

    Raises
    ------
    InvalidInputError
        If ``cell`` is not a positive finite number.
    """

    def __init__(self, cell: float = 4.0):
        self.cell = checks.real(cell, "SegmentIndex", "cell", low=0.0, strict_low=True)
        self._buckets: dict[tuple[int, int], set[int]] = {}
        self._range: dict[int, tuple[int, int, int, int]] = {}  # id -> (ix0, iy0, ix1, iy1), inclusive

    def __len__(self) -> int:
        return len(self._range)

    def __contains__(self, key) -> bool:
        return int(key) in self._range

    def keys(self) -> np.ndarray:
        """All ids, ascending."""
        return np.array(sorted(self._range), int)

    def _cells(self, lo, hi):
        """Inclusive cell ranges (n, 4) = (ix0, iy0, ix1, iy1) of boxes ``lo``, ``hi`` (n, 2)."""
        a = np.floor(np.asarray(lo, float) / self.cell)
        b = np.floor(np.asarray(hi, float) / self.cell)
        return np.column_stack([a, b]).astype(np.int64)

    def update(self, keys, lo, hi):
        """Register (or move) the ids ``keys`` (n,) under the boxes ``lo``, ``hi`` (n, 2 each; ``lo <= hi``).

        Raises
        ------
        InvalidInputError
            If the shapes disagree or a box is not finite or has ``lo > hi``.
        """
        keys = np.asarray(keys, int).reshape(-1)
        lo = np.asarray(lo, float).reshape(-1, 2)
        hi = np.asarray(hi, float).reshape(-1, 2)
        if not (len(keys) == len(lo) == len(hi)):
            raise checks.fail(
                "SegmentIndex.update", "keys, lo and hi", f"disagree in length ({len(keys)}, {len(lo)}, {len(hi)})"
            )
        if len(keys) == 0:
            return
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(lo <= hi)):
            raise checks.fail("SegmentIndex.update", "lo, hi", "must be finite boxes with lo <= hi")
        buckets, ranges = self._buckets, self._range
        for key, rng in zip(keys.tolist(), map(tuple, self._cells(lo, hi).tolist())):
            old = ranges.get(key)
            if old == rng:
                continue
            if old is not None:
                self._unregister(key, old)
            ranges[key] = rng
            for ix in range(rng[0], rng[2] + 1):
                for iy in range(rng[1], rng[3] + 1):
                    bucket = buckets.get((ix, iy))
                    if bucket is None:
                        buckets[(ix, iy)] = {key}
                    else:
                        bucket.add(key)

    def _unregister(self, key, rng):
        buckets = self._buckets
        for ix in range(rng[0], rng[2] + 1):
            for iy in range(rng[1], rng[3] + 1):
                bucket = buckets[(ix, iy)]
                bucket.discard(key)
                if not bucket:
                    del buckets[(ix, iy)]

    def remove(self, keys):
        """Forget the ids ``keys`` (ids not registered are ignored)."""
        for key in np.asarray(keys, int).reshape(-1).tolist():
            rng = self._range.pop(key, None)
            if rng is not None:
                self._unregister(key, rng)

    def clear(self):
        """Forget every id."""
        self._buckets.clear()
        self._range.clear()

    def query(self, lo, hi) -> np.ndarray:
        """Ids, ascending, registered in a cell the box ``lo``, ``hi`` (2,) covers.

        A superset of the ids whose boxes meet the query box (every one of
        them is returned; ids in the same cells whose boxes miss it may be
        too): test them exactly.
        """
        lo, hi = np.asarray(lo, float).reshape(2), np.asarray(hi, float).reshape(2)
        if np.isnan(lo).any() or np.isnan(hi).any():
            raise checks.fail("SegmentIndex.query", "lo, hi", f"the box has NaN corners ({lo}, {hi})")
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            return self.keys()  # an unbounded box: every id
        ix0, iy0, ix1, iy1 = self._cells(lo[None], hi[None])[0].tolist()
        buckets = self._buckets
        if (ix1 - ix0 + 1) * (iy1 - iy0 + 1) > len(buckets):  # a box larger than the map: every occupied cell
            found = [b for (ix, iy), b in buckets.items() if ix0 <= ix <= ix1 and iy0 <= iy <= iy1]
        else:
            found = [b for b in (buckets.get((ix, iy)) for ix in range(ix0, ix1 + 1) for iy in range(iy0, iy1 + 1))
                     if b]  # fmt: skip
        if not found:
            return np.zeros(0, int)
        out = np.fromiter(set().union(*found), int)
        out.sort()
        return out


def duplicate_pairs(G, gid, index: SegmentIndex, rows, geometry, params, pad: float = 0.0):
    """The duplicate pairs of map lines with a line among ``rows``, found through the index.

    The pairs are those the builder's full search finds among all the lines
    (:meth:`~cga_lessons.mapping2d.builder.MapBuilder.remove_duplicates`):
    oriented angles (seen from the origin) closer than ``params.dup_angle``,
    sorted by (angle, row) and compared directly or across 2 pi as
    :func:`~cga_lessons.mapping2d.geometry.close_angle_pairs` does; spheres
    that meet or nest (3.19); the centre of the shorter within
    ``params.dup_distance`` of the longer's line (2.130).  Spheres that meet
    have boxes that meet, so the index's candidates hold every such pair.

    Parameters
    ----------
    G : SegmentSet
        The map lines, one per id of ``gid`` (ascending), registered in ``index`` under their sphere boxes.
    index : SegmentIndex or None
        None: the pairs of close angles among all the lines, those with a line
        in ``rows`` kept (one vectorised pass, faster below a few thousand
        lines; quadratic in the lines of one direction).
    rows : array of int
        The rows whose pairs are wanted.
    geometry : PlainGeometry or ConformalGeometry
    params : CleanupParams
        ``dup_angle`` and ``dup_distance``.
    pad : float
        The query boxes are enlarged by this (m), as the registered boxes are.

    Returns
    -------
    a, b : ndarray of int
        Rows of each pair: ``a`` the longer (of equal lengths, the lower row), ``b`` the other.
    """
    rows = np.asarray(rows, int)
    n = len(G)
    if index is None:  # every pair of close angles with a line in rows (a small map: faster than the queries)
        _, th = geometry.hough(G, np.zeros(2))
        a, b = close_angle_pairs(th, params.dup_angle)
        mine = np.zeros(n, bool)
        mine[rows] = True
        return _duplicates(G, a[mine[a] | mine[b]], b[mine[a] | mine[b]], geometry, params)
    lo, hi = sphere_boxes(G.start[rows], G.end[rows], pad)
    found = [np.searchsorted(gid, index.query(lo[i], hi[i])) for i in range(len(rows))]
    first = np.repeat(rows, [len(f) for f in found])
    other = np.concatenate(found) if found else np.zeros(0, int)
    u, v = np.minimum(first, other), np.maximum(first, other)
    pair = np.unique(u[u != v] * n + v[u != v])
    u, v = pair // n, pair % n
    _, tu = geometry.hough(G.take(u), np.zeros(2))
    _, tv = geometry.hough(G.take(v), np.zeros(2))
    swap = (tv < tu) | ((tv == tu) & (v < u))  # sorted by (angle, row)
    a, b = np.where(swap, v, u), np.where(swap, u, v)
    ta, tb = np.where(swap, tv, tu), np.where(swap, tu, tv)
    close = (tb < ta + params.dup_angle) | (ta + 2 * np.pi < tb + params.dup_angle)
    return _duplicates(G, a[close], b[close], geometry, params)


def _duplicates(G, a, b, geometry, params):
    """Of the pairs of close angles ``(a, b)``, the duplicates, oriented: ``a`` the longer (or the lower row)."""
    la, lb = G.take(a).length, G.take(b).length
    swap = (lb > la) | ((lb == la) & (b < a))
    a, b = np.where(swap, b, a), np.where(swap, a, b)  # a: the longer
    A, B = G.take(a), G.take(b)
    dup = geometry.overlap_rows(A, B, 0.0) & (geometry.centre_line_distance_rows(B, A) < params.dup_distance)
    return a[dup], b[dup]
