"""Logarithm, roots and interpolation of motors; the dilator (cga_lessons.conformal.versor_log, versor_powers).

Every check compares with an independent truth: the closed forms of the
thesis (2.94, 2.100, 2.110) typed out here, NumPy rotation matrices for the
helix of a screw, an exponential summed here by scaling and squaring, and
kingdon's square root of a Study number.
"""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.conformal import dilator, motor_interpolate, motor_log, rotor_log, versor_root, versor_sqrt

PROPS = settings(deadline=None, max_examples=40)


# ------------------------------------------------------------------ helpers
def err(A, B):
    """Largest coefficient difference of two multivectors."""
    return float(np.abs((A - B).to_array()).max())


def taylor_exp(B):
    """exp(B) by scaling and squaring of the series (2.37), independent of cga.exp."""
    k = max(0, int(np.ceil(np.log2(max(np.abs(B.to_array()).max(), 1e-300)))) + 4)
    X = B * (0.5**k)
    out = term = cga.G41.scalar(1.0)
    for i in range(1, 25):
        term = term * X * (1.0 / i)
        out = out + term
    for _ in range(k):
        out = out * out
    return out


def rot(n, angle):
    """Rotation matrix about the unit axis n by +angle (Rodrigues)."""
    n = np.asarray(n, float) / np.linalg.norm(n)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def rotor_sign(M):
    R, _ = cga.decompose_motor(M)
    return 1.0 if R.scalar() >= 0 else -1.0


def power(X, n):
    out = X
    for _ in range(n - 1):
        out = out * X
    return out


def screw_motor(n, c, angle, d):
    """Rotation by angle about the line through c along n, then slide d along n: T(c + d n) R ~T(c)."""
    n = np.asarray(n, float) / np.linalg.norm(n)
    return cga.translator(np.asarray(c) + d * n) * cga.rotor(n, angle) * cga.translator(-np.asarray(c, float))


def thesis_screw_log(n, c, angle, d):
    """-angle/2 (l + e m) with m = c . l - (d/angle) n, Eq. (2.110)."""
    n = np.asarray(n, float) / np.linalg.norm(n)
    l = cga.vector(n) * cga.IE
    m = (cga.vector(c) | l) - cga.vector(n) * (d / angle)
    return (l + cga.einf * m) * (-angle / 2)


def random_angles(rng, size):
    """A mix: uniform in [0, 2 pi), within 1e-6 of 0, of pi (both sides), and of 2 pi."""
    u = rng.integers(0, 5, size)
    tiny = 10 ** rng.uniform(-12, -6, size)
    return np.select(
        [u == 0, u == 1, u == 2, u == 3],
        [rng.uniform(0, 2 * np.pi, size), tiny, np.pi - tiny, np.pi + tiny],
        default=2 * np.pi - tiny * 1e3,
    )


def random_translation(rng, scale_max=1e3):
    t = rng.normal(size=3)
    return t / np.linalg.norm(t) * 10 ** rng.uniform(-3, np.log10(scale_max))


def to_kingdon(alg, X):
    names = {b: "e" + "".join(str(i + 1) for i in range(5) if b >> i & 1) for b in range(32)}
    names[0] = "e"
    return alg.multivector({names[b]: float(v) for b, v in X.coeffs.items()})


def from_kingdon(X):
    return cga.Multivector(cga.G41, {int(k): float(v) for k, v in zip(X.keys(), X.values())})


# ------------------------------------------------------------- closed forms
@pytest.mark.parametrize("theta", [0.0, 1e-9, 0.3, 1.0, 2.5, np.pi - 1e-9, np.pi])
def test_log_of_rotor_about_coordinate_axes_is_minus_half_angle_plane(theta):
    for axis, blade in (([0, 0, 1], "e12"), ([1, 0, 0], "e23"), ([0, 1, 0], "e31")):
        B = motor_log(cga.rotor(axis, theta))
        assert B.grades_present() in ([], [2])
        assert abs(B[blade] - (-theta / 2)) < 1e-15
        assert abs(np.abs(B.to_array()).sum() - theta / 2) < 1e-15  # nothing else
        assert err(rotor_log(cga.rotor(axis, theta)), B) == 0.0


