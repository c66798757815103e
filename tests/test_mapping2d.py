"""Tests of the line map builder (cga_lessons.mapping2d*, thesis 3.4-3.21) and its loop closure."""

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import (
    CorrectionParams,
    CorrespondenceParams,
    LoopParams,
    MapBuilder,
    MapParams,
    PlainGeometry,
    PoseGraph,
    Segment,
    SegmentSet,
    build_map,
    compose,
    correspondences,
    load_scene,
    map_errors,
    map_point_errors,
    pose_correction,
    pose_errors,
    proximity_matrix,
    read_carmen_log,
    relative,
    scans_to_world,
    simulate_odometry,
    simulate_scans,
    theta_correction,
    translation_correction,
)
from cga_lessons.mapping2d.hypotheses import loop_hypotheses
from cga_lessons.mapping2d.lines import diff_theta, extract_segments


def _set(*pairs):
    return SegmentSet.from_segments([Segment(a, b, 50) for a, b in pairs])


# ---------------------------------------------------------------- building blocks


def test_transform_is_the_rigid_motion_3_4():
    S = _set(([1.0, 0.0], [1.0, 2.0]))
    T = PlainGeometry().transform(S, (1.0, 2.0, np.pi / 2))
    assert np.allclose(T.start, [[1.0, 3.0]]) and np.allclose(T.end, [[-1.0, 3.0]])
    # the point sums move with the points
    pts = np.linspace([1.0, 0.0], [1.0, 2.0], 50) @ np.array([[0, 1], [-1, 0]]) + [1.0, 2.0]
    x, y = pts[:, 0], pts[:, 1]
    assert np.allclose(T.sums[0], [50, x.sum(), y.sum(), x @ x, x @ y, y @ y])


def test_proximity_matrix_is_the_thesis_formula():
    G = _set(([2.0, -1.0], [2.0, 1.0]), ([-1.0, 3.0], [1.0, 3.0]))
    L = _set(([2.1, -1.0], [2.0, 1.0]))
    M, dth, drho = proximity_matrix(G, L, (0.0, 0.0))
    geo = PlainGeometry()
    rg, tg = geo.hough(G, (0, 0))
    rl, tl = geo.hough(L, (0, 0))
    expect = np.sqrt(diff_theta(tg[:, None], tl[None, :], 0.3) ** 2 + (rg[:, None] - rl[None, :]) ** 2)
    assert M.shape == (2, 1) and np.allclose(M, expect)
    assert np.allclose(rg, [2.0, -3.0]) and np.allclose(tg, [0.0, 3 * np.pi / 2])  # oriented: normal to the right


def test_correspondence_conflict_rule_keeps_the_closer_angle():
    # two global lines compete for one local line: the one with the smaller angle difference keeps it
    G = _set(([2.0, -1.0], [2.0, 1.0]), ([2.05, -1.0], [1.97, 1.0]))
    L = _set(([2.02, -1.0], [2.02, 1.0]))
    C, M, dth = correspondences(G, L, (0.0, 0.0), CorrespondenceParams())
    assert C.tolist() == [0, -1]
    # the other way round when the second is better aligned
    G2 = _set(([2.1, -1.0], [1.95, 1.0]), ([2.03, -1.0], [2.03, 1.0]))
    assert correspondences(G2, L, (0.0, 0.0), CorrespondenceParams())[0].tolist() == [-1, 0]


def test_correspondence_guards_keep_thin_objects_and_faces_apart():
    L = _set(([2.0, -1.0], [2.0, 1.0]))
    other_face = _set(([2.0, 1.0], [2.0, -1.0]))  # the same wall run the other way: its back face
    far_along = _set(([2.0, 3.0], [2.0, 5.0]))  # collinear but 2 m away: spheres do not meet (case 5)
    offset = _set(([2.4, -1.0], [2.4, 1.0]))  # parallel, 40 cm behind: beyond xi_d
    for G in (other_face, far_along, offset):
        assert correspondences(G, L, (0.0, 0.0), CorrespondenceParams())[0].tolist() == [-1]


def test_theta_correction_3_8_is_the_mean():
    assert np.isclose(theta_correction([0.01, 0.02, 0.06]), 0.03)
    assert np.isclose(theta_correction([0.01, 0.04], [3.0, 1.0]), 0.0175)
    with pytest.raises(InvalidInputError, match="theta_correction"):
        theta_correction([])


