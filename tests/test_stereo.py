"""Section 4.1: conformal entities from two views, least-squares fits, real stereo data.

Truth: the scene's own parameters (bundled and seeded random rigs and
scenes), an independent Pratt fit (SciPy's QZ on the classical algebraic
parametrisation), OpenCV drawing checked at known pixels, and the Middlebury
pair's own photometry.
"""

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as hst

from cga_lessons import conformal as cga
from cga_lessons import stereo as st
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.conformal import fitting as sf
from cga_lessons.conformal.plane_ransac import ransac_plane
from cga_lessons.stereo import camera as cam
from cga_lessons.stereo import experiments as ex
from cga_lessons.stereo import real as real
from cga_lessons.stereo import triangulation as tri
from cga_lessons.stereo.render import render_views

KEYS = ["points", "segment", "circle_key", "plane_key", "sphere_key"]


def bundled():
    rig, scene = st.load_rig(), st.load_scene()
    return rig, scene, st.sample_scene(scene, rig, np.random.default_rng(0))


def assert_entities_close(truth, rec, tol=1e-9):
    """Every parameter of every entity (raw values, not only the error summary)."""
    np.testing.assert_allclose(rec["point"].points, truth["point"].points, atol=tol)
    np.testing.assert_allclose(rec["pair"].endpoints, truth["pair"].endpoints, atol=tol)
    for q in ("direction", "closest_point", "length"):
        np.testing.assert_allclose(getattr(rec["line"], q), getattr(truth["line"], q), atol=tol)
    for q in ("center", "radius"):
        np.testing.assert_allclose(getattr(rec["circle"], q), getattr(truth["circle"], q), atol=tol)
        np.testing.assert_allclose(getattr(rec["sphere"], q), getattr(truth["sphere"], q), atol=tol)
    np.testing.assert_allclose(rec["circle"].center_via_plane, truth["circle"].center, atol=tol)
    sign = np.sign(rec["circle"].normal @ truth["circle"].normal)
    np.testing.assert_allclose(sign * rec["circle"].normal, truth["circle"].normal, atol=tol)
    sign = np.sign(rec["plane"].normal @ truth["plane"].normal)
    np.testing.assert_allclose(sign * rec["plane"].normal, truth["plane"].normal, atol=tol)
    np.testing.assert_allclose(sign * rec["plane"].distance, truth["plane"].distance, atol=tol)


# ------------------------------------------------------------ rig, scene
def test_bundled_rig_is_the_stated_head():
    rig, scene, samples = bundled()
    assert rig.image_size == (640, 480)
    assert rig.baseline == pytest.approx(0.12, abs=1e-12)
    np.testing.assert_allclose(rig.K, [[700, 0, 319.5], [0, 700, 239.5], [0, 0, 1]])
    np.testing.assert_allclose(0.5 * (rig.C1 + rig.C2), [0.0, 0.0, 1.2], atol=1e-12)
    np.testing.assert_allclose(rig.R1[2], [np.cos(np.radians(20)), 0.0, -np.sin(np.radians(20))], atol=1e-12)
    for k, X in samples.items():
        assert rig.in_view(X).all(), k
    x1, x2 = rig.project(samples["plane"])
    np.testing.assert_allclose(x1[:, 1], x2[:, 1], atol=1e-9)  # a parallel rig: epipolar lines are rows


def test_samples_lie_on_their_objects():
    rig, scene, s = bundled()
    assert len(s["circle_key"]) == 3 and len(s["plane_key"]) == 3 and len(s["sphere_key"]) == 4
    for k in ("circle", "circle_key"):
        d = s[k] - scene.circle_center
        np.testing.assert_allclose(np.linalg.norm(d, axis=1), scene.circle_radius, atol=1e-12)
        np.testing.assert_allclose(d @ scene.circle_normal, 0.0, atol=1e-12)
    for k in ("plane", "plane_key"):
        np.testing.assert_allclose((s[k] - scene.board_center) @ scene.board_normal, 0.0, atol=1e-12)
    for k in ("sphere", "sphere_key"):
        d = s[k] - scene.sphere_center
        np.testing.assert_allclose(np.linalg.norm(d, axis=1), scene.sphere_radius, atol=1e-12)
        for C in (rig.C1, rig.C2):  # on the cap both cameras see
            assert np.all(np.sum(d * (C - s[k]), axis=1) > 0)


