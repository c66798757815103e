"""Monte Carlo localization in a line map (relocalization_likelihood, relocalization_sampling, relocalization_mcl).

The truth is independent of the filter: the simulator's poses on the office scene (scans by
:func:`cga_lessons.mapping2d.laser.simulate_scan`, drift by :func:`cga_lessons.mapping2d.laser.simulate_odometry`),
and the beam model written out by hand for single beams against one wall.
"""

import numpy as np
import pytest

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import laser, relative, wrap_angle
from cga_lessons.relocalization import BeamModel, MCLConfig
from cga_lessons.relocalization.beam import beam_likelihood
from cga_lessons.relocalization.coverage import build_coverage
from cga_lessons.relocalization.likelihood import LikelihoodField
from cga_lessons.relocalization.mcl import MonteCarloLocalizer
from cga_lessons.relocalization.sampling import KLDConfig, kld_bound, kld_resample, low_variance_indices

TOL_XY, TOL_TH = 0.10, np.radians(2.0)
WALL = np.array([[[2.0, -5.0], [2.0, 5.0]]])  # one wall, x = 2, facing a laser at the origin


@pytest.fixture(scope="module")
def office():
    return laser.load_scene("office")


def located(est, truth):
    err = np.hypot(*(est.pose[:2] - truth[:2]))
    return err <= TOL_XY and abs(float(wrap_angle(est.pose[2] - truth[2]))) <= TOL_TH


def drive(mcl, scene, truth, increments, rng):
    """Feed the filter the scans at ``truth`` with the odometry ``increments`` (one fewer); the estimates."""
    steps = [np.zeros(3), *increments]
    return [mcl.update(u, laser.simulate_scan(scene, p, rng)) for u, p in zip(steps, truth)]


# --------------------------------------------------------------------------- the beam model


def gauss_beam(d, sigma, z_rand, max_range):
    """The hit-plus-random likelihood of one beam, written out."""
    return (1 - z_rand) * np.exp(-0.5 * d**2 / sigma**2) / (sigma * np.sqrt(2 * np.pi)) + z_rand / max_range


def test_one_beam_matches_the_closed_form():
    model = BeamModel(max_range=5.0, sigma_hit=0.05, z_rand=0.1, resolution=0.01, max_beams=2)
    field = LikelihoodField(WALL, model=model)
    angles = np.array([-0.2, 0.3])
    for x in (0.0, 0.5, 1.2):  # laser at (x, 0.4) looking along +x: each beam ends d from the wall
        for miss in (0.0, 0.03, 0.08, 0.5):
            ranges = (2.0 - x - miss) / np.cos(angles)
            log_w, per_beam = field.log_likelihood([[x, 0.4, 0.0]], (ranges, angles))
            want = np.log(gauss_beam(miss, 0.05, 0.1, 5.0)) * 2
            # the field is exact at cell centres: an end point is off by at most half a cell diagonal (7 mm)
            lo = np.log(gauss_beam(miss + 0.0071, 0.05, 0.1, 5.0)) * 2
            hi = np.log(gauss_beam(max(miss - 0.0071, 0.0), 0.05, 0.1, 5.0)) * 2
            assert lo - 1e-6 <= per_beam[0] * 2 <= hi + 1e-6, (x, miss, per_beam[0] * 2, want)
            assert log_w[0] == pytest.approx(model.beam_weight * per_beam[0] * 2)
    assert float(beam_likelihood(0.03, model)) == pytest.approx(gauss_beam(0.03, 0.05, 0.1, 5.0))


def test_distance_field_is_the_distance_to_the_segments():
    segs = np.array([[[0.0, 0.0], [3.0, 0.0]], [[3.0, 0.0], [3.0, 2.0]], [[0.5, 1.5], [1.7, 2.4]]])
    field = LikelihoodField(segs, model=BeamModel(resolution=0.05))
    pts = np.random.default_rng(0).uniform([-0.2, -0.2], [3.2, 2.6], (400, 2))
    flat, inside = field.cells(pts)
    a, v = segs[:, 0], segs[:, 1] - segs[:, 0]
    rel = pts[:, None] - a[None]
    t = np.clip(np.einsum("pmi,mi->pm", rel, v) / np.einsum("mi,mi->m", v, v), 0, 1)
    exact = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1)).min(axis=1)
    got = field.distance.ravel()[flat]
    half_diagonal = 0.05 * np.sqrt(2) / 2  # a point is that far at most from its cell's centre
    near = exact < 0.25  # within the band where the field is exact (4 sigma_hit and two cells)
    assert inside.all() and near.sum() > 50
    assert np.all(np.abs(got - exact)[near] <= half_diagonal + 1e-6)
    assert np.all(got >= exact - half_diagonal - 1e-6)  # farther out: an upper bound


