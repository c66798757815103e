"""Tests of cga_lessons.mapping2d.trajectories: ATE, RPE per metre, TUM files.

Independent truths: closed forms (a trajectory shifted by a known offset, odometry that turns a known angle too far
each step or overshoots each step by a known factor) and evo, the field's own evaluation tool, as the peer library
(the same trajectories through its APE/RPE, and its TUM reader on the files written here).
"""

import math

import numpy as np
import pytest
from evo.core import metrics
from evo.core.trajectory import PoseTrajectory3D
from evo.tools import file_interface

from cga_lessons import data_path
from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import compose, laser, read_carmen_log, wrap_angle, write_tum
from cga_lessons.mapping2d.trajectories import (
    AbsoluteTrajectoryError,
    RelativePoseError,
    absolute_trajectory_error,
    odometry_repeats_poses,
    relative_pose_error,
)
from cga_lessons.mapping2d.tum import TrajectoryFileExistsError, read_tum

LOGS = ("intel", "aces", "csail", "freiburg-101", "seattle", "orebro")


def evo_trajectory(poses, timestamps=None):
    """A planar trajectory as evo holds it: z = 0 and the quaternion of the yaw (w, x, y, z)."""
    p = np.asarray(poses, float)
    xyz = np.column_stack([p[:, :2], np.zeros(len(p))])
    quat = np.column_stack([np.cos(p[:, 2] / 2), np.zeros((len(p), 2)), np.sin(p[:, 2] / 2)])
    ts = np.arange(len(p), dtype=float) if timestamps is None else np.asarray(timestamps, float)
    return PoseTrajectory3D(positions_xyz=xyz, orientations_quat_wxyz=quat, timestamps=ts)


def odometry_walk(steps):
    """Poses from composing increments (x, y, theta) from the origin."""
    out = [np.zeros(3)]
    for inc in steps:
        out.append(compose(out[-1], inc))
    return np.array(out)


@pytest.fixture(scope="module")
def wander():
    """A truth that wanders (random turns, 0.2-0.6 m steps) and a drifting estimate of it (the odometry model)."""
    rng = np.random.default_rng(3)
    inc = np.column_stack([rng.uniform(0.2, 0.6, 150), rng.normal(0, 0.02, 150), rng.normal(0, 0.3, 150)])
    truth = odometry_walk(inc)
    truth[:, 2] = wrap_angle(truth[:, 2])
    est = laser.simulate_odometry(truth, np.random.default_rng(4))
    return truth, est


# --------------------------------------------------------------------------- ATE


def test_ate_of_a_shifted_trajectory_is_the_shift():
    truth = odometry_walk([[0.5, 0.0, 0.2]] * 30)
    ate = absolute_trajectory_error(truth + [0.3, -0.4, 0.0], truth)
    assert isinstance(ate, AbsoluteTrajectoryError) and ate.n_poses == 31 and ate.align == "none"
    assert ate.position_rmse == pytest.approx(0.5, abs=1e-12) and ate.heading_rmse == 0.0
    turned = truth + [0.0, 0.0, 0.1]
    turned[0, 2] = truth[0, 2] - 0.1  # the sign does not matter, a wrap across pi neither
    turned[5, 2] = truth[5, 2] + 0.1 - 2 * np.pi
    ate = absolute_trajectory_error(turned, truth)
    assert ate.position_rmse == 0.0 and ate.heading_rmse == pytest.approx(0.1, abs=1e-12)
    with pytest.raises(AttributeError):  # frozen
        ate.position_rmse = 0.0


def test_ate_se2_alignment_undoes_a_rigid_motion():
    truth = odometry_walk([[0.5, 0.0, 0.2], [0.4, 0.1, -0.1]] * 20)
    motion = np.array([2.0, -1.0, 0.7])
    moved = compose(motion, truth)  # the whole trajectory in another frame
    assert absolute_trajectory_error(moved, truth).position_rmse > 1.0
    ate = absolute_trajectory_error(moved, truth, align="se2")
    assert ate.position_rmse < 1e-12 and ate.heading_rmse < 1e-12
    assert np.allclose(compose(ate.alignment, motion), 0.0, atol=1e-12)  # the inverse motion