def test_translation_correction_3_9_to_3_12():
    rng = np.random.default_rng(0)
    t_true = np.array([0.07, -0.04])
    theta = rng.uniform(0, 2 * np.pi, 6)
    n = np.column_stack([np.cos(theta), np.sin(theta)])
    rho_l = rng.uniform(1, 4, 6)
    rho_g = rho_l + n @ t_true  # (3.11) exactly
    assert np.allclose(translation_correction(rho_g, rho_l, theta), t_true)
    # one line (3.9): only the normal component, the closest points' displacement
    t1 = translation_correction(rho_g[:1], rho_l[:1], theta[:1])
    assert np.allclose(t1, n[0] * (n[0] @ t_true))
    # parallel lines: the direction along them comes from matching edges, or stays zero
    th = np.array([0.0, np.pi])
    rl = np.array([1.0, 1.0])
    rg = rl + np.array([[1, 0], [-1, 0]]) @ t_true
    assert np.allclose(translation_correction(rg, rl, th, weak_ratio=0.02), [t_true[0], 0.0])
    along = (np.array([[0.0, -0.04], [0.01, -0.04]]), np.ones(2))
    assert np.allclose(translation_correction(rg, rl, th, weak_ratio=0.02, along=along), t_true)


def test_pose_correction_is_3_8_and_3_12_solved_together():
    rng = np.random.default_rng(11)
    m = 6
    theta = rng.uniform(0, 2 * np.pi, m)
    n = np.column_stack([np.cos(theta), np.sin(theta)])
    lever = rng.uniform(-4, 4, (m, 2))
    t_true, phi = np.array([0.06, -0.03]), 0.015
    J_lever = n[:, 1] * lever[:, 0] - n[:, 0] * lever[:, 1]  # n . (quarter turn of the lever)
    offset = n @ t_true + phi * J_lever  # (3.11) at the centroids, linear in the correction
    vt, vo = rng.uniform(1e-5, 1e-4, m), rng.uniform(1e-5, 1e-4, m)
    d, cov = pose_correction(np.full(m, phi), vt, offset, vo, n, lever)
    assert np.allclose(d, [*t_true, phi]) and np.all(np.linalg.eigvalsh(cov) > 0)
    # the angles alone give the inverse-variance mean of (3.8)
    dth = rng.normal(0.01, 0.003, m)
    d, _ = pose_correction(dth, vt, offset, np.full(m, np.inf), n, lever, prior_cov=np.eye(3) * 1e6)
    assert np.isclose(d[2], theta_correction(dth, 1.0 / vt), atol=1e-9)
    # the heading held by the prior, the offsets give the weighted least squares of (3.12)
    rho_l = rng.uniform(1, 4, m)
    rho_g = rho_l + n @ t_true + rng.normal(0, 0.002, m)
    prior = np.diag([1e12, 1e12, 1e-14])
    d, _ = pose_correction(np.zeros(m), vt, rho_g - rho_l, vo, n, lever, prior_cov=prior)
    assert np.allclose(d[:2], translation_correction(rho_g, rho_l, theta, 1.0 / vo), atol=1e-9)
    # parallel lines without a prior leave a direction open
    with pytest.raises(InvalidInputError, match="pose_correction"):
        pose_correction([0.0, 0.0], [1e-4] * 2, [0.1, 0.1], [1e-4] * 2, [[1, 0], [1, 0]], [[0, 0], [0, 0]])


