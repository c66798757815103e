"""The joint adjustment of poses and map lines (mapping2d_adjust), the lagged odometry model, against known truth."""

import numpy as np
import pytest

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import OdometryPriorParams, Segment, build_map, compose, map_errors, pose_errors, relative
from cga_lessons.mapping2d.adjust import AdjustParams, adjust_map
from cga_lessons.mapping2d.corrections import chain_covariance
from cga_lessons.mapping2d.frame import turn_about
from cga_lessons.mapping2d.geometry import SegmentSet
from cga_lessons.mapping2d.laser import OdometryModel, load_scene, simulate_odometry, simulate_scans

MOUNT = np.array([0.2, 0.05, 0.1])


def _observe(walls, poses, mount, edges, n=40):
    """Every wall seen from every pose: its points (noise-free) in the laser frame, as segments with their sums."""
    segs, scan, line = [], [], []
    for k, pose in enumerate(poses):
        laser = compose(pose, mount)
        c, s = np.cos(laser[2]), np.sin(laser[2])
        for j, (a, b) in enumerate(walls):
            t = np.linspace(0.0, 1.0, n)[:, None]
            pts = (a + t * (b - a) - laser[:2]) @ np.array([[c, -s], [s, c]])  # world -> laser frame
            x, y = pts[:, 0], pts[:, 1]
            sums = [n, x.sum(), y.sum(), x @ x, x @ y, y @ y]
            segs.append(Segment(pts[0], pts[-1], n, sums, edges, edges))
            scan.append(k)
            line.append(j)
    return SegmentSet.from_segments(segs), np.array(scan), np.array(line)


def _problem(rng, walls, T=10, shift=(0.05, 0.05, 0.02)):
    truth = np.column_stack([rng.uniform(1, 4, T), rng.uniform(1, 3, T), rng.uniform(-np.pi, np.pi, T)])
    start = truth + rng.normal(size=truth.shape) * shift
    start[0] = truth[0]
    inc = relative(truth[:-1], truth[1:])
    return truth, start, inc


ROOM = np.array([[[0, 0], [6, 0]], [[6, 0], [6, 4]], [[6, 4], [0, 4]], [[0, 4], [0, 0]], [[2, 1], [3, 2.5]]], float)


def _map_lines(walls, rng, jitter=0.03):
    moved = walls + rng.normal(size=walls.shape) * jitter  # the builder's lines are a start, not the truth
    x, y = moved[:, :, 0], moved[:, :, 1]
    sums = np.column_stack(
        [np.full(len(walls), 2.0), x.sum(1), y.sum(1), (x * x).sum(1), (x * y).sum(1), (y * y).sum(1)]
    )
    return SegmentSet(moved[:, 0].copy(), moved[:, 1].copy(), sums, np.zeros((len(walls), 2), int))


def test_adjust_map_recovers_the_true_poses_from_noise_free_lines():
    rng = np.random.default_rng(0)
    truth, start, inc = _problem(rng, ROOM)
    obs, scan, line = _observe(ROOM, truth, MOUNT, edges=False)
    covs = np.tile(np.diag([0.01, 0.01, 0.01]), (len(inc), 1, 1))
    res = adjust_map(start, inc, covs, obs, scan, line, _map_lines(ROOM, rng), mount=MOUNT,
                     params=AdjustParams(tolerance=(1e-10, 1e-10), iterations=30))  # fmt: skip
    assert np.abs(res.poses - truth).max() < 1e-7
    assert res.lines == len(ROOM) and res.observations == len(obs)


