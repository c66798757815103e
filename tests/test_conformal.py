"""The conformal model: entities (table 2.1, section 2.4) and versors (table 2.2), against Euclidean truth."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError

RNG = np.random.default_rng(20261121)


def rot_matrix(axis, angle):
    """Rodrigues' formula: right-hand rotation by angle about axis (independent truth)."""
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def circumcircle(a, b, c):
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    center = a + (np.cross(n, ab) * ac.dot(ac) + np.cross(ac, n) * ab.dot(ab)) / (2 * n.dot(n))
    return center, np.linalg.norm(a - center), n / np.linalg.norm(n)


point = st.lists(st.floats(-10, 10, allow_nan=False), min_size=3, max_size=3).map(np.array)
unit_axis = st.lists(st.floats(-1, 1, allow_nan=False), min_size=3, max_size=3).filter(
    lambda v: np.linalg.norm(v) > 0.1
)
angle = st.floats(-np.pi, np.pi, allow_nan=False)


# ---------------------------------------------------------------- points
def test_constants_and_null_basis_eq_2_53_2_54_2_60():
    assert float(cga.eo * cga.eo) == 0.0 and float(cga.einf * cga.einf) == 0.0
    assert float(cga.einf | cga.eo) == -1.0
    assert cga.E == (cga.einf ^ cga.eo)
    assert cga.Ic == cga.G41.blade("e+-123")
    assert float(cga.Ic * cga.Ic) == -1.0


@settings(max_examples=50, deadline=None)
@given(point)
def test_up_is_null_and_normalised_eq_2_61_2_62(x):
    X = cga.up(x)
    scale = 1 + x.dot(x) ** 2
    assert abs(float(X * X)) <= 1e-12 * scale
    assert float(X | cga.einf) == pytest.approx(-1.0)
    assert X["e+"] == pytest.approx(0.5 * (x.dot(x) - 1)) and X["e-"] == pytest.approx(0.5 * (x.dot(x) + 1))  # (2.63)
    assert np.allclose(cga.down(X * 3.7), x)  # (2.111) scale invariance


@settings(max_examples=50, deadline=None)
@given(point, point)
def test_inner_product_is_squared_distance_eq_2_66(a, b):
    assert float(cga.up(a) | cga.up(b)) == pytest.approx(-0.5 * np.sum((a - b) ** 2), abs=1e-9)


def test_up_down_batch_and_symbolic():
    pts = RNG.normal(size=(100, 3))
    X = cga.up(pts)
    assert X.shape == (100,)
    assert np.allclose(cga.down(X), pts, atol=1e-14)
    x, y, z = sp.symbols("x y z", real=True)
    Xs = cga.up([x, y, z])
    assert (Xs * Xs).simplify().coeffs == {}
    assert sp.simplify(cga.down(Xs * (x**2 + 1)) - sp.Matrix([x, y, z])) == sp.zeros(3, 1)


@pytest.mark.parametrize(
    "bad",
    [[1.0, 2.0], [[1.0, 2.0, np.nan]], [1.0, np.inf, 0.0], "abc", np.zeros((2, 2, 3))],
)
def test_up_rejects_bad_input(bad):
    with pytest.raises(InvalidInputError, match="up"):
        cga.up(bad)


def test_down_rejects_point_at_infinity_and_non_points():
    with pytest.raises(DegenerateGeometryError, match="down"):
        cga.down(cga.einf)
    with pytest.raises(InvalidInputError, match="down"):
        cga.down(cga.E)


# ----------------------------------------------------------- point pairs
def test_point_pair_endpoints_round_trip_eq_2_131():
    a, b = RNG.normal(size=(2, 3))
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(a, b))
    assert np.allclose(p1, a, atol=1e-12) and np.allclose(p2, b, atol=1e-12)
    # standard form and arbitrary scale give the same points
    q1, q2 = cga.point_pair_endpoints(cga.standard_form(cga.point_pair(a, b)) * 2.5)
    assert np.allclose(q1, a) and np.allclose(q2, b)
    r1, r2 = cga.point_pair_endpoints(-cga.point_pair(a, b))  # b ^ a: orientation swaps the order
    assert np.allclose(r1, b) and np.allclose(r2, a)


def test_point_pair_endpoints_batch():
    a, b = RNG.normal(size=(2, 50, 3))
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(a, b))
    assert np.allclose(p1, a, atol=1e-11) and np.allclose(p2, b, atol=1e-11)