@pytest.mark.parametrize("t", [[2.0, 0.0, 0.0], [0.3, -1.2, 4.0], [1e3, -7e2, 5e2], [1e-9, 0.0, 0.0]])
def test_log_of_translator_is_e_t_over_2(t):
    B = motor_log(cga.translator(t))
    # e t / 2 = (e- + e+) t / 2 = -(t_i / 2) (e_i+ + e_i-) for each i (2.100), typed out
    expected = {f"e{i + 1}{s}": -t[i] / 2 for i in range(3) for s in "+-"}
    assert set(B.blades()) <= set(expected)
    for name, value in expected.items():
        assert abs(B[name] - value) <= 1e-15 * max(1.0, abs(value))
    assert err(cga.exp(B), cga.translator(t)) == 0.0


def test_log_of_screw_matches_eq_2_110():
    rng = np.random.default_rng(1)
    for _ in range(100):
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        c = rng.normal(size=3) * 5
        c -= (c @ n) * n
        angle, d = rng.uniform(1e-3, np.pi - 1e-3), rng.uniform(-10, 10)
        expected = thesis_screw_log(n, c, angle, d)
        assert err(motor_log(screw_motor(n, c, angle, d)), expected) < 1e-12 * max(1, np.abs(c).max(), abs(d))
        assert err(motor_log(cga.screw(n, c, angle, d)), expected) < 1e-10 * max(1, np.abs(c).max(), abs(d))


def test_sign_branch_beyond_pi():
    n, t = np.array([1.0, 2.0, -0.5]), np.array([0.4, -3.0, 2.0])
    for theta in (np.pi + 1e-9, 4.0, 2 * np.pi - 1e-3):
        M = cga.motor(n, theta, t)
        B = motor_log(M)
        # the shorter motion: 2 pi - theta about -n
        assert abs(2 * np.linalg.norm(cga.euclidean(B.grade(2) * cga.IE)) - (2 * np.pi - theta)) < 1e-12
        assert err(taylor_exp(B), -M) < 1e-12
        x = np.array([[1.0, 0.0, 2.0], [-3.0, 5.0, 0.5]])
        assert np.allclose(cga.apply_to_points(cga.exp(B), x), cga.apply_to_points(M, x), atol=1e-12)


# -------------------------------------------------------------- round trips
def test_round_trip_hundreds_of_motors_near_0_pi_2pi_and_far():
    rng = np.random.default_rng(7)
    angles = random_angles(rng, 400)
    worst = 0.0
    for theta in angles:
        t = random_translation(rng)
        M = cga.motor(rng.normal(size=3), theta, t)
        B = motor_log(M)
        assert B.grades_present() == [2]
        half = np.linalg.norm(cga.euclidean(B.grade(2) * cga.IE))
        assert half <= np.pi / 2 + 1e-15  # principal branch: angle in [0, pi]
        scale = max(1.0, np.linalg.norm(t))
        worst = max(worst, err(taylor_exp(B), rotor_sign(M) * M) / scale)
    assert worst < 1e-10  # relative to |t|; the squarings of taylor_exp cost about 1e-11 near theta = pi


def test_round_trip_with_cga_exp_for_moderate_translations():
    # cga.exp itself loses digits (and can raise) for small angles with |t| ~ 1e3; see the report.
    rng = np.random.default_rng(8)
    for theta in random_angles(rng, 300):
        t = random_translation(rng, 10.0)
        M = cga.motor(rng.normal(size=3), theta, t)
        assert err(cga.exp(motor_log(M)), rotor_sign(M) * M) < 1e-9


def test_log_accepts_round_off_but_not_a_scaled_motor():
    M = cga.motor([0.0, 1.0, 1.0], 1.2, [1.0, 2.0, 3.0])
    assert err(motor_log(M * (1 + 1e-12)), motor_log(M)) < 1e-11
    with pytest.raises(InvalidInputError, match=r"^motor_log: M: not a unit motor: M ~M = 4"):
        motor_log(2 * M)
    assert err(motor_log((2 * M) / (2 * M).norm()), motor_log(M)) < 1e-14


