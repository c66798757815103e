"""Versors far from the origin, scaled versors, and the inputs the versor functions must refuse.

Independent truths: rigid transforms built here with plain NumPy (Rodrigues' formula), the same with mpmath at
50 digits, kingdon's sandwich, SciPy's ``Rotation``.  Tables 2.2 and Eqs. (2.94)-(2.110), (2.135)-(2.145).

Relative errors are taken against |answer|, or against 1e-6 of the inputs' size when the answer is a
near-total cancellation (R x = -t), where no floating-point method -- the Rodrigues truth included -- has
relative accuracy.
"""

import time

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector
from cga_lessons.conformal import G41

RNG = np.random.default_rng(20250607)
EPS = np.finfo(float).eps


def rodrigues(axis, angle):
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * np.outer(n, n)


def rel_err(got, truth, *inputs):
    """max over rows of |got - truth| / max(|truth|, 1e-6 |inputs|)."""
    got, truth = np.atleast_2d(got), np.atleast_2d(truth)
    size = sum(np.linalg.norm(np.atleast_2d(v), axis=-1) for v in inputs)
    scale = np.maximum(np.linalg.norm(truth, axis=-1), 1e-6 * size + 1e-300)
    return float(np.max(np.linalg.norm(got - truth, axis=-1) / scale))


def scaled(magnitude_log10):
    """A vector with a random direction and a norm 10**e, e in [-2, magnitude_log10]."""
    return st.builds(
        lambda d, e: np.array(d) / np.linalg.norm(d) * 10.0**e,
        st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.05),
        st.floats(-2, magnitude_log10),
    )


axes = st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.05)
angles = st.floats(-np.pi, np.pi)


# ------------------------------------------------------------------ the rigid map at scale
@settings(max_examples=30, deadline=None)
@given(axes, angles, scaled(7), st.lists(scaled(6), min_size=1, max_size=4))
def test_apply_to_points_and_motor_to_matrix_at_scale(axis, angle, t, xs):
    """Eq. (2.103): M x ~M = R x + t to 1e-9 of |answer| for |t| <= 1e7 and |x| <= 1e6 (typically ~1e-16)."""
    x = np.array(xs)
    M = cga.motor(axis, angle, t)
    R = rodrigues(axis, angle)
    truth = x @ R.T + t
    assert rel_err(cga.apply_to_points(M, x), truth, x, t) < 1e-9
    assert rel_err(cga.apply_to_points(M, x[0]), truth[0], x[0], t) < 1e-9
    H = cga.motor_to_matrix(M)
    assert np.abs(H[:3, :3] - R).max() < 1e-12
    assert rel_err(H[:3, 3], t) < 1e-12
    assert np.array_equal(H[3], [0.0, 0.0, 0.0, 1.0])
    R_part, tt = cga.decompose_motor(M)  # (2.141)-(2.144)
    assert rel_err(tt, t) < 1e-12


def test_the_reported_translation_case():
    t = [123456.7, -234567.8, 345678.9]
    for x in ([0.0, 0.0, 0.0], [1.0, -2.0, 3.0]):
        got = cga.apply_to_points(cga.translator(t), x)
        assert rel_err(got, np.add(x, t)) < 1e-15  # was about 3 units off
        assert rel_err(cga.down(cga.apply(cga.translator(t), cga.up(x))), np.add(x, t)) < 1e-15