def test_correct_recovers_a_known_pose_and_gates_a_wrong_pair():
    room = load_scene("room")
    truth = room.trajectory
    res = build_map(simulate_scans(room, truth), truth, loop_closure=False)  # noise-free: the four walls
    exact = MapParams(correction=CorrectionParams(registration_xy=0.0, registration_theta=0.0))  # a simulated scan
    b = MapBuilder(PlainGeometry(), exact, max_range=5.0)
    b.path = [0.0]
    b.add_lines(SegmentSet.from_segments(res.segments), 0)
    ranges, angles = simulate_scans(room, truth[20][None], np.random.default_rng(5))[0]
    L = SegmentSet.from_segments(extract_segments(ranges, angles, max_range=5.0))
    Lw = b.geometry.to_global(L, truth[20], b.mount)
    C, _, _ = correspondences(b.lines, Lw, truth[20][:2], b.params.correspondence)
    assert sorted(C[C >= 0]) == [0, 2, 3]  # three walls seen: two parallel, one across
    # a wrong local line: segment 0 turned by 5 degrees about its centre (clutter against its wall)
    c = 0.5 * (L.start[0] + L.end[0])
    R = np.array([[np.cos(0.09), -np.sin(0.09)], [np.sin(0.09), np.cos(0.09)]])
    L.start[0], L.end[0] = c + (L.start[0] - c) @ R.T, c + (L.end[0] - c) @ R.T
    predicted = compose(truth[20], [0.04, -0.03, 0.015])
    prior = np.diag([0.05**2, 0.05**2, 0.02**2])
    idx = np.arange(len(b.lines))
    pose, cov, pairs, applied = b.correct(L, predicted, prior, idx)
    assert applied
    err = relative(truth[20], pose)
    assert np.hypot(err[0], err[1]) < 0.01 and abs(err[2]) < np.radians(0.1)
    assert 0 not in pairs[1] and len(pairs[1]) == 2  # the wrong pair fell out at the gate
    assert np.all(np.linalg.eigvalsh(cov) < np.linalg.eigvalsh(prior).max())
    # without the gate the wrong pair drags the pose off
    ungated = CorrectionParams(gate=1e6, registration_xy=0.0, registration_theta=0.0)
    b.params = MapParams(correction=ungated)
    b.corrector.correction = ungated
    pose_ungated, _, _, _ = b.correct(L, predicted, prior, idx)
    assert abs(relative(truth[20], pose_ungated)[2]) > np.radians(1.0)


def test_refit_moves_the_map_with_the_poses():
    room = load_scene("room")
    truth = room.trajectory[:50]
    scans = simulate_scans(room, truth, np.random.default_rng(6))
    b = MapBuilder(PlainGeometry(), MapParams(), max_range=5.0)
    for k, (r, a) in enumerate(scans):
        b.path.append(0.2 * k)
        b.fuse(SegmentSet.from_segments(extract_segments(r, a, max_range=5.0)), truth[k], k)
    sums = b.lines.sums.copy()
    b.refit(truth)
    assert np.allclose(b.lines.sums, sums)  # all the points each line gathered, no more, no less
    assert np.median(map_errors(b.lines.to_segments(), room.walls)) < 0.01
    before = b.lines
    T = np.array([0.3, -0.2, 0.1])  # move every pose rigidly: the map moves with it (3.4)
    b.refit(compose(T, truth))
    moved = PlainGeometry().transform(before, T)
    assert np.allclose(b.lines.start, moved.start, atol=1e-9) and np.allclose(b.lines.end, moved.end, atol=1e-9)


# ---------------------------------------------------------------- loop closure


def _loop_poses(n=40, radius=3.0):
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.mod(a + np.pi / 2 + np.pi, 2 * np.pi) - np.pi])


def test_pose_graph_recovers_consistent_poses():
    truth = _loop_poses()
    g = PoseGraph()
    cov = np.diag([0.01**2, 0.01**2, 0.005**2])
    for k in range(1, len(truth)):
        g.add(k - 1, k, relative(truth[k - 1], truth[k]), cov)
    for i, j in ((0, 39), (5, 25), (12, 33)):
        g.add(i, j, relative(truth[i], truth[j]), cov, loop=True)
    rng = np.random.default_rng(7)
    start = truth + np.vstack([np.zeros(3), np.cumsum(rng.normal(0, [0.05, 0.05, 0.02], (39, 3)), axis=0)])
    out = g.optimize(start, iterations=20, tol=1e-12)
    assert np.allclose(out, truth, atol=1e-8)
    assert g.loops == [(0, 39), (5, 25), (12, 33)]
    assert np.allclose(g.errors(out), 0.0, atol=1e-8)
    with pytest.raises(InvalidInputError, match="PoseGraph.add"):
        g.add(0, 1, [0.1, np.nan, 0.0], cov)