def test_silent_beams_and_unknown_space():
    model = BeamModel(max_range=5.0, max_beams=2, z_rand=0.1, p_dropout=0.05)
    field = LikelihoodField(WALL, model=model)
    silent = (np.array([np.inf, np.nan]), np.array([-0.1, 0.1]))
    # facing the wall 1 m away the silence needs two dropouts; facing away nothing is there to return
    log_w, per_beam = field.log_likelihood([[1.0, 0.0, 0.0], [1.0, 0.0, np.pi]], silent)
    assert per_beam[0] == pytest.approx(np.log(0.05))
    assert per_beam[1] == pytest.approx(np.log(0.9))
    # with a coverage grid, an end point where no mapping beam went says nothing: 1 / max_range
    scan = (np.array([2.0, 2.0]), np.array([-0.01, 0.01]))
    cov = build_coverage([scan], [[0.0, 0.0, 0.0]], max_range=5.0)
    known = LikelihoodField(WALL, cov, model=model)
    behind = (np.array([1.0, 1.0]), np.array([-0.01, 0.01]))  # from (2.5, 3): ends at x = 3.5, behind the wall
    log_w, per_beam = known.log_likelihood([[2.5, 3.0, 0.0]], behind)
    assert log_w[0] == pytest.approx(model.beam_weight * 2 * -np.log(5.0), abs=1e-5)
    assert per_beam[0] == pytest.approx(0.0, abs=1e-6)  # no beam the map can judge: no measure of fit
    # one beam ends on the wall (judged), one in unknown space (left out of the fit per beam)
    mixed = (np.array([1.0, 3.0]), np.array([-0.01, 0.01]))
    log_w, per_beam = known.log_likelihood([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]], mixed)
    # the judged beam's end lies on the wall, up to half a cell diagonal of the grid (3.5 cm)
    lo, hi = (np.log(gauss_beam(d, model.sigma_hit, 0.1, 5.0)) for d in (0.05 * np.sqrt(0.5), 0.0))
    assert lo - 1e-6 <= per_beam[0] <= hi + 1e-6  # not the mean with the unknown beam's log(1/5)
    _, per_beam = field.log_likelihood([[2.5, 3.0, 0.0]], behind)  # no coverage: a miss in mapped space
    assert per_beam[0] == pytest.approx(np.log(0.1 / 5.0), abs=1e-3)


# --------------------------------------------------------------------------- resampling


def test_low_variance_and_kld():
    rng = np.random.default_rng(1)
    w = rng.random(50)
    w /= w.sum()
    idx = low_variance_indices(w, 1000, rng)
    counts = np.bincount(idx, minlength=50)
    assert np.all(np.abs(counts - 1000 * w) <= 1.0 + 1e-9)  # systematic: never more than one off
    assert np.all(np.diff(kld_bound(np.arange(2, 500))) > 0)
    cfg = KLDConfig(n_min=100, n_max=5000)
    tight = np.column_stack([rng.normal(0, 0.02, (5000, 2)), rng.normal(0, 0.01, 5000)])
    spread = np.column_stack([rng.uniform(0, 20, (5000, 2)), rng.uniform(-np.pi, np.pi, 5000)])
    uniform = np.full(5000, 1 / 5000)
    assert len(kld_resample(tight, uniform, cfg, rng)) <= 300
    assert len(kld_resample(spread, uniform, cfg, rng)) == 5000


# --------------------------------------------------------------------------- the filter on the office scene


