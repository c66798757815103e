"""The 2D map builder holds a log's own poses (issue 14): fed a corrected log's poses as its odometry, ``build_map``
must give them back within 5 cm RMS.

The logs' poses are a SLAM back end's; their scans agree with them to 0.3-0.57 degrees RMS per scan, correlated
over neighbouring scans (``benchmarks/bench_log_consistency.py``).  The builder learns how good the odometry is from
the innovations of scan-to-scan registrations (:class:`cga_lessons.mapping2d.noise.InnovationModel`); a Gaussian
likelihood read those registrations' occasional wrong pairs and correlated errors as odometry drift (0.02-0.2 of the
drift model), and every scan was then corrected by its registration error: Seattle's poses came out 8.7 cm RMS off,
Orebro's 6.3, CSAIL's 6.5 (CSAIL also needs one scale for the whole run in the final adjustment: with the running
windows' it stayed at 5.7 cm).  The whole logs are short (240-410 scans, 2-4 s each).
"""

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.mapping2d import build_map, pose_errors, read_carmen_log
from cga_lessons.mapping2d.noise import InnovationModel

HELD = 0.05  # m RMS: the target


@pytest.mark.parametrize("name", ["seattle", "orebro", "csail"])
def test_a_logs_own_poses_are_held(name):
    log = read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
    result = build_map(log.scans, log.poses, max_range=8.0)
    rmse, heading = pose_errors(result.poses, log.poses)
    assert rmse <= HELD
    assert np.degrees(heading) <= 0.3  # the scans' own disagreement with the poses is 0.3-0.57 degrees RMS


def _innovations(model, rng, n, q_true):
    """Feed ``n`` innovations of an odometry ``q_true`` times its drift model, steps of every size."""
    R = np.diag([0.025**2, 0.025**2, 0.009**2])
    C = np.diag([0.005**2, 0.005**2, 0.001**2])
    for _ in range(n):
        B = np.diag([0.02**2, 0.02**2, 0.017**2]) * rng.uniform(0.2, 3.0)
        model.add(rng.multivariate_normal(np.zeros(3), C + 0.3 * R + q_true * B), C, B, R)
    return model


def test_a_drifting_odometry_is_not_called_exact_while_the_evidence_is_thin():
    """Twelve innovations of an odometry that drifts by its model: the ratio against an exact odometry may lie
    below the test's quantile, but the model as stated is not rejected either, so q is not set to its floor (a
    wrongly exact odometry left a drifting one uncorrected: CSAIL, seed 1, 2 m off before the model caught up)."""
    thin = 0
    for seed in range(6):
        model = _innovations(InnovationModel(), np.random.default_rng(seed), 12, 1.0)
        assert model.q >= 0.1
        thin += model.ratio <= model.threshold
    assert thin >= 1  # the case the second condition is for


def test_the_whole_runs_scale_reads_every_innovation():
    model = _innovations(InnovationModel(window=50), np.random.default_rng(2), 300, 1.0)
    assert len(model.g) == 50 and len(model.history) == 300
    q, c = model.overall()
    assert 0.5 <= q <= 2.0 and 0.1 < c < 1.0