@settings(max_examples=25, deadline=None)
@given(axes, angles, scaled(7), st.lists(scaled(6), min_size=2, max_size=5))
def test_conformal_route_at_scale_keeps_the_weight(axis, angle, t, xs):
    """apply(M, up(x)) on conformal points (batch and single): the Euclidean part to 1e-9 of |answer| and the
    weight X . e = -1 (2.111) kept to a few roundings of the point's own e+/e- coefficients.  ``down`` reads
    points up to about |y| < 3e7: its own test of a zero weight is relative to
    |X+| + |X-| ~ |y|^2 (model.py), so beyond that the coefficients are read here."""
    x = np.array(xs)
    M = cga.motor(axis, angle, t)
    truth = x @ rodrigues(axis, angle).T + t
    d = sum(float(M[b]) ** 2 for b in ("1", "e12", "e13", "e23"))  # M ~M (2.145), 1 up to round-off
    raw = M >> cga.up(x[0])  # V X ~V = (M ~M) V X V^-1
    ref = d * cga.apply(M, cga.up(x[0])).to_array()
    assert np.allclose(raw.to_array(), ref, rtol=0, atol=8 * EPS * np.abs(ref).max())
    for Y, pts, want in ((cga.apply(M, cga.up(x)), x, truth), (cga.apply(M, cga.up(x[0])), x[0], truth[0])):
        w = np.asarray(Y["e-"] - Y["e+"])
        y = np.stack([np.asarray(Y[b]) for b in ("e1", "e2", "e3")], axis=-1)
        a, b = np.atleast_1d(Y["e+"]), np.atleast_1d(Y["e-"])
        # the weight to a few roundings of the coefficients themselves (the old e+/e- products lost eps |t|^2 |x|^2)
        assert np.all(np.abs(w - 1.0) <= 8 * EPS * np.maximum(np.maximum(np.abs(a), np.abs(b)), 1.0))
        assert rel_err(y, want, pts, t) < 1e-9
        if np.all(np.linalg.norm(np.atleast_2d(want), axis=-1) < 9e6):
            assert rel_err(cga.down(Y), want, pts, t) < 1e-9


def test_up_and_down_hold_points_exactly_up_to_their_limit():
    """What the conformal representation itself holds (2.62, 2.111): up(x) has e+/e- coefficients
    (x^2 -+ 1)/2 with the weight exactly 1 while x^2 < 2^53; down(up(x)) is exact; down refuses a weight it cannot
    tell from round-off (at |x| = 1e8, x^2 > 2^53: X+ and X- round to the same number)."""
    x = RNG.normal(size=(200, 3))
    x *= 2e7 / np.linalg.norm(x, axis=1)[:, None]
    X = cga.up(x)
    assert np.all(X["e-"] - X["e+"] == 1.0)
    assert np.array_equal(cga.down(X), x)
    with pytest.raises(DegenerateGeometryError, match="^down:"):
        cga.down(cga.up([1e8, 0.0, 0.0]))
    with pytest.raises(DegenerateGeometryError, match="^down:"):
        cga.down(cga.up(np.array([[1.0, 0.0, 0.0], [1e8, 0.0, 0.0]])))


