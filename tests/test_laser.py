"""Tests of the laser simulator, odometry model and CARMEN log reader (cga_lessons.mapping2d.laser)."""

import gzip

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons import data_path
from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import compose, invert, read_carmen_log, relative, wrap_angle
from cga_lessons.mapping2d.laser import OdometryModel, Scene, beam_angles, load_scene, simulate_odometry, simulate_scan

poses = st.tuples(
    st.floats(-20, 20, allow_nan=False), st.floats(-20, 20, allow_nan=False), st.floats(-np.pi, np.pi)
).map(np.array)


@given(poses, poses)
@settings(max_examples=60, deadline=None)
def test_compose_invert_relative_roundtrip(a, b):
    assert np.allclose(compose(a, relative(a, b))[:2], b[:2], atol=1e-9)
    assert abs(wrap_angle(compose(a, relative(a, b))[2] - b[2])) < 1e-9
    ident = compose(a, invert(a))
    assert np.allclose(ident[:2], 0, atol=1e-9) and abs(wrap_angle(ident[2])) < 1e-9


def test_compose_is_the_rigid_motion_3_4():
    # v' = R(theta) v + T, closed form for a quarter turn
    assert np.allclose(compose([2.0, 1.0, np.pi / 2], [1.0, 0.5, 0.0]), [1.5, 2.0, np.pi / 2])


def test_beam_angles_are_the_robots_laser():
    a = beam_angles()
    assert a.shape == (361,)
    assert np.isclose(a[0], -np.pi / 2) and np.isclose(a[-1], np.pi / 2)
    assert np.allclose(np.diff(a), np.radians(0.5))


def test_simulate_scan_closed_form_ranges_in_the_room():
    room = load_scene("room")  # inner walls x = 0, 6 and y = 0, 4
    r, a = simulate_scan(room, [3.0, 2.0, 0.0])
    assert np.isclose(r[180], 3.0)  # ahead: east wall
    assert np.isclose(r[0], 2.0) and np.isclose(r[-1], 2.0)  # right and left
    i45 = np.argmin(abs(a - np.pi / 4))
    assert np.isclose(r[i45], 2 * np.sqrt(2))  # hits (5, 4)
    # general beam: distance to the first wall crossed, computed independently
    for i in range(0, 361, 7):
        c, s = np.cos(a[i]), np.sin(a[i])
        t = [
            d
            for d in (
                (6 - 3) / c if c > 1e-12 else np.inf,
                (4 - 2) / s if s > 1e-12 else np.inf,
                (0 - 2) / s if s < -1e-12 else np.inf,
            )
            if d > 0
        ]
        assert np.isclose(r[i], min(t))


def test_simulate_scan_range_limit_noise_and_mount():
    office = load_scene("office")
    pose = np.array([12.0, 7.0, 0.0])  # middle of the long corridor: ahead is far
    r, _ = simulate_scan(office, pose, max_range=5.0)
    assert np.isinf(r[180]) and np.all(r[np.isfinite(r)] <= 5.0)
    clean, _ = simulate_scan(office, pose, max_range=50.0)
    noisy, _ = simulate_scan(office, pose, np.random.default_rng(3), max_range=50.0, range_noise=0.01)
    err = noisy - clean
    assert abs(np.std(err) - 0.01) < 0.002 and abs(np.mean(err)) < 0.002
    # a laser mounted 0.3 m ahead of the robot sees what a robot 0.3 m ahead sees
    m1, _ = simulate_scan(office, pose, mount=(0.3, 0.0, 0.2))
    m2, _ = simulate_scan(office, compose(pose, [0.3, 0.0, 0.2]))
    assert np.array_equal(np.isinf(m1), np.isinf(m2)) and np.allclose(m1[np.isfinite(m1)], m2[np.isfinite(m2)])


