"""What keeps map building from slowing down as the map and the log grow: windowed graph solves, bounded queries."""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import CorrespondenceParams, MapParams, PlainGeometry, SegmentSet, compose, relative
from cga_lessons.mapping2d.builder import MapBuilder
from cga_lessons.mapping2d.graph import PoseGraph
from cga_lessons.mapping2d.observations import Growing, PathLog


def _loop_poses(n, radius=3.0):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.mod(a + np.pi, 2 * np.pi) - np.pi / 2])


def _tail_loop_graph():
    """A chain of 60 poses, its last 30 on a circle closed by a revisit of pose 30, with drifting steps."""
    head = np.column_stack([np.linspace(-9, -3, 30), np.zeros(30), np.zeros(30)])
    tail = _loop_poses(30) + [-3.0 - 3.0, 0.0, 0.0]
    truth = np.vstack([head, tail])
    drift = np.array([0.0, 0.0, 0.004])
    chain = [truth[0]]
    for k in range(1, len(truth)):
        chain.append(compose(chain[-1], relative(truth[k - 1], truth[k]) + (drift if k > 30 else 0.0)))
    g = PoseGraph()
    step = np.diag([0.02**2, 0.02**2, 0.01**2])
    for k in range(1, len(truth)):
        g.add(k - 1, k, relative(chain[k - 1], chain[k]), step)
    g.add(30, 59, relative(truth[30], truth[59]), np.diag([0.01**2, 0.01**2, 0.002**2]), loop=True)
    return g, np.array(chain)


def test_windowed_solve_equals_the_full_solve_when_the_window_holds_the_loop():
    g, chain = _tail_loop_graph()
    full = g.optimize(chain, iterations=30, tol=1e-12)
    window = g.optimize(chain, iterations=30, tol=1e-12, first_free=30)  # from the revisit's anchor on
    assert np.abs(relative(chain[59], full[59])).max() > 0.01  # the revisit moves the chain
    assert np.allclose(window, full, atol=1e-9)
    assert np.array_equal(window[:30], chain[:30])
    # a window that starts after the anchor cannot give the full solve
    short = g.optimize(chain, iterations=30, tol=1e-12, first_free=45)
    assert np.abs(short - full).max() > 1e-3


def test_graph_edge_arrays_follow_the_edges_added():
    g, chain = _tail_loop_graph()
    before = g.optimize(chain, iterations=3)
    g.add(40, 50, relative(chain[40], chain[50]), np.eye(3) * 1e-4, loop=True)  # added after a solve
    i, j, z, info, loop = g._edge_arrays()
    assert len(i) == len(g) and (i[-1], j[-1], bool(loop[-1])) == (40, 50, True)
    assert np.allclose(info[-1], np.eye(3) * 1e4) and np.allclose(z[-1], relative(chain[40], chain[50]))
    assert not np.array_equal(g.optimize(chain, iterations=3), before)


def _corridor(n_lines, length=2.0):
    """Wall segments along a straight corridor, ``n_lines`` on each side."""
    x = np.arange(n_lines) * length
    low, high = np.zeros(n_lines), np.full(n_lines, 2.0)
    start = np.concatenate([np.column_stack([x, low]), np.column_stack([x + length, high])])
    end = np.concatenate([np.column_stack([x + length, low]), np.column_stack([x, high])])
    sums = np.column_stack([np.full(2 * n_lines, 10.0), 5 * (start + end), np.ones((2 * n_lines, 3))])
    return SegmentSet(start, end, sums, np.zeros((2 * n_lines, 2), int))


def test_queries_look_at_the_neighbourhood_not_at_the_whole_map():
    counts = []
    for n in (50, 500, 2000):  # corridors of 100 m, 1 km and 4 km
        b = MapBuilder(PlainGeometry(), MapParams(correspondence=CorrespondenceParams(active_path=0.0)))
        b.INDEX_MIN_LINES = 0  # the index, however small the map
        b.path = [0.0]
        b.add_lines(_corridor(n), 0)
        b.remove_duplicates()  # the lines added are all checked once ...
        centre = np.array([50.0, 1.0])
        assert b.near(centre).tolist() == np.flatnonzero(b.segment_distance(centre) < 8.0).tolist()
        counts.append(len(b.index.query(centre - 8.0, centre + 8.0)))
        assert not b._dirty  # ... and then none is left to check
    assert counts[0] == counts[1] == counts[2]  # the candidates near the robot do not grow with the map


def test_growing_arrays_and_the_path_log():
    a = Growing((2,), capacity=1)
    for k in range(100):
        a.append([k, -k])
    assert len(a) == 100 and np.array_equal(a.view[:, 0], np.arange(100))
    a.extend(np.zeros((0, 2)))
    assert len(a) == 100
    path = PathLog([0.0])
    for _ in range(1, 10):
        path.append(path[-1] + 0.5)
    assert len(path) == 10 and path[-1] == 4.5 and list(path)[:2] == [0.0, 0.5]
    assert np.array_equal(path.array, np.arange(10) * 0.5)