def mp_rigid(M):
    """(R, t) of a float motor in mpmath at 50 digits, from its coefficients (2.141, 2.144), and the check."""
    c = {b: mpmath.mpf(float(v)) for b, v in M.coeffs.items()}
    r0, r12, r13, r23 = (c.get(b, mpmath.mpf(0)) for b in (0, 3, 5, 6))
    n1, n2, n3, n123 = (-c.get(b, mpmath.mpf(0)) for b in (17, 18, 20, 23))
    rr = r0**2 + r12**2 + r13**2 + r23**2
    t = [
        2 * (n1 * r0 + n2 * r12 + n3 * r13 + n123 * r23) / rr,
        2 * (n2 * r0 - n1 * r12 + n3 * r23 - n123 * r13) / rr,
        2 * (n3 * r0 - n1 * r13 - n2 * r23 + n123 * r12) / rr,
    ]
    w, x, y, z = (v / mpmath.sqrt(rr) for v in (r0, -r23, r13, -r12))
    R = mpmath.matrix(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
    return R, mpmath.matrix(t)


def test_conformal_coefficients_against_mpmath():
    """Every coefficient of apply(M, up(x)) against up(R x + t) at 50 digits: a few eps of each coefficient's
    natural size (|y| for e1 e2 e3, y^2/2 for e+ e-).  The plain e+/e- matrix product loses eps |t|^2 |x|^2."""
    mpmath.mp.dps = 50
    for scale_t, scale_x in ((1e7, 1e6), (1e6, 1e6), (1e4, 1e6), (1e7, 1.0)):
        M = cga.motor(RNG.normal(size=3), RNG.uniform(-3, 3), RNG.normal(size=3) / np.sqrt(3) * scale_t)
        x = RNG.normal(size=(6, 3)) / np.sqrt(3) * scale_x
        Y = cga.apply(M, cga.up(x))
        R, t = mp_rigid(M)
        for i in range(len(x)):
            y = R * mpmath.matrix([mpmath.mpf(float(v)) for v in x[i]]) + t
            y2 = sum(v**2 for v in y)
            want = [y[0], y[1], y[2], (y2 - 1) / 2, (y2 + 1) / 2]
            got = [Y[b][i] for b in ("e1", "e2", "e3", "e+", "e-")]
            size = [mpmath.sqrt(y2)] * 3 + [y2 / 2 + 1] * 2
            assert max(abs(g - v) / s for g, v, s in zip(got, want, size)) < 8 * EPS


def test_lines_at_scale_against_mpmath():
    """A dual line (grade 3) far away: apply(M, L) against the grade-3 compound of the rigid map's 5x5 matrix
    (the outermorphism, 2.82) at 50 digits; each coefficient within a few eps of the largest one of its kind."""
    mpmath.mp.dps = 50
    M = cga.motor(RNG.normal(size=3), 1.3, RNG.normal(size=3) * 3e5)
    a, b = RNG.normal(size=(2, 4, 3)) * 1e5
    L = cga.line_from_points(a, b)
    got = cga.apply(M, L)
    R, t = mp_rigid(M)
    u = R.T * t
    h = sum(v**2 for v in t) / 2
    A = mpmath.matrix(5, 5)  # the e+/e- matrix, exact: [[R, -t, t], [u, 1 - h, h], [u, -h, 1 + h]]
    for i in range(3):
        for j in range(3):
            A[i, j] = R[i, j]
        A[i, 3], A[i, 4], A[3, i], A[4, i] = -t[i], t[i], u[i], u[i]
    A[3, 3], A[3, 4], A[4, 3], A[4, 4] = 1 - h, h, -h, 1 + h
    blades = G41.grade_blades[3]
    idx = [[i for i in range(5) if bl >> i & 1] for bl in blades]
    C = mpmath.matrix(10, 10)
    for r, I in enumerate(idx):
        for c, J in enumerate(idx):
            C[r, c] = mpmath.det(mpmath.matrix([[A[i, j] for j in J] for i in I]))
    for k in range(4):
        x = mpmath.matrix([mpmath.mpf(float(L.batch_item(k)[bl])) for bl in blades])
        want = C * x
        # blades with e+ or e- (or both) against the largest of theirs; the Euclidean trivector e123 alone
        for group in ([i for i, bl in enumerate(blades) if bl & 24], [i for i, bl in enumerate(blades) if not bl & 24]):
            size = max(abs(want[i]) for i in group) + 1e-300
            err = max(abs(got.batch_item(k)[blades[i]] - want[i]) for i in group)
            assert err / size < 64 * EPS


def test_apply_matches_kingdon_at_moderate_scale():
    """The sandwich M X ~M through kingdon (e4 = e+, e5 = e-: the bitmaps of G41) for points, point pairs, lines
    and circles ~100 units out, a motor translating by ~50; kingdon multiplies in the e+/e- basis, so the
    comparison is at 1e-9 of the coefficients' size."""
    kingdon = pytest.importorskip("kingdon")
    K = kingdon.Algebra(4, 1)

    def name(b):
        return "e" + "".join(str(i + 1) for i in range(5) if b >> i & 1) if b else "e"

    def to_k(X):
        return K.multivector({name(b): v for b, v in X.coeffs.items()})

    M = cga.motor(RNG.normal(size=3), 0.8, RNG.normal(size=3) * 50)
    p, q, r = (RNG.normal(size=(20, 3)) * 100 for _ in range(3))
    kM = to_k(M)
    for X in (cga.up(p), cga.point_pair(p, q), cga.line_from_points(p, q), cga.circle_from_points(p, q, r)):
        got, want = cga.apply(M, X), kM >> to_k(X)
        size = max(float(np.max(np.abs(v))) for v in X.coeffs.values())
        for b in X.coeffs:
            w = np.broadcast_to(np.asarray(getattr(want, name(b)), float), (20,))
            assert np.allclose(np.asarray(got[b]), w, rtol=0, atol=1e-9 * size), name(b)


def composed(scale, k=4):
    Hs, Ms = np.eye(4), []
    for _ in range(k):
        axis, angle, t = RNG.normal(size=3), RNG.uniform(-3, 3), RNG.normal(size=3) * scale
        Ms.append(cga.motor(axis, angle, t))
        H = np.eye(4)
        H[:3, :3], H[:3, 3] = rodrigues(axis, angle), t
        Hs = Hs @ H
    M = Ms[0]
    for Mi in Ms[1:]:
        M = M * Mi  # (2.99)
    return M, Hs


def test_composed_motors_are_motors_to_the_precision_of_their_product():
    """The product of motors (2.99) is taken in the e+/e- basis, where the e+ e+ and e- e- terms cancel: it
    carries ~eps |t|^2 of round-off (in its rotor and its E = e+e- and <n ~R>_3 parts).  Up to |t| ~ 1e4 it is
    still taken as a motor and applied as the composed rigid map, to that precision; further out the motor
    functions refuse it and say why, instead of reading a rigid map into it."""
    for scale in (1.0, 1e2, 1e3):
        M, H = composed(scale)
        assert G41.rigid_motion(M) is not None
        x = RNG.normal(size=(50, 3)) * 1e6
        tol = 1e-14 + 64 * EPS * scale**2
        assert rel_err(cga.apply_to_points(M, x), x @ H[:3, :3].T + H[:3, 3], x) < tol
        assert np.abs(cga.motor_to_matrix(M) - H).max() < tol * max(1.0, np.abs(H).max())
    M, H = composed(1e6)
    with pytest.raises(InvalidInputError, match="^motor_to_matrix: M: not a motor.*a product of motors far"):
        cga.motor_to_matrix(M)
    # composing the rigid maps themselves (here with matrices) keeps full precision at any distance
    H2 = cga.motor_to_matrix(cga.matrix_to_motor(H))
    assert np.abs(H2 - H).max() < 8 * EPS * np.abs(H).max()


# ------------------------------------------------------------------ scaled motors
@pytest.mark.parametrize("s", [2.0, -3.0, 1e-8, 1e8])
def test_a_scaled_motor_is_the_same_motion(s):
    """s M X (s M)^-1 = M X M^-1 (2.82): the same matrix, points, conformal action and translation; only the
    raw sandwich V >> X = V X ~V scales, by s^2."""
    M = cga.motor(RNG.normal(size=3), 1.2, RNG.normal(size=3) * 1e3)
    x = RNG.normal(size=(5, 3)) * 1e3
    X = cga.up(x)
    assert np.allclose(cga.motor_to_matrix(s * M), cga.motor_to_matrix(M), rtol=1e-14, atol=1e-12)
    assert np.allclose(cga.apply_to_points(s * M, x), cga.apply_to_points(M, x), rtol=1e-14, atol=1e-9)
    assert np.allclose(cga.apply(s * M, X).to_array(), cga.apply(M, X).to_array(), rtol=1e-14, atol=1e-6)
    assert np.allclose(((s * M) >> X).to_array(), s**2 * (M >> X).to_array(), rtol=1e-13, atol=1e-6 * s**2)
    R, t = cga.decompose_motor(s * M)
    assert np.allclose(t, cga.decompose_motor(M)[1], rtol=1e-14)
    assert (cga.translator(t) * R).isclose(s * M, rtol=1e-12, atol=1e-12 * abs(s))
    angle, axis = cga.rotor_angle_axis(s * M)
    assert angle == pytest.approx(cga.rotor_angle_axis(M)[0], abs=1e-14)
    batch = Multivector(G41, {b: np.array([v, 2 * v]) for b, v in M.coeffs.items()})  # M and 2M as a batch
    assert np.allclose(cga.decompose_motor(batch)[1], [t, t], rtol=1e-14)


# ------------------------------------------------------------------ matrix_to_motor
@pytest.mark.parametrize("k", range(1, 13))
def test_matrix_to_motor_near_pi_against_scipy(k):
    """Shepperd's quaternion of the rotation block: exact to round-off at pi - 10^-k, where the old axis from
    (R + I)/2 was 3e-7 off."""
    axis = RNG.normal(size=3)
    axis /= np.linalg.norm(axis)
    rot = Rotation.from_rotvec(axis * (np.pi - 10.0**-k))
    H = np.eye(4)
    H[:3, :3], H[:3, 3] = rot.as_matrix(), RNG.normal(size=3) * 1e6
    M = cga.matrix_to_motor(H)
    assert np.abs(cga.motor_to_matrix(M)[:3, :3] - H[:3, :3]).max() < 8 * EPS
    assert rel_err(cga.motor_to_matrix(M)[:3, 3], H[:3, 3]) < 4 * EPS
    x, y, z, w = rot.as_quat()
    q = np.array([M["1"], -M["e23"], M["e13"], -M["e12"]])  # R = w - x e23 - y e31 - z e12 (2.96)
    assert min(np.abs(q - [w, x, y, z]).max(), np.abs(q + [w, x, y, z]).max()) < 4 * EPS
    angle, got_axis = cga.rotor_angle_axis(M)
    assert angle == pytest.approx(np.pi - 10.0**-k, abs=4 * EPS)
    assert np.abs(got_axis - axis).max() < 1e-14


def test_matrix_to_motor_round_trips_random_motions():
    for _ in range(20):
        H = np.eye(4)
        H[:3, :3] = Rotation.random(random_state=RNG).as_matrix()
        H[:3, 3] = RNG.normal(size=3) * 10.0 ** RNG.uniform(-3, 7)
        M = cga.matrix_to_motor(H)
        assert sum(M[b] ** 2 for b in ("1", "e12", "e13", "e23")) == pytest.approx(1.0, abs=4 * EPS)  # R ~R
        assert np.abs(cga.motor_to_matrix(M) - H).max() <= 8 * EPS * max(1.0, np.abs(H).max())


@pytest.mark.parametrize(
    ("H", "what"),
    [
        (np.diag([1.0, 2.0, 3.0, 1.0]), "not a rotation"),
        (np.diag([1 + 4e-6, 1 + 4e-6, 1 + 4e-6, 1.0]), "not a rotation"),  # a scaling within allclose's rtol
        (np.array([[1.0, 1e-6, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]), "not a rotation"),  # a shear
        (np.diag([1.0, 1.0, -1.0, 1.0]), "reflection"),
        (np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.5, 0, 0, 1]]), "last row"),
        (np.diag([1.0, 1.0, 1.0, 2.0]), "last row"),
        (np.full((4, 4), np.nan), "NaN or inf"),
        (np.eye(3), r"expected shape \(4, 4\)"),
        (np.eye(4) * (1 + 0j), "real numbers"),
        ([["a"] * 4] * 4, "must be an array of numbers"),
    ],
)
def test_matrix_to_motor_refuses_what_is_not_a_rigid_motion(H, what):
    with pytest.raises(InvalidInputError, match=f"^matrix_to_motor: H: .*{what}"):
        cga.matrix_to_motor(H)