def test_observe_noise_is_seeded_and_sized():
    rig, _, s = bundled()
    a = st.observe(rig, s["plane"], 0.5, np.random.default_rng(4))
    b = st.observe(rig, s["plane"], 0.5, np.random.default_rng(4))
    np.testing.assert_array_equal(a[0], b[0])
    clean = rig.project(s["plane"])
    assert 0.4 < np.std(a[0] - clean[0]) < 0.6
    with pytest.raises(InvalidInputError, match="rng"):
        st.observe(rig, s["plane"], 0.5)


# ----------------------------------------------------- entities from 4.1
@pytest.mark.parametrize("method", ["midpoint", "dlt"])
def test_noise_free_entities_recover_the_bundled_scene(method):
    rig, scene, s = bundled()
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, s[k]) for k in KEYS}, method)
    assert_entities_close(scene.truth(), rec)
    errs = st.entity_errors(scene.truth(), rec)
    assert max(max(vars(v).values()) for v in errs.values()) < 1e-9


@pytest.mark.parametrize("seed", range(6))
def test_noise_free_entities_on_random_rigs_and_scenes(seed):
    rng = np.random.default_rng(seed)
    rig = st.random_rig(rng)
    scene = st.random_scene(rng, rig)
    s = st.sample_scene(scene, rig, rng)
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, s[k]) for k in KEYS})
    assert_entities_close(scene.truth(), rec)


def test_entities_are_the_conformal_blades():
    rig, scene, s = bundled()
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, s[k]) for k in KEYS})
    X = rec["point"].blade  # (2.61): null vectors with x . e = -1
    np.testing.assert_allclose((X * X).scalar(), 0.0, atol=1e-12)
    np.testing.assert_allclose((X | cga.einf).scalar(), -1.0, atol=1e-12)
    for name, blade, grade in (("pair", "blade", 2), ("line", "blade", 3), ("circle", "blade", 3)):
        assert getattr(rec[name], blade).grades_present() == [grade]
    for k, ent in (("sphere_key", "sphere"), ("plane_key", "plane"), ("circle_key", "circle")):
        for x in s[k]:  # the defining points lie on the entity: x ^ blade = 0 (2.76)
            assert (cga.up(x) ^ rec[ent].blade).iszero(atol=1e-9)
    assert not (cga.up(scene.sphere_center) ^ rec["sphere"].blade).iszero(atol=1e-6)


def test_truth_blades_are_the_true_entities():
    rig, scene, s = bundled()
    truth = scene.truth()
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, s[k]) for k in KEYS})
    np.testing.assert_allclose(rec["line"].midpoint, truth["line"].midpoint, atol=1e-9)
    c, r, n = cga.circle_center_radius(truth["circle"].blade)
    np.testing.assert_allclose(c, scene.circle_center, atol=1e-12)
    assert r == pytest.approx(scene.circle_radius, abs=1e-12) and abs(abs(n @ scene.circle_normal) - 1) < 1e-12
    c, r = cga.sphere_center_radius(truth["sphere"].blade)
    np.testing.assert_allclose(c, scene.sphere_center, atol=1e-12)
    assert r == pytest.approx(scene.sphere_radius, abs=1e-12)
    for x in scene.board_corners():  # every corner lies on the true plane, and on the reconstructed one
        assert (cga.up(x) ^ truth["plane"].blade).iszero(atol=1e-9)
    for name in ("pair", "line", "circle", "plane", "sphere"):  # the same dual forms as the reconstruction's
        assert truth[name].blade.grades_present() == rec[name].blade.grades_present(), name
    assert truth["plane"].radius == pytest.approx(0.5 * np.hypot(*scene.board_size))


