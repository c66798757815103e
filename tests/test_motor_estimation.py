"""Motors from points and lines, mean motors, quaternions: checked against plain NumPy and SciPy."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector
from cga_lessons.conformal.motor_estimation import (
    mean_motor,
    motor_from_points,
    quaternion_to_rotor,
    rotor_to_quaternion,
)
from cga_lessons.conformal.motor_lines import motor_from_lines

seeds = st.integers(0, 2**32 - 1)
unit_axis = st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1)
angle = st.floats(-3.1, 3.1)
translation = st.tuples(*[st.floats(-10, 10)] * 3)


def random_motor(rng, scale=3.0):
    H = np.eye(4)
    H[:3, :3] = Rotation.random(random_state=rng).as_matrix()
    H[:3, 3] = rng.normal(size=3) * scale
    return cga.matrix_to_motor(H), H


def kabsch(x, y, w):
    """The independent truth: weighted Kabsch/Umeyama (no scale) with plain NumPy SVD."""
    xb, yb = w @ x / w.sum(), w @ y / w.sum()
    U, _, Vt = np.linalg.svd(((x - xb) * w[:, None]).T @ (y - yb))
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(Vt.T @ U.T))])
    R = Vt.T @ D @ U.T
    return R, yb - R @ xb


# ------------------------------------------------------------ quaternions
@settings(max_examples=40, deadline=None)
@given(seeds)
def test_quaternion_matches_scipy_both_orders_and_double_cover(seed):
    q = np.random.default_rng(seed).normal(size=4)  # SciPy order (x, y, z, w), not normalised
    expected = Rotation.from_quat(q).as_matrix()
    for quat in (q, -q):  # q and -q: the same rotation
        R = quaternion_to_rotor(quat, scalar_first=False)
        assert np.allclose(cga.motor_to_matrix(R)[:3, :3], expected, atol=1e-12)
        assert np.allclose(rotor_to_quaternion(R, scalar_first=False), quat / np.linalg.norm(quat), atol=1e-14)
    R = quaternion_to_rotor(np.roll(q, 1))  # scalar first, the default
    assert np.allclose(cga.motor_to_matrix(R)[:3, :3], expected, atol=1e-12)
    assert np.allclose(rotor_to_quaternion(R), np.roll(q, 1) / np.linalg.norm(q), atol=1e-14)


@settings(max_examples=40, deadline=None)
@given(unit_axis, angle)
def test_rotor_quaternion_is_scipys_rotvec_quaternion(axis, ang):
    n = np.array(axis) / np.linalg.norm(axis)
    q = rotor_to_quaternion(cga.rotor(n, ang), scalar_first=False)
    expected = Rotation.from_rotvec(ang * n).as_quat()
    assert min(np.abs(q - expected).max(), np.abs(q + expected).max()) < 1e-14
    # the blade map of the docstring: w = <R>_0, (x, y, z) = -(<R>_e23, <R>_e31, <R>_e12)
    R = cga.rotor(n, ang)
    assert np.allclose(q, [-R["e23"], -R["e31"], -R["e12"], R["1"]], atol=1e-15)


def test_quaternion_batches_round_trip():
    q = np.random.default_rng(1).normal(size=(7, 4))
    R = quaternion_to_rotor(q)
    assert R.shape == (7,)
    assert np.allclose(rotor_to_quaternion(R), q / np.linalg.norm(q, axis=1, keepdims=True), atol=1e-15)
    single = rotor_to_quaternion(R.batch_item(3))
    assert np.allclose(single, q[3] / np.linalg.norm(q[3]), atol=1e-15)


@pytest.mark.parametrize(
    "func, arg, err, text",
    [
        (quaternion_to_rotor, [0.0, 0, 0, 0], DegenerateGeometryError, "zero quaternion"),
        (quaternion_to_rotor, [1.0, np.nan, 0, 0], InvalidInputError, "NaN"),
        (quaternion_to_rotor, [1.0, 0, 0], InvalidInputError, "shape"),
        (quaternion_to_rotor, "abcd", InvalidInputError, "numbers"),
        (rotor_to_quaternion, cga.motor([0, 0, 1], 0.3, [1, 0, 0]), InvalidInputError, "blades"),
        (rotor_to_quaternion, np.array([1.0, 0, 0, 0]), InvalidInputError, "Multivector"),
        (rotor_to_quaternion, cga.rotor([0, 0, 1], 0.3) * 0.0, DegenerateGeometryError, "zero rotor"),
    ],
)
def test_quaternion_errors(func, arg, err, text):
    with pytest.raises(err, match=text):
        func(arg)


# ------------------------------------------------------------------ points
@settings(max_examples=30, deadline=None)
@given(seeds, st.integers(3, 40), st.floats(0.0, 0.5))
def test_points_agree_with_kabsch_and_align_vectors(seed, n, noise):
    rng = np.random.default_rng(seed)
    M0, _ = random_motor(rng)
    x = rng.normal(size=(n, 3)) * rng.uniform(0.5, 5) + rng.normal(size=3) * 10
    y = cga.apply_to_points(M0, x) + rng.normal(size=(n, 3)) * noise
    w = rng.uniform(0.1, 3.0, n)
    H = cga.motor_to_matrix(motor_from_points(x, y, w))
    R, t = kabsch(x, y, w)
    assert np.abs(H[:3, :3] - R).max() < 1e-9
    assert np.abs(H[:3, 3] - t).max() < 1e-9 * max(1.0, np.abs(t).max())
    xb, yb = w @ x / w.sum(), w @ y / w.sum()
    R_sp, _ = Rotation.align_vectors(y - yb, x - xb, weights=w)
    assert np.abs(H[:3, :3] - R_sp.as_matrix()).max() < 1e-9


@settings(max_examples=30, deadline=None)
@given(unit_axis, angle, translation, seeds)
def test_points_recover_a_motor_without_noise(axis, ang, t, seed):
    M0 = cga.motor(axis, ang, t)
    x = np.random.default_rng(seed).normal(size=(5, 3)) * 2
    M = motor_from_points(x, cga.apply_to_points(M0, x))
    assert np.abs(cga.motor_to_matrix(M) - cga.motor_to_matrix(M0)).max() < 1e-10
    assert abs(float((M * ~M).scalar()) - 1.0) < 1e-13  # unit motor
    sign = np.sign(M["1"] * M0["1"]) or 1.0  # M and -M are the same motion
    assert (M - M0 * sign).iszero(atol=1e-10)


def test_points_far_from_the_origin_keep_their_accuracy():
    rng = np.random.default_rng(5)
    far = 1e6
    x = rng.normal(size=(30, 3)) + far * np.array([1.0, -0.6, 0.3])
    M0 = cga.motor([1, 2, 3], 1.0, [5, 6, 7])
    y = cga.apply_to_points(M0, x)
    M = motor_from_points(x, y)
    H, H0 = cga.motor_to_matrix(M), cga.motor_to_matrix(M0)
    assert np.abs(H[:3, :3] - H0[:3, :3]).max() < 1e-9  # rotation: unitless
    assert np.abs(H[:3, 3] - H0[:3, 3]).max() / far < 1e-9  # translation relative to the scene's distance
    assert np.abs(cga.apply_to_points(M, x) - y).max() / far < 1e-12
    noisy = y + rng.normal(size=y.shape) * 1e-3  # with noise: still Kabsch on the shifted data
    R, t = kabsch(x - x[0], noisy - x[0], np.ones(30))
    H = cga.motor_to_matrix(motor_from_points(x, noisy))
    assert np.abs(H[:3, :3] - R).max() < 1e-9


@settings(max_examples=30, deadline=None)
@given(seeds, st.integers(2, 30), st.floats(-3.1, 3.1))
def test_planar_points_match_the_2d_closed_form(seed, n, theta):
    rng = np.random.default_rng(seed)
    x = rng.normal(size=(n, 2)) * 3
    c, s = np.cos(theta), np.sin(theta)
    y = x @ np.array([[c, -s], [s, c]]).T + rng.normal(size=2) * 5 + rng.normal(size=(n, 2)) * 0.2
    w = rng.uniform(0.2, 2.0, n)
    H = cga.motor_to_matrix(motor_from_points(x, y, w))
    a, b = x - w @ x / w.sum(), y - w @ y / w.sum()
    phi = np.arctan2(w @ (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), w @ np.sum(a * b, axis=1))
    R2 = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    assert np.abs(H[:2, :2] - R2).max() < 1e-10
    assert np.abs(H[:2, 3] - (w @ y - R2 @ (w @ x)) / w.sum()).max() < 1e-9
    assert not H[2, [0, 1, 3]].any() and not H[:2, 2].any()  # a motion in the plane z = 0, exactly
    assert abs(H[2, 2] - 1.0) < 1e-15


def test_planar_points_without_noise_and_the_3d_version_of_them_agree():
    x = np.array([[0.0, 0.0], [2.0, 1.0], [-1.0, 3.0]])
    M0 = cga.motor([0, 0, 1], 2.9, [1.0, -2.0, 0.0])
    y = cga.apply_to_points(M0, np.pad(x, ((0, 0), (0, 1))))
    M2 = motor_from_points(x, y[:, :2])
    M3 = motor_from_points(np.pad(x, ((0, 0), (0, 1))), y)  # coplanar but not collinear: fine in 3D too
    for M in (M2, M3):
        assert np.abs(cga.motor_to_matrix(M) - cga.motor_to_matrix(M0)).max() < 1e-12


def test_zero_weights_drop_points():
    rng = np.random.default_rng(2)
    x, y = rng.normal(size=(8, 3)), rng.normal(size=(8, 3))
    w = np.array([1.0, 2, 0, 1, 0, 3, 1, 0])
    keep = w > 0
    H = cga.motor_to_matrix(motor_from_points(x, y, w))
    assert np.allclose(H, cga.motor_to_matrix(motor_from_points(x[keep], y[keep], w[keep])), atol=1e-12)


_pts = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])


@pytest.mark.parametrize(
    "source, target, weights, err, text",
    [
        (_pts[:2], _pts[:2], None, DegenerateGeometryError, "source: needs at least 3 points"),
        (_pts[:, :2][:1], _pts[:, :2][:1], None, DegenerateGeometryError, "source: needs at least 2 points"),
        (_pts * [1, 0, 0], _pts, None, DegenerateGeometryError, "source: the points are collinear"),
        (_pts, _pts * [1, 0, 0], None, DegenerateGeometryError, "target: the points are collinear"),
        (np.ones((4, 3)), _pts, None, DegenerateGeometryError, "source: the points coincide"),
        (_pts[:, :2], np.ones((4, 2)), None, DegenerateGeometryError, "target: the points coincide"),
        (_pts, _pts[:3], None, InvalidInputError, "target: shape"),
        (_pts, _pts[:, :2], None, InvalidInputError, "target: shape"),
        (_pts[:, :1], _pts[:, :1], None, InvalidInputError, r"source: must have shape \(N, 3\) or \(N, 2\)"),
        (_pts + [np.nan, 0, 0], _pts, None, InvalidInputError, "source: contains NaN or inf"),
        (_pts, _pts + [0, np.inf, 0], None, InvalidInputError, "target: contains NaN or inf"),
        (_pts, _pts, [1, 1, -1, 1], InvalidInputError, "weights: negative"),
        (_pts, _pts, [0, 0, 0, 0], InvalidInputError, "weights: all weights are zero"),
        (_pts, _pts, [1, 1, 1], InvalidInputError, "weights: shape"),
        (_pts, _pts, [1, 1, np.nan, 1], InvalidInputError, "weights: contains NaN"),
        (
            _pts,
            _pts,
            [1, 1, 0, 0],
            DegenerateGeometryError,
            "source: needs at least 3 points with positive weight, got 2",
        ),
    ],
)
def test_points_degenerate_input(source, target, weights, err, text):
    with pytest.raises(err, match="^motor_from_points: " + text):
        motor_from_points(source, target, weights)


# ------------------------------------------------------------------- lines
def plucker_cost(M, source, target, w, length_scale=1.0):
    """The cost of motor_from_lines, computed independently with the sandwich M L ~M (2.103)."""
    moved = cga.apply(M, source)
    d, m = cga.line_direction(moved), cga.line_moment(moved)
    dt, mt = cga.line_direction(target), cga.line_moment(target)
    # c: least-squares point closest to the target lines
    P = np.eye(3) - dt[:, :, None] * dt[:, None, :]
    A = np.vstack(list(np.sqrt(w)[:, None, None] * P))
    c = np.linalg.lstsq(A, np.concatenate(list(np.sqrt(w)[:, None, None] * P @ np.cross(dt, mt)[:, :, None])))[0]
    c = c.ravel()
    dm = (m - np.cross(c, d)) - (mt - np.cross(c, dt))
    return float(w @ (np.sum(dm**2, axis=1) + length_scale**2 * np.sum((d - dt) ** 2, axis=1)))


def lines_of(M, a, b):
    return cga.line_from_points(cga.apply_to_points(M, a), cga.apply_to_points(M, b))


@settings(max_examples=20, deadline=None)
@given(seeds, st.integers(2, 8))
def test_lines_recover_a_motor_without_noise(seed, n):
    rng = np.random.default_rng(seed)
    M0, H0 = random_motor(rng)
    a = rng.normal(size=(n, 3)) * 3
    b = a + rng.normal(size=(n, 3))
    source, target = cga.line_from_points(a, b), lines_of(M0, a, b)
    M = motor_from_lines(source, target)
    assert np.abs(cga.motor_to_matrix(M) - H0).max() < 1e-10
    assert cga.apply(M, cga.normalize_line(source)).isclose(cga.normalize_line(target), atol=1e-9)
    as_list = [cga.line_from_points(p, q) for p, q in zip(a, b)]  # a list of lines is the same as a batch
    target_list = [target.batch_item(i) for i in range(n)]
    assert np.abs(cga.motor_to_matrix(motor_from_lines(as_list, target_list)) - H0).max() < 1e-10


def test_noisy_lines_agree_with_the_point_estimate_and_minimise_their_cost():
    rng = np.random.default_rng(11)
    M0, H0 = random_motor(rng)
    a = rng.normal(size=(30, 3)) * 3
    b = a + rng.normal(size=(30, 3)) * 2
    noise = 0.01
    an = cga.apply_to_points(M0, a) + rng.normal(size=a.shape) * noise
    bn = cga.apply_to_points(M0, b) + rng.normal(size=b.shape) * noise
    source, target = cga.line_from_points(a, b), cga.line_from_points(an, bn)
    w = rng.uniform(0.5, 2.0, 30)
    M = motor_from_lines(source, target, w)
    Hl, Hp = cga.motor_to_matrix(M), cga.motor_to_matrix(motor_from_points(np.vstack([a, b]), np.vstack([an, bn])))
    for H in (Hl, Hp):
        assert np.abs(H[:3, :3] - H0[:3, :3]).max() < 5 * noise
        assert np.abs(H[:3, 3] - H0[:3, 3]).max() < 20 * noise
    assert np.abs(Hl - Hp).max() < 20 * noise
    # the start (max_iterations=0): for its rotor, the translation already minimises the cost
    M_start = motor_from_lines(source, target, w, max_iterations=0)
    start = plucker_cost(M_start, source, target, w)
    for v in np.vstack([np.eye(3), -np.eye(3)]) * 1e-4:
        assert plucker_cost(cga.translator(v) * M_start, source, target, w) > start
    # a local minimum of the stated cost: no small motor does better
    best = plucker_cost(M, source, target, w)
    assert best < plucker_cost(M0, source, target, w)
    for k in range(12):
        v = np.zeros(6)
        v[k % 6] = 1e-4 * (1 if k < 6 else -1)
        dM = cga.translator(v[3:]) * cga.rotor(v[:3] if k % 6 < 3 else [0, 0, 1], np.linalg.norm(v[:3]))
        assert plucker_cost(dM * M, source, target, w) > best


def test_lines_estimate_does_not_depend_on_the_origin():
    rng = np.random.default_rng(4)
    M0, _ = random_motor(rng)
    a, b = rng.normal(size=(6, 3)) * 2, rng.normal(size=(6, 3)) * 2
    an, bn = (cga.apply_to_points(M0, p) + rng.normal(size=p.shape) * 0.05 for p in (a, b))
    H = cga.motor_to_matrix(motor_from_lines(cga.line_from_points(a, b), cga.line_from_points(an, bn)))
    # move both frames' origins (by metres: CGA lines built far away carry ~|x|^3 eps errors of their own)
    s, s2 = np.array([10.0, -5.0, 2.0]), np.array([-3.0, 1.0, 7.0])
    H2 = cga.motor_to_matrix(
        motor_from_lines(cga.line_from_points(a + s, b + s), cga.line_from_points(an + s2, bn + s2))
    )
    assert np.abs(H2[:3, :3] - H[:3, :3]).max() < 1e-11
    assert np.abs(H2[:3, 3] - (H[:3, 3] + s2 - H[:3, :3] @ s)).max() < 1e-10


def test_lines_degenerate_input():
    L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])
    L2 = cga.line_from_points([0, 1, 0], [1, 1, 0])  # parallel to L1
    L3 = cga.line_from_points([0, 0, 1], [0, 1, 1])
    with pytest.raises(DegenerateGeometryError, match="^motor_from_lines: source_lines: the lines are all parallel"):
        motor_from_lines([L1, L2], [L1, L3])
    with pytest.raises(DegenerateGeometryError, match="^motor_from_lines: target_lines: the lines are all parallel"):
        motor_from_lines([L1, L3], [L1, L2])
    with pytest.raises(DegenerateGeometryError, match="^motor_from_lines: source_lines: needs at least 2"):
        motor_from_lines([L1], [L1])
    both = "source_lines, target_lines"
    with pytest.raises(InvalidInputError, match=f"^motor_from_lines: {both}: must have the same length, got 2 and 3"):
        motor_from_lines([L1, L3], [L1, L3, L2])
    with pytest.raises(InvalidInputError, match="^motor_from_lines: source_lines: expected CGA lines"):
        motor_from_lines([cga.up([1.0, 2, 3]), L3], [L1, L3])
    nan_line = Multivector(cga.G41, {b: np.nan for b in L1.coeffs})
    with pytest.raises(InvalidInputError, match="^motor_from_lines: source_lines: contains NaN or inf"):
        motor_from_lines([nan_line, L3], [L1, L3])
    with pytest.raises(InvalidInputError, match="^motor_from_lines: weights: negative"):
        motor_from_lines([L1, L3], [L1, L3], [1.0, -1.0])
    with pytest.raises(InvalidInputError, match="^motor_from_lines: length_scale"):
        motor_from_lines([L1, L3], [L1, L3], length_scale=0.0)


# ------------------------------------------------------------------- means
@settings(max_examples=30, deadline=None)
@given(seeds, st.integers(1, 12), st.floats(0.05, 1.5))
def test_mean_rotation_is_scipys_mean(seed, n, spread):
    rng = np.random.default_rng(seed)
    rots = Rotation.from_rotvec(rng.normal(size=(n, 3)) * spread) * Rotation.random(random_state=rng)
    w = rng.uniform(0.1, 2.0, n)
    t = rng.normal(size=(n, 3)) * 4
    flips = rng.choice([-1.0, 1.0], n)  # the double cover: -M is the same motion
    motors = [
        cga.translator(ti) * quaternion_to_rotor(q * f, scalar_first=False)
        for ti, q, f in zip(t, rots.as_quat(), flips)
    ]
    H = cga.motor_to_matrix(mean_motor(motors, w))
    assert np.abs(H[:3, :3] - rots.mean(weights=w).as_matrix()).max() < 1e-10
    assert np.abs(H[:3, 3] - w @ t / w.sum()).max() < 1e-12 * max(1.0, np.abs(t).max())


def test_mean_motor_inputs_and_errors():
    M = cga.motor([1, 0, 0], 0.7, [1, 2, 3])
    assert (mean_motor([M]) - M).iszero(atol=1e-14)
    assert (mean_motor([M * 2.0, -M]) - M).iszero(atol=1e-14)  # scaled and sign-flipped copies
    batch = cga.motor(np.eye(3), [0.1, 0.2, 0.3], np.eye(3))
    single = mean_motor([batch.batch_item(i) for i in range(3)])
    assert (mean_motor(batch) - single).iszero(atol=1e-14)
    with pytest.raises(DegenerateGeometryError, match="^mean_motor: motors: the mean rotation is not unique"):
        mean_motor([cga.rotor([0, 0, 1], 0.0), cga.rotor([0, 0, 1], np.pi)])
    with pytest.raises(InvalidInputError, match="^mean_motor: motors: needs at least one"):
        mean_motor([])
    with pytest.raises(InvalidInputError, match=r"^mean_motor: motors\[1\]: M ~M is not a scalar"):
        mean_motor([M, M + 0.5 * cga.e1 * cga.e2 * cga.ep * cga.em])
    with pytest.raises(InvalidInputError, match=r"^mean_motor: motors\[0\]: expected a motor"):
        mean_motor([np.eye(4)])
    with pytest.raises(InvalidInputError, match="^mean_motor: weights: all weights are zero"):
        mean_motor([M, M], [0.0, 0.0])