def test_global_localization_converges_and_the_particles_adapt(office):
    rng = np.random.default_rng(3)
    truth = office.trajectory[40:48]
    mcl = MonteCarloLocalizer(office.walls, rng=np.random.default_rng(4))
    assert len(mcl.particles) == MCLConfig().kld.n_max
    est = drive(mcl, office, truth, laser.OdometryModel().increments(truth, rng), rng)
    assert est[-1].converged
    assert located(est[-1], truth[-1])
    assert all(located(e, t) for e, t in zip(est, truth) if e.converged)  # never confidently wrong
    assert est[-1].n_particles <= MCLConfig().kld.n_max // 20  # fewer once converged
    assert np.all(np.linalg.eigvalsh(est[-1].covariance) >= -1e-12)


def test_seeded_runs_repeat(office):
    truth = office.trajectory[100:103]
    scans = [laser.simulate_scan(office, p, np.random.default_rng(0)) for p in truth]
    poses = []
    for _ in range(2):
        mcl = MonteCarloLocalizer(office.walls, rng=7, initial_pose=truth[0])
        for k, s in enumerate(scans):
            e = mcl.update(np.zeros(3) if k == 0 else relative(truth[k - 1], truth[k]), s)
        poses.append(e.pose)
    assert np.array_equal(poses[0], poses[1])


def test_recovers_after_a_kidnapping(office):
    rng = np.random.default_rng(11)
    T = office.trajectory
    before, after = T[200:206], T[430:444]  # carried from one room to another, the odometry none the wiser
    model = laser.OdometryModel()
    increments = [*model.increments(before, rng), np.zeros(3), *model.increments(after, rng)]
    mcl = MonteCarloLocalizer(office.walls, rng=np.random.default_rng(12), initial_pose=before[0])
    est = drive(mcl, office, np.concatenate([before, after]), increments, rng)
    assert located(est[len(before) - 1], before[-1]) and est[len(before) - 1].converged
    assert not located(est[len(before)], after[0])  # just carried: the belief is still in the old room
    assert est[-1].converged and located(est[-1], after[-1])


# --------------------------------------------------------------------------- bad input


def test_bad_inputs_raise(office):
    scan = laser.simulate_scan(office, office.trajectory[0])
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer: map_segments: is empty"):
        MonteCarloLocalizer(np.zeros((0, 2, 2)), rng=0)
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer: map_segments: expected shape"):
        MonteCarloLocalizer(np.zeros((3, 2)), rng=0)
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer: map_segments: contains NaN"):
        MonteCarloLocalizer(np.array([[[0.0, 0.0], [np.nan, 1.0]]]), rng=0)
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer: rng"):
        MonteCarloLocalizer(office.walls, rng=None)
    mcl = MonteCarloLocalizer(office.walls, rng=0, initial_pose=office.trajectory[0])
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer.update: odometry_increment"):
        mcl.update([0.0, 0.0], scan)
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer.update: odometry_increment"):
        mcl.update([0.0, np.inf, 0.0], scan)
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer.update: scan"):
        mcl.update(np.zeros(3), (scan[0][:-1], scan[1]))
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer.update: scan angles"):
        mcl.update(np.zeros(3), (scan[0], np.full_like(scan[1], np.nan)))
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer.update: scan"):
        mcl.update(np.zeros(3), scan[0])
    with pytest.raises(InvalidInputError, match="MonteCarloLocalizer: initial_pose"):
        MonteCarloLocalizer(office.walls, rng=0, initial_pose=[0.0, np.nan, 0.0])
    with pytest.raises(InvalidInputError, match="LikelihoodField.log_likelihood: particles"):
        mcl.field.log_likelihood(np.zeros((4, 2)), scan)
    with pytest.raises(InvalidInputError, match="BeamModel: sigma_hit"):
        BeamModel(sigma_hit=float("nan"))
    with pytest.raises(InvalidInputError, match="KLDConfig: n_min"):
        KLDConfig(n_min=500, n_max=100)
    with pytest.raises(InvalidInputError, match="MCLConfig: proposal_sd"):
        MCLConfig(proposal_sd=(0.05, -1.0, 0.01))


# --------------------------------------------------------------------------- the coarse search and honest ambiguity