def test_circle_centre_two_ways_and_2_121_as_printed():
    rng = np.random.default_rng(7)
    for _ in range(5):
        c, n, r = rng.normal(size=3), rng.normal(size=3), rng.uniform(0.1, 2)
        pts = st.circle_polyline(c, n, r, n=3)[:3]
        Z = cga.circle_from_points(*pts)
        np.testing.assert_allclose(st.circle_center_via_plane(Z), c, atol=1e-10)
        np.testing.assert_allclose(cga.circle_center_radius(Z)[0], c, atol=1e-10)
        # (2.121) as printed contracts the axis with the *dual* plane: a vector, and zero
        printed = (cga.standard_form(Z) ^ cga.einf) | cga.circle_plane(Z)
        assert printed.grades_present() in ([], [1]) and printed.iszero(atol=1e-10)


def test_drawing_procedures_of_4_1():
    rig, scene, s = bundled()
    rec = st.reconstruct_entities(rig, {k: st.observe(rig, s[k]) for k in KEYS})
    np.testing.assert_allclose(st.line_polyline(rec["line"].blade, rec["pair"].blade), scene.segment, atol=1e-9)
    ring = st.circle_polyline(scene.circle_center, scene.circle_normal, scene.circle_radius, n=16)
    assert ring.shape == (17, 3)
    np.testing.assert_allclose(ring[0], ring[-1], atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(ring - scene.circle_center, axis=1), scene.circle_radius, atol=1e-12)
    np.testing.assert_allclose((ring - scene.circle_center) @ scene.circle_normal, 0.0, atol=1e-12)
    sq = st.square_polyline([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], np.sqrt(2.0))
    edges = np.linalg.norm(np.diff(sq, axis=0), axis=1)
    np.testing.assert_allclose(edges, 2.0, atol=1e-12)  # a square of side 2
    np.testing.assert_allclose(np.sort(np.abs(sq[:4, :2]).ravel()), 1.0, atol=1e-12)


def test_minimal_constructions_raise_on_degenerate_points():
    rig, scene, s = bundled()
    views = {k: st.observe(rig, s[k]) for k in KEYS}
    flat = s["sphere_key"].copy()
    flat[3] = flat[:3].mean(axis=0)  # four coplanar points: no sphere
    with pytest.raises(DegenerateGeometryError, match="coplanar"):
        st.reconstruct_entities(rig, {**views, "sphere_key": rig.project(flat)})
    line = s["segment"][0] + np.outer([0.0, 0.3, 0.8], s["segment"][1] - s["segment"][0])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        st.reconstruct_entities(rig, {**views, "circle_key": rig.project(line)})


