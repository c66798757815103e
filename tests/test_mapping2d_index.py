"""The spatial index of the line map, the local duplicate search and the partial refit against brute force."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import CorrespondenceParams, MapParams, PlainGeometry, SegmentSet, compose
from cga_lessons.mapping2d.builder import MapBuilder
from cga_lessons.mapping2d.geometry import close_angle_pairs
from cga_lessons.mapping2d.hypotheses import angle_density
from cga_lessons.mapping2d.index import SegmentIndex, sphere_boxes
from cga_lessons.mapping2d.laser import load_scene, simulate_scans
from cga_lessons.mapping2d.lines import extract_segments


def _random_segments(rng, n, size=40.0, scale=2.0):
    start = rng.uniform(-size / 2, size / 2, (n, 2))
    length = rng.exponential(scale, n) + 0.05
    a = rng.uniform(0, 2 * np.pi, n)
    end = start + length[:, None] * np.column_stack([np.cos(a), np.sin(a)])
    sums = np.column_stack([np.full(n, 10.0), 10 * (start + end) / 2, np.ones((n, 3))])
    return SegmentSet(start, end, sums, np.zeros((n, 2), int))


def _distance(p, a, b):
    """Point to segment, the textbook way (end points, or the foot of the perpendicular if it falls inside)."""
    ax, ay, bx, by, px, py = *map(float, a), *map(float, b), *map(float, p)
    dx, dy = bx - ax, by - ay
    inside = 0.0 <= (px - ax) * dx + (py - ay) * dy <= dx * dx + dy * dy
    ends = min(math.hypot(px - ax, py - ay), math.hypot(px - bx, py - by))
    return min(ends, abs((px - ax) * dy - (py - ay) * dx) / math.hypot(dx, dy)) if inside else ends


def _brute_near(G, centre, radius):
    return [i for i in range(len(G)) if _distance(centre, G.start[i], G.end[i]) < radius]


def test_near_returns_exactly_the_brute_force_neighbours_as_the_map_changes():
    rng = np.random.default_rng(0)
    b = MapBuilder(PlainGeometry(), MapParams(correspondence=CorrespondenceParams(active_path=0.0)))
    b.INDEX_MIN_LINES = 0  # the index, however small the map
    b.path = [0.0]
    b.add_lines(_random_segments(rng, 300), 0)
    for step in range(6):
        for _ in range(20):
            centre, radius = rng.uniform(-25, 25, 2), rng.choice([0.5, 3.0, 8.0, 30.0])
            assert b.near(centre, radius=radius).tolist() == _brute_near(b.lines, centre, radius)
        # the map changes as it does while mapping: lines grow, lines are added, lines are merged away
        rows = rng.choice(len(b.lines), 30, replace=False)
        b.lines.end[rows] += rng.normal(0, 3.0, (30, 2))
        b._touch(rows)
        b.add_lines(_random_segments(rng, 40), step + 1)
        keep = np.sort(rng.choice(len(b.lines), len(b.lines) - 25, replace=False))
        b.index.remove(np.setdiff1d(b.line_ids, b.line_ids[keep]))
        b._lines, b.line_ids, b.last_seen = b.lines.take(keep), b.line_ids[keep], b.last_seen[keep]
    assert len(b.index) == len(b.lines)


def test_index_query_is_a_superset_of_the_boxes_that_meet_and_checks_its_input():
    rng = np.random.default_rng(1)
    S = _random_segments(rng, 200)
    lo, hi = sphere_boxes(S.start, S.end)
    index = SegmentIndex(cell=3.0)
    index.update(np.arange(200), lo, hi)
    for _ in range(50):
        qlo = rng.uniform(-25, 20, 2)
        qhi = qlo + rng.uniform(0, 10, 2)
        meet = np.flatnonzero(np.all(lo <= qhi, axis=1) & np.all(hi >= qlo, axis=1))
        got = index.query(qlo, qhi)
        assert set(meet) <= set(got) and np.all(np.diff(got) > 0)
    assert len(index.query([-np.inf, -np.inf], [np.inf, np.inf])) == 200
    with pytest.raises(InvalidInputError, match="SegmentIndex: cell"):
        SegmentIndex(cell=0.0)
    with pytest.raises(InvalidInputError, match="SegmentIndex.update: keys, lo and hi"):
        index.update([1, 2], lo[:1], hi[:1])
    with pytest.raises(InvalidInputError, match="lo <= hi"):
        index.update([1], hi[:1] + 1.0, lo[:1])
    with pytest.raises(InvalidInputError, match="SegmentIndex.query: lo, hi: the box has NaN"):
        index.query([np.nan, 0.0], [1.0, 1.0])


def _full_duplicate_pairs(G, p):
    """The duplicate pairs as the full search of every pair finds them (the builder's rule before the index)."""
    geo = PlainGeometry()
    _, th = geo.hough(G, np.zeros(2))
    a, b = close_angle_pairs(th, p.dup_angle)
    length = G.length
    swap = (length[b] > length[a]) | ((length[b] == length[a]) & (b < a))
    a, b = np.where(swap, b, a), np.where(swap, a, b)
    A, B = G.take(a), G.take(b)
    dup = geo.overlap_rows(A, B, 0.0) & (geo.centre_line_distance_rows(B, A) < p.dup_distance)
    return a[dup], b[dup]


def _remove_duplicates_everywhere(b):
    """The duplicate removal over every pair of lines, as the builder did before it had an index."""
    while len(b.lines) > 1:
        G = b.lines
        a, c = _full_duplicate_pairs(G, b.params.cleanup)
        if len(a) == 0:
            return
        alive = np.ones(len(G), bool)
        for i in np.lexsort((c, a, -G.length[a])):
            if alive[a[i]] and alive[c[i]]:
                b._merge_into(a[i], G.start[c[i]], G.end[c[i]], G.sums[c[i]], G.edge[c[i]])
                alive[c[i]] = False
        keep = np.flatnonzero(alive)
        b._lines, b.line_ids, b.last_seen = G.take(keep), b.line_ids[keep], b.last_seen[keep]


def _noisy_copies(rng, n):
    """Segments, each repeated up to three times with small shifts and turns: many duplicates, some across 2 pi."""
    base = _random_segments(rng, n, size=20.0)
    reps = rng.integers(1, 4, n)
    idx = np.repeat(np.arange(n), reps)
    shift = rng.normal(0, 0.03, (len(idx), 2))
    start, end = base.start[idx] + shift, base.end[idx] + shift + rng.normal(0, 0.02, (len(idx), 2))
    horizontal = rng.random(len(idx)) < 0.2  # lines along +x: their angles lie at the 0 / 2 pi cut
    end[horizontal] = start[horizontal] + [1.0, 0.0] + rng.normal(0, 0.01, (horizontal.sum(), 2))
    return SegmentSet(start, end, base.sums[idx], base.edge[idx])


def test_duplicate_search_of_changed_lines_merges_as_the_search_of_every_pair():
    rng = np.random.default_rng(2)
    p = MapParams()
    for trial in range(6):
        S = _noisy_copies(rng, 120)
        ours = MapBuilder(PlainGeometry(), p)
        ours.INDEX_MIN_LINES = 0 if trial % 2 else 10**9  # the index's queries, or all pairs of close angles
        ref = MapBuilder(PlainGeometry(), p)
        for b in (ours, ref):
            b.add_lines(S, 0)
        ours.remove_duplicates()
        _remove_duplicates_everywhere(ref)
        assert np.array_equal(ours.line_ids, ref.line_ids) and len(ours.lines) < len(S)
        assert np.array_equal(ours.lines.start, ref.lines.start) and np.array_equal(ours.lines.end, ref.lines.end)
        # then a few new lines: only they are searched, with the same merges as a search of every pair
        extra = _noisy_copies(rng, 15)
        for b in (ours, ref):
            b.add_lines(extra, 1)
        ours.remove_duplicates()
        _remove_duplicates_everywhere(ref)
        assert np.array_equal(ours.line_ids, ref.line_ids)
        assert np.array_equal(ours.lines.start, ref.lines.start) and np.array_equal(ours.lines.end, ref.lines.end)
        assert len(ours.index) == len(ours.lines)


def test_partial_refit_equals_the_refit_of_every_line():
    room = load_scene("room")
    truth = room.trajectory[:60]
    scans = simulate_scans(room, truth, np.random.default_rng(6))
    b = MapBuilder(PlainGeometry(), MapParams(), max_range=5.0, refit_tolerance=(0.0, 0.0))
    for k, (r, a) in enumerate(scans):
        b.path.append(0.2 * k)
        b.fuse(SegmentSet.from_segments(extract_segments(r, a, max_range=5.0)), truth[k], k)
    b.refit(truth)
    moved = truth.copy()
    moved[40:] = compose([0.05, -0.02, 0.01], truth[40:])  # the end of the run moves, as after a loop closure
    b.refit(moved, first=40)
    # the reference: every line refitted from every observation
    full = MapBuilder(PlainGeometry(), MapParams(), max_range=5.0)
    for k, (r, a) in enumerate(scans):
        full.path.append(0.2 * k)
        full.fuse(SegmentSet.from_segments(extract_segments(r, a, max_range=5.0)), truth[k], k)
    full.refit(truth)
    full._unfit.update(full.line_ids.tolist())  # every line out of date: a refit of all
    full.refit_tolerance = (0.0, 0.0)
    full.refit(moved)
    assert np.array_equal(b.lines.start, full.lines.start) and np.array_equal(b.lines.sums, full.lines.sums)
    with pytest.raises(InvalidInputError, match="MapBuilder: refit_tolerance"):
        MapBuilder(PlainGeometry(), MapParams(), refit_tolerance=(-1.0, 0.0))


def test_angle_density_by_grid_is_close_to_the_sum_over_pairs():
    rng = np.random.default_rng(3)
    a = np.concatenate([rng.normal(0.01, 0.03, 800), rng.uniform(-0.7, 0.7, 1200)])
    w = rng.uniform(0.1, 3.0, len(a))
    exact = angle_density(a, w, 0.02, exact_max=10**9)
    grid = angle_density(a, w, 0.02)
    assert np.max(np.abs(grid - exact)) < 1e-3 * exact.max()
    pairs = [[wj * math.exp(-0.5 * ((ai - aj) / 0.02) ** 2) for aj, wj in zip(a[:50], w[:50])] for ai in a[:50]]
    small = np.array([sum(row) for row in pairs])
    assert np.allclose(angle_density(a[:50], w[:50], 0.02), small, rtol=1e-12)  # few angles: every pair
