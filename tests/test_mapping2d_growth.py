"""What keeps map building from slowing down as the map and the log grow: windowed graph solves, bounded queries."""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import CorrespondenceParams, MapParams, PlainGeometry, SegmentSet, compose, relative
from cga_lessons.mapping2d.builder import MapBuilder
from cga_lessons.mapping2d.drift import MapDrift, Relaxation
from cga_lessons.mapping2d.graph import PoseGraph, chain_uncertainty
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


# ---------------------------------------------------------------- issue 14: revisits of a map driven again and again


def _laps(n_laps=6, per_lap=80, seed=0):
    """A robot driving a 5 m circle ``n_laps`` times with drifting odometry (a heading bias of 0.004 rad a step);
    every 4th pose from the second lap's second on is tied to the first lap's pose at the same place (an old
    anchor, ever older): the truth, the steps' and the revisits' measurements."""
    a = np.linspace(0, 2 * np.pi, per_lap, endpoint=False)
    lap = np.column_stack([5 * np.cos(a), 5 * np.sin(a), np.mod(a + np.pi, 2 * np.pi) - np.pi / 2])
    truth = np.tile(lap, (n_laps, 1))
    rng = np.random.default_rng(seed)
    steps = [relative(truth[k - 1], truth[k]) + rng.normal(0, [0.02, 0.02, 0.01]) + [0, 0, 0.004]
             for k in range(1, len(truth))]  # fmt: skip
    revisits = {k: k % per_lap for k in range(per_lap + 1, len(truth), 4)}
    return truth, steps, revisits


def _graph(truth, steps, revisits, k):
    """The pose graph of the steps and revisits up to scan ``k``."""
    g = PoseGraph()
    for i in range(1, k + 1):
        g.add(i - 1, i, steps[i - 1], np.diag([0.02**2, 0.02**2, 0.01**2]))
        if i in revisits:
            j = revisits[i]
            g.add(j, i, relative(truth[j], truth[i]), np.diag([0.01**2, 0.01**2, 0.002**2]), loop=True)
    return g


def _relaxed_run(horizon, n_laps=6, seed=0):
    """Poses predicted from the steps, the graph relaxed at each revisit by a Relaxation of ``horizon`` scans:
    a list of (scan, poses freed, exact?, poses after the relaxation)."""
    truth, steps, revisits = _laps(n_laps, seed=seed)
    relax, log = Relaxation(horizon, (0.005, 0.001), 3.0), []
    poses = np.zeros_like(truth)
    poses[0] = truth[0]
    for k in range(1, len(truth)):
        poses[k] = compose(poses[k - 1], steps[k - 1])
        if k in revisits:
            new, first = relax.relax(_graph(truth, steps, revisits, k), poses[: k + 1], revisits[k], [k])
            log.append((k, k + 1 - first, relax.exact == k, new.copy()))
            poses[: k + 1] = new
    return log


def test_windowed_relaxation_is_bounded_and_its_scheduled_solves_are_the_optimum():
    """Revisits of ever older anchors: relaxing every pose since the anchor frees more poses every lap; the
    windowed relaxation frees a few, no more in the last lap than in the second, and its scheduled exact solves
    (at scans 81, 165, 333: each at twice the last, from the earliest anchor deferred) give the optimum of the
    whole graph, computed from the other run's poses (within 1e-4 m and rad, Gauss-Newton's stopping step): the
    deferred corrections all made."""
    for seed in (0, 1):
        windowed, full = _relaxed_run(horizon=40, seed=seed), _relaxed_run(horizon=10**9, seed=seed)
        assert [k for k, _, exact, _ in windowed if exact] == [81, 165, 333]
        by_lap = {lap: max(n for k, n, exact, _ in windowed if k // 80 == lap and not exact) for lap in (2, 5)}
        assert by_lap[5] <= by_lap[2] <= 40  # bounded: no growth with the laps
        assert max(n for k, n, _, _ in full if k // 80 == 5) > 400  # every pose since the anchor: the history
        for (k, _, exact, poses), (k2, _, _, other) in zip(windowed, full):
            assert k == k2
            if exact and k > 81:
                truth, steps, revisits = _laps(seed=seed)
                best = _graph(truth, steps, revisits, k).optimize(other, iterations=50, tol=1e-12)
                assert np.abs(relative(best, poses)).max() < 1e-4, (seed, k)
                assert np.abs(relative(best, other)).max() > 1e-3  # (the other run's poses were not the optimum)


def test_map_drift_propagates_as_the_chain_and_is_brought_back_by_a_revisit():
    """Without revisits the drift from the map is the chain's from the first pose: the heading variances summed,
    the position's trace the steps' variances plus each heading error times its lever (two formulas); a revisit
    brings the pose back to its anchor's drift plus the revisit's covariance."""
    truth, _, _ = _laps(n_laps=1)
    n = len(truth)
    rng = np.random.default_rng(3)
    var_xy, var_th = rng.uniform(1e-5, 1e-4, n), rng.uniform(1e-6, 1e-5, n)
    var_xy[0] = var_th[0] = 0.0
    drift = MapDrift(n)
    for k in range(1, n):
        drift.step(k, truth, var_xy[k], var_th[k])
    k = n - 1
    s_xy, s_th = chain_uncertainty(truth, var_xy, var_th, 0, k)
    assert np.isclose(drift.cov[k][2, 2], s_th**2, rtol=1e-12)
    assert np.isclose(np.trace(drift.cov[k][:2, :2]), s_xy**2 + var_xy.sum(), rtol=1e-12)
    assert drift.between(0, k)[0] <= s_xy + 1e-12  # the largest axis of the position's ellipse, within the trace
    before = drift.between(5, k)
    tie = np.diag([1e-4, 1e-4, 1e-6])
    drift.revisit(k, 5, tie)
    assert np.allclose(drift.cov[k], drift.cov[5] + tie)
    assert drift.between(5, k)[1] < before[1]
    assert np.isclose(drift.between(5, k)[1], np.sqrt(2 * drift.cov[5][2, 2] + 1e-6))