def test_pose_graph_spreads_a_loop_error_and_resists_a_wrong_loop():
    truth = _loop_poses()
    drift = np.array([0.0, 0.0, 0.01])  # each step turns 0.01 rad too much, as odometry with a bias
    chain = [truth[0]]
    for k in range(1, len(truth)):
        chain.append(compose(chain[-1], relative(truth[k - 1], truth[k]) + drift))
    chain = np.array(chain)
    g = PoseGraph()
    step = np.diag([0.02**2, 0.02**2, 0.01**2])
    for k in range(1, len(truth)):
        g.add(k - 1, k, relative(chain[k - 1], chain[k]), step)
    tight = np.diag([0.01**2, 0.01**2, 0.002**2])
    for j in (39, 30, 20):
        g.add(0, j, relative(truth[0], truth[j]), tight, loop=True)
    out = g.optimize(chain, robust=3.0)
    assert pose_errors(out, truth)[0] < 0.2 * pose_errors(chain, truth)[0]
    g.add(10, 35, relative(truth[10], compose(truth[35], [2.0, 1.0, 0.3])), tight, loop=True)  # a false revisit
    with_wrong = g.optimize(chain, robust=3.0)
    assert pose_errors(with_wrong, truth)[0] < 0.3 * pose_errors(chain, truth)[0]
    no_kernel = g.optimize(chain, robust=0.0)
    assert pose_errors(no_kernel, truth)[0] > 2 * pose_errors(with_wrong, truth)[0]


def test_loop_hypotheses_find_a_known_rigid_motion():
    office = load_scene("office")
    centre = np.array([9.0, 7.0])
    walls = office.walls[np.hypot(*(office.walls.mean(axis=1) - centre).T) < 6.0]
    O = SegmentSet.from_segments([Segment(a, b, 100) for a, b in walls])
    phi0, t0 = 0.06, np.array([0.45, -0.3])  # the drifted view: the old lines turned and shifted about centre
    R = np.array([[np.cos(phi0), -np.sin(phi0)], [np.sin(phi0), np.cos(phi0)]])
    Q = SegmentSet((O.start - centre) @ R.T + centre + t0, (O.end - centre) @ R.T + centre + t0, O.sums, O.edge)
    margin = CorrespondenceParams().overlap_margin
    best = loop_hypotheses(PlainGeometry(), Q, O, centre, 0.3, 2.0, LoopParams(), margin)[0]
    _, phi, t = best
    assert np.isclose(phi, -phi0, atol=0.02)  # within the vote's resolution, loop_angle_tol
    assert np.allclose(t, -(R.T @ t0), atol=0.1)


def test_loop_closure_finds_the_room_again_after_a_blind_stretch():
    room = load_scene("room")
    truth = room.trajectory
    rng = np.random.default_rng(0)
    scans = simulate_scans(room, truth, rng)
    odo = simulate_odometry(truth, rng)
    blind = (np.full(len(scans[0][1]), np.inf), scans[0][1])
    scans[40:150] = [blind] * 110  # the laser sees nothing for 7.4 m, beyond active_path: the map goes old
    res = build_map(scans, odo, active_path=5.0)
    lost = build_map(scans, odo, active_path=5.0, loop_closure=False)
    assert res.loops and all(j < 40 < 150 <= k for j, k in res.loops)
    assert pose_errors(res.poses, truth)[0] < 0.05
    assert pose_errors(res.poses, truth)[0] < 0.5 * pose_errors(lost.poses, truth)[0]
    assert np.hypot(*(res.poses[-1, :2] - truth[-1, :2])) < 0.03
    assert np.median(map_errors(res.segments, room.walls)) < 0.015


def test_a_revisit_beyond_the_lasers_reach_of_the_drifted_pose_is_closed():
    # ACES: the robot returns to its start after 170 m; the drifting odometry puts it 21-27 m off by then and the
    # corrected chain about 5 m and 15 degrees off, farther than the old lines the drifted pose can see (8 m).
    # The search then takes the old lines of its whole 3-sigma window; the log's own poses are the truth.
    log = read_carmen_log(data_path("carmen", "aces-corrected.log.gz"))
    truth = log.poses[:262]
    odo = simulate_odometry(log.poses, np.random.default_rng(3))[:262]
    res = build_map(log.scans[:262], odo, max_range=8.0)
    assert any(j < 20 and 240 <= k for j, k in res.loops)  # the start, found again
    assert np.hypot(*(res.poses[-1, :2] - truth[-1, :2])) < 0.1
    assert np.hypot(*(odo[-1, :2] - truth[-1, :2])) > 10.0