# ------------------------------------------------------------ interpolation
@PROPS
@given(
    axis=st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda a: np.linalg.norm(a) > 0.1),
    point=st.tuples(*[st.floats(-50, 50)] * 3),
    angle=st.floats(1e-7, np.pi - 1e-7),
    slide=st.floats(-100, 100),
    seed=st.integers(0, 2**16),
)
def test_interpolation_follows_the_helix_of_the_screw(axis, point, angle, slide, seed):
    rng = np.random.default_rng(seed)
    n = np.array(axis) / np.linalg.norm(axis)
    c = np.array(point)
    M0 = cga.motor(rng.normal(size=3), rng.uniform(0, 2 * np.pi), rng.normal(size=3) * 10)
    M1 = screw_motor(n, c, angle, slide) * M0
    x = rng.normal(size=(4, 3)) * 5
    y = cga.apply_to_points(M0, x)
    s_values = np.linspace(-0.5, 1.5, 9)
    batch = motor_interpolate(M0, M1, s_values)
    assert batch.shape == (9,)
    scale = max(1.0, np.abs(c).max(), abs(slide), np.abs(y).max())
    for i, s in enumerate(s_values):
        helix = c + (y - c) @ rot(n, s * angle).T + s * slide * n
        Ms = motor_interpolate(M0, M1, s)
        assert np.allclose(cga.apply_to_points(Ms, x), helix, atol=1e-9 * scale)
        assert err(batch.batch_item(i), Ms) < 1e-12 * scale
    assert err(motor_interpolate(M0, M1, 0.0), M0) < 1e-12 * scale
    assert err(motor_interpolate(M0, M1, 1.0), M1) < 1e-10 * scale


def test_interpolation_takes_the_short_way_unless_told():
    M0 = cga.motor([0.3, 0.1, 1.0], 0.4, [1.0, 0.0, 2.0])
    D = cga.motor([0.0, 0.0, 1.0], 1.5 * np.pi, [0.0, 3.0, 1.0])  # rotor scalar < 0: the long way as a versor
    M1 = D * M0
    x = np.array([2.0, -1.0, 0.5])
    short, long = motor_interpolate(M0, M1, 1.0), motor_interpolate(M0, M1, 1.0, shortest=False)
    assert err(short, -M1) < 1e-12 and err(long, M1) < 1e-12
    assert np.allclose(cga.apply_to_points(short, x), cga.apply_to_points(M1, x), atol=1e-12)
    # half way: the short way turns by -pi/4 about z, the long way by 3 pi/4
    for shortest, turn in ((True, -np.pi / 4), (False, 3 * np.pi / 4)):
        R_half, _ = cga.decompose_motor(motor_interpolate(cga.G41.scalar(1.0), D, 0.5, shortest=shortest))
        assert err(R_half, cga.rotor([0, 0, 1], turn)) < 1e-12


# --------------------------------------------------------------------- roots
def test_roots_of_rotors_and_translators_in_closed_form():
    for theta in (0.0, 0.2, 2.0, np.pi, 4.0, 6.0):
        for n in (1, 2, 3, 5):
            assert err(versor_root(cga.rotor([1, -1, 2], theta), n), cga.rotor([1, -1, 2], theta / n)) < 1e-15
    t = np.array([3.0, -6.0, 9.0])
    assert err(versor_root(cga.translator(t), 3), cga.translator(t / 3)) < 1e-15
    assert err(versor_sqrt(cga.translator(t)), cga.translator(t / 2)) < 1e-15


def test_roots_power_back_to_the_motor():
    rng = np.random.default_rng(11)
    for _ in range(200):
        theta = rng.choice([rng.uniform(0, 2 * np.pi - 0.5), 10 ** rng.uniform(-9, -6), np.pi - 1e-7])
        t = random_translation(rng)
        M = cga.motor(rng.normal(size=3), theta, t)
        scale = max(1.0, np.linalg.norm(t))
        for n in (1, 2, 3, 4, 7):
            assert err(power(versor_root(M, n), n), M) < 1e-11 * scale
        X = versor_sqrt(M)
        assert err(X * X, M) < 1e-11 * scale
        assert err(X, versor_root(M, 2)) < 1e-11 * scale  # the closed form and the log agree


def test_sqrt_matches_kingdon_on_study_numbers():
    kingdon = pytest.importorskip("kingdon")
    alg = kingdon.Algebra(4, 1)
    rng = np.random.default_rng(3)
    cases = [cga.rotor(rng.normal(size=3), rng.uniform(0, 2 * np.pi - 0.5)) for _ in range(10)]
    cases += [cga.translator(rng.normal(size=3) * 100) for _ in range(5)]
    cases += [screw_motor(rng.normal(size=3), rng.normal(size=3), rng.uniform(0.1, 3), 0.0) for _ in range(10)]
    for M in cases:
        assert 4 not in M.grades_present() or np.abs(M.grade(4).to_array()).max() < 1e-12
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # kingdon warns when the input is not a Study number
            K = from_kingdon(to_kingdon(alg, M.grade(0, 2)).sqrt())
        assert err(versor_sqrt(M), K) < 1e-12 * max(1.0, np.abs(M.to_array()).max())


