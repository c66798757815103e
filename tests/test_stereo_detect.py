"""Automatic registration of conformal entities (future work 6.2.2): detection in point clouds.

Truth: the seeded scene generator (:mod:`cga_lessons.stereo.detect_scenes`)
knows every entity and which points it made; scenes are seen through a
simulated stereo head with 0.5 and 1 px noise and triangulated (A.14).
Independent checks: Monte-Carlo spreads for the predicted covariances (of the
triangulated points and of the fitted parameters), the total-least-squares
line of :mod:`cga_lessons.map3d`, and the conformal blades read back with
:func:`cga_lessons.map3d.entity_parameters`.
"""

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons import map3d
from cga_lessons import stereo as st
from cga_lessons.algebra import InvalidInputError
from cga_lessons.stereo import detect as sd
from cga_lessons.stereo import detect_ml as dml
from cga_lessons.stereo import detect_models as dm
from cga_lessons.stereo import detect_noise as dn
from cga_lessons.stereo import detect_scenes as ss
from cga_lessons.stereo import detect_scores as sc
from cga_lessons.stereo import triangulation as tri
from cga_lessons.stereo.detect_params import present

SEEDS = range(5)
KINDS = ss.KINDS


def _run(noise_px, seed):
    scene = ss.stereo_scene(np.random.default_rng(seed), ss.SceneConfig(noise_px=noise_px))
    ents = sd.detect_entities(scene.points, np.random.default_rng(100 + seed), noise=scene.noise)
    return scene, ents, sc.evaluate(scene, ents)


@pytest.fixture(scope="module")
def rig_runs():
    """Five seeded scenes at 0.5 px and five at 1 px, seen by the stereo head, and what the detector found."""
    return {(px, s): _run(px, s) for px in (0.5, 1.0) for s in SEEDS}


def _totals(runs):
    tot = {k: np.zeros(3, int) for k in KINDS}
    for _, _, ev in runs:
        for k in KINDS:
            tot[k] += [ev.kinds[k].tp, ev.kinds[k].detected, ev.kinds[k].truth]
    return tot


@pytest.mark.parametrize("noise_px", [0.5, 1.0])
def test_precision_and_recall_through_the_stereo_rig(rig_runs, noise_px):
    runs = [rig_runs[(noise_px, s)] for s in SEEDS]
    for s, (scene, ents, ev) in zip(SEEDS, runs):
        per_kind = {k: (ev.kinds[k].precision, ev.kinds[k].recall) for k in KINDS}
        print(f"{noise_px} px, seed {s}: {len(scene.points)} points, {len(ents)} entities, (precision, recall) "
              f"{per_kind}")  # fmt: skip
        assert len(scene.truth) == 12 and np.sum(scene.labels < 0) == 300  # 3 of each kind, 300 clutter points
    tot = _totals(runs)
    for k, (tp, det, tru) in tot.items():
        print(
            f"{noise_px} px, {k}: precision {tp / det:.3f}  recall {tp / tru:.3f}  ({tp} of {det} detected, {tru} true)"
        )
        assert tp / det >= 0.9 and tp / tru >= 0.9


def test_each_point_in_one_entity_and_inliers_are_the_objects_points(rig_runs):
    for scene, ents, ev in rig_runs.values():
        owner = np.concatenate([e.inliers for e in ents])
        assert len(owner) == len(np.unique(owner))
        for i, j in ((m.detection, m.truth) for m in ev.matches):
            lab = scene.labels[ents[i].inliers]
            assert np.mean(lab == j) > 0.95  # inliers are the object's points (clutter in the gate is rare)
            assert np.mean(np.isin(scene.truth[j].indices, ents[i].inliers)) > 0.8  # ... and most of them