def test_intel_log_whole_run_beats_odometry_tenfold():
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    truth = log.poses
    odo = simulate_odometry(truth, np.random.default_rng(1))
    res = build_map(log.scans, odo, max_range=8.0)
    odo_pos, odo_head = pose_errors(odo, truth)
    pos, head = pose_errors(res.poses, truth)
    assert odo_pos / pos >= 10.0 and odo_head / head >= 10.0
    assert len(res.loops) >= 10
    cloud = scans_to_world(log.scans, truth, max_range=8.0, step=3)  # the log's points at the true poses
    err = map_point_errors(res.segments, cloud)
    assert np.median(err) < 0.10 and np.mean(err < 0.25) > 0.8


def test_pose_and_map_errors_closed_form():
    truth = np.zeros((4, 3))
    est = truth + [[0.3, 0.4, 0.1]]
    pos, head = pose_errors(est, truth)
    assert np.isclose(pos, 0.5) and np.isclose(head, 0.1)
    walls = np.array([[[0.0, 0.0], [4.0, 0.0]]])
    d = map_errors([Segment([1.0, 0.03], [2.0, -0.05]), Segment([5.0, 0.0], [6.0, 0.0])], walls)
    assert np.allclose(d, [0.03, 0.05, 1.0, 2.0])
    with pytest.raises(InvalidInputError, match="pose_errors"):
        pose_errors(est[:3], truth)


# ---------------------------------------------------------------- the whole map


def test_build_map_noise_free_recovers_truth_and_walls():
    room = load_scene("room")
    truth = room.trajectory[:90]
    scans = simulate_scans(room, truth)  # no range noise
    res = build_map(scans, truth)  # perfect odometry
    assert res.poses.shape == (90, 3) and np.all(res.corrected[1:])
    assert pose_errors(res.poses, truth)[0] < 1e-3
    assert np.max(map_errors(res.segments, room.walls)) < 0.01
    assert 3 <= len(res.segments) <= 6  # the four walls (a corner may cut one)


def test_build_map_office_meets_the_targets():
    office = load_scene("office")
    rng = np.random.default_rng(7)
    truth = office.trajectory
    scans = simulate_scans(office, truth, rng)
    odo = simulate_odometry(truth, rng)
    res = build_map(scans, odo)
    odo_pos, _ = pose_errors(odo, truth)
    pos, head = pose_errors(res.poses, truth)
    assert odo_pos / pos >= 5.0  # the target: at least 5x below odometry
    assert head < np.radians(1.0)
    assert np.median(map_errors(res.segments, office.walls)) < 0.05
    assert res.corrected[1:].mean() > 0.6  # the rest: rejected by the whole-scan check, or nothing matched


def test_build_map_with_a_mounted_laser():
    room = load_scene("room")
    truth = room.trajectory[:60]
    mount = (0.25, 0.05, 0.1)
    rng = np.random.default_rng(1)
    scans = simulate_scans(room, truth, rng, mount=mount)
    odo = simulate_odometry(truth, rng)
    res = build_map(scans, odo, mount=mount)
    assert pose_errors(res.poses, truth)[0] < 0.25 * pose_errors(odo, truth)[0]
    assert np.median(map_errors(res.segments, room.walls)) < 0.03


def test_build_map_degenerate_scans_give_no_correction_never_nan():
    room = load_scene("room")
    truth = room.trajectory[:30]
    rng = np.random.default_rng(2)
    scans = simulate_scans(room, truth, rng)
    odo = simulate_odometry(truth, rng)
    a = scans[0][1]
    scans[0] = (np.full(361, np.inf), a)  # nothing seen at the start: the map starts later
    scans[10] = (np.full(361, np.inf), a)  # no returns
    scans[11] = (np.full(361, np.nan), a)  # all beams NaN
    r = np.full(361, np.inf)
    r[150:210] = 2.0 / np.cos(a[150:210])  # one wall segment in view
    scans[12] = (r, a)
    res = build_map(scans, odo, adjust=False)  # scan by scan: the blind scans keep their predictions
    assert np.all(np.isfinite(res.poses))
    assert not res.corrected[0] and not res.corrected[10] and not res.corrected[11]
    assert np.allclose(res.poses[10], res.predicted[10]) and np.allclose(res.poses[11], res.predicted[11])
    assert all(np.all(np.isfinite(s.start)) and np.all(np.isfinite(s.end)) for s in res.segments)
    # the final adjustment moves them with their neighbours (through the odometry), never to NaN
    adjusted = build_map(scans, odo)
    assert np.all(np.isfinite(adjusted.poses)) and np.all(np.isfinite(adjusted.predicted))
    step = relative(adjusted.poses[9], adjusted.poses[10])
    assert np.allclose(step, relative(odo[9], odo[10]), atol=0.02)
    # nothing at all: an empty map, the odometry increments as poses
    empty = build_map([(np.full(361, np.inf), a)] * 5, odo[:5])
    assert empty.segments == [] and np.allclose(empty.poses, odo[:5]) and not empty.corrected.any()