# ---------------------------------------------------------- least squares
def random_cap(rng, n, half_angle=1.2):
    c, r = rng.normal(size=3), rng.uniform(0.05, 3.0)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    d = rng.normal(size=(4 * n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    d = d[d @ axis > np.cos(half_angle)][:n]
    return c, r, c + r * d


def pratt_fit(X):
    """Independent Pratt fit: a|x|^2 + b.x + c = 0 with |b|^2 - 4ac = 1, by SciPy's generalised eigensolver."""
    Zm = np.column_stack([np.sum(X * X, axis=1), X, np.ones(len(X))])
    M = Zm.T @ Zm
    N = np.zeros((5, 5))
    N[1:4, 1:4] = np.eye(3)
    N[0, 4] = N[4, 0] = -2.0
    w, V = scipy.linalg.eig(M, N)
    w = np.real(w)
    i = np.argmin(np.where(w > -1e-12, w, np.inf))
    a, b, c = V[0, i].real, V[1:4, i].real, V[4, i].real
    return -b / (2 * a), np.sqrt(b @ b / (4 * a * a) - c / a)


@pytest.mark.parametrize("seed", range(6))
def test_conformal_fits_noise_free(seed):
    rng = np.random.default_rng(seed)
    c, r, X = random_cap(rng, 40)
    fit = sf.fit_sphere(X)
    np.testing.assert_allclose(fit.center, c, atol=1e-9 * max(1, r))
    assert fit.radius == pytest.approx(r, abs=1e-9 * max(1, r))
    assert fit.rms < 1e-9
    n = rng.normal(size=3)
    n /= np.linalg.norm(n)
    ring = st.circle_polyline(c, n, r, n=7)[:7]
    fc = sf.fit_circle(ring)
    np.testing.assert_allclose(fc.center, c, atol=1e-9 * max(1, r))
    assert fc.radius == pytest.approx(r, abs=1e-9 * max(1, r))
    assert abs(abs(fc.normal @ n) - 1) < 1e-12
    for x in ring:  # the fitted blade is the circle: x ^ z* = 0
        assert (cga.up(x) ^ fc.blade).iszero(atol=1e-8)
    P = c + rng.normal(size=(30, 2)) @ np.linalg.svd(n[None])[2][1:]
    fp = sf.fit_plane(P)
    assert abs(abs(fp.normal @ n) - 1) < 1e-12
    assert fp.distance == pytest.approx(fp.normal @ c, abs=1e-9)
    np.testing.assert_allclose(cga.plane_normal_distance(fp.blade)[0], fp.normal, atol=1e-12)


@pytest.mark.parametrize("seed", range(6))
def test_conformal_sphere_fit_is_pratts_fit_and_plane_fit_is_tls(seed):
    rng = np.random.default_rng(seed)
    c, r, X = random_cap(rng, 60, half_angle=0.9)
    X = X + rng.normal(scale=0.05 * r, size=X.shape)
    fit = sf.fit_sphere(X)
    pc, pr = pratt_fit(X)
    np.testing.assert_allclose(fit.center, pc, atol=1e-7 * max(1.0, r))
    assert fit.radius == pytest.approx(pr, rel=1e-7)
    # minimality: the conformal objective sum (x.s)^2 / s^2 is lowest at the fit
    D = cga.up(X)

    def objective(center, radius):
        s = cga.sphere(center, radius)
        return float(np.sum(np.asarray((D | s).scalar()) ** 2) / (s * s).scalar())

    best = objective(fit.center, fit.radius)
    for _ in range(20):
        assert best <= objective(fit.center + rng.normal(scale=0.01 * r, size=3), fit.radius) + 1e-15
    geometric = sf.fit_sphere_geometric(X)
    assert best <= objective(geometric.center, geometric.radius) + 1e-15
    Y = rng.normal(size=(50, 3)) * [1.0, 2.0, 0.05]
    a, b = sf.fit_plane(Y), sf.fit_plane_euclidean(Y)
    assert abs(abs(a.normal @ b.normal) - 1) < 1e-12
    assert abs(np.sign(a.normal @ b.normal) * a.distance - b.distance) < 1e-12


@settings(max_examples=30, deadline=None)
@given(
    angle=hst.floats(0.0, 6.0),
    scale=hst.floats(0.01, 100.0),
    shift=hst.tuples(*[hst.floats(-50.0, 50.0)] * 3),
)
def test_conformal_fits_commute_with_similarities(angle, scale, shift):
    rng = np.random.default_rng(1)
    _, _, X = random_cap(rng, 30)
    X = X + rng.normal(scale=0.01, size=X.shape)
    R = st.rotation_matrix([1.0, 2.0, 3.0], angle)
    Y = scale * X @ R.T + np.array(shift)
    for fit in (sf.fit_sphere, sf.fit_circle):
        a, b = fit(X), fit(Y)
        np.testing.assert_allclose(b.center, scale * R @ a.center + shift, atol=1e-7 * max(1, scale))
        assert b.radius == pytest.approx(scale * a.radius, rel=1e-7)


def test_fits_reject_degenerate_points():
    rng = np.random.default_rng(2)
    flat = np.column_stack([rng.normal(size=(20, 2)), np.zeros(20)])
    with pytest.raises(DegenerateGeometryError, match="fit_sphere: X: the points lie on a plane"):
        sf.fit_sphere(flat)
    line = np.outer(np.linspace(0, 1, 10), [1.0, 2.0, 3.0])
    for fit in (sf.fit_plane, sf.fit_circle, sf.fit_plane_euclidean):
        with pytest.raises(DegenerateGeometryError, match="line"):
            fit(line)
    with pytest.raises(DegenerateGeometryError, match="at least 4 points, got 3"):
        sf.fit_sphere(flat[:3])
    with pytest.raises(InvalidInputError, match="NaN"):
        sf.fit_plane(np.where(flat == flat[0, 0], np.nan, flat))
    with pytest.raises(InvalidInputError, match=r"shape \(N, 3\)"):
        sf.fit_circle(flat[:, :2])


def test_least_squares_beats_minimal_sets_at_half_a_pixel():
    rig, scene, _ = bundled()
    rows = ex.entity_error_table(rig, scene, np.random.default_rng(3), noise_px=0.5, trials=15)
    err = {(r.entity, r.estimator.split(",")[0].split(":")[0]): r for r in rows}
    for entity in ("circle", "plane", "sphere"):
        ls, minimal = err[(entity, "conformal LS")], err[(entity, "4.1")]
        assert ls.position_mm < minimal.position_mm
        if entity != "sphere":
            assert ls.angle_deg < minimal.angle_deg
    assert err[("plane", "conformal LS")].angle_deg == pytest.approx(err[("plane", "Euclidean LS (SVD)")].angle_deg)
    clean = ex.entity_error_table(rig, scene, np.random.default_rng(3), noise_px=0.0, trials=1)
    assert all(isinstance(r, st.EntityErrorRow) for r in clean)
    assert max(v for r in clean for v in (r.position_mm, r.radius_mm, r.angle_deg) if v == v) < 1e-6
    assert clean[0].entity == "point" and np.isnan(clean[0].radius_mm) and np.isnan(clean[0].angle_deg)


def test_ransac_planes_in_a_synthetic_cloud():
    rng = np.random.default_rng(8)
    floor = np.column_stack([rng.uniform(-2, 2, 800), rng.uniform(0, 4, 800), rng.normal(scale=0.003, size=800)])
    wall = np.column_stack([rng.uniform(-2, 2, 500), 4 + rng.normal(scale=0.003, size=500), rng.uniform(0, 2, 500)])
    junk = rng.uniform([-2, 0, 0], [2, 4, 2], size=(200, 3))
    fits, labels = cga.segment_planes(np.vstack([floor, wall, junk]), rng, n_planes=3, threshold=0.01, min_inliers=100)
    assert len(fits) == 2
    assert abs(fits[0].normal[2]) > 0.9999 and abs(fits[1].normal[1]) > 0.9999
    assert np.mean(labels[:800] == 0) > 0.97 and np.mean(labels[800:1300] == 1) > 0.97
    with pytest.raises(InvalidInputError, match="threshold"):
        ransac_plane(floor, rng, threshold=0.0)


# ------------------------------------------------------------ experiments
def test_fundamental_comparison_and_triangulation_curve():
    rig = st.load_rig()
    rows = {(r.normalize, r.rank2): r for r in ex.fundamental_comparison(rig, np.random.default_rng(1), trials=10)}
    assert rows[(True, True)].epipolar_px < 0.5 * rows[(False, True)].epipolar_px
    assert rows[(True, True)].cond_Z < 1e-3 * rows[(False, True)].cond_Z
    assert rows[(True, True)].s3_over_s2 < 1e-14 < rows[(True, False)].s3_over_s2
    c = ex.triangulation_error_curve(rig, np.random.default_rng(2), [0.0, 0.5, 1.0], n_points=100)
    assert c.midpoint[0] < 1e-9 and c.dlt[0] < 1e-9
    np.testing.assert_allclose(c.midpoint[1:], c.predicted[1:], rtol=0.3)  # first-order theory
    text = ex.format_table([{"a": "x", "b": 1.23456, "c": float("nan")}], ["a", "b", "c"], {"b": ".2f"})
    assert text.splitlines()[2].split() == ["x", "1.23", "-"]
    # typed rows print by field name, exactly as the dicts of their fields
    row = st.EntityErrorRow("plane", "fit", position_mm=1.23456, angle_deg=0.5)
    cols = ["entity", "estimator", "position_mm", "radius_mm", "angle_deg"]
    as_dict = dict(zip(cols, ["plane", "fit", 1.23456, float("nan"), 0.5]))
    fmt = {"position_mm": ".2f"}
    assert ex.format_table([row], cols, fmt) == ex.format_table([as_dict], cols, fmt)
    assert ex.format_table([row], cols, fmt).splitlines()[2].split() == ["plane", "fit", "1.23", "-", "0.5"]
    assert all(isinstance(r, st.FundamentalRow) for r in rows.values()) and len(rows) == 4
    with pytest.raises(InvalidInputError, match="format_table: rows, columns: row 0 has no 'zzz'"):
        ex.format_table([row], ["entity", "zzz"])


def test_render_views_paints_the_objects_where_they_project():
    rig, scene, s = bundled()
    left, right = render_views(rig, scene, s)
    assert left.shape == (480, 640, 3) and left.dtype == np.uint8

    def colour(img, P, X):
        u, v = np.round(cam.project(P, X)[0]).astype(int)
        return tuple(int(c) for c in img[v, u])

    for img, P in ((left, rig.P1), (right, rig.P2)):
        ball = scene.sphere_center - 0.6 * scene.sphere_radius * np.array([0, 0, 1.0])
        assert colour(img, P, ball) == (200, 60, 40)
        assert colour(img, P, scene.circle_center) == (245, 245, 240)
        assert colour(img, P, scene.board_center) == (150, 110, 70)


# ---------------------------------------------------------------- real data
def test_motorcycle_conventions_and_disparity_is_triangulation():
    left, right, disp, calib = real.load_motorcycle()
    assert np.isinf(disp).any() and not np.isnan(disp).any()  # unknown disparities are inf
    rr, cc = np.nonzero(np.isfinite(disp))
    d = disp[rr, cc]
    diffs = {}
    for sign in (-1, 1):  # which column of the right image matches?
        c2 = np.round(cc + sign * d).astype(int)
        ok = (c2 >= 0) & (c2 < disp.shape[1])
        diffs[sign] = np.mean(np.abs(left[rr[ok], cc[ok]].astype(float) - right[rr[ok], c2[ok]]))
    assert diffs[-1] < 0.3 * diffs[1]  # right (row, col - d), as in Middlebury; not col + d
    X, px = real.disparity_to_points(disp, calib, step=7)
    P1, P2 = real.motorcycle_cameras(calib)
    dd = disp[px[:, 1].astype(int), px[:, 0].astype(int)]
    Xt = tri.triangulate(P1, P2, px, px - np.column_stack([dd, np.zeros_like(dd)]))  # (A.14)
    np.testing.assert_allclose(Xt, X, atol=1e-9)
    assert 2.0 < X[:, 2].min() and X[:, 2].max() < 5.1


def test_motorcycle_planes():
    _, _, disp, calib = real.load_motorcycle()
    X, _ = real.disparity_to_points(disp, calib, step=6)
    fits, labels = cga.segment_planes(X, np.random.default_rng(0), n_planes=3, threshold=0.015, min_inliers=300)
    assert len(fits) == 3
    floor = fits[0]
    assert floor.inliers > 0.25 * len(X) and floor.rms < 0.01
    assert floor.normal @ [0.0, 1.0, 0.0] > 0.9 or floor.normal @ [0.0, -1.0, 0.0] > 0.9  # image "down"
    angles = [np.degrees(np.arccos(abs(floor.normal @ f.normal))) for f in fits[1:]]
    assert max(angles) > 80  # a wall or shelf front stands on the floor


def test_every_function_taking_a_rig_or_a_scene_refuses_another_object_in_the_same_words():
    rig = st.stereo_head()
    scene = st.load_scene()
    rng = np.random.default_rng(0)
    calls = {
        "random_scene": lambda: st.random_scene(rng, "rig"),
        "observe": lambda: st.observe("rig", np.zeros((1, 3))),
        "reconstruct_entities": lambda: st.reconstruct_entities("rig", {}),
        "random_points_in_view": lambda: ex.random_points_in_view("rig", 3, rng),
        "render_views": lambda: render_views("rig", scene),
    }
    expected = r"a StereoRig \(stereo_head, random_rig, load_rig\)"
    for func, call in calls.items():
        with pytest.raises(InvalidInputError, match=rf"^{func}: rig: .*{expected}"):
            call()
    with pytest.raises(InvalidInputError, match=r"^sample_scene: scene: .*a StereoScene \(load_scene, random_scene\)"):
        st.sample_scene("scene", rig, rng)
    with pytest.raises(InvalidInputError, match=r"^render_views: scene: .*a StereoScene \(load_scene, random_scene\)"):
        render_views(rig, "scene")
