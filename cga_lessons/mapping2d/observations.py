"""What the 2D line map was built from: every scan's local segments, kept so that the map can be refitted.

:class:`Observations` stores the segments of each scan (laser frame), the
scan and the map line each was fused into, in arrays that grow by doubling
(appending a scan costs its own rows, not a copy of all the rows before),
with the rows of each map line and of each scan at hand: refitting a few
lines (:func:`refit_lines`) reads only their rows, so a loop closure that
moves a few poses costs what those poses saw, not the whole log.
"""

from __future__ import annotations

import numpy as np

from .geometry import SegmentSet

__all__ = ["Growing", "Observations", "refit_lines"]


class Growing:
    """An array that grows along its first axis by doubling its storage; :attr:`view` is the filled part."""

    def __init__(self, shape=(), dtype=float, capacity: int = 64):
        self._data = np.zeros((capacity, *shape), dtype)
        self.n = 0

    def __len__(self):
        return self.n

    @property
    def view(self) -> np.ndarray:
        return self._data[: self.n]

    def extend(self, values):
        values = np.asarray(values, self._data.dtype)
        m = self.n + len(values)
        if m > len(self._data):
            grown = np.zeros((max(m, 2 * len(self._data)), *self._data.shape[1:]), self._data.dtype)
            grown[: self.n] = self._data[: self.n]
            self._data = grown
        self._data[self.n : m] = values
        self.n = m

    def append(self, value):
        self.extend(np.asarray(value, self._data.dtype)[None])


class PathLog:
    """Distance travelled (m) up to each scan: a list's ``append``, ``[]`` and ``len`` over a growing array."""

    def __init__(self, values=()):
        self._a = Growing()
        self._a.extend(np.asarray(list(values), float).reshape(-1))

    def append(self, value):
        self._a.append(float(value))

    def __len__(self):
        return len(self._a)

    def __getitem__(self, i):
        return self._a.view[i]

    def __iter__(self):
        return iter(self._a.view.tolist())

    def __repr__(self):
        return f"PathLog({self._a.view.tolist()!r})"

    @property
    def array(self) -> np.ndarray:
        return self._a.view


class Observations:
    """Every fused scan's segments (laser frame), its scan and the id of the map line each went into."""

    def __init__(self):
        self.start, self.end = Growing((2,)), Growing((2,))
        self.sums, self.edge = Growing((6,)), Growing((2,), int)
        self.scan, self.line = Growing((), int), Growing((), int)
        self._of_line: dict[int, list[int]] = {}  # line id (current) -> its rows
        self._of_scan: dict[int, list[int]] = {}  # scan -> its rows
        self.n_scans = 0  # one more than the highest scan index added

    def __len__(self):
        return len(self.scan)

    def add(self, L: SegmentSet, k: int, ids):
        """Record scan ``k``'s segments ``L`` (laser frame), fused into the map lines ``ids`` (one per segment)."""
        r0 = len(self.scan)
        self.start.extend(L.start)
        self.end.extend(L.end)
        self.sums.extend(L.sums)
        self.edge.extend(L.edge)
        self.scan.extend(np.full(len(L), k, int))
        self.line.extend(ids)
        for r, i in enumerate(np.asarray(ids, int).tolist(), r0):
            self._of_line.setdefault(i, []).append(r)
        self._of_scan.setdefault(int(k), []).extend(range(r0, r0 + len(L)))
        self.n_scans = max(self.n_scans, int(k) + 1)

    def merge(self, into: int, other: int):
        """Line ``other`` was merged into line ``into``: its rows are now ``into``'s."""
        rows = self._of_line.pop(int(other), [])
        if rows:
            self._of_line.setdefault(int(into), []).extend(rows)

    def rows_of_lines(self, ids) -> np.ndarray:
        """Rows (ascending) of the lines ``ids`` (current ids)."""
        parts = [self._of_line.get(i, ()) for i in np.asarray(ids, int).reshape(-1).tolist()]
        out = np.fromiter((r for p in parts for r in p), int)
        out.sort()
        return out

    def lines_of_scans(self, scans, resolve) -> np.ndarray:
        """Current ids (unique, ascending) of the lines the scans ``scans`` saw; ``resolve`` maps old ids to current."""
        rows = [r for s in np.asarray(scans, int).reshape(-1).tolist() for r in self._of_scan.get(s, ())]
        if not rows:
            return np.zeros(0, int)
        return np.unique(resolve(self.line.view[np.array(rows, int)]))

    def scan_counts(self, ids):
        """Scans that saw the lines ``ids`` (current ids) and how many of them each saw: two arrays, by scan."""
        rows = self.rows_of_lines(ids)
        return np.unique(self.scan.view[rows], return_counts=True)

    def take(self, rows) -> SegmentSet:
        return SegmentSet.trusted(
            self.start.view[rows], self.end.view[rows], self.sums.view[rows], self.edge.view[rows]
        )

    def all(self) -> SegmentSet:
        return SegmentSet.trusted(
            self.start.view.copy(), self.end.view.copy(), self.sums.view.copy(), self.edge.view.copy()
        )


def refit_lines(geometry, mount, G: SegmentSet, rows_of_line, W: SegmentSet, edge_match):
    """Lines refitted from their observations (section 3.1.4's fusion, done at once).

    ``W`` are the observations in the global frame, ``rows_of_line`` (len(W),)
    the index, into ``G``, of the line each belongs to; every line of ``G``
    must have one at least.  The sums of all the points a line gathered give
    its least-squares line (kept in the sense of ``G``'s segment); its ends
    are the outermost ends of its observations along it, except where
    observations saw a real edge: then the mean of the edge sightings within
    ``edge_match`` of the outermost one.  Each line depends on its own rows
    only, in their order: refitting some lines gives, for them, exactly what
    refitting all would.
    """
    row = np.asarray(rows_of_line, int)
    n = len(G)
    sums = np.zeros((n, 6))
    np.add.at(sums, row, W.sums)
    c = sums[:, 1:3] / sums[:, :1]
    sxx = sums[:, 3] - sums[:, 0] * c[:, 0] ** 2
    sxy = sums[:, 4] - sums[:, 0] * c[:, 0] * c[:, 1]
    syy = sums[:, 5] - sums[:, 0] * c[:, 1] ** 2
    ang = 0.5 * np.arctan2(2 * sxy, sxx - syy)
    d = np.column_stack([np.cos(ang), np.sin(ang)])
    flip = np.einsum("ij,ij->i", d, G.end - G.start) < 0
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
        near = edge & (sign * pos > outer_edge[row] - edge_match)
        cnt = np.bincount(row[near], minlength=n)
        tot = np.bincount(row[near], weights=pos[near], minlength=n)
        has = cnt > 0
        ends[:, side] = sign * extreme
        ends[has, side] = tot[has] / cnt[has]
        counts[:, side] = cnt
    return SegmentSet.trusted(c + d * ends[:, :1], c + d * ends[:, 1:], sums, counts)