def test_root_near_minus_translator_is_refused_or_exact():
    t = np.array([1.0, 0.0, 0.0])
    M = cga.motor([0, 0, 1], 2 * np.pi - 1e-9, t)
    with pytest.raises(DegenerateGeometryError, match=r"^versor_root: M: near -T"):
        versor_root(M, 2)
    with pytest.raises(DegenerateGeometryError, match=r"^versor_sqrt: M: near -T"):
        versor_sqrt(M)
    X = -versor_root(-M, 3)  # odd n: a well-conditioned root of M from the shorter motion
    assert err(power(X, 3), M) < 1e-14
    minus_T = -cga.translator([0.0, 2.0, 0.0])  # a full turn: the axis is taken along t
    assert err(power(versor_root(minus_T, 4), 4), minus_T) < 1e-14


# ------------------------------------------------------------------ dilator
@pytest.mark.parametrize("scale", [2.0, 0.5, 1e-3, 1e3, 1.0, 7])
def test_dilator_scales_points(scale):
    x = np.random.default_rng(2).normal(size=(20, 3)) * 10
    D = dilator(scale)
    # The image's weight -e . X = 1/scale is the difference of its e+ and e- parts, of size scale |x|^2: the
    # sandwich's round-off in them costs about eps |scale x|^2 of relative accuracy (7e-8 at |scale x| = 3e4).
    cond = 1e-15 * (max(1.0, scale) ** 2 + 1 / scale) * (1 + np.sum(x**2, axis=1))[:, None]
    y = cga.down(cga.apply(D, cga.up(x)))
    assert np.all(np.abs(y - scale * x) <= cond * np.abs(scale * x) + 1e-15)
    assert abs(float(D * ~D) - 1.0) < 1e-12
    assert err(D, cga.exp(cga.E * (-np.log(scale) / 2))) < 1e-12 * max(scale, 1 / scale)
    c = np.array([1.0, -2.0, 0.5])
    y = cga.down(cga.apply(dilator(scale, c), cga.up(x)))
    assert np.all(np.abs(y - (c + scale * (x - c))) <= 10 * cond * np.abs(c + scale * (x - c)).max() + 1e-14)


def test_dilators_compose_and_are_not_motors():
    assert err(dilator(2.0) * dilator(3.0), dilator(6.0)) < 1e-14
    with pytest.raises(InvalidInputError, match=r"^motor_log: M: not a motor: it does not commute with e"):
        motor_log(dilator(2.0))


# -------------------------------------------------------------- bad input
M_OK = cga.motor([0, 0, 1], 0.5, [1.0, 2.0, 3.0])