def test_build_map_rejects_bad_input():
    room = load_scene("room")
    scans = simulate_scans(room, room.trajectory[:3])
    with pytest.raises(InvalidInputError, match="build_map: scans, odometry: 3 scans but 2"):
        build_map(scans, room.trajectory[:2])
    with pytest.raises(InvalidInputError, match="method"):
        build_map(scans, room.trajectory[:3], method="icp")
    with pytest.raises(InvalidInputError, match="unknown parameter"):
        build_map(scans, room.trajectory[:3], dleta=0.2)
    with pytest.raises(InvalidInputError, match="odometry"):
        build_map(scans, np.zeros((3, 2)))


# ---------------------------------------------------------------- the conformal version (3.13-3.21)

from cga_lessons import conformal as cga  # noqa: E402
from cga_lessons.mapping2d import (  # noqa: E402
    ConformalGeometry,
    c2e,
    e2c,
    laser_motor,
    point_pair_structure,
    robot_motor,
    segment_point_pair,
    sphere_case,
)


def test_e2c_3_13():
    xy = np.array([[3.0, 4.0], [-1.5, 0.25]])
    X = e2c(xy)
    assert np.allclose(X["e1"], xy[:, 0]) and np.allclose(X["e2"], xy[:, 1])
    assert np.allclose((X | cga.einf).scalar(), -1.0)  # normalised: X . e = -1
    assert np.allclose((X | X).scalar(), 0.0)  # a null vector
    assert np.allclose(0.5 * (X["e-"] + X["e+"]), 0.5 * (xy**2).sum(1))  # the (x^2 + y^2)/2 e part
    assert np.allclose(c2e(X), xy)
    with pytest.raises(InvalidInputError, match="e2c"):
        e2c([1.0, 2.0, 3.0])


def test_point_pair_structure_3_14_3_15():
    rng = np.random.default_rng(4)
    for _ in range(20):
        a, b = rng.uniform(-6, 6, (2, 2))
        seg = Segment(a, b)
        d = point_pair_structure(segment_point_pair(seg))
        assert np.allclose(d.start, a) and np.allclose(d.end, b)  # (2.131)
        assert np.isclose(d.rho, seg.rho)  # (3.14)
        assert np.allclose(d.closest_point, seg.closest_point)  # (3.15)
        assert abs(diff_theta(d.theta, seg.theta, np.pi)) < 1e-9
        assert np.allclose(d.abc, seg.abc)


def test_eq_3_15_erratum_printed_sign_gives_the_antipode():
    a, b = np.array([1.0, -1.0, 0.0]), np.array([1.0, 2.0, 0.0])
    L = cga.normalize_line(cga.point_pair(a, b) ^ cga.einf)  # L* = PP* ^ e, normalised (2.126)
    Ls = cga.standard_form(L)
    printed = cga.euclidean(-((L | cga.E) | ((cga.ep | Ls) * cga.IE)))  # (3.15) as printed
    correct = cga.euclidean((L | cga.E) | ((cga.ep | Ls) * cga.IE))
    assert np.allclose(correct, [1.0, 0.0, 0.0]) and np.allclose(printed, [-1.0, 0.0, 0.0])
    assert np.allclose(cga.line_closest_point(L), correct)