def test_real_edges_fix_the_position_along_a_corridor():
    """Two parallel walls say nothing along the corridor; their real ends do (with odometry that knows little)."""
    corridor = np.array([[[0, 0], [8, 0]], [[8, 2], [0, 2]]], float)
    rng = np.random.default_rng(1)
    T = 8
    across = np.full(T, 1.0) + rng.normal(size=T) * 0.1
    truth = np.column_stack([np.linspace(2, 6, T), across, rng.normal(size=T) * 0.2])
    start = truth + np.array([0.3, 0.02, 0.01])  # every pose 30 cm along the corridor
    start[0] = truth[0]
    inc = relative(truth[:-1], truth[1:]) + rng.normal(size=(T - 1, 3)) * [0.2, 0.0, 0.0]  # bad along the corridor
    covs = np.tile(np.diag([1.0, 1.0, 1e-2]), (T - 1, 1, 1))
    G = _map_lines(corridor, rng, 0.0)
    G = SegmentSet(G.start, G.end, G.sums, np.ones((2, 2), int))
    found = {}
    for edges in (True, False):
        obs, scan, line = _observe(corridor, truth, MOUNT, edges=edges)
        res = adjust_map(start, inc, covs, obs, scan, line, G, mount=MOUNT, floors=(0.0, 0.0, 1e-4),
                         params=AdjustParams(tolerance=(1e-10, 1e-10), iterations=30))  # fmt: skip
        found[edges] = np.abs(res.poses[:, 0] - truth[:, 0]).max()
    assert found[True] < 3e-3  # the odometry, 1 m sd against the edges' 1 cm, pulls a millimetre
    assert found[False] > 0.05  # without the edges the odometry's wrong steps stand


def test_one_wrong_association_does_not_bend_the_map():
    rng = np.random.default_rng(2)
    truth, start, inc = _problem(rng, ROOM)
    obs, scan, line = _observe(ROOM, truth, MOUNT, edges=False)
    line = line.copy()
    line[7] = (line[7] + 2) % len(ROOM)  # one segment fused into the opposite wall
    covs = np.tile(np.diag([0.01, 0.01, 0.01]), (len(inc), 1, 1))
    res = adjust_map(start, inc, covs, obs, scan, line, _map_lines(ROOM, rng), mount=MOUNT,
                     floors=(1e-6, 1e-4, 1e-4))  # fmt: skip
    assert np.abs(res.poses[:, :2] - truth[:, :2]).max() < 2e-3
    assert res.outliers >= 1


def test_the_first_scans_lines_hold_the_turn_of_the_whole_map():
    """Issue 14: the first pose is fixed, so only the first scan's lines (and the first odometry step) say how the
    whole map is turned about it.  With the Intel log's learnt angle floor (0.92 degrees) on the first scan's two
    lines, a first odometry step 2.67 degrees off, and a builder's map turned by as much, the adjustment left every
    later heading 0.62 degrees off; without the floor on the first scan, 0.12 degrees."""
    rng = np.random.default_rng(3)
    T = 8
    truth = np.column_stack([rng.uniform(1.5, 4.5, T), rng.uniform(1, 3, T), rng.uniform(-np.pi, np.pi, T)])
    obs, scan, line = _observe(ROOM, truth, MOUNT, edges=False)
    keep = np.flatnonzero((scan > 0) | (line < 2))  # the first scan sees two walls
    obs, scan, line = obs.take(keep), scan[keep], line[keep]
    inc = relative(truth[:-1], truth[1:])
    turn = np.radians(2.67)
    inc[0, 2] += turn  # the first odometry step turns too far
    covs = np.tile(np.diag([1e-2, 1e-2, np.radians(1.27) ** 2]), (T - 1, 1, 1))
    start = turn_about(truth, truth[0, :2], turn)  # the builder's poses and map: turned by the first step
    start[0] = truth[0]
    G = _map_lines(ROOM, rng, 0.0)
    c, R = truth[0, :2], np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    G = SegmentSet((G.start - c) @ R.T + c, (G.end - c) @ R.T + c, G.sums, G.edge)
    floors = (np.radians(0.92) ** 2, 0.0046**2, 9e-4)  # the Intel log's learnt floors
    scan_cov = np.diag([0.0141**2, 0.0141**2, np.radians(0.29) ** 2])  # and registration error
    res = adjust_map(start, inc, covs, obs, scan, line, G, mount=MOUNT, floors=floors, scan_cov=scan_cov)
    assert np.degrees(np.abs(res.poses[2:, 2] - truth[2:, 2])).max() < 0.25
    assert np.abs(res.poses[:, :2] - truth[:, :2]).max() < 0.01