# ------------------------------------------------------------------ rotor_angle_axis
def test_rotor_angle_axis_range_and_conventions():
    """(2.135)-(2.137) with the angle folded into [0, pi]: R and -R are the same rotation."""
    n = np.array([2.0, -1.0, 2.0]) / 3
    assert cga.rotor_angle_axis(cga.rotor([0, 0, 1], 2 * np.pi)) == (0.0, pytest.approx([0.0, 0.0, 1.0]))
    assert cga.rotor_angle_axis(cga.rotor(n, 4 * np.pi))[0] == 0.0
    for ang in (0.3, np.pi - 1e-9, np.pi):
        angle, axis = cga.rotor_angle_axis(cga.rotor(n, ang))
        assert angle == pytest.approx(ang, abs=1e-15) and np.allclose(axis, n, atol=1e-15)
    for ang in (2 * np.pi - 0.1, np.pi + 1e-9, -0.3):  # beyond pi: the other way round
        angle, axis = cga.rotor_angle_axis(cga.rotor(n, ang))
        assert angle == pytest.approx(2 * np.pi - ang if ang > 0 else -ang, abs=1e-15)
        assert np.allclose(axis, -n, atol=1e-15)
    angle, axis = cga.rotor_angle_axis(-cga.rotor(n, 0.3))
    assert angle == pytest.approx(0.3) and np.allclose(axis, n)
    angle, axis = cga.rotor_angle_axis(cga.motor(n, 0.7, [1e7, 0.0, 0.0]))  # a motor: its rotation part
    assert angle == pytest.approx(0.7, abs=1e-15) and np.allclose(axis, n, atol=1e-15)


