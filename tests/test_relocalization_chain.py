"""Tests of a chain of poses fitted to its scans and to the odometry together (relocalization_chain).

Truths used: the simulator's ground-truth poses and its ray casting, and the
odometry increments between the true poses (exact, or drawn from the drift
model whose covariance the fit assumes).
"""

import numpy as np
import pytest

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import compose, relative
from cga_lessons.mapping2d.laser import OdometryModel, Scene, simulate_scan
from cga_lessons.relocalization.chain import refine_chains
from cga_lessons.relocalization.geometry import Observation, prepare_map
from cga_lessons.relocalization.odometry import odometry_misfit

REACH = 8.0


def _scene(polygons):
    return Scene("test", polygons, np.zeros((1, 3)))


def _box(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


@pytest.fixture(scope="module")
def corridor():
    # two walls 2 m apart and 60 m long: no end within the laser's reach
    return _scene([[[-30.0, 0.0], [30.0, 0.0]], [[-30.0, 2.0], [30.0, 2.0]]])


@pytest.fixture(scope="module")
def room():
    return _scene([_box(0.0, 0.0, 6.0, 4.0), _box(2.0, 1.5, 2.6, 2.1)])


def _observations(scene, truth, rng, noise=0.0):
    scans = [simulate_scan(scene, p, rng, range_noise=noise, max_range=REACH) for p in truth]
    return [Observation.from_scan(r, a, REACH) for r, a in scans]


def test_a_chain_slid_along_a_corridor_is_pulled_back_to_the_odometry(corridor):
    truth = np.array([[0.0, 1.0, 0.0], [1.0, 1.05, 0.02], [2.0, 0.95, -0.01]])
    obs = _observations(corridor, truth, np.random.default_rng(0))
    M = prepare_map(corridor.walls).lines
    inc = relative(truth[:-1], truth[1:])
    # each pose slid along the corridor by a different amount, as per-scan snapping leaves it
    start = truth + np.array([[0.0, 0.0, 0.0], [0.4, 0.0, 0.0], [-0.3, 0.0, 0.0]])
    assert odometry_misfit(start, truth) is not None
    out = refine_chains(M, obs, inc, start[None], np.full(3, 0.01))[0]
    # across the corridor and in heading the scans fix every pose: the truth
    assert np.allclose(out[:, 1:], truth[:, 1:], atol=1e-6)
    # along it only the steps are fixed, by the odometry: the chain is rigid again
    assert np.allclose(relative(out[:-1], out[1:]), inc, atol=1e-6)
    assert odometry_misfit(out, truth) is None


def test_noise_free_scans_give_the_true_chain_in_a_room(room):
    truth = np.array([[1.0, 1.0, 0.3], [1.6, 0.9, 0.5], [2.2, 0.8, 0.7], [3.0, 1.0, 1.0]])
    obs = _observations(room, truth, np.random.default_rng(1))
    M = prepare_map(room.walls).lines
    rng = np.random.default_rng(2)
    # a wrong odometry (3 cm, 1 degree a step): exact scans in a closed room overrule it
    inc = relative(truth[:-1], truth[1:]) + rng.normal(scale=[0.03, 0.03, 0.017], size=(3, 3))
    start = truth + rng.normal(scale=[0.08, 0.08, 0.03], size=truth.shape)
    out = refine_chains(M, obs, inc, np.stack([start, truth]), np.full(4, 0.01))
    assert np.abs(out - truth[None]).max() < 1e-3


def test_the_weights_follow_the_drift_model(corridor):
    """Along a corridor the fit is the odometry's; across it the scans': the noisy chain's position error
    along the corridor is the odometry's, and across it far below (the scans' 1 cm noise averaged)."""
    rng = np.random.default_rng(3)
    model = OdometryModel()
    truth = compose(np.array([0.0, 1.0, 0.0]), np.array([[0.8 * k, 0.0, 0.0] for k in range(5)]))
    M = prepare_map(corridor.walls).lines
    along, across = [], []
    for _ in range(20):
        obs = _observations(corridor, truth, rng, noise=0.01)
        inc = model.increments(truth, rng)
        out = refine_chains(M, obs, inc, truth[None], np.full(5, 0.01), model)[0]
        err = relative(out[0], out[1:]) - relative(truth[0], truth[1:])
        along.append(err[:, 0])
        across.append(out[:, 1] - truth[:, 1])
    # the last pose's x relative to the first: the odometry's four steps, sigma_xy sqrt(3.2 m) = 3.6 cm
    sd_along = np.std(np.array(along)[:, -1])
    assert 0.018 < sd_along < 0.055
    assert np.std(across) < 0.005


def test_an_anchor_holds_the_pose_before_the_chain(room):
    truth = np.array([[1.0, 1.0, 0.3], [1.6, 0.9, 0.5], [2.2, 0.8, 0.7]])
    obs = _observations(room, truth[1:], np.random.default_rng(4))
    M = prepare_map(room.walls).lines
    inc = relative(truth[:-1], truth[1:])
    out = refine_chains(M, obs, inc, truth[None, 1:] + 0.05, np.full(2, 0.01), anchor=truth[None, 0])
    assert np.abs(out[0] - truth[1:]).max() < 1e-3


def test_bad_input_is_refused(room):
    M = prepare_map(room.walls).lines
    obs = _observations(room, np.array([[1.0, 1.0, 0.0], [1.5, 1.0, 0.0]]), np.random.default_rng(5))
    chain = np.array([[[1.0, 1.0, 0.0], [1.5, 1.0, 0.0]]])
    inc = np.array([[0.5, 0.0, 0.0]])
    with pytest.raises(InvalidInputError, match="refine_chains: chains"):
        refine_chains(M, obs, inc, chain * np.nan, [0.01, 0.01])
    with pytest.raises(InvalidInputError, match="refine_chains: chains"):
        refine_chains(M, obs, inc, chain[0], [0.01, 0.01])
    with pytest.raises(InvalidInputError, match="refine_chains: sigmas: must be > 0"):
        refine_chains(M, obs, inc, chain, [0.01, 0.0])
    with pytest.raises(InvalidInputError, match="refine_chains: increments: need 1"):
        refine_chains(M, obs, np.zeros((2, 3)), chain, [0.01, 0.01])
    with pytest.raises(InvalidInputError, match="refine_chains: observations: need 2"):
        refine_chains(M, obs[:1], inc, chain, [0.01, 0.01])
    with pytest.raises(InvalidInputError, match="refine_chains: increments: contains NaN or inf"):
        refine_chains(M, obs, np.full_like(inc, np.inf), chain, [0.01, 0.01])