def _truth_vector(det, t):
    """The true parameters in the detection's order (PARAM_NAMES), signs of normals matched; for lines the
    true point is the foot of the detected point on the true line (a line's point is only defined across it)."""
    p = t.params
    if t.kind == "plane":
        n = p.normal * np.sign(p.normal @ det.params.normal)
        return np.concatenate([n, [n @ p.center]])
    if t.kind == "sphere":
        return np.concatenate([p.center, [p.radius]])
    if t.kind == "circle":
        n = p.normal * np.sign(p.normal @ det.params.normal)
        return np.concatenate([p.center, n, [p.radius]])
    d = p.direction * np.sign(p.direction @ det.params.direction)
    foot = p.point + ((det.params.point - p.point) @ d) * d
    return np.concatenate([foot, d])


def _det_vector(det):
    keys = {"plane": ("normal", "distance"), "sphere": ("center", "radius"),
            "circle": ("center", "normal", "radius"), "line": ("point", "direction")}[det.kind]  # fmt: skip
    return np.concatenate([np.atleast_1d(getattr(det.params, k)) for k in keys])


def test_parameters_within_their_predicted_uncertainty(rig_runs):
    """Errors against the truth, in units of the standard deviations of the returned covariance."""
    z = {k: [] for k in KINDS}
    for scene, ents, ev in rig_runs.values():
        for i, j, err in ((m.detection, m.truth, m.errors) for m in ev.matches):
            det = ents[i]
            sd_ = np.sqrt(np.maximum(np.diag(det.covariance), 0))
            e = _det_vector(det) - _truth_vector(det, scene.truth[j])
            ok = sd_ > 1e-9  # (a line's point has no spread along it, a unit normal none along itself)
            z[det.kind].extend(e[ok] / sd_[ok])
            # and in metres: within the matching tolerance derived from the noise (4 x its RMS scale)
            assert (err.offset or 0.0) <= ev.tolerance and (det.kind in ("plane", "line") or
                                                             err.center <= ev.tolerance)  # fmt: skip
    for k, v in z.items():
        v = np.abs(v)
        rms = float(np.sqrt(np.mean(v**2)))
        print(f"{k}: {len(v)} parameter errors, RMS z = {rms:.2f}, max |z| = {v.max():.2f}")
        assert 0.4 < rms < 2.5  # the covariance is the right size (first order, plus bias of the fits)
        assert np.mean(v < 4.0) > 0.95


def test_detected_blades_read_back_to_their_parameters(rig_runs):
    scene, ents, _ = rig_runs[(0.5, 0)]
    for e in ents:
        back = map3d.entity_parameters(e.kind, e.blade)
        for k, v in present(back).items():  # the fields the blade gives (not a drawing's center, length)
            if k == "point":  # (2.129): the closest point to the origin, ours is another point of the line
                w = v - e.params.point
                np.testing.assert_allclose(w - (w @ e.params.direction) * e.params.direction, 0, atol=1e-9)
            elif k in ("normal", "direction"):
                np.testing.assert_allclose(abs(v @ getattr(e.params, k)), 1.0, atol=1e-9)
            else:
                np.testing.assert_allclose(v, getattr(e.params, k), atol=1e-9)
        assert e.covariance.shape == (len(e.covariance_names),) * 2
        np.testing.assert_allclose(e.covariance, e.covariance.T, atol=1e-15)
        assert np.all(np.linalg.eigvalsh(e.covariance) > -1e-12)


def test_deterministic_with_a_seed():
    scene = ss.stereo_scene(np.random.default_rng(7), ss.SceneConfig(noise_px=0.75))
    runs = [sd.detect_entities(scene.points, np.random.default_rng(3), noise=scene.noise) for _ in range(2)]
    assert [e.kind for e in runs[0]] == [e.kind for e in runs[1]]
    for a, b in zip(*runs):
        np.testing.assert_array_equal(a.inliers, b.inliers)
        assert type(a.params) is type(b.params)
        for k, v in present(a.params).items():
            np.testing.assert_array_equal(v, getattr(b.params, k))
        np.testing.assert_array_equal(a.covariance, b.covariance)
    again = ss.stereo_scene(np.random.default_rng(7), ss.SceneConfig(noise_px=0.75))
    np.testing.assert_array_equal(again.points, scene.points)