def test_coarse_search_finds_the_pose_and_weighs_back_to_the_uniform_prior(office):
    from cga_lessons.relocalization.mcl_search import CoarseSearch

    field = LikelihoodField(office.walls)
    search = CoarseSearch(field, field.free_space(0.2))
    rng = np.random.default_rng(5)
    truth = office.trajectory[60]
    beams = field.select_beams(laser.simulate_scan(office, truth, rng))
    draws, log_q = search.sample(beams, 20_000, rng)
    near = (np.hypot(*(draws[:, :2] - truth[:2]).T) < 0.2) & (np.abs(wrap_angle(draws[:, 2] - truth[2])) < 0.05)
    uniform = 20_000 * np.pi * 0.2**2 * 0.1 / (2 * np.pi * search.area)  # expected of a uniform draw, closed form
    assert uniform < 1.0 and near.sum() >= 50
    # a scan with no return scores every pose alike: the draw is uniform over (cell, heading) entries, and the
    # importance weights p0 / q average to one, whatever the cells' free areas (E_q[p0 / q] = 1)
    room = np.array(
        [[[0.0, 0.0], [1.6, 0.0]], [[1.6, 0.0], [1.6, 1.4]], [[1.6, 1.4], [0.0, 1.4]], [[0.0, 1.4], [0.0, 0.0]]]
    )
    small = LikelihoodField(room)
    s2 = CoarseSearch(small, small.free_space(0.2))
    assert s2.free.sum() * len(s2.headings) <= 10_000  # every entry can be drawn
    _, lq = s2.sample((np.zeros(0), np.zeros(0), np.zeros(0)), 40_000, rng)
    assert np.mean(np.exp(-lq)) == pytest.approx(1.0, abs=0.03)
    assert np.std(np.exp(-lq)) > 0.05  # partly free cells near the walls: weights differ, and are corrected


def test_a_symmetric_room_is_reported_ambiguous_not_converged():
    # a 6 x 4 m rectangle: every scan fits the pose and its half-turn about the centre equally
    box = [np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 4.0], [0.0, 4.0]])]
    truth = np.column_stack([np.linspace(1.5, 4.0, 8), np.full(8, 1.3), np.zeros(8)])
    scene = laser.Scene("box", box, truth)
    rng = np.random.default_rng(2)
    mcl = MonteCarloLocalizer(scene.walls, rng=np.random.default_rng(3))
    est = drive(mcl, scene, truth, laser.OdometryModel().increments(truth, rng), rng)
    assert not any(e.converged for e in est)
    twin = np.array([6.0 - truth[-1, 0], 4.0 - truth[-1, 1], np.pi])
    w = np.exp(mcl.log_w - mcl.log_w.max())
    w /= w.sum()
    for pose in (truth[-1], twin):  # both places keep a share of the belief
        d = np.hypot(*(mcl.particles[:, :2] - pose[:2]).T)
        turned = np.abs(wrap_angle(mcl.particles[:, 2] - pose[2]))
        assert w[(d < 0.3) & (turned < 0.1)].sum() > 0.1


def test_an_ambiguous_answer_confirms_only_when_every_rival_lost():
    from types import SimpleNamespace

    from cga_lessons.relocalization.mcl_proposal import Proposal, confirms

    mode, rival = np.array([1.0, 2.0, 0.3]), np.array([7.0, 2.0, 0.3 + np.pi])
    groups = [np.arange(0, 10), np.arange(10, 20)]
    gate = MCLConfig().gate

    def answer(rival_share, best=mode, complete=True):
        w = np.zeros(30)
        w[:10], w[10:20], w[20:] = 0.5 / 10, rival_share * 0.5 / 10, 0.01
        result = SimpleNamespace(status="ambiguous", pose=best)
        return confirms(Proposal(result, [mode, rival], groups, complete), mode + [0.05, 0.0, 0.01], w, gate, 0.95)

    bar = 0.05 / 0.95  # the rival's weight against the mode's candidate: a posterior of at most 5 % between the two
    assert answer(0.99 * bar) and not answer(1.01 * bar)
    assert not answer(0.0, best=rival)  # chapter 5's best answer lies elsewhere
    assert not answer(0.0, complete=False)  # a tied candidate was not tested