def test_point_pair_from_three_spheres_is_real_intersection():
    """PP = s1 ^ s2 ^ s3 (table 2.1): endpoints lie on all three spheres."""
    c1, c2, c3 = np.array([0.0, 0, 0]), np.array([1.0, 0, 0]), np.array([0.0, 1, 0])
    PP = cga.sphere(c1, 1.0) ^ cga.sphere(c2, 1.0) ^ cga.sphere(c3, 1.0)
    for p in cga.point_pair_endpoints(PP):
        for c in (c1, c2, c3):
            assert np.linalg.norm(p - c) == pytest.approx(1.0)


def test_point_pair_guards():
    with pytest.raises(DegenerateGeometryError, match="point_pair"):
        cga.point_pair([1.0, 2, 3], [1.0, 2, 3])
    # three spheres with no common point: an imaginary point pair
    PP = cga.sphere([0.0, 0, 0], 1.0) ^ cga.sphere([5.0, 0, 0], 1.0) ^ cga.sphere([0.0, 5, 0], 1.0)
    with pytest.raises(DegenerateGeometryError, match="imaginary"):
        cga.point_pair_endpoints(PP)
    a = np.array([4.0, 0.0, 0.0])
    b = a + [0, 5e-5, 0]
    raw = cga.up(a) ^ cga.up(b)  # a raw wedge of plain points carries their frame (point_wedges): read about a, exact
    p1, p2 = cga.point_pair_endpoints(raw)
    assert np.array_equal(p1, a) and np.abs(p2 - b).max() <= 1e-15
    with pytest.raises(DegenerateGeometryError, match="accuracy guard"):  # its coefficients only (the frame dropped)
        cga.point_pair_endpoints(cga.Multivector(cga.G41, dict(raw.coeffs)))
    wide = cga.Multivector(cga.G41, dict((cga.up(a) ^ cga.up(a + [0, 1e-3, 0])).coeffs))
    p1, _ = cga.point_pair_endpoints(wide)  # above the guard: accurate
    assert np.allclose(p1, a, atol=1e-7)
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(a, a + [0, 5e-5, 0]))  # anchored: read about a, exact
    assert np.abs(p1 - a).max() <= 1e-15 and np.abs(p2 - a - [0, 5e-5, 0]).max() <= 1e-15


def test_point_pair_sphere_eq_2_134():
    a, b = RNG.normal(size=(2, 3))
    c, r = cga.sphere_center_radius(cga.point_pair_sphere(cga.point_pair(a, b)))
    assert np.allclose(c, (a + b) / 2) and r == pytest.approx(np.linalg.norm(a - b) / 2)


# ---------------------------------------------------------------- spheres
def test_sphere_forms_agree_eq_2_72_2_75():
    center, radius = RNG.normal(size=3), 1.7
    dirs = RNG.normal(size=(4, 3))
    pts = center + radius * dirs / np.linalg.norm(dirs, axis=1)[:, None]
    for S in (cga.sphere(center, radius), cga.sphere_from_points(*pts)):
        c, r = cga.sphere_center_radius(S)
        assert np.allclose(c, center) and r == pytest.approx(radius)
    s = cga.sphere(center, radius)
    assert float(s * s) == pytest.approx(radius**2)  # (2.73)
    assert float(cga.einf | s) == pytest.approx(-1.0)  # (2.74)
    for p in pts:  # (2.71) and (2.76)
        assert abs(float(cga.up(p) | s)) < 1e-10
        assert (cga.up(p) ^ cga.sphere_from_points(*pts)).iszero(atol=1e-9)


def test_sphere_batch_and_side_eq_2_118():
    centers, radii = RNG.normal(size=(10, 3)), RNG.uniform(0.5, 2, size=10)
    c, r = cga.sphere_center_radius(cga.sphere(centers, radii))
    assert np.allclose(c, centers) and np.allclose(r, radii)
    s = cga.sphere([0.0, 0, 0], 1.0)
    assert cga.point_sphere_side([0.1, 0.2, 0.3], s) == 1
    assert cga.point_sphere_side([1.0, 0, 0], s) == 0
    assert cga.point_sphere_side([2.0, 0, 0], s) == -1
    assert list(cga.point_sphere_side(np.array([[0, 0, 0.5], [0, 3, 0]]), s)) == [1, -1]