@pytest.mark.parametrize(
    ("R", "error", "what"),
    [
        (cga.vector([1.0, 2.0, 3.0]), InvalidInputError, "not an even versor"),
        (cga.up([1.0, 2.0, 3.0]), InvalidInputError, "not an even versor"),
        (G41.scalar(1.0) + cga.E * 0.5, InvalidInputError, "does not commute with e"),  # a dilator
        (G41.scalar(1.0) + cga.eo * cga.e1, InvalidInputError, "does not commute with e"),  # a transversion
        (cga.einf * cga.e1, DegenerateGeometryError, "no rotor part"),
        (Multivector(G41, {}), DegenerateGeometryError, "zero multivector"),
    ],
)
def test_rotor_angle_axis_refuses_what_is_not_a_rotor(R, error, what):
    with pytest.raises(error, match=f"^rotor_angle_axis: R: .*{what}"):
        cga.rotor_angle_axis(R)


def test_motor_functions_refuse_non_motors():
    dilator = G41.scalar(1.0) + cga.E * 0.5  # a versor (V ~V = 0.75), but not a rigid motion
    assert G41.rigid_motion(dilator) is None
    for func in (cga.motor_to_matrix, cga.decompose_motor):
        with pytest.raises(InvalidInputError, match=rf"^{func.__name__}: M: .*does not commute with e"):
            func(dilator)
        with pytest.raises(InvalidInputError, match=rf"^{func.__name__}: M: not an even versor"):
            func(cga.plane([0.0, 0.0, 1.0], 2.0))
    with pytest.raises(InvalidInputError, match="^motor_to_matrix: M: one numeric motor"):
        cga.motor_to_matrix(cga.motor(RNG.normal(size=(2, 3)), [0.1, 0.2], RNG.normal(size=(2, 3))))
    # the dilator still acts as a versor through the general route: a + b E scales by (a - b)/(a + b)
    x = np.array([1.0, 2.0, 3.0])
    assert np.allclose(cga.apply_to_points(dilator, x), x / 3, rtol=1e-15)
    assert np.allclose(cga.down(dilator * cga.up(x) * ~dilator), x / 3, rtol=1e-15)