@pytest.mark.parametrize(
    ("call", "error", "pattern"),
    [
        (lambda: motor_log(np.eye(4)), InvalidInputError, r"^motor_log: M: expected a motor"),
        (lambda: motor_log(cga.e1 + M_OK), InvalidInputError, r"^motor_log: M: odd grades present"),
        (lambda: motor_log(M_OK + cga.e1 * cga.ep), InvalidInputError, r"^motor_log: M: not a motor"),
        (lambda: motor_log(M_OK * 2), InvalidInputError, r"^motor_log: M: not a unit motor"),
        (
            lambda: motor_log(cga.Multivector(cga.G41, {**M_OK.coeffs, 3: np.nan})),
            InvalidInputError,
            r"^motor_log: M: .*NaN or inf",
        ),
        (lambda: motor_log(cga.rotor([0, 0, 1], [0.1, 0.2])), InvalidInputError, r"^motor_log: M: a batch"),
        (lambda: motor_log(cga.G41.scalar(0.0) * 0), DegenerateGeometryError, r"^motor_log: M: the zero"),
        (lambda: rotor_log(M_OK), InvalidInputError, r"^rotor_log: R: not a rotor about the origin"),
        (lambda: motor_interpolate(M_OK, 3.0, 0.5), InvalidInputError, r"^motor_interpolate: M1: expected"),
        (lambda: motor_interpolate(M_OK, M_OK, np.nan), InvalidInputError, r"^motor_interpolate: s: .*NaN"),
        (lambda: motor_interpolate(M_OK, M_OK, [0.1, np.inf]), InvalidInputError, r"^motor_interpolate: s: "),
        (lambda: motor_interpolate(M_OK, M_OK, np.zeros((2, 2))), InvalidInputError, r"^motor_interpolate: s: "),
        (lambda: motor_interpolate(M_OK, M_OK, []), InvalidInputError, r"^motor_interpolate: s: "),
        (lambda: motor_interpolate(M_OK, M_OK, 1j), InvalidInputError, r"^motor_interpolate: s: "),
        (lambda: motor_interpolate(M_OK, M_OK, True), InvalidInputError, r"^motor_interpolate: s: "),
        (lambda: versor_root(M_OK, 0), InvalidInputError, r"^versor_root: n: must be >= 1, got 0"),
        (lambda: versor_root(M_OK, 2.0), InvalidInputError, r"^versor_root: n: "),
        (lambda: versor_root(M_OK, True), InvalidInputError, r"^versor_root: n: "),
        (lambda: versor_sqrt(dilator(3.0)), InvalidInputError, r"^versor_sqrt: M: not a motor"),
        (lambda: dilator(0.0), InvalidInputError, r"^dilator: scale: must be > 0"),
        (lambda: dilator(-2.0), InvalidInputError, r"^dilator: scale: "),
        (lambda: dilator(np.inf), InvalidInputError, r"^dilator: scale: "),
        (lambda: dilator("2"), InvalidInputError, r"^dilator: scale: must be a real number"),
        (lambda: dilator(True), InvalidInputError, r"^dilator: scale: "),
        (lambda: dilator(2.0, [1.0, 2.0]), InvalidInputError, r"^dilator: center: expected shape \(3,\)"),
        (lambda: dilator(2.0, [1.0, np.nan, 0.0]), InvalidInputError, r"^dilator: center: contains NaN"),
    ],
)
def test_bad_input_is_named(call, error, pattern):
    with pytest.raises(error, match=pattern):
        call()


def test_sympy_motor_is_refused():
    sympy = pytest.importorskip("sympy")
    a = sympy.Symbol("a")
    R = cga.rotor([0, 0, 1], a)
    with pytest.raises(InvalidInputError, match=r"^motor_log: M: numeric coefficients only"):
        motor_log(R)


def test_screw_parameters_invert_the_screw_of_2_110():
    """screw_parameters(screw(axis, point, angle, d)) gives the same screw back: the closed form of (2.110)."""
    rng = np.random.default_rng(110)
    for _ in range(200):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        point = rng.normal(scale=5.0, size=3)
        angle, d = rng.uniform(0.01, np.pi - 0.01), rng.normal()
        a, n, c, dist = cga.screw_parameters(cga.screw(axis, point, angle, d))
        assert a == pytest.approx(angle, abs=1e-9)
        np.testing.assert_allclose(n, axis, atol=1e-9)
        assert dist == pytest.approx(d, abs=1e-9)
        foot = point - (point @ axis) * axis  # the axis point nearest the origin
        np.testing.assert_allclose(c, foot, atol=1e-8)
    with pytest.raises(cga.DegenerateGeometryError, match="screw_parameters: M: no rotation"):
        cga.screw_parameters(cga.translator([1.0, 2.0, 3.0]))


def test_motor_log_accepts_unit_motors_with_long_translations():
    """The unit check reads |R|^2 from the rotor part: M ~M summed in full cancels |t|^2 terms and rejected these."""
    rng = np.random.default_rng(7)
    for scale in (1e4, 1e6, 1e7):
        for _ in range(20):
            axis = rng.normal(size=3)
            angle, t = rng.uniform(0.1, 3.0), rng.normal(size=3) * scale
            B = cga.motor_log(cga.motor(axis, angle, t))  # raised "not a unit motor" for two thirds of these
            assert cga.exp(B).isclose(cga.motor(axis, angle, t), rtol=1e-9) or cga.exp(B).isclose(
                -cga.motor(axis, angle, t), rtol=1e-9
            )
            a, n, _, _ = cga.screw_parameters(cga.motor(axis, angle, t))
            assert a == pytest.approx(angle, abs=1e-9)
            np.testing.assert_allclose(n, axis / np.linalg.norm(axis), atol=1e-9)
