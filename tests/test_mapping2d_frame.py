"""The map's frame (mapping2d.frame): its turn from the odometry's frame, read from every odometry heading."""

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.mapping2d import build_map, pose_errors, read_carmen_log
from cga_lessons.mapping2d.frame import map_turn, turn_about


@pytest.mark.parametrize("step_sd", [1e-6, 1e-3, 5e-3, 2e-2])
def test_map_turn_is_the_generalised_least_squares_estimate(step_sd):
    """Against the closed form: r_k = epsilon + delta_k - (walk)_k has covariance s_r I + min(S_j, S_k) (S the
    walk's summed variances), epsilon the prior N(0, s_r); the estimate is (1' C^-1 r) / (1' C^-1 1 + 1 / s_r)
    with its variance 1 / (1' C^-1 1 + 1 / s_r), solved here with the whole matrix."""
    rng = np.random.default_rng(7)
    T, s_r = 250, 0.004**2
    steps = (step_sd * rng.uniform(0.3, 2.0, T - 1)) ** 2
    odometry = np.cumsum(rng.normal(0, 0.3, T))
    built = odometry + 0.003 + rng.normal(0, 0.004, T) - np.concatenate([[0], np.cumsum(rng.normal(0, np.sqrt(steps)))])
    built[0] = odometry[0]
    S = np.concatenate([[0.0], np.cumsum(steps)])[1:]
    C = np.minimum.outer(S, S) + s_r * np.eye(T - 1)
    r = np.angle(np.exp(1j * (built - odometry)))[1:]
    ci1, cir = np.linalg.solve(C, np.ones(T - 1)), np.linalg.solve(C, r)
    info = ci1.sum() + 1 / s_r
    eps, var = map_turn(built, odometry, steps, s_r)
    assert eps == pytest.approx(cir.sum() / info, rel=1e-9, abs=1e-15)
    assert var == pytest.approx(1 / info, rel=1e-9)


def test_turn_about_turns_positions_and_headings_about_the_centre():
    poses = np.array([[1.0, 0.0, 0.1], [3.0, 2.0, -3.1]])
    out = turn_about(poses, np.array([1.0, 0.0]), np.pi / 2)
    assert np.allclose(out[:, :2], [[1.0, 0.0], [-1.0, 2.0]])
    assert np.allclose(out[:, 2], [0.1 + np.pi / 2, -3.1 + np.pi / 2])
    assert np.allclose(turn_about(out, np.array([1.0, 0.0]), -np.pi / 2), poses)


def test_a_logs_own_poses_are_held_on_aces():
    """Fed the ACES log's corrected poses as odometry (the whole log), the builder leaves them within 5 cm RMS: the
    map the scans build is turned from the log's frame (the first scans' registration), and every heading of an
    odometry that has proved exact says by how much (without taking that turn out: 10.6 cm).  The benchmark
    (benchmarks/bench_logs.py) measures all six logs."""
    log = read_carmen_log(data_path("carmen", "aces-corrected.log.gz"))
    held = build_map(log.scans, log.poses, max_range=8.0)
    assert pose_errors(held.poses, log.poses)[0] < 0.05