@pytest.mark.parametrize("delta", [10.0, 1e6])
def test_apply_to_points_of_a_reflection_is_the_affine_reflection(delta):
    """A plane n + delta e (2.89) is odd, not a motor: it moves points by x - 2 (n.x - delta) n (2.90), read off
    the motor P e1 times the reflection in e1 (cga_lessons.conformal.similarities), exact at any distance (the
    affine part of its 5x5 matrix, used before, lost ~eps delta^2 far away)."""
    n = np.array([0.0, 0.6, 0.8])
    x = RNG.normal(size=(10, 3)) * 10
    got = cga.apply_to_points(cga.plane(n, delta), x)
    assert np.allclose(got, x - 2 * (x @ n - delta)[:, None] * n, rtol=0, atol=1e-13 * delta)


# ------------------------------------------------------------------ overflow and scalars
@pytest.mark.parametrize("big", [1e200, 1e-200, 1e300])
def test_axis_of_any_size_keeps_the_rotation(big):
    want = cga.motor([1.0, 1.0, 0.0], 0.5, [1.0, 2.0, 3.0])
    got = cga.motor([big, big, 0.0], 0.5, [1.0, 2.0, 3.0])
    assert got.isclose(want, atol=1e-15)
    assert cga.rotor([0.0, 0.0, -big], 0.5).isclose(cga.rotor([0.0, 0.0, -1.0], 0.5), atol=1e-15)