def test_laser_motor_3_16_3_18():
    pose, mount = np.array([2.0, -1.0, 0.7]), np.array([0.3, 0.1, 0.0])
    M = laser_motor(pose, mount)
    x = np.array([[1.0, 0.5], [-2.0, 3.0]])
    moved = c2e(M * e2c(x) * ~M)  # (3.18) on points
    lp = compose(pose, mount)
    R = np.array([[np.cos(lp[2]), -np.sin(lp[2])], [np.sin(lp[2]), np.cos(lp[2])]])
    assert np.allclose(moved, x @ R.T + lp[:2])
    # on point pairs, as the map builder uses it: the same as the plain rigid motion (3.4)
    S = SegmentSet.from_segments([Segment(x[0], x[1], 10)])
    a, b = ConformalGeometry().to_global(S, pose, mount), PlainGeometry().to_global(S, pose, mount)
    assert np.allclose(a.start, b.start) and np.allclose(a.end, b.end) and np.allclose(a.sums, b.sums)
    assert np.allclose((robot_motor(pose) * ~robot_motor(pose)).scalar(), 1.0)


def test_laser_motor_erratum_3_17():
    pose, x = np.array([2.0, -1.0, 0.7]), np.array([[1.0, 0.5]])
    turned = np.array([0.3, 0.1, 0.4])  # a laser turned on the robot
    lp = compose(pose, turned)
    R = np.array([[np.cos(lp[2]), -np.sin(lp[2])], [np.sin(lp[2]), np.cos(lp[2])]])
    truth = x @ R.T + lp[:2]
    M_printed, M_correct = laser_motor(pose, turned, printed=True), laser_motor(pose, turned)
    assert np.allclose(c2e(M_correct * e2c(x) * ~M_correct), truth)
    assert not np.allclose(c2e(M_printed * e2c(x) * ~M_printed), truth, atol=1e-3)
    # with a laser facing forward the printed form is right
    straight = np.array([0.3, 0.1, 0.0])
    Mp, Mc = laser_motor(pose, straight, printed=True), laser_motor(pose, straight)
    assert np.allclose(c2e(Mp * e2c(x) * ~Mp), c2e(Mc * e2c(x) * ~Mc))


def test_sphere_cases_3_19():
    g = ([0.0, 0.0], [2.0, 0.0])
    assert sphere_case(*g, [1.5, 0.0], [3.0, 0.0]) == 1  # intersect, continuation of the segment
    assert sphere_case(*g, [0.8, 0.01], [1.2, 0.01]) == 2  # inside, the same segment
    assert sphere_case(*g, [1.0, -0.2], [1.0, 1.6]) == 3  # intersect, another line
    assert sphere_case(*g, [0.9, 0.2], [1.2, 0.3]) == 4  # inside, another line
    assert sphere_case(*g, [3.0, 0.0], [4.0, 0.0]) == 5  # apart
    assert sphere_case(*g, [2.2, 0.0], [3.0, 0.0], margin=0.3) == 1  # the margin joins a small gap


def test_conformal_geometry_equals_plain_geometry():
    rng = np.random.default_rng(5)
    segs = []
    for _ in range(7):
        a = rng.uniform(-5, 5, 2)
        d = rng.uniform(-np.pi, np.pi)
        segs.append(Segment(a, a + rng.uniform(0.3, 3) * np.array([np.cos(d), np.sin(d)]), 20))
    G, L = SegmentSet.from_segments(segs[:4]), SegmentSet.from_segments(segs[4:] + segs[:1])
    P, C = PlainGeometry(), ConformalGeometry()
    c = np.array([0.4, -0.3])
    for f in ("hough",):
        for X in (G, L):
            assert np.allclose(getattr(P, f)(X, c), getattr(C, f)(X, c))
    assert np.array_equal(P.overlap(G, L, 0.3), C.overlap(G, L, 0.3))
    assert np.allclose(P.centre_line_distance(G, L), C.centre_line_distance(G, L))
    assert np.allclose(P.moment_difference(G, L, c), C.moment_difference(G, L, c))
    assert np.isclose(P.distance([1.0, 2.0], [4.0, 6.0]), C.distance([1.0, 2.0], [4.0, 6.0]))
    A, B = G.take([0, 1, 2, 3, 0]), L.take([0, 1, 2, 3, 3])
    for margin in (0.0, 0.3):
        assert np.array_equal(P.overlap_rows(A, B, margin), C.overlap_rows(A, B, margin))
        assert np.array_equal(P.overlap_rows(A, B, margin), np.diag(P.overlap(A, B, margin)))
    assert np.allclose(P.centre_line_distance_rows(A, B), C.centre_line_distance_rows(A, B))
    assert np.allclose(P.centre_line_distance_rows(A, B), np.diag(P.centre_line_distance(A, B)))
    poses, mount = rng.uniform(-3, 3, (len(A), 3)), np.array([0.2, -0.1, 0.3])
    a, b = P.to_global_rows(A, poses, mount), C.to_global_rows(A, poses, mount)
    assert np.allclose(a.start, b.start) and np.allclose(a.end, b.end) and np.allclose(a.sums, b.sums)
    one = P.to_global(A.take([2]), poses[2], mount)  # row by row: the rigid motion (3.4) of each pose
    assert np.allclose(one.start, a.start[2]) and np.allclose(one.sums, a.sums[2])