def test_ate_equals_evos_ape(wander):
    truth, est = wander
    ate = absolute_trajectory_error(est, truth)
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((evo_trajectory(truth), evo_trajectory(est)))
    rot = metrics.APE(metrics.PoseRelation.rotation_angle_rad)
    rot.process_data((evo_trajectory(truth), evo_trajectory(est)))
    assert ate.position_rmse > 0.5  # the odometry drifted: a test that can fail
    assert ate.position_rmse == pytest.approx(ape.get_statistic(metrics.StatisticsType.rmse), rel=1e-12)
    assert ate.heading_rmse == pytest.approx(rot.get_statistic(metrics.StatisticsType.rmse), rel=1e-9)
    # with alignment: evo's Umeyama alignment (SE(3), no scale) of planar data is the plane's
    aligned = evo_trajectory(est)
    aligned.align(evo_trajectory(truth))
    ape = metrics.APE(metrics.PoseRelation.translation_part)
    ape.process_data((evo_trajectory(truth), aligned))
    ate_aligned = absolute_trajectory_error(est, truth, align="se2")
    assert ate_aligned.position_rmse < ate.position_rmse
    assert ate_aligned.position_rmse == pytest.approx(ape.get_statistic(metrics.StatisticsType.rmse), rel=1e-9)


# --------------------------------------------------------------------------- RPE


def test_rpe_of_a_known_turn_error_per_step():
    truth = odometry_walk([[1.0, 0.0, 0.0]] * 10)  # straight ahead, 1 m a step
    est = odometry_walk([[1.0, 0.0, 0.01]] * 10)  # the odometer turns 0.01 rad too far each step
    rpe = relative_pose_error(est, truth, delta=1.0)
    assert isinstance(rpe, RelativePoseError) and rpe.pairs == tuple((k, k + 1) for k in range(10))
    assert rpe.heading_per_metre == pytest.approx(0.01, abs=1e-12)
    assert rpe.translation_per_metre == pytest.approx(0.0, abs=1e-12)
    # over 2 m segments: 0.02 rad, and the second metre runs 0.01 rad off the straight line
    rpe = relative_pose_error(est, truth, delta=2.0)
    assert rpe.lengths == (2.0,) * 5 and rpe.heading_per_metre == pytest.approx(0.01, abs=1e-12)
    assert rpe.translation_per_metre == pytest.approx(math.sin(0.005), abs=1e-12)  # |(1, 0) - R(0.01) (1, 0)| / 2
    assert rpe.translation_rmse == pytest.approx(2 * math.sin(0.005), abs=1e-12)


def test_rpe_of_a_known_scale_error_and_uneven_steps():
    steps = np.array([0.3, 0.5, 0.4, 0.2, 0.9, 0.1, 0.6])
    truth = odometry_walk([[d, 0.0, 0.0] for d in steps])
    est = odometry_walk([[1.1 * d, 0.0, 0.0] for d in steps])  # every step overshoots by 10 %
    rpe = relative_pose_error(est, truth, delta=0.75)
    # segments end where the travelled path first reaches 0.75 m: 0.3+0.5, 0.4+0.2+0.9, 0.1+0.6 is short
    assert rpe.pairs == ((0, 2), (2, 5)) and np.allclose(rpe.lengths, [0.8, 1.5])
    assert rpe.translation_per_metre == pytest.approx(0.1, abs=1e-12) and rpe.heading_per_metre == 0.0
    assert rpe.translation_rmse == pytest.approx(math.sqrt((0.08**2 + 0.15**2) / 2), abs=1e-12)


@pytest.mark.parametrize("delta", [1.0, 2.5])
def test_rpe_equals_evos_rpe(wander, delta):
    truth, est = wander
    rpe = relative_pose_error(est, truth, delta=delta)
    ref, e = evo_trajectory(truth), evo_trajectory(est)
    found = {}
    for relation in (metrics.PoseRelation.translation_part, metrics.PoseRelation.rotation_angle_rad):
        m = metrics.RPE(
            relation, delta=delta, delta_unit=metrics.Unit.meters, all_pairs=False, pairs_from_reference=True
        )
        m.process_data((ref, e))
        found[relation] = m
    m = found[metrics.PoseRelation.translation_part]
    assert [j for _, j in rpe.pairs] == list(m.delta_ids) and len(rpe.pairs) > 20
    assert rpe.translation_rmse > 0.01  # drift: a test that can fail
    assert rpe.translation_rmse == pytest.approx(m.get_statistic(metrics.StatisticsType.rmse), rel=1e-9)
    per_metre = np.sqrt(np.mean((m.error / np.array(rpe.lengths)) ** 2))
    assert rpe.translation_per_metre == pytest.approx(per_metre, rel=1e-9)
    m = found[metrics.PoseRelation.rotation_angle_rad]
    assert rpe.heading_rmse == pytest.approx(m.get_statistic(metrics.StatisticsType.rmse), rel=1e-9)
    assert rpe.heading_per_metre == pytest.approx(np.sqrt(np.mean((m.error / np.array(rpe.lengths)) ** 2)), rel=1e-9)