BAD_SCALARS = [np.nan, np.inf, -np.inf, "1", None, 1j, np.complex128(1.0), True, np.bool_(False), [np.nan]]


@pytest.mark.parametrize("bad", BAD_SCALARS, ids=repr)
def test_bad_angles_and_distances_raise_naming_the_function_and_argument(bad):
    L = cga.line_from_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    calls = {
        "rotor: angle": lambda: cga.rotor([0.0, 0.0, 1.0], bad),
        "motor: angle": lambda: cga.motor([0.0, 0.0, 1.0], bad, [0.0, 0.0, 0.0]),
        "rotor_about_line: angle": lambda: cga.rotor_about_line(L, bad),
        "screw: angle": lambda: cga.screw([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], bad, 0.5),
        "screw: distance": lambda: cga.screw([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 0.5, bad),
    }
    for prefix, call in calls.items():  # (screw takes one angle and one distance: a list is refused too)
        with pytest.raises(InvalidInputError, match=f"^{prefix}: "):
            call()


def test_errors_name_the_function_the_caller_called():
    with pytest.raises(DegenerateGeometryError, match="^motor: rotation_axis: .*zero"):
        cga.motor([0, 0, 0], 1.0, [0, 0, 0])
    with pytest.raises(InvalidInputError, match="^motor: translation"):
        cga.motor([0, 0, 1], 1.0, [np.nan, 0, 0])
    with pytest.raises(InvalidInputError, match="^motor: rotation_axis"):
        cga.motor([np.inf, 0, 0], 1.0, [0, 0, 0])
    with pytest.raises(DegenerateGeometryError, match="^screw: axis: .*zero"):
        cga.screw([0, 0, 0], [0, 0, 0], 1.0, 0.5)
    with pytest.raises(DegenerateGeometryError, match="^screw: angle: is 0"):
        cga.screw([0, 0, 1], [0, 0, 0], 0.0, 0.5)
    with pytest.raises(InvalidInputError, match="^rotor: angle: must be a finite real number"):
        cga.rotor([0, 0, 1], sp.I)
    with pytest.raises(InvalidInputError, match="^rotor: angle: must be a finite real number"):
        cga.rotor([0, 0, 1], sp.oo)
    # arrays of angles (a batch of rotors) are fine; integers too
    assert cga.rotor([0.0, 0.0, 1.0], np.array([0.1, 0.2])).shape == (2,)
    assert cga.rotor([0, 0, 1], 1).isclose(cga.rotor([0, 0, 1], 1.0))


# ------------------------------------------------------------------ symbolic
def test_symbolic_rotor_and_screw_stay_exact_and_fast():
    R = cga.rotor([0, 0, 1], sp.pi / 2)  # (2.94)-(2.96)
    for v in R.coeffs.values():
        assert not v.atoms(sp.Float), v
    assert sp.simplify(R["1"] - sp.sqrt(2) / 2) == 0 and sp.simplify(R["e12"] + sp.sqrt(2) / 2) == 0
    assert not cga.rotor([0.6, 0.8, 0], sp.pi / 3)["e23"].atoms(sp.Float)  # a numeric axis is taken as exact
    d, th = sp.symbols("d theta", real=True)
    t0 = time.perf_counter()
    S = cga.screw([1, 2, 2], [1, -1, 0.5], th, d)  # (2.110) as T_dr T_p R ~T_p: minutes before
    assert time.perf_counter() - t0 < 5.0
    num = cga.screw([1.0, 2.0, 2.0], [1.0, -1.0, 0.5], 1.1, 0.35)
    at = {d: sp.Rational(35, 100), th: sp.Rational(11, 10)}
    for b in set(S.coeffs) | set(num.coeffs):
        assert float(sp.N(S[b].subs(at) if b in S.coeffs else 0)) == pytest.approx(num[b], abs=1e-14)