def test_sphere_degenerate():
    with pytest.raises(DegenerateGeometryError, match="coplanar"):
        cga.sphere_from_points([0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0], [1.0, 1, 0])
    with pytest.raises(DegenerateGeometryError, match="coplanar"):
        cga.sphere_from_points([0.0, 0, 0], [0.0, 0, 0], [0.0, 1, 0], [1.0, 1, 2])
    with pytest.raises(InvalidInputError, match="radius"):
        cga.sphere([0.0, 0, 0], -1.0)
    with pytest.raises(DegenerateGeometryError, match="imaginary"):
        cga.sphere_center_radius(cga.up([0.0, 0, 0]) + 0.5 * cga.einf)
    with pytest.raises(DegenerateGeometryError):
        cga.sphere_center_radius(cga.plane([0.0, 0, 1], 1.0))


# ----------------------------------------------------------------- planes
def test_plane_from_points_eq_2_77_and_2_89():
    a, b, c = RNG.normal(size=(3, 3))
    n_true = np.cross(b - a, c - a)
    n_true /= np.linalg.norm(n_true)
    n, d = cga.plane_normal_distance(cga.plane_from_points(a, b, c))
    assert np.allclose(n, n_true) and d == pytest.approx(n_true @ a)
    n2, d2 = cga.plane_normal_distance(cga.plane(3 * n_true, n_true @ a))
    assert np.allclose(n2, n_true) and d2 == pytest.approx(n_true @ a)
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        cga.plane_from_points([0.0, 0, 0], [1.0, 1, 1], [2.0, 2, 2])
    with pytest.raises(DegenerateGeometryError, match="zero"):
        cga.plane([0.0, 0, 0], 1.0)


# ------------------------------------------------------------------ lines
def test_line_properties_eq_2_125_to_2_130():
    a, b, x = RNG.normal(size=(3, 3))
    L = cga.line_from_points(a, b)
    r = (b - a) / np.linalg.norm(b - a)
    assert float(L * L) == pytest.approx(np.sum((a - b) ** 2))  # (2.125)
    assert float(cga.normalize_line(L) * cga.normalize_line(L)) == pytest.approx(1.0)  # (2.126)
    assert np.allclose(cga.line_direction(L), r)  # (2.127)
    assert np.allclose(cga.line_moment(L), np.cross(a, r))  # (2.128), corrected
    assert np.allclose(cga.line_closest_point(L), a - r * (a @ r))  # (2.129)
    assert cga.point_line_distance(x, L) == pytest.approx(np.linalg.norm(np.cross(x - a, r)))  # (2.130)
    assert cga.point_line_distance(a + 2 * r, L) == pytest.approx(0.0, abs=1e-7)
    xs = RNG.normal(size=(20, 3))
    assert np.allclose(cga.point_line_distance(xs, L), np.linalg.norm(np.cross(xs - a, r), axis=1))
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        cga.line_from_points(a, a)


# ---------------------------------------------------------------- circles
def test_circle_center_radius_eq_2_80_2_119_to_2_124():
    a, b, c = RNG.normal(size=(3, 3))
    center, radius, normal = circumcircle(a, b, c)
    Z = cga.circle_from_points(a, b, c)
    cc, rr, nn = cga.circle_center_radius(Z)
    assert np.allclose(cc, center) and rr == pytest.approx(radius) and np.allclose(nn, normal)
    z = cga.standard_form(Z)
    # (2.122) corrected: rho^2 = -z^2 / (e ^ z)^2
    rho2 = -float((z * z).grade(0)) / float(((cga.einf ^ z) * (cga.einf ^ z)).grade(0))
    assert rho2 == pytest.approx(radius**2)
    n, d = cga.plane_normal_distance(cga.circle_plane(Z))
    assert abs(abs(n @ normal) - 1) < 1e-12 and abs(d) == pytest.approx(abs(normal @ a))
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        cga.circle_from_points([0.0, 0, 0], [1.0, 0, 0], [3.0, 0, 0])


# ---------------------------------------------------------------- versors
@settings(max_examples=40, deadline=None)
@given(unit_axis, angle, point, point)
def test_motor_matches_matrix_eq_2_102_2_103(axis, ang, t, x):
    M = cga.motor(axis, ang, t)
    expected = rot_matrix(axis, ang) @ x + t
    assert np.allclose(cga.down(cga.apply(M, cga.up(x))), expected, atol=1e-9)
    assert float(M * ~M) == pytest.approx(1.0)  # (2.145)
    # versors preserve the null cone (2.82)
    Y = cga.apply(M, cga.up(x))
    assert abs(float(Y * Y)) < 1e-8 * (1 + x @ x + t @ t) ** 2