# --------------------------------------------------------------------------- TUM files


def test_tum_round_trip_and_evo_reads_it(tmp_path, wander):
    truth, _ = wander
    ts = 1.13486e9 + 0.2 * np.arange(len(truth))
    path = write_tum(tmp_path / "truth.tum", truth, ts)
    poses, back_ts = read_tum(path)
    assert np.array_equal(back_ts, ts) and np.array_equal(poses[:, :2], truth[:, :2])
    assert np.allclose(wrap_angle(poses[:, 2] - truth[:, 2]), 0.0, atol=1e-12)
    traj = file_interface.read_tum_trajectory_file(str(path))
    assert traj.check()[0] and np.array_equal(traj.timestamps, ts)
    assert np.allclose(traj.positions_xyz, np.column_stack([truth[:, :2], np.zeros(len(truth))]), atol=0)
    yaw = np.array([2 * math.atan2(q[3], q[0]) for q in traj.orientations_quat_wxyz])
    assert np.allclose(wrap_angle(yaw - truth[:, 2]), 0.0, atol=1e-12)
    assert [p.name for p in tmp_path.iterdir()] == ["truth.tum"]  # no temporary file left
    assert oct(path.stat().st_mode & 0o777) != oct(0o600)  # an ordinary file, not mkstemp's private one


def test_tum_refuses_to_overwrite(tmp_path):
    path = tmp_path / "t.tum"
    path.write_text("mine\n")
    with pytest.raises(TrajectoryFileExistsError, match=r"write_tum: path: .* exists") as exc:
        write_tum(path, [[0, 0, 0]], [0.0])
    assert isinstance(exc.value, ValueError) and isinstance(exc.value, FileExistsError)
    assert path.read_text() == "mine\n" and [p.name for p in tmp_path.iterdir()] == ["t.tum"]
    write_tum(path, [[1, 2, 0.5]], [3.0], overwrite=True)
    poses, ts = read_tum(path)
    assert np.allclose(poses, [[1, 2, 0.5]]) and ts.tolist() == [3.0]


@pytest.mark.parametrize(
    "poses, stamps, message",
    [
        ([[0, 0]], [0.0], "poses: expected shape (N, 3), got (1, 2)"),
        (np.zeros((0, 3)), [], "poses: expected at least 1 rows, got 0"),
        ([[0, np.nan, 0]], [0.0], "poses: contains NaN or inf"),
        ([[0, 0, 0], [1, 0, 0]], [0.0], "timestamps: expected shape (2,), got (1,)"),
        ([[0, 0, 0], [1, 0, 0]], [0.0, np.inf], "timestamps: contains NaN or inf"),
        ([[0, 0, 0], [1, 0, 0]], [1.0, 1.0], "timestamps: must increase strictly"),
        ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [0.0, 2.0, 1.0], "timestamps[2] = 1.0 follows 2.0"),
    ],
)
def test_write_tum_bad_inputs(tmp_path, poses, stamps, message):
    with pytest.raises(InvalidInputError, match="^write_tum: ") as exc:
        write_tum(tmp_path / "t.tum", poses, stamps)
    assert message in str(exc.value) and list(tmp_path.iterdir()) == []


def test_write_tum_missing_folder_and_bad_keyword(tmp_path):
    with pytest.raises(InvalidInputError, match="write_tum: path: no such folder"):
        write_tum(tmp_path / "nowhere" / "t.tum", [[0, 0, 0]], [0.0])
    with pytest.raises(InvalidInputError, match="write_tum: overwrite: must be True or False, got 'yes'"):
        write_tum(tmp_path / "t.tum", [[0, 0, 0]], [0.0], overwrite="yes")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "text, message",
    [
        ("", "holds no pose"),
        ("# only a comment\n\n", "holds no pose"),
        ("0 0 0 0 0 0 1\n", "line 1: expected 8 numbers"),
        ("# c\n0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1 9\n", "line 3: expected 8 numbers"),
        ("0 0 0 0 0 0 0 one\n", "line 1: not a number"),
        ("0 0 nan 0 0 0 0 1\n", "line 1: NaN or inf"),
        ("0 0 0 0 0 0 0 2\n", "line 1: the quaternion is not a unit quaternion"),
        ("0 0 0 0.5 0 0 0 1\n", "line 1: not a planar pose"),
        ("0 0 0 0 0.6 0 0 0.8\n", "line 1: not a planar pose"),
        ("0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n", "line 3: timestamp 1.0 does not increase"),
    ],
)
def test_read_tum_malformed_files_name_the_file_and_line(tmp_path, text, message):
    path = tmp_path / "bad.tum"
    path.write_text(text)
    with pytest.raises(InvalidInputError, match="^read_tum: path: bad.tum") as exc:
        read_tum(path)
    assert message in str(exc.value)