def test_simulate_scan_empty_world_has_no_returns():
    r, a = simulate_scan(np.zeros((0, 2, 2)), [0.0, 0.0, 0.0])
    assert r.shape == a.shape == (361,) and np.all(np.isinf(r))


def test_simulate_scan_rejects_bad_pose():
    with pytest.raises(InvalidInputError, match="simulate_scan"):
        simulate_scan(load_scene("room"), [1.0, np.nan, 0.0])


@pytest.mark.parametrize("name", ["room", "corridor", "office"])
def test_bundled_scenes_trajectories_stay_in_free_space(name):
    scene = load_scene(name)
    assert scene.trajectory.shape[1] == 3 and len(scene.trajectory) > 50
    for pose in scene.trajectory[::10]:
        r, _ = simulate_scan(scene, pose, n_beams=73, fov=2 * np.pi * 72 / 73)
        assert np.nanmin(r) > 0.15  # the robot never touches an obstacle
    steps = np.hypot(*np.diff(scene.trajectory[:, :2], axis=0).T)
    assert steps.max() < 0.26


def test_odometry_model_noise_free_and_pure_bias():
    traj = load_scene("room").trajectory
    rng = np.random.default_rng(0)
    quiet = OdometryModel(0.0, 0.0, 0.0, 0.0)
    odo = simulate_odometry(traj, rng, quiet)
    assert np.allclose(odo[:, :2], traj[:, :2], atol=1e-9)
    assert np.allclose(wrap_angle(odo[:, 2] - traj[:, 2]), 0, atol=1e-9)
    # a pure heading bias: the heading error is bias x distance travelled
    bias = OdometryModel(0.0, 0.0, 0.0, 0.01)
    odo = simulate_odometry(traj, rng, bias)
    dist = np.concatenate([[0], np.cumsum(np.hypot(*np.diff(traj[:, :2], axis=0).T))])
    assert np.allclose(wrap_angle(odo[:, 2] - traj[:, 2]), wrap_angle(0.01 * dist), atol=1e-9)


def test_odometry_drift_statistics():
    # straight 10 m line in 0.1 m steps: heading error variance sigma_h^2 * 10
    traj = np.column_stack([np.linspace(0, 10, 101), np.zeros(101), np.zeros(101)])
    model = OdometryModel(sigma_xy=0.0, sigma_heading=0.02, sigma_turn=0.0, heading_bias=0.0)
    rng = np.random.default_rng(1)
    final = np.array([simulate_odometry(traj, rng, model)[-1, 2] for _ in range(400)])
    assert abs(np.std(final) - 0.02 * np.sqrt(10)) < 0.01
    assert simulate_odometry(traj, rng)[0].tolist() == traj[0].tolist()
    with pytest.raises(InvalidInputError, match="rng"):
        simulate_odometry(traj, None)


def test_read_carmen_log_intel():
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    assert len(log) == 910 and log.ranges.shape == (910, 180)
    assert np.isclose(log.angles[0], -np.pi / 2) and np.allclose(np.diff(log.angles), np.pi / 180)
    assert np.isinf(log.ranges).any() and np.all(log.ranges[np.isfinite(log.ranges)] < 80)
    assert np.allclose(log.poses[0], [0.600266, -0.0320327, -0.354665])
    assert len(log.scans) == 910 and log.scans[3][0].shape == (180,)


def _write(tmp_path, text, name="log.txt"):
    p = tmp_path / name
    if name.endswith(".gz"):
        with gzip.open(p, "wt") as f:
            f.write(text)
    else:
        p.write_text(text)
    return p


GOOD = "FLASER 3 1.0 2.0 81.9 0.5 0.25 0.1 0.5 0.25 0.1 12.5 host 12.5\n"