@settings(max_examples=40, deadline=None)
@given(unit_axis, angle, point)
def test_motor_decomposition_round_trip_eq_2_140_2_145(axis, ang, t):
    M = cga.motor(axis, ang, t)
    R, tt = cga.decompose_motor(M)
    assert np.allclose(tt, t, atol=1e-9)
    assert (cga.translator(tt) * R).isclose(M, atol=1e-9)
    assert R.isclose(cga.rotor(axis, ang), atol=1e-12)


def test_motors_compose():
    a1, a2 = RNG.normal(size=(2, 3))
    M1, M2 = cga.motor(a1, 0.4, [1.0, 0, 0]), cga.motor(a2, -1.1, [0, 2.0, 0.5])
    H = cga.motor_to_matrix(M2) @ cga.motor_to_matrix(M1)
    assert np.allclose(cga.motor_to_matrix(M2 * M1), H)  # (2.99)
    assert cga.matrix_to_motor(H).isclose(M2 * M1, atol=1e-9) or cga.matrix_to_motor(H).isclose(-(M2 * M1), atol=1e-9)


def test_translator_and_rotor_conventions_eq_2_94_2_100():
    x, t = np.array([1.0, 2.0, 3.0]), np.array([0.5, -1.0, 2.0])
    assert np.allclose(cga.down(cga.apply(cga.translator(t), cga.up(x))), x + t)
    assert cga.translator(t).isclose(cga.exp(cga.einf * cga.vector(t) * 0.5))  # (2.100)
    R = cga.rotor([0, 0, 1.0], np.pi / 2)
    assert np.allclose(cga.down(cga.apply(R, cga.up([1.0, 0, 0]))), [0, 1.0, 0])
    assert R.isclose(cga.exp(cga.vector([0, 0, 1.0]) * cga.IE * (-np.pi / 4)))  # (2.94)
    with pytest.raises(DegenerateGeometryError, match="zero"):
        cga.rotor([0, 0, 0], 1.0)


def test_rotor_about_line_and_screw_eq_2_104_2_110():
    a, b, x = RNG.normal(size=(3, 3))
    r = (b - a) / np.linalg.norm(b - a)
    RL = cga.rotor_about_line(cga.line_from_points(a, b), 0.9)
    expected = rot_matrix(r, 0.9) @ (x - a) + a
    assert np.allclose(cga.down(cga.apply(RL, cga.up(x))), expected)
    T = cga.translator(a)
    assert RL.isclose(T * cga.rotor(r, 0.9) * ~T, atol=1e-12)  # (2.104)
    S = cga.screw(r, a, 0.9, 0.35)
    assert np.allclose(cga.down(cga.apply(S, cga.up(x))), expected + 0.35 * r)
    assert S.isclose(cga.translator(0.35 * r) * RL, atol=1e-12)  # (2.110) = T_dr R_L
    angle, axis = cga.rotor_angle_axis(RL)  # (2.135)-(2.138)
    assert angle == pytest.approx(0.9) and np.allclose(axis, r)


def test_rotor_angle_axis_eq_2_135_2_136():
    for ang in (1e-9, 0.3, 2.0, np.pi - 1e-9):
        axis = RNG.normal(size=3)
        got_angle, got_axis = cga.rotor_angle_axis(cga.rotor(axis, ang))
        assert got_angle == pytest.approx(ang, abs=1e-12)
        assert np.allclose(got_axis, axis / np.linalg.norm(axis), atol=1e-6)


def test_reflection_and_inversion_eq_2_84_to_2_91():
    x = RNG.normal(size=3)
    n, delta = np.array([0.0, 0.6, 0.8]), 0.7
    y = cga.down(cga.reflect_in_plane(cga.plane(n, delta), cga.up(x)))
    assert np.allclose(y, x - 2 * (n @ x - delta) * n)  # (2.90)
    p, rho = RNG.normal(size=3), 1.3
    y = cga.down(cga.invert_in_sphere(cga.sphere(p, rho), cga.up(x)))
    assert np.allclose(y, rho**2 * (x - p) / np.sum((x - p) ** 2) + p)  # (2.88)
    # translation as two reflections in parallel planes (2.92, figure 2.7)
    P1, P2 = cga.plane(n, delta), cga.plane(n, 0.0)
    assert (P1 * P2).isclose(cga.translator(2 * delta * n))
    with pytest.raises(InvalidInputError, match="sphere"):
        cga.reflect_in_plane(cga.sphere(p, rho), cga.up(x))