def test_noise_estimated_from_the_cloud():
    """Without a sensor fact: isotropic 8 mm noise, sigma estimated from the data, still >= 0.9 per kind."""
    runs = []
    for s in range(3):
        scene = ss.cloud_scene(np.random.default_rng(20 + s), ss.SceneConfig(noise_m=0.008))
        est = dn.estimate_noise(scene.points)
        assert 0.8 * 0.008 < est < 1.25 * 0.008
        ents = sd.detect_entities(scene.points, np.random.default_rng(s))
        runs.append((scene, ents, sc.evaluate(scene, ents)))
    for k, (tp, det, tru) in _totals(runs).items():
        print(f"estimated noise, {k}: precision {tp / det:.3f}  recall {tp / tru:.3f}")
        assert tp / det >= 0.9 and tp / tru >= 0.9


def test_results_are_typed_and_consistent(rig_runs):
    """Detections carry their kind's parameter record; the score's counts agree with its matches."""
    for scene, ents, ev in rig_runs.values():
        assert isinstance(ev, st.DetectionScore) and set(ev.kinds) == set(KINDS)
        for e in ents:
            assert isinstance(e, st.DetectedEntity) and type(e.params).kind == e.kind
            assert e.kind in e.evidence.support  # the chosen kind was among those fitted
            assert (e.params.center is not None) if e.kind == "plane" else True
            assert e.params.length > 0 if e.kind == "line" else True
        for kind in KINDS:
            s = ev.kinds[kind]
            tp = sum(scene.truth[m.truth].kind == kind for m in ev.matches)
            assert (s.tp, s.detected, s.truth) == (tp, sum(e.kind == kind for e in ents),
                                                   sum(t.kind == kind for t in scene.truth))  # fmt: skip
            assert s.precision == (tp / s.detected if s.detected else 1.0)
        assert ev.all.tp == len(ev.matches) == sum(s.tp for s in ev.kinds.values())
        for m in ev.matches:
            assert isinstance(m.errors, st.DetectionError) and ents[m.detection].kind == scene.truth[m.truth].kind
            assert (m.errors.radius is None) == (ents[m.detection].kind in ("plane", "line"))


@pytest.mark.parametrize(
    "cls, fields, arg",
    [
        (cga.PlaneParameters, {"normal": [0.0, 0.0, np.nan], "distance": 1.0}, "normal"),
        (
            st.PatchParameters,
            {"normal": [0.0, 0.0, 1.0], "distance": 1.0, "center": [0.0, 0.0, 1.0], "sides": (0.2, -0.1)},
            "sides",
        ),
        (cga.SphereParameters, {"center": [0.0, 0.0], "radius": 1.0}, "center"),
        (cga.CircleParameters, {"center": [0.0, 0.0, 1.0], "radius": "1", "normal": [0.0, 0.0, 1.0]}, "radius"),
        (cga.LineParameters, {"point": [0.0, 0.0, 1.0], "direction": [0.0, 0.0, 1.0], "length": -1.0}, "length"),
    ],
)
def test_parameter_records_check_their_fields(cls, fields, arg):
    with pytest.raises(InvalidInputError, match=rf"{cls.__name__}: {arg}"):
        cls(**fields)


# ------------------------------------------------------------ model selection
def _patch(rng, n=400, sigma=0.003):
    st_ = rng.uniform(-0.3, 0.3, size=(n, 2))
    return np.column_stack([st_, np.zeros(n)]) + rng.normal(scale=sigma, size=(n, 3))


def _cap(rng, radius, n=400, half_angle=1.2, sigma=0.003):
    """Points uniform (by area) on the cap of a sphere about +z, centred at the origin."""
    z = rng.uniform(np.cos(half_angle), 1.0, n)
    phi = rng.uniform(0, 2 * np.pi, n)
    s = np.sqrt(1 - z * z)
    d = np.column_stack([s * np.cos(phi), s * np.sin(phi), z])
    return radius * d + rng.normal(scale=sigma, size=d.shape)