def test_chain_covariance_is_the_spread_of_composed_noisy_steps():
    """Against Monte Carlo: steps drawn from the drift model and composed, their sample covariance."""
    params = OdometryPriorParams(odo_heading_bias=0.0)  # the bias is a drift, not a spread: leave it out to compare
    rng = np.random.default_rng(3)
    truth = np.array([[0, 0, 0], [1.0, 0.1, 0.3], [1.8, 0.8, 0.9], [2.0, 1.9, 1.4], [1.5, 2.8, 2.2]])
    u, cov = chain_covariance(truth, 0, 4, params)
    np.testing.assert_allclose(u, relative(truth[0], truth[4]), atol=1e-12)
    model = OdometryModel(params.odo_sigma_xy, params.odo_sigma_heading, params.odo_sigma_turn, 0.0)
    ends = []
    for _ in range(20000):
        steps = model.increments(truth, rng)
        p = np.zeros(3)
        for s in steps:
            p = compose(p, s)
        ends.append(p)
    ends = np.array(ends)
    sample = np.cov(ends.T)
    scale = np.sqrt(np.outer(np.diag(cov), np.diag(cov)))
    assert np.abs(sample - cov).max() / scale.max() < 0.05
    assert np.allclose(np.diag(sample), np.diag(cov), rtol=0.1)


def test_build_map_adjusts_the_office_closer_to_the_simulator():
    office = load_scene("office")
    rng = np.random.default_rng(7)
    truth = office.trajectory
    scans = simulate_scans(office, truth, rng)
    odo = simulate_odometry(truth, rng)
    plain = build_map(scans, odo, adjust=False)
    adjusted = build_map(scans, odo)
    pos0, head0 = pose_errors(plain.poses, truth)
    pos1, head1 = pose_errors(adjusted.poses, truth)
    assert pos1 < pos0 and head1 < head0
    assert pos1 < 0.012 and head1 < np.radians(0.06)
    assert np.median(map_errors(adjusted.segments, office.walls)) < np.median(map_errors(plain.segments, office.walls))


def test_adjust_map_and_learn_lag_refuse_bad_input():
    rng = np.random.default_rng(4)
    truth, start, inc = _problem(rng, ROOM, T=4)
    obs, scan, line = _observe(ROOM, truth, MOUNT, edges=False)
    covs = np.tile(np.eye(3) * 0.01, (len(inc), 1, 1))
    G = _map_lines(ROOM, rng)
    bad = start.copy()
    bad[1, 0] = np.nan
    with pytest.raises(InvalidInputError, match="adjust_map: poses"):
        adjust_map(bad, inc, covs, obs, scan, line, G)
    with pytest.raises(InvalidInputError, match="adjust_map: increments"):
        adjust_map(start, inc[:-1], covs, obs, scan, line, G)
    with pytest.raises(InvalidInputError, match="adjust_map: line"):
        adjust_map(start, inc, covs, obs, scan, line + 10, G)
    with pytest.raises(InvalidInputError, match="adjust_map: params.loss"):
        adjust_map(start, inc, covs, obs, scan, line, G, params=AdjustParams(loss="tukey"))
    with pytest.raises(InvalidInputError, match="learn_lag"):
        build_map([(np.ones(5), np.linspace(0, 1, 5))] * 2, np.zeros((2, 3)), learn_lag=0)


def test_the_adjustment_brings_a_real_log_closer_to_its_corrected_poses():
    """Intel's first 300 scans with drifting odometry: against the log's own corrected poses."""
    from cga_lessons import data_path
    from cga_lessons.mapping2d import read_carmen_log

    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    n = 300
    truth = log.poses[:n]
    odo = simulate_odometry(truth, np.random.default_rng(0))
    scan_by_scan = build_map(log.scans[:n], odo, max_range=8.0, adjust=False)
    adjusted = build_map(log.scans[:n], odo, max_range=8.0)
    before, after = pose_errors(scan_by_scan.poses, truth)[0], pose_errors(adjusted.poses, truth)[0]
    assert after < 0.5 * before
    assert pose_errors(odo, truth)[0] > 50 * after


def test_solve_spd_solves_a_sparse_positive_definite_system_and_reports_a_singular_one():
    from scipy import sparse

    from cga_lessons.mapping2d.least_squares import solve_spd

    rng = np.random.default_rng(5)
    J = sparse.random(300, 120, density=0.05, random_state=6, format="csr") + sparse.eye(300, 120)
    H = (J.T @ J).tocsc()
    b = rng.normal(size=120)
    np.testing.assert_allclose(solve_spd(H, b), np.linalg.solve(H.toarray(), b), rtol=1e-9, atol=1e-9)
    singular = sparse.csc_matrix(np.diag([1.0, 0.0, 2.0]))
    assert solve_spd(singular, np.ones(3)) is None