def test_apply_batch_fast_path_matches_sandwich():
    M = cga.motor(RNG.normal(size=3), 0.8, RNG.normal(size=3))
    pts = RNG.normal(size=(200, 3))
    X = cga.up(pts)
    fast = cga.apply(M, X)
    for i in (0, 17, 199):
        assert fast.batch_item(i).isclose(M * X.batch_item(i) * ~M, atol=1e-12)
    assert np.allclose(cga.apply_to_points(M, pts), cga.down(fast), atol=1e-12)
    lines = cga.line_from_points(pts[:100], pts[100:])  # grade-3 batch
    moved = cga.apply(M, lines)
    assert moved.batch_item(5).isclose(M * lines.batch_item(5) * ~M, atol=1e-12)


def test_symbolic_motor_decomposition():
    th, t1, t2, t3 = sp.symbols("theta t1 t2 t3", real=True)
    M = cga.motor([0, 0, 1], th, [t1, t2, t3])
    R, t = cga.decompose_motor(M)
    assert sp.simplify(t - sp.Matrix([t1, t2, t3])) == sp.zeros(3, 1)
    assert (R - cga.rotor([0, 0, 1], th)).simplify().coeffs == {}


def test_circle_as_sphere_intersection_eq_2_78_2_79():
    s1, s2 = cga.sphere([0.0, 0, 0], 2.0), cga.sphere([1.0, 0, 0], 2.0)
    z = s1 ^ s2
    th = RNG.uniform(0, 2 * np.pi, size=5)
    rad = np.sqrt(4 - 0.25)
    pts = np.stack([np.full(5, 0.5), rad * np.cos(th), rad * np.sin(th)], axis=1)
    assert np.allclose((cga.up(pts) | z).to_array(), 0, atol=1e-12)  # (2.79) on the circle
    assert not (cga.up([0.5, 0.0, 0.0]) | z).iszero()  # the centre is not on it
    c, r, n = cga.circle_center_radius(z)
    assert np.allclose(c, [0.5, 0, 0]) and r == pytest.approx(rad) and abs(n[0]) == pytest.approx(1.0)


def test_line_pluecker_form_eq_2_81_2_107_2_108():
    a, b = RNG.normal(size=(2, 3))
    L = cga.line_from_points(a, b)
    M = cga.vector(a) ^ cga.vector(b)
    assert L.isclose(cga.einf * M + cga.vector(b - a) * cga.E)  # (2.81) e M + r E
    r = (b - a) / np.linalg.norm(b - a)
    t = a - r * (a @ r)  # from the origin to the line
    Ln = cga.normalize_line(L)
    assert Ln.isclose(cga.einf * (cga.vector(t) ^ cga.vector(r)) + cga.vector(r) * cga.E)  # (2.107)
    l = cga.vector(r) * cga.IE
    assert cga.standard_form(Ln).isclose(cga.einf * (cga.vector(t) | l) + l)  # (2.108)


def test_rotor_reverse_eq_2_97():
    R = cga.rotor([1.0, 2.0, 2.0], 0.8)
    s = np.sin(0.4) * np.array([1.0, 2.0, 2.0]) / 3
    blades = cga.G41.blade("e23", s[0]) + cga.G41.blade("e31", s[1]) + cga.G41.blade("e12", s[2])
    assert (~R).isclose(np.cos(0.4) + blades)


def test_affine_representation_eq_2_112_2_113():
    x = RNG.normal(size=3)
    X = cga.up(x) * 2.5
    eX = (cga.einf ^ X) * (1.0 / -float(cga.einf | X))
    assert eX.isclose(cga.einf * cga.vector(x) + (cga.einf ^ cga.eo))  # (2.112)
    assert (eX * cga.E).isclose(1 + cga.einf * cga.vector(x))  # (2.113)


def test_sphere_centre_point_eq_2_117():
    c, r = RNG.normal(size=3), 0.9
    s = cga.sphere(c, r)
    assert (s + cga.einf * (0.5 * float(s * s))).isclose(cga.up(c))


