"""Appendix A: pinhole camera (A.1-A.5), fundamental matrix (A.6-A.13), triangulation (A.14).

Truth comes from OpenCV (projectPoints, decomposeProjectionMatrix,
findFundamentalMat with FM_8POINT, triangulatePoints), from the explicit
pinhole formulas, and from the ground-truth geometry of seeded random rigs.
"""

import cv2
import numpy as np
import pytest

from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.stereo import camera as cam
from cga_lessons.stereo import epipolar as epi
from cga_lessons.stereo import observe, random_rig, rotation_matrix
from cga_lessons.stereo import triangulation as tri
from cga_lessons.stereo.experiments import random_points_in_view

SEEDS = range(8)


def random_camera(rng, skew=0.0):
    K = cam.calibration_matrix(rng.uniform(300, 1500), rng.uniform(300, 1500), rng.uniform(200, 400),
                               rng.uniform(150, 300), skew)  # fmt: skip
    R = rotation_matrix(rng.normal(size=3), rng.uniform(0, np.pi))
    C = rng.normal(scale=2.0, size=3)
    return K, R, C


def points_in_front(rng, R, C, n=30):
    """World points 1-6 m in front of a camera (R, C)."""
    Xc = np.column_stack([rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(1, 6, n)])
    return C + Xc @ R  # camera-to-world: R^T Xc


def unit_sign(F):
    F = F / np.linalg.norm(F)
    first_large = np.flatnonzero(np.abs(F.ravel()) > 0.5 * np.abs(F).max())[0]
    return F if F.flat[first_large] > 0 else -F


# ------------------------------------------------------------- one camera
def test_calibration_matrix_A2():
    K = cam.calibration_matrix(800.0, 780.0, 320.5, 240.25, 0.5)
    assert K.tolist() == [[800.0, 0.5, 320.5], [0.0, 780.0, 240.25], [0.0, 0.0, 1.0]]
    with pytest.raises(InvalidInputError, match="calibration_matrix: alpha_x: must be > 0"):
        cam.calibration_matrix(-1.0, 780.0, 0.0, 0.0)
    with pytest.raises(InvalidInputError, match="NaN"):
        cam.calibration_matrix(np.nan, 780.0, 0.0, 0.0)


