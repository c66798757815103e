"""Scan registration by closest points and motors, against the simulator's true poses and a log's corrected poses."""

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.mapping2d import laser, read_carmen_log, relative, wrap_angle
from cga_lessons.mapping2d.scan_registration import IcpParams, register_scans


def _points(scan, max_range=np.inf):
    r, a = scan
    r = np.asarray(r, float)
    m = np.isfinite(r) & (r < max_range)
    return np.column_stack([r[m] * np.cos(np.asarray(a)[m]), r[m] * np.sin(np.asarray(a)[m])])


@pytest.mark.parametrize("scene_name", ["room", "office"])
def test_simulated_scans_register_to_the_true_relative_pose(scene_name):
    scene = laser.load_scene(scene_name)
    rng = np.random.default_rng(5)
    traj = scene.trajectory
    errors = []
    for k in range(0, len(traj) - 1, max(1, len(traj) // 12)):
        a, b = traj[k], traj[k + 1]
        scans = [laser.simulate_scan(scene, p, rng, range_noise=0.01) for p in (a, b)]
        truth = relative(a, b)
        start = truth + np.array([0.08, -0.06, np.radians(3.0)])  # an odometry guess off by 10 cm and 3 degrees
        reg = register_scans(_points(scans[1]), _points(scans[0]), initial=start)
        e = reg.pose - truth
        errors.append((np.hypot(e[0], e[1]), abs(wrap_angle(e[2]))))
    errors = np.array(errors)
    # 1 cm range noise over hundreds of beams: the fit is good to millimetres and tenths of a degree.  Where the
    # scan sees parallel walls only, the position along them is not observable and stays near the start (10 cm
    # off): so the median position, and every heading.
    assert np.median(errors[:, 0]) < 0.01
    assert np.max(errors[:, 1]) < np.radians(0.3)


def test_a_real_log_heading_is_recovered_better_than_the_odometry_guess():
    """Intel's consecutive scans from a drifting odometry guess: the registration's heading beats the guess's."""
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    truth = log.poses[:120]
    odo = laser.simulate_odometry(truth, np.random.default_rng(0))
    better = []
    for k in range(0, 119, 2):
        guess = relative(odo[k], odo[k + 1])
        true = relative(truth[k], truth[k + 1])
        reg = register_scans(_points(log.scans[k + 1], 8.0), _points(log.scans[k], 8.0), initial=guess)
        better.append(abs(wrap_angle(reg.pose[2] - true[2])) < abs(wrap_angle(guess[2] - true[2])))
    assert np.mean(better) > 0.6


def test_bad_input_names_the_function_and_the_argument():
    pts = np.random.default_rng(1).normal(size=(50, 2))
    with pytest.raises(InvalidInputError, match="register_scans: source: expected shape"):
        register_scans(np.zeros((5, 3)), pts)
    with pytest.raises(InvalidInputError, match="register_scans: target: contains NaN"):
        register_scans(pts, np.vstack([pts, [np.nan, 0.0]]))
    with pytest.raises(InvalidInputError, match="register_scans: initial"):
        register_scans(pts, pts, initial=(0.0, np.inf, 0.0))
    with pytest.raises(DegenerateGeometryError, match="register_scans: source: needs at least 3 points"):
        register_scans(pts[:2], pts)
    with pytest.raises(DegenerateGeometryError, match="do not overlap"):
        register_scans(pts + 100.0, pts, params=IcpParams(max_distance=0.5))