def test_circle_axis_and_sphere_eq_2_120_2_124():
    a, b, c = RNG.normal(size=(3, 3))
    center, radius, normal = circumcircle(a, b, c)
    Zd = cga.circle_from_points(a, b, c)
    Lz = cga.standard_form(Zd) ^ cga.einf  # (2.120): the axis through the centre
    assert np.allclose(np.abs(cga.line_direction(Lz) @ normal), 1.0)
    assert cga.point_line_distance(center, Lz) == pytest.approx(0.0, abs=1e-6)  # sqrt(rho^2): sqrt(eps) resolution
    # (2.124) corrected: the dual circle over its dual plane; its vector part is the sphere s_z
    s = (Zd * cga.circle_plane(Zd).inv()).grade(1)
    cc, rr = cga.sphere_center_radius(s)
    assert np.allclose(cc, center) and rr == pytest.approx(radius)
    # as printed, z / P_z* with the standard z has no vector part that is that sphere
    printed = cga.standard_form(Zd) * cga.circle_plane(Zd).inv()
    assert printed.grade(1).iszero(atol=1e-9)


def test_circle_centre_sphere_eq_2_121():
    """(2.121): axis . plane = e ^ s_e0, the sphere centred on the circle's centre through the origin."""
    a, b, c = RNG.normal(size=(3, 3))
    center, _, _ = circumcircle(a, b, c)
    Zd = cga.circle_from_points(a, b, c)
    Lz = cga.standard_form(Zd) ^ cga.einf  # (2.120)
    printed = Lz | cga.circle_plane(Zd)  # with the dual plane P_z* of (2.119), as printed
    assert printed.iszero(atol=1e-12)
    q = Lz | cga.standard_form(cga.circle_plane(Zd))  # with the plane in standard form
    es = cga.einf ^ cga.sphere(center, np.linalg.norm(center))
    k, m = q.to_array(), es.to_array()
    i = int(np.argmax(np.abs(m)))
    assert not q.iszero() and np.allclose(k, m * (k[i] / m[i]), atol=1e-10)


# ------------------------------------------------------------------ errata of section 2.3.5 and 2.4, decided


def test_rotor_composition_order_eq_2_99_erratum():
    """(2.99) sets R = R1 R2 and then applies (R2 R1): only R2 R1 applies R1 first (the matrix H2 H1)."""
    R1, R2 = cga.rotor([0, 0, 1], np.pi / 2), cga.rotor([1, 0, 0], np.pi / 2)
    x = cga.up([1.0, 0.0, 0.0])
    first_r1 = cga.down(cga.apply(R2, cga.apply(R1, x)))  # turn by R1, then by R2: (1,0,0) -> (0,1,0) -> (0,0,1)
    assert np.allclose(first_r1, [0.0, 0.0, 1.0])
    assert np.allclose(cga.down(cga.apply(R2 * R1, x)), first_r1)  # corrected: R = R2 R1
    assert not np.allclose(cga.down(cga.apply(R1 * R2, x)), first_r1)  # printed: R = R1 R2


def test_rotation_about_a_line_applied_to_a_point_eq_2_105_erratum():
    """(2.105) prints T R ~T x ~R ~T: one T is missing; T R ~T x T ~R ~T turns x about the line (2.104)."""
    a, b, x = RNG.normal(size=(3, 3))
    r = (b - a) / np.linalg.norm(b - a)
    T, R, X = cga.translator(a), cga.rotor(r, 0.9), cga.up(x)
    expected = rot_matrix(r, 0.9) @ (x - a) + a
    corrected = T * R * ~T * X * T * ~R * ~T
    printed = T * R * ~T * X * ~R * ~T
    assert np.allclose(cga.down(corrected.grade(1)), expected)
    assert not printed.grade(1).isclose(corrected.grade(1), atol=1e-6)


def test_unit_norm_of_a_general_rotation_eq_2_139_erratum():
    """(2.139)'s first line reverses T R ~T as ~T ~T ~R; the reverse is T ~R ~T, and only that product is 1."""
    T, R = cga.translator(RNG.normal(size=3)), cga.rotor(RNG.normal(size=3), 1.3)
    RL = T * R * ~T
    assert (RL * ~RL).isclose(1.0, atol=1e-12)
    assert (T * R * ~T * T * ~R * ~T).isclose(1.0, atol=1e-12)  # corrected first line
    assert not (T * R * ~T * ~T * ~R).isclose(1.0, atol=1e-6)  # printed first line