def test_fuse_ends_3_20_3_21():
    P, C = PlainGeometry(), ConformalGeometry()
    cases = [
        (([0.0, 0.0], [3.0, 0.0]), ([2.0, 0.0], [4.0, 0.0])),  # extends the end
        (([0.0, 0.0], [3.0, 0.0]), ([4.0, 0.0], [2.0, 0.0])),  # opposite sense: ends swapped (3.20-3.21)
        (([0.0, 0.0], [3.0, 0.0]), ([1.0, 0.0], [2.0, 0.0])),  # inside: nothing changes
        (([1.0, 0.0], [2.0, 0.0]), ([-1.0, 0.0], [3.0, 0.0])),  # the local one is longer
    ]
    expect = [([0, 0], [4, 0]), ([4, 0], [0, 0]), ([0, 0], [3, 0]), ([-1, 0], [3, 0])]
    for (g, l), (s, e) in zip(cases, expect):
        a = P.fuse_ends(np.array(g[0]), np.array(g[1]), np.array(l[0]), np.array(l[1]))
        b = C.fuse_ends(np.array(g[0]), np.array(g[1]), np.array(l[0]), np.array(l[1]))
        assert np.allclose(a[0], s) and np.allclose(a[1], e)
        assert np.allclose(a[0], b[0]) and np.allclose(a[1], b[1]) and a[2:] == b[2:]


def test_plain_and_conformal_build_the_same_map():
    office = load_scene("office")
    rng = np.random.default_rng(3)
    truth = office.trajectory[:30]
    scans = simulate_scans(office, truth, rng)
    odo = simulate_odometry(truth, rng)
    a = build_map(scans, odo, method="plain")
    b = build_map(scans, odo, method="conformal")
    assert b.method == "conformal" and np.allclose(a.poses, b.poses, atol=1e-9)
    assert len(a.segments) == len(b.segments) > 3
    for s, t in zip(a.segments, b.segments):
        assert np.allclose(s.start, t.start, atol=1e-8) and np.allclose(s.end, t.end, atol=1e-8)
    assert np.array_equal(a.n_matches, b.n_matches) and np.array_equal(a.corrected, b.corrected)


@pytest.mark.parametrize("method", ["plain", "conformal"])
def test_a_log_placed_a_thousand_kilometres_away_maps_as_at_the_origin(method):
    """The builder works near its first pose: map coordinates of 1e6 m (a UTM-like frame) give the same poses."""
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    scans, truth = log.scans[:25], log.poses[:25]
    far = truth + np.array([1e6, -2e6, 0.0])
    near = build_map(scans, truth, method=method, max_range=8.0, adjust=False)
    away = build_map(scans, far, method=method, max_range=8.0, adjust=False)
    # the builder subtracts a multiple of 1024 m: the rest of the offset (576 m and 128 m here) leaves micrometres
    np.testing.assert_allclose(away.poses - [1e6, -2e6, 0.0], near.poses, atol=1e-4)
    assert len(away.segments) == len(near.segments)
    np.testing.assert_allclose(away.segments[0].start - [1e6, -2e6], near.segments[0].start, atol=1e-4)
    # the final adjustment works near the first pose too; its robust rounds stop when the poses move less than
    # 1 mm and 0.3 mrad a round, and converge about a third a round, so two starts micrometres apart end within
    # millimetres (at 1e6 m without the shift, eps |x| alone would be 0.2 nm; the conformal entities' |x|^2 far more)
    near = build_map(scans, truth, method=method, max_range=8.0)
    away = build_map(scans, far, method=method, max_range=8.0)
    np.testing.assert_allclose(away.poses[:, :2] - [1e6, -2e6], near.poses[:, :2], atol=1e-2)
    np.testing.assert_allclose(away.poses[:, 2], near.poses[:, 2], atol=2e-3)