@pytest.mark.parametrize(
    "name, expected",
    [("plane", "plane"), ("sphere", "sphere"), ("huge sphere", "plane"), ("circle", "circle"), ("line", "line")],
)
def test_model_selection_on_single_objects(name, expected):
    rng = np.random.default_rng(11)
    sigma = 0.003
    if name == "plane":
        X = _patch(rng)
    elif name == "sphere":
        X = _cap(rng, 0.25)
    elif name == "huge sphere":  # radius 50 m seen over 0.6 m: the sagitta (0.9 mm) is below the noise
        X = _cap(rng, 50.0, half_angle=0.006) - [0, 0, 50.0]
    elif name == "circle":
        t = rng.uniform(0, 2 * np.pi, 150)
        X = 0.2 * np.column_stack([np.cos(t), np.sin(t), np.zeros_like(t)]) + rng.normal(scale=sigma, size=(150, 3))
    else:
        X = np.outer(rng.uniform(-0.4, 0.4, 80), [0.6, 0.8, 0.0]) + rng.normal(scale=sigma, size=(80, 3))
    ents = sd.detect_entities(X, np.random.default_rng(0), noise=sigma)
    assert [e.kind for e in ents] == [expected]
    assert len(ents[0].inliers) > 0.95 * len(X)
    assert 0.7 < ents[0].chi2 < 1.3


def test_non_maximum_suppression_merges_the_halves_of_one_plane_only():
    from cga_lessons.stereo.detect_search import Search, merge

    rng = np.random.default_rng(3)
    sigma = 0.003
    X = np.vstack([_patch(rng, 400, sigma), _patch(rng, 400, sigma) + [0.65, 0.0, 0.1]])  # a step of 10 cm
    search = Search(X, dn.NoiseModel(sigma), sd.DetectConfig(), eps=0.06)
    left = np.flatnonzero((X[:, 0] < 0) & (np.arange(len(X)) < 400))
    right = np.flatnonzero((X[:, 0] >= 0) & (np.arange(len(X)) < 400))
    other = np.arange(400, 800)
    ents = [search.entity("plane", dm.fit("plane", X[i]), i) for i in (left, right, other)]
    out = merge(search, ents)
    assert len(out) == 2  # the two halves of the first patch, not the patch 10 cm higher next to it
    assert len(out[0].inliers) > 0.97 * 400 and np.array_equal(out[1].inliers, other)


# ------------------------------------------------------------ the noise model
def test_triangulation_covariance_matches_monte_carlo_and_the_parallel_rig_formula():
    cfg = ss.SceneConfig()
    rig = ss.scene_rig(cfg)
    rng = np.random.default_rng(5)
    X = rig.C1 + np.array([2.0, -0.1, -0.4])
    x1, x2 = rig.project(X[None])
    C = dn.triangulation_covariance(rig.P1, rig.P2, x1, x2, 1.0)[0]
    y1, y2 = st.observe(rig, np.repeat(X[None], 4000, axis=0), 1.0, rng)
    Y = tri.triangulate(rig.P1, rig.P2, y1, y2)
    np.testing.assert_allclose(np.cov(Y.T), C, rtol=0.1, atol=0.05 * np.abs(C).max())
    Z = (X - rig.C1) @ rig.R1[2]  # depth; sigma_Z = sqrt(2) Z^2 sigma / (f b) for a parallel pair
    sz = np.sqrt(rig.R1[2] @ C @ rig.R1[2])
    assert sz == pytest.approx(np.sqrt(2) * Z**2 / (cfg.focal_px * cfg.baseline), rel=0.02)


def test_estimate_noise_on_a_plane():
    rng = np.random.default_rng(2)
    X = _patch(rng, 3000, sigma=0.004)
    assert dn.estimate_noise(X) == pytest.approx(0.004, rel=0.15)


def test_parameter_covariance_matches_monte_carlo():
    """The returned covariance of a sphere's centre and radius against the spread of 300 noisy fits."""
    rng = np.random.default_rng(9)
    sigma = 0.004
    base = _cap(rng, 0.2, n=200, sigma=0.0)
    nm = dn.NoiseModel(sigma)
    idx = np.arange(len(base))
    est = []
    for _ in range(300):
        X = base + rng.normal(scale=sigma, size=base.shape)
        p = dml.fit_ml("sphere", X, nm, idx)
        est.append(np.concatenate([p.center, [p.radius]]))
    p = dml.fit_ml("sphere", base + rng.normal(scale=sigma, size=base.shape), nm, idx)
    C = dml.covariance("sphere", p, base, nm, idx)
    emp = np.std(est, axis=0)
    np.testing.assert_allclose(emp, np.sqrt(np.diag(C)), rtol=0.2)