def test_sphere_of_a_circle_by_division_eq_2_124_holds_up_to_scale():
    """(2.124) s_z* = z / P_z*: the quotient of the standard circle by its dual plane is the dual sphere of (2.123)
    up to a scale (its sign depends on the side of the division; the grade-2 part is round-off)."""
    Zd = cga.circle_from_points(*RNG.normal(size=(3, 3)))
    z, Pz = cga.standard_form(Zd), Zd ^ cga.einf
    s_dual = cga.dual_form(((cga.einf | z) * z).grade(1))  # (2.123), dualised
    for q in (z * Pz.inv(), Pz.inv() * z):
        assert q.grade(2).iszero(atol=1e-12)
        k = float(q.grade(4).to_array() @ s_dual.to_array()) / float(s_dual.to_array() @ s_dual.to_array())
        assert q.grade(4).isclose(s_dual * k, atol=1e-12) and abs(k) > 1e-6
    right = float((z * Pz.inv()).grade(4).to_array() @ s_dual.to_array())
    left = float((Pz.inv() * z).grade(4).to_array() @ s_dual.to_array())
    assert right * left < 0  # the two divisions differ by the sign only


def test_point_pair_endpoints_order_eq_2_131_erratum():
    """(2.131) p_1,2 = (PP* +- sqrt) / (PP* . e): with the division on the right, p1 = a of PP* = a ^ b comes from
    the numerator PP* - sqrt (2.132) as the text says, so the printed +- gives b first; the corrected form is -+."""
    a, b = np.array([0.3, -1.0, 2.0]), np.array([1.5, 0.4, -0.2])
    B = cga.up(a) ^ cga.up(b)
    root = np.sqrt(float((B * B).scalar()))
    inv = (B | cga.einf).inv()
    plus, minus = cga.down(((B + root) * inv).grade(1)), cga.down(((B - root) * inv).grade(1))
    assert np.allclose(minus, a) and np.allclose(plus, b)  # corrected -+ order: p1 = a first
    p1, p2 = cga.point_pair_endpoints(B)
    assert np.allclose(p1, a) and np.allclose(p2, b)


# ------------------------------------------------------------ bad input: the checks layer's words
def test_point_input_is_refused_clearly():
    with pytest.raises(InvalidInputError, match=r"^up: x: must be real numbers, got complex"):
        cga.up([1.0 + 2j, 0.0, 0.0])  # was truncated to its real part
    with pytest.raises(InvalidInputError, match=r"^up: x: magnitudes up to 1e\+200, beyond 1e\+153"):
        cga.up([[0.0, 0.0, 0.0], [1e200, 0.0, 0.0]])
    with pytest.raises(InvalidInputError, match=r"^sphere: radius: must be a real number"):
        cga.sphere([0, 0, 0], "1.0")  # was read as 1.0
    with pytest.raises(InvalidInputError, match=r"^sphere: center, radius: must have the same length, got 2 and 3"):
        cga.sphere(np.eye(3)[:2], [1.0, 2.0, 3.0])
    assert cga.sphere([0, 0, 0], [1.0, 2.0]).shape == (2,)  # one centre, several radii: concentric spheres
    with pytest.raises(InvalidInputError, match=r"^plane: distance: is NaN or inf"):
        cga.plane([0, 0, 1], np.nan)
    n, d = cga.plane_normal_distance(cga.plane([3e200, 0.0, 4e200], 1.0))  # |normal|^2 overflows: scaled first
    assert np.allclose(n, [0.6, 0.0, 0.8]) and d == 1.0
    with pytest.raises(InvalidInputError, match=r"^point_sphere_side: atol: must be >= 0"):
        cga.point_sphere_side([0, 0, 0], cga.sphere([0, 0, 0], 1.0), atol=-1.0)
    PP = cga.point_pair([0, 0, 0], [1, 0, 0])
    with pytest.raises(DegenerateGeometryError, match=r"^point_pair_endpoints: PP: .* below min_separation = 2"):
        cga.point_pair_endpoints(PP, min_separation=2.0)
    with pytest.raises(InvalidInputError, match=r"^point_pair_endpoints: min_separation: must be >= 0"):
        cga.point_pair_endpoints(PP, min_separation=-1.0)