@pytest.mark.parametrize("seed", SEEDS)
def test_projection_matrix_A1_equals_A3_and_pinhole_formula(seed):
    rng = np.random.default_rng(seed)
    K, R, C = random_camera(rng, skew=rng.uniform(-2, 2))
    P = cam.projection_matrix(K, R, C)
    np.testing.assert_allclose(P, cam.projection_matrix_rt(K, R, -R @ C), rtol=0, atol=1e-9 * np.abs(P).max())
    # explicit pinhole model: camera coordinates, perspective division, then K (with skew)
    X = points_in_front(rng, R, C)
    Xc = (X - C) @ R.T
    u = K[0, 0] * Xc[:, 0] / Xc[:, 2] + K[0, 1] * Xc[:, 1] / Xc[:, 2] + K[0, 2]
    v = K[1, 1] * Xc[:, 1] / Xc[:, 2] + K[1, 2]
    x, depth = cam.project(P, X, return_depth=True)
    np.testing.assert_allclose(x, np.column_stack([u, v]), rtol=0, atol=1e-9)
    np.testing.assert_allclose(depth, Xc[:, 2], rtol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_project_A5_matches_opencv(seed):
    rng = np.random.default_rng(seed)
    K, R, C = random_camera(rng)  # OpenCV's camera matrix has no skew
    X = points_in_front(rng, R, C)
    rvec, _ = cv2.Rodrigues(R)
    ref = cv2.projectPoints(X, rvec, -R @ C, K, None)[0][:, 0]
    np.testing.assert_allclose(cam.project(cam.projection_matrix(K, R, C), X), ref, rtol=0, atol=1e-8)


def test_homogeneous_A4_roundtrip_and_point_at_infinity():
    rng = np.random.default_rng(0)
    X = rng.normal(size=(10, 3))
    lam = rng.uniform(0.1, 10, size=(10, 1)) * rng.choice([-1, 1], size=(10, 1))
    np.testing.assert_allclose(cam.from_homogeneous(lam * cam.to_homogeneous(X)), X, rtol=1e-13)
    with pytest.raises(DegenerateGeometryError, match="at infinity"):
        cam.from_homogeneous([[1.0, 2.0, 3.0, 0.0]])


@pytest.mark.parametrize("seed", SEEDS)
def test_camera_center_and_optical_planes_fig_A2(seed):
    rng = np.random.default_rng(seed)
    K, R, C = random_camera(rng, skew=0.3)
    P = 3.7 * cam.projection_matrix(K, R, C) * (-1) ** seed  # P is defined up to scale
    np.testing.assert_allclose(cam.camera_center(P), C, atol=1e-10)
    planes = cam.optical_planes(P)
    np.testing.assert_allclose(planes @ np.append(C, 1.0), 0.0, atol=1e-10)  # all pass through C
    # p1 holds the points imaged on column x = 0, p2 those on row y = 0 (A.5)
    for row, pix in ((0, [0.0, rng.uniform(0, 400)]), (1, [rng.uniform(0, 400), 0.0])):
        o, d = cam.back_project(P, [pix])
        Xs = o + np.array([[1.0], [4.0]]) * d
        np.testing.assert_allclose(cam.to_homogeneous(Xs) @ planes[row], 0.0, atol=1e-9)
    # p3, with unit normal, is the depth along the principal axis
    X = points_in_front(rng, R, C, 5)
    np.testing.assert_allclose(cam.to_homogeneous(X) @ planes[2], (X - C) @ R[2], rtol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_decompose_projection_inverts_A1_like_opencv(seed):
    rng = np.random.default_rng(seed)
    K, R, C = random_camera(rng, skew=0.2)
    P = -2.5 * cam.projection_matrix(K, R, C)
    K2, R2, C2 = cam.decompose_projection(P)
    np.testing.assert_allclose(K2, K, rtol=1e-10)
    np.testing.assert_allclose(R2, R, atol=1e-12)
    np.testing.assert_allclose(C2, C, atol=1e-10)
    Kc, Rc, Ch = cv2.decomposeProjectionMatrix(-P)[:3]
    np.testing.assert_allclose(Kc / Kc[2, 2], K2, rtol=1e-8)
    np.testing.assert_allclose(Rc, R2, atol=1e-10)
    np.testing.assert_allclose(Ch[:3, 0] / Ch[3, 0], C2, atol=1e-9)


def test_pseudo_inverse_footnote_A14():
    rng = np.random.default_rng(3)
    P = cam.projection_matrix(*random_camera(rng))
    Pp = cam.pseudo_inverse(P)
    np.testing.assert_allclose(P @ Pp, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(Pp, np.linalg.pinv(P), rtol=1e-9, atol=1e-15)
    with pytest.raises(DegenerateGeometryError):
        cam.pseudo_inverse(np.ones((3, 4)))


@pytest.mark.parametrize("seed", SEEDS)
def test_back_projected_rays_A14_pass_through_the_points(seed):
    rng = np.random.default_rng(seed)
    K, R, C = random_camera(rng, skew=0.1)
    P = cam.projection_matrix(K, R, C) * (-1) ** seed
    X = points_in_front(rng, R, C)
    o, d = cam.back_project(P, cam.project(P, X))
    np.testing.assert_allclose(o, np.tile(C, (len(X), 1)), atol=1e-10)
    t = np.sum((X - o) * d, axis=1)
    assert np.all(t > 0)  # the ray points in front of the camera
    np.testing.assert_allclose(o + t[:, None] * d, X, atol=1e-9)


def test_camera_input_errors():
    P = cam.projection_matrix(np.eye(3), np.eye(3), np.zeros(3))
    with pytest.raises(InvalidInputError, match=r"project: X: expected shape \(3,\) or \(N, 3\)"):
        cam.project(P, np.zeros((4, 2)))
    with pytest.raises(InvalidInputError, match="NaN"):
        cam.project(P, [[0.0, np.nan, 1.0]])
    with pytest.raises(DegenerateGeometryError, match="principal plane"):
        cam.project(P, [[1.0, 1.0, 0.0]])
    with pytest.raises(InvalidInputError, match="projection_matrix: R: is not a rotation"):
        cam.projection_matrix(np.eye(3), 2 * np.eye(3), np.zeros(3))
    with pytest.raises(DegenerateGeometryError, match="projection_matrix_rt: K: is singular"):  # zero focal length
        cam.projection_matrix_rt(np.diag([0.0, 1.0, 1.0]), np.eye(3), np.zeros(3))
    with pytest.raises(DegenerateGeometryError, match="at infinity"):
        cam.camera_center(np.hstack([np.eye(3)[:, :2], np.zeros((3, 1)), np.ones((3, 1))]))


# ------------------------------------------------------------- two views
def test_two_view_geometry_builds_on_the_camera_without_a_circle():
    """epipolar imports camera; camera does not import epipolar (nor re-export its names)."""
    import ast
    import inspect

    tree = ast.parse(inspect.getsource(cam))
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    imported |= {a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.level for a in n.names}
    assert "epipolar" not in imported and "cga_lessons.stereo.epipolar" not in imported
    for name in ("fundamental_8point", "cameras_from_fundamental", "skew", "epipolar_lines"):
        assert not hasattr(cam, name) and callable(getattr(epi, name))


def test_skew_A12_is_the_cross_product():
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=(2, 3))
    np.testing.assert_allclose(epi.skew(a) @ b, np.cross(a, b), rtol=1e-14)
    np.testing.assert_allclose(epi.skew(a).T, -epi.skew(a))


def test_eight_point_matrix_A7_A9_is_the_bilinear_form():
    rng = np.random.default_rng(1)
    x1, x2 = rng.uniform(0, 640, size=(2, 12, 2))
    F = rng.normal(size=(3, 3))
    Z = epi.eight_point_matrix(x1, x2)
    direct = np.einsum("ni,ij,nj->n", cam.to_homogeneous(x2), F, cam.to_homogeneous(x1))
    np.testing.assert_allclose(Z @ F.ravel(), direct, rtol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("normalize", [True, False])
def test_fundamental_8point_noise_free_reproduces_truth(seed, normalize):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    x1, x2 = rig.project(random_points_in_view(rig, 8 + seed * 5, rng))
    F = epi.fundamental_8point(x1, x2, normalize=normalize)
    np.testing.assert_allclose(F, rig.F, rtol=0, atol=1e-9)
    residual = np.einsum("ni,ij,nj->n", cam.to_homogeneous(x2), F, cam.to_homogeneous(x1))  # (A.6)
    assert np.max(np.abs(residual)) < 1e-9
    assert np.max(epi.epipolar_distance(F, x1, x2)) < 1e-7  # pixels


def test_fundamental_of_a_parallel_rig_has_a_stable_sign():
    """Two equal entries (+-1/sqrt 2) in a parallel rig's F: round-off must not flip the sign convention."""
    K = cam.calibration_matrix(700.0, 700.0, 319.5, 239.5)
    P1 = cam.projection_matrix(K, np.eye(3), [0.06, 0.0, 0.0])
    P2 = cam.projection_matrix(K, np.eye(3), [-0.06, 0.0, 0.0])
    F_true = epi.fundamental_from_cameras(P1, P2)
    rng = np.random.default_rng(0)
    for _ in range(5):
        X = np.column_stack([rng.uniform(-1, 1, 20), rng.uniform(-1, 1, 20), rng.uniform(1, 5, 20)])
        x1, x2 = cam.project(P1, X), cam.project(P2, X)
        for normalize in (True, False):
            np.testing.assert_allclose(epi.fundamental_8point(x1, x2, normalize=normalize), F_true, atol=1e-9)
    np.testing.assert_allclose(np.abs(F_true), [[0, 0, 0], [0, 0, 1], [0, 1, 0]] / np.sqrt(2), atol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_fundamental_8point_is_opencvs_estimator_with_noise(seed):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    x1, x2 = observe(rig, random_points_in_view(rig, 40, rng), 0.5, rng)
    F = epi.fundamental_8point(x1, x2)
    Fc, _ = cv2.findFundamentalMat(x1, x2, cv2.FM_8POINT)
    assert np.linalg.norm(F - unit_sign(Fc)) < 1e-5  # OpenCV's double-precision normal equations
    assert np.linalg.norm(F - rig.F) > 1e-4  # ... while noise moves both away from the truth


@pytest.mark.parametrize("seed", SEEDS)
def test_rank2_step_and_epipoles_are_the_other_centre(seed):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    x1, x2 = observe(rig, random_points_in_view(rig, 30, rng), 1.0, rng)
    F = epi.fundamental_8point(x1, x2)
    s = np.linalg.svd(F, compute_uv=False)
    assert s[2] < 1e-14 * s[0]
    s_raw = np.linalg.svd(epi.fundamental_8point(x1, x2, rank2=False), compute_uv=False)
    assert s_raw[2] > 1e-9 * s_raw[0]  # with noise the least-squares F has full rank
    e1, e2 = epi.epipoles(rig.F)
    for e, P, C in ((e1, rig.P1, rig.C2), (e2, rig.P2, rig.C1)):
        img = P @ np.append(C, 1.0)  # the epipole is the image of the other camera's centre
        assert np.linalg.norm(np.cross(e, img / np.linalg.norm(img))) < 1e-9


@pytest.mark.parametrize("seed", range(4))
def test_normalisation_matters_with_noise(seed):
    """Hartley's normalisation: same data, a better F (the notebook's table, as a check on random rigs)."""
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    dn, du = [], []
    for _ in range(20):
        x1, x2 = observe(rig, random_points_in_view(rig, 20, rng), 0.5, rng)
        y1, y2 = rig.project(random_points_in_view(rig, 100, rng))
        dn.append(np.mean(epi.epipolar_distance(epi.fundamental_8point(x1, x2, normalize=True), y1, y2)))
        du.append(np.mean(epi.epipolar_distance(epi.fundamental_8point(x1, x2, normalize=False), y1, y2)))
    assert np.median(du) > 1.3 * np.median(dn)


def test_fundamental_degenerate_input():
    rng = np.random.default_rng(5)
    rig = random_rig(rng)
    X = random_points_in_view(rig, 20, rng)
    x1, x2 = rig.project(X)
    with pytest.raises(DegenerateGeometryError, match="at least 8 correspondences, got 7"):
        epi.fundamental_8point(x1[:7], x2[:7])
    line = rig.C1 + 3 * rig.R1[2] + np.linspace(-0.5, 0.5, 12)[:, None] * rig.R1[0]  # all on one 3D line
    with pytest.raises(DegenerateGeometryError, match="degenerate"):
        epi.fundamental_8point(*rig.project(line))
    centre = rig.C1 + 3 * rig.R1[2]  # all on one plane in space
    plane = centre + rng.uniform(-0.5, 0.5, (15, 1)) * rig.R1[0] + rng.uniform(-0.4, 0.4, (15, 1)) * rig.R1[1]
    with pytest.raises(DegenerateGeometryError, match="degenerate"):
        epi.fundamental_8point(*rig.project(plane))
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        epi.fundamental_8point(np.ones((9, 2)), x2[:9])
    with pytest.raises(InvalidInputError, match="NaN"):
        epi.fundamental_8point(np.where(np.arange(20)[:, None] == 3, np.nan, x1), x2)
    with pytest.raises(InvalidInputError, match="fundamental_8point: x1, x2: must have the same length, got 20 and 19"):
        epi.fundamental_8point(x1, x2[:19])
    with pytest.raises(InvalidInputError, match=r"fundamental_8point: x1: expected shape \(2,\) or \(N, 2\)"):
        epi.fundamental_8point(X, X)


def projective_map(Xa, Xb):
    """4x4 H with Xb ~ H Xa (homogeneous rows), by linear least squares; and its residual."""
    rows = []
    for a, b in zip(Xa, Xb):
        for i in range(4):
            for j in range(i + 1, 4):  # b_i (H a)_j - b_j (H a)_i = 0
                r = np.zeros((4, 4))
                r[j] += b[i] * a
                r[i] -= b[j] * a
                rows.append(r.ravel())
    _, s, vt = np.linalg.svd(np.array(rows))
    return vt[-1].reshape(4, 4), s[-1] / s[0]


@pytest.mark.parametrize("seed", SEEDS)
def test_cameras_from_fundamental_A10_A13(seed):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    X = random_points_in_view(rig, 12, rng)
    x1, x2 = rig.project(X)
    F = epi.fundamental_8point(x1, x2)
    v, lam = rng.normal(size=3), rng.uniform(0.5, 2.0)
    for P1, P2 in (epi.cameras_from_fundamental(F), epi.cameras_from_fundamental(F, v, lam)):
        np.testing.assert_array_equal(P1, np.hstack([np.eye(3), np.zeros((3, 1))]))  # (A.10)
        np.testing.assert_allclose(epi.fundamental_from_cameras(P1, P2), F, atol=1e-9)  # the pair has F
        Xp = tri.triangulate(P1, P2, x1, x2, method="dlt")  # a projective reconstruction
        np.testing.assert_allclose(cam.project(P1, Xp), x1, atol=1e-6)
        np.testing.assert_allclose(cam.project(P2, Xp), x2, atol=1e-6)
        # ... equal to the true scene up to a projective transformation of space
        H, residual = projective_map(cam.to_homogeneous(X), cam.to_homogeneous(Xp))
        assert residual < 1e-9
    with pytest.raises(DegenerateGeometryError, match="rank 2"):
        epi.cameras_from_fundamental(epi.fundamental_8point(*observe(rig, X, 1.0, rng), rank2=False))
    with pytest.raises(InvalidInputError, match="non-zero"):
        epi.cameras_from_fundamental(F, lam=0.0)


# ---------------------------------------------------------- triangulation
@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("method", ["midpoint", "dlt"])
def test_triangulate_noise_free_reproduces_truth(seed, method):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    X = random_points_in_view(rig, 50, rng)
    Xt = tri.triangulate(rig.P1, rig.P2, *rig.project(X), method=method)
    assert Xt.shape == (50, 3)
    np.testing.assert_allclose(Xt, X, rtol=0, atol=1e-9)


@pytest.mark.parametrize("seed", SEEDS)
def test_dlt_matches_opencv_triangulatePoints(seed):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    X = random_points_in_view(rig, 40, rng)
    x1, x2 = observe(rig, X, 1.0, rng)
    ref = cv2.triangulatePoints(rig.P1, rig.P2, x1.T, x2.T)
    np.testing.assert_allclose(tri.triangulate(rig.P1, rig.P2, x1, x2, "dlt"), (ref[:3] / ref[3]).T, atol=1e-8)


@pytest.mark.parametrize("seed", SEEDS)
def test_midpoint_is_the_middle_of_the_common_perpendicular_fig_A4(seed):
    rng = np.random.default_rng(seed)
    rig = random_rig(rng)
    X = random_points_in_view(rig, 30, rng)
    x1, x2 = observe(rig, X, 2.0, rng)
    Xm = tri.triangulate(rig.P1, rig.P2, x1, x2)
    o1, d1 = cam.back_project(rig.P1, x1)
    o2, d2 = cam.back_project(rig.P2, x2)
    for i in range(len(X)):  # independent: least squares for the two ray parameters
        (s, t), *_ = np.linalg.lstsq(np.column_stack([d1[i], -d2[i]]), o2[i] - o1[i], rcond=None)
        q1, q2 = o1[i] + s * d1[i], o2[i] + t * d2[i]
        assert abs(np.dot(q2 - q1, d1[i])) < 1e-9 and abs(np.dot(q2 - q1, d2[i])) < 1e-9
        np.testing.assert_allclose(Xm[i], 0.5 * (q1 + q2), atol=1e-9)
    assert np.median(np.linalg.norm(Xm - tri.triangulate(rig.P1, rig.P2, x1, x2, "dlt"), axis=1)) < 0.05


def test_triangulate_degenerate_input():
    K = cam.calibration_matrix(500.0, 500.0, 320.0, 240.0)
    P1 = cam.projection_matrix(K, np.eye(3), np.zeros(3))
    P2 = cam.projection_matrix(K, np.eye(3), [0.2, 0.0, 0.0])
    x = np.array([[300.0, 200.0], [310.0, 250.0]])
    for method in ("midpoint", "dlt"):  # same pixel in a parallel rig: parallel rays
        with pytest.raises(DegenerateGeometryError, match="parallel rays"):
            tri.triangulate(P1, P2, x, x, method=method)
    for method in ("midpoint", "dlt"):  # both cameras at the same place
        with pytest.raises(DegenerateGeometryError, match="share their centre"):
            tri.triangulate(P1, 2 * cam.projection_matrix(K, np.eye(3), [0.0, 1e-14, 0.0]), x, x + 5.0, method=method)
    with pytest.raises(InvalidInputError, match="triangulate: method: must be one of 'midpoint', 'dlt'"):
        tri.triangulate(P1, P2, x, x, method="mid")
    with pytest.raises(InvalidInputError, match="NaN"):
        tri.triangulate(P1, P2, [[np.nan, 1.0]], x[:1])
    with pytest.raises(InvalidInputError, match="triangulate: x1, x2: must have the same length, got 2 and 1"):
        tri.triangulate(P1, P2, x, x[:1])
    with pytest.raises(InvalidInputError, match=r"triangulate: P2: expected shape \(3, 4\)"):
        tri.triangulate(P1, P2[:, :3], x, x)