def test_read_carmen_log_plain_and_gzip(tmp_path):
    for name in ("a.log", "a.log.gz"):
        log = read_carmen_log(_write(tmp_path, "# comment\nODOM 0 0 0 0 0 0 0 x 0\n" + GOOD * 2, name))
        assert log.ranges.shape == (2, 3) and np.isinf(log.ranges[0, 2])
        assert np.allclose(log.poses[1], [0.5, 0.25, 0.1]) and np.allclose(log.angles, [-np.pi / 2, 0, np.pi / 2])


@pytest.mark.parametrize(
    "bad, match",
    [
        ("FLASER 3 1.0 2.0 3.0 0.5 0.25\n", "line 2.*truncated"),
        ("FLASER 3 1.0 2.0 abc 0.5 0.25 0.1 0.5 0.25 0.1 12.5 host 12.5\n", "line 2.*non-numeric"),
        ("FLASER x\n", "line 2.*beam count"),
        ("FLASER 4 1.0 2.0 3.0 4.0 0.5 0.25 0.1 0.5 0.25 0.1 12.5 host 12.5\n", "line 2.*4 beams"),
        ("FLASER 3 1.0 2.0 nan 0.5 0.25 0.1 0.5 0.25 0.1 12.5 host 12.5\n", "line 2.*non-finite"),
    ],
)
def test_read_carmen_log_malformed_line_names_the_line(tmp_path, bad, match):
    with pytest.raises(InvalidInputError, match=match):
        read_carmen_log(_write(tmp_path, GOOD + bad + GOOD))


def test_read_carmen_log_finds_the_drivers_no_return_value(tmp_path):
    """A value the driver writes for "no return" (here 50.00 m, as in ACES's log) becomes inf; a real far wall
    read once stays; the raw values are kept with detect_codes=False."""
    walls = 49.6 + 0.01 * np.arange(12)  # a far wall, read at a different distance in each scan
    text = "".join(f"FLASER 4 1.0 {w:.2f} 50.0 2.0 0 0 0 0 0 0 1 host 1\n" for w in walls)
    log = read_carmen_log(_write(tmp_path, text))
    assert log.no_return_codes == (50.0,)
    assert np.isinf(log.ranges[:, 2]).all() and np.allclose(log.ranges[:, 1], walls)
    raw = read_carmen_log(_write(tmp_path, text), detect_codes=False)
    assert raw.no_return_codes == () and np.allclose(raw.ranges[:, 2], 50.0)
    few = read_carmen_log(_write(tmp_path, "".join(text.splitlines(keepends=True)[:3])))  # 50 m in 3 beams: a wall
    assert few.no_return_codes == () and np.isfinite(few.ranges).all()


def test_the_bundled_logs_no_return_values_read_from_their_files():
    """Counted in the files' own text: ACES writes 50.00 in 620 beams, Örebro the SICK codes 32.759-32.767 m."""
    for name, codes in (("aces", {50.0}), ("orebro", {32.759, 32.763, 32.765, 32.767})):
        with gzip.open(data_path("carmen", f"{name}-corrected.log.gz"), "rt") as f:
            fields = [line.split() for line in f if line.startswith("FLASER")]
        raw = [t[2 : 2 + int(t[1])] for t in fields]
        n_code = sum(float(v) in codes for r in raw for v in r)
        log = read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
        n_raw_inf = sum(float(v) >= 80 or float(v) <= 0 for r in raw for v in r)
        assert int(np.isinf(log.ranges).sum()) == n_raw_inf + n_code
        assert n_code == {"aces": 620, "orebro": 968}[name]


def test_read_carmen_log_empty_or_missing(tmp_path):
    with pytest.raises(InvalidInputError, match="no FLASER"):
        read_carmen_log(_write(tmp_path, "PARAM a 1 x 0\n"))
    with pytest.raises(InvalidInputError, match="no such file"):
        read_carmen_log(tmp_path / "missing.log")


def test_scene_rejects_bad_polygon():
    with pytest.raises(InvalidInputError, match="polygon 0"):
        Scene("bad", [[[0.0, 0.0]]], np.zeros((1, 3)))