def test_down_reads_points_only():
    X = cga.up(RNG.normal(size=(5, 3)) * 100)
    M = cga.motor([1.0, 2.0, 3.0], 0.7, [1e3, -2e3, 5e2])
    assert np.allclose(cga.down(cga.apply(M, X)), cga.apply_to_points(M, cga.down(X)), atol=1e-9)
    assert np.allclose(cga.down(1e-200 * X), cga.down(X)) and np.allclose(cga.down(1e200 * X), cga.down(X))
    for S in (
        cga.sphere([1.0, 2.0, 3.0], 0.5),
        cga.sphere(RNG.normal(size=(4, 3)), 0.5),
        1e-200 * cga.sphere([0, 0, 0], 1),
    ):
        with pytest.raises(InvalidInputError, match=r"^down: X: X \. X != 0: a sphere"):
            cga.down(S)
    with pytest.raises(InvalidInputError, match=r"^down: X: expected a multivector of G\(4,1\), got ndarray"):
        cga.down(np.zeros(32))
    with pytest.raises(InvalidInputError, match=r"^euclidean: X: contains NaN or inf"):
        cga.euclidean(cga.Multivector(cga.G41, {1: np.nan}))
    with pytest.raises(InvalidInputError, match=r"^point_weight: X: expected a conformal point or sphere"):
        cga.point_weight(cga.line_from_points([0, 0, 0], [1, 0, 0]))


def test_fits_refuse_bad_input_by_name():
    ring = np.array([[1.0, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0], [0.6, 0.8, 0]])
    with pytest.raises(DegenerateGeometryError, match=r"^fit_sphere: X: the points lie on a circle"):
        cga.fit_sphere(ring)  # was: one sphere of the pencil through the circle, chosen by round-off
    with pytest.raises(DegenerateGeometryError, match=r"^fit_sphere_kasa: X: all points coincide"):
        cga.fit_sphere_kasa(np.ones((5, 3)))
    with pytest.raises(InvalidInputError, match=r"^fit_plane: X: must be an array of numbers"):
        cga.fit_plane([[0.0, 0.0, 0.0], [1.0, 0.0], [0.0, 1.0, 0.0]])
    with pytest.raises(InvalidInputError, match=r"^fit_circle: X: magnitudes up to 1e\+300, beyond 1e\+153"):
        cga.fit_circle(ring * 1e300)
    sphere_pts = np.vstack([np.eye(3), -np.eye(3)])
    with pytest.raises(InvalidInputError, match=r"^fit_sphere_geometric: init: has no 'radius'"):
        cga.fit_sphere_geometric(sphere_pts, init={"center": [0, 0, 0]})
    with pytest.raises(InvalidInputError, match=r"^fit_sphere_geometric: iterations: must be a whole number"):
        cga.fit_sphere_geometric(sphere_pts, iterations=2.5)
    with pytest.raises(DegenerateGeometryError, match=r"^fit_sphere_geometric: X: the points lie on a plane"):
        cga.fit_sphere_geometric(ring, init={"center": [0, 0, 1], "radius": 1.0})
    fit = cga.fit_sphere_geometric(sphere_pts, init={"center": [0.1, 0, 0], "radius": 2.0})
    assert np.allclose(fit.center, 0, atol=1e-12) and fit.radius == pytest.approx(1.0)
    with pytest.raises(InvalidInputError, match=r"^fit_circle_euclidean: iterations: must be >= 0"):
        cga.fit_circle_euclidean(ring, iterations=-1)
    cloud = np.array([[x, y, 0.0] for x in range(4) for y in range(4)], float)
    rng = np.random.default_rng(0)
    for kw, match in [
        ({"rng": 0}, r"^segment_planes: rng: expected a numpy.random.Generator"),
        ({"threshold": 0.0}, r"^segment_planes: threshold: must be > 0"),
        ({"min_inliers": 2.5}, r"^segment_planes: min_inliers: must be a whole number"),
        ({"n_planes": True}, r"^segment_planes: n_planes: must be a whole number, got the bool"),
        ({"iterations": 0}, r"^segment_planes: iterations: must be >= 1"),
    ]:
        with pytest.raises(InvalidInputError, match=match):
            cga.segment_planes(cloud, **{"rng": rng, "min_inliers": 5, **kw})
    with pytest.raises(DegenerateGeometryError, match=r"^segment_planes: X: every sampled triple is collinear"):
        cga.segment_planes(np.outer(np.arange(6.0), [1, 2, 3]), rng, min_inliers=3)
    fits, labels = cga.segment_planes(cloud, rng, n_planes=1, threshold=0.01, iterations=20, min_inliers=5)
    assert len(fits) == 1 and np.all(labels == 0)