def test_conformal_line_fit_is_total_least_squares():
    rng = np.random.default_rng(4)
    d = np.array([0.2, -0.5, 0.84])
    X = [1.0, 2.0, -0.5] + np.outer(rng.uniform(-1, 1, 60), d) + rng.normal(scale=0.01, size=(60, 3))
    mine = cga.fit_line(X)
    c = X.mean(axis=0)  # total least squares: through the centroid along the principal direction (an SVD)
    tls = np.linalg.svd(X - c)[2][0]
    off = (X - c) - np.outer((X - c) @ tls, tls)
    np.testing.assert_allclose(abs(mine.direction @ tls), 1.0, atol=1e-12)
    np.testing.assert_allclose(mine.point, c, atol=1e-12)
    assert mine.rms == pytest.approx(np.sqrt(np.mean(np.sum(off**2, axis=1))), rel=1e-10)
    t = (X - c) @ mine.direction
    np.testing.assert_allclose(mine.ends, c + np.outer([t.min(), t.max()], mine.direction), atol=1e-12)


# ------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    "X, kwargs, arg",
    [
        (np.zeros((50, 2)), {}, "X"),
        (np.zeros(150), {}, "X"),
        ([["a", "b", "c"]] * 50, {}, "X"),
        (np.full((50, 3), np.nan), {}, "X"),
        (np.vstack([np.random.default_rng(0).normal(size=(49, 3)), [[np.inf, 0, 0]]]), {}, "X"),
        (np.random.default_rng(0).normal(size=(10, 3)), {}, "X"),  # fewer than the smallest support (15)
        (np.zeros((50, 3)), {}, "X"),  # all points coincide
        (np.random.default_rng(0).normal(size=(50, 3)), {"noise": -0.01}, "noise"),
        (np.random.default_rng(0).normal(size=(50, 3)), {"noise": np.nan}, "noise"),
        (np.random.default_rng(0).normal(size=(50, 3)), {"noise": np.zeros((49, 3, 3))}, "noise"),
        (np.random.default_rng(0).normal(size=(50, 3)), {"noise": np.tile(-np.eye(3), (50, 1, 1))}, "noise"),
        (np.random.default_rng(0).normal(size=(50, 3)), {"noise": "loud"}, "noise"),
        (np.random.default_rng(0).normal(size=(50, 3)), {"config": {"kinds": ("plane",)}}, "config"),
    ],
)
def test_bad_input_raises_naming_function_and_argument(X, kwargs, arg):
    with pytest.raises(InvalidInputError, match=rf"detect_entities: {arg}"):
        sd.detect_entities(X, np.random.default_rng(0), **kwargs)
    assert issubclass(InvalidInputError, ValueError)


def test_bad_rng_and_config_raise():
    X = np.random.default_rng(0).normal(size=(50, 3))
    with pytest.raises(InvalidInputError, match="detect_entities: rng"):
        sd.detect_entities(X, 42)
    for bad in ({"kinds": ("cube",)}, {"confidence": 1.5}, {"hypotheses": 0}, {"neighbourhoods": ()},
                {"removal_confidence": 0.9}, {"connect_radius": -1.0}):  # fmt: skip
        with pytest.raises(InvalidInputError, match="DetectConfig"):
            sd.DetectConfig(**bad)
    with pytest.raises(InvalidInputError, match="triangulation_covariance: sigma_px"):
        dn.triangulation_covariance(np.eye(3, 4), np.eye(3, 4), np.zeros((1, 2)), np.zeros((1, 2)), 0.0)
    with pytest.raises(InvalidInputError, match="stereo_scene: rng"):
        ss.stereo_scene(0)