def test_read_tum_missing_file(tmp_path):
    with pytest.raises(InvalidInputError, match="read_tum: path: no such file"):
        read_tum(tmp_path / "missing.tum")


# --------------------------------------------------------------------------- bad inputs


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda t: absolute_trajectory_error(t[:, :2], t), "absolute_trajectory_error: poses: expected shape (N, 3)"),
        (lambda t: absolute_trajectory_error(t, t[:-1]), "absolute_trajectory_error: poses, truth: must have the same"),
        (lambda t: absolute_trajectory_error(t, t + [0, np.nan, 0]), "absolute_trajectory_error: truth: contains NaN"),
        (lambda t: absolute_trajectory_error(t + [np.inf, 0, 0], t), "absolute_trajectory_error: poses: contains NaN"),
        (lambda t: absolute_trajectory_error(t, t, align="sim3"), "absolute_trajectory_error: align: must be one of"),
        (lambda t: absolute_trajectory_error("abc", t), "absolute_trajectory_error: poses: must be numbers"),
        (lambda t: relative_pose_error(t, t, delta=0), "relative_pose_error: delta: must be > 0.0"),
        (lambda t: relative_pose_error(t, t, delta=np.nan), "relative_pose_error: delta: is NaN or inf"),
        (lambda t: relative_pose_error(t, t, delta="1"), "relative_pose_error: delta: must be a real number"),
        (lambda t: relative_pose_error(t, t, delta=100.0), "relative_pose_error: truth, delta: truth travels 5.000 m"),
        (lambda t: relative_pose_error(t[:1], t[:1]), "relative_pose_error: truth, delta: truth travels 0.000 m"),
        (lambda t: relative_pose_error(t[:, :2], t), "relative_pose_error: poses: expected shape (N, 3)"),
        (lambda t: odometry_repeats_poses(t), "odometry_repeats_poses: log: must have poses and odometry"),
    ],
)
def test_bad_inputs_raise_invalid_input_naming_function_and_argument(call, message):
    truth = odometry_walk([[1.0, 0.0, 0.0]] * 5)
    with pytest.raises(InvalidInputError) as exc:
        call(truth)
    assert isinstance(exc.value, ValueError) and str(exc.value).startswith(message)


# --------------------------------------------------------------------------- logs


@pytest.mark.parametrize("name", LOGS)
def test_the_corrected_logs_repeat_their_poses_as_odometry(name):
    log = read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
    assert odometry_repeats_poses(log)
    # one odometry pose moved by a millimetre, or turned by a milliradian, and they no longer repeat
    log.odometry[len(log) // 2, 0] += 1e-3
    assert not odometry_repeats_poses(log)
    log.odometry[len(log) // 2, 0] -= 1e-3
    log.odometry[-1, 2] += 1e-3
    assert not odometry_repeats_poses(log)


def test_simulated_odometry_does_not_repeat_the_poses():
    from types import SimpleNamespace

    truth = odometry_walk([[0.5, 0.0, 0.1]] * 20)
    odo = laser.simulate_odometry(truth, np.random.default_rng(0))
    assert not odometry_repeats_poses(SimpleNamespace(poses=truth, odometry=odo))
    with pytest.raises(
        InvalidInputError, match="odometry_repeats_poses: log.poses, log.odometry: must have the same length"
    ):
        odometry_repeats_poses(SimpleNamespace(poses=truth, odometry=odo[:-1]))
    with pytest.raises(InvalidInputError, match="odometry_repeats_poses: tol: must be >= 0.0"):
        odometry_repeats_poses(SimpleNamespace(poses=truth, odometry=odo), tol=-1)


def test_the_data_folder_holds_the_six_logs_with_their_provenance():
    readme = data_path("carmen", "README.md").read_text()
    for name in LOGS:
        assert data_path("carmen", f"{name}-corrected.log.gz").is_file()
        assert f"`{name}-corrected.log.gz`" in readme
    assert "acschaefer/ple" in readme
