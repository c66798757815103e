"""Blades of G(4,1): contractions, dual, regressive product, join/meet, projection, factorisation, classification.

Independent truths: the kingdon library (a second implementation of G(4,1)), closed forms of elementary geometry
(plane-plane, line-plane, sphere-sphere, sphere-line, circle-plane) and the thesis's own formulas (2.58, 2.59, 2.79,
table 2.1, Theorem 2.4.1).
"""

import math

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st
from kingdon import Algebra as KingdonAlgebra

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra, DegenerateGeometryError, InvalidInputError, Multivector
from cga_lessons.conformal import (
    BladeKind,
    blade_factors,
    classify,
    dual,
    intersect,
    is_blade,
    is_versor,
    join,
    left_contraction,
    meet,
    project,
    regressive_product,
    reject,
    require_blade,
    right_contraction,
    scalar_product,
    undual,
)

G = cga.G41
K = KingdonAlgebra(4, 1)  # e1 e2 e3 e4 e5 with e4^2 = +1, e5^2 = -1: ours are e1 e2 e3 e+ e-
SEEDS = st.integers(0, 2**32 - 1)
FAST = settings(deadline=None, max_examples=25)


# ------------------------------------------------------------------ helpers
def to_kingdon(X: Multivector):
    """Same bitmap, same name: our e+ is kingdon's e4, our e- its e5 (checked in the first test)."""
    names = {b: ("e" + "".join(str(i + 1) for i in range(5) if b >> i & 1)) if b else "e" for b in X.coeffs}
    return K.multivector({names[b]: v for b, v in X.coeffs.items()})


def from_kingdon(Y) -> Multivector:
    return Multivector(G, {int(k): float(v) for k, v in zip(Y.keys(), Y.values()) if float(v) != 0.0})


def close(A, B, rtol=1e-10):
    """|A - B| <= rtol max(|A|, |B|, 1) in the coefficient norm."""
    a, b = A.to_array(), B.to_array()
    return np.linalg.norm(a - b) <= rtol * max(np.linalg.norm(a), np.linalg.norm(b), 1.0)


def proportional(A, B, rtol=1e-9):
    """A = lam B for some non-zero lam (returned), within rtol."""
    a, b = A.to_array(), B.to_array()
    lam = float(a @ b / (b @ b))
    assert lam != 0.0 and np.linalg.norm(a - lam * b) <= rtol * np.linalg.norm(a), (A, B)
    return lam


def random_mv(rng):
    return G.from_array(rng.normal(size=32))


def random_vector(rng):
    return G.vector(rng.normal(size=5))


def random_blade(rng, k):
    out = Multivector(G, {0: 1.0})
    for _ in range(k):
        out = out ^ random_vector(rng)
    return out


def unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


# --------------------------------------------------------- basis and kingdon
def test_kingdon_basis_matches_ours():
    for i, sq in enumerate([1, 1, 1, 1, -1]):
        e = Multivector(G, {1 << i: 1.0})
        assert float(e * e) == sq
        assert from_kingdon(to_kingdon(e) * to_kingdon(e)) == Multivector(G, {0: float(sq)})
    rng = np.random.default_rng(0)
    A, B = random_mv(rng), random_mv(rng)
    assert close(from_kingdon(to_kingdon(A) * to_kingdon(B)), A * B, 1e-13)
    assert close(from_kingdon(to_kingdon(A) ^ to_kingdon(B)), A ^ B, 1e-13)


@FAST
@given(SEEDS)
def test_contractions_and_scalar_product_match_kingdon(seed):
    rng = np.random.default_rng(seed)
    A, B = random_mv(rng), random_mv(rng)
    kA, kB = to_kingdon(A), to_kingdon(B)
    assert close(left_contraction(A, B), from_kingdon(kA.lc(kB)), 1e-12)
    assert close(right_contraction(A, B), from_kingdon(kA.rc(kB)), 1e-12)
    assert close(left_contraction(A, B), A << B, 1e-12)  # the project's operator
    assert close(right_contraction(A, B), ~left_contraction(~B, ~A), 1e-12)
    assert math.isclose(scalar_product(A, B), float(from_kingdon(kA.sp(kB)).scalar()), rel_tol=1e-12, abs_tol=1e-12)


@FAST
@given(SEEDS)
def test_dual_and_regressive_product_match_kingdon(seed):
    rng = np.random.default_rng(seed)
    A, B = random_mv(rng), random_mv(rng)
    assert close(dual(A), from_kingdon(to_kingdon(A).dual()), 1e-12)  # polarity A I^-1 (2.31)
    assert close(undual(A), from_kingdon(to_kingdon(A).undual()), 1e-12)
    assert close(dual(A), A.dual(), 0.0) and close(dual(A), cga.dual_form(A), 0.0)  # the project's dual
    assert close(undual(dual(A)), A, 1e-14)
    # kingdon's A & B (Hodge complement) is our regressive product with the arguments swapped
    assert close(regressive_product(B, A), from_kingdon(to_kingdon(A) & to_kingdon(B)), 1e-12)
    assert close(regressive_product(A, B), left_contraction(dual(A), B), 1e-12)


@FAST
@given(SEEDS, st.integers(1, 4), st.integers(1, 4))
def test_meet_in_general_position_matches_kingdon(seed, a, b):
    rng = np.random.default_rng(seed)
    A, B = random_blade(rng, a), random_blade(rng, b)
    M = meet(A, B)
    if a + b >= 5:
        assert M.grades_present() == [a + b - 5]
        assert close(M, from_kingdon(to_kingdon(A) & to_kingdon(B)), 1e-9)
    else:  # disjoint spans: the meet is a scalar, the join the outer product
        assert M.grades_present() == [0] and math.isclose(abs(float(M)), 1.0, rel_tol=1e-9)
        assert close(join(A, B), A ^ B, 0.0)


@FAST
@given(SEEDS, st.integers(1, 3), st.integers(0, 2), st.integers(0, 2))
def test_join_and_meet_of_blades_with_a_common_factor(seed, c, a, b):
    if c + a + b > 5 or a + b == 0:
        return
    rng = np.random.default_rng(seed)
    C, Ap, Bp = random_blade(rng, c), random_blade(rng, a), random_blade(rng, b)
    A, B = Ap ^ C, C ^ Bp
    J, M = join(A, B), meet(A, B)
    assert J.grades_present() == [a + b + c] and M.grades_present() == [c]
    proportional(M, C)  # the meet spans the common factor
    for f in blade_factors(A) + blade_factors(B):
        assert (f ^ J).iszero(1e-9 * np.linalg.norm(J.to_array()) * np.linalg.norm(f.to_array()))


# --------------------------------------------------- factors, blade, versor
@FAST
@given(SEEDS, st.integers(1, 5))
def test_blade_factors_rebuild_the_blade(seed, k):
    rng = np.random.default_rng(seed)
    A = random_blade(rng, k) * float(rng.uniform(0.01, 100))
    f = blade_factors(A)
    out = f[0]
    for v in f[1:]:
        out = out ^ v
    assert len(f) == k and close(out, A, 1e-11) and is_blade(A)
    assert require_blade(A)[1] == k


@FAST
@given(SEEDS, st.integers(2, 3))
def test_sums_of_blades_in_general_position_are_not_blades(seed, k):
    rng = np.random.default_rng(seed)
    A = random_blade(rng, k) + random_blade(rng, k)
    assert not is_blade(A)
    assert is_blade(random_mv(rng).grade(1)) and is_blade(random_mv(rng).grade(4))  # always blades in 5D
    assert not is_blade(random_mv(rng))  # mixed grades


def test_conformal_entities_are_blades_far_from_the_origin():
    c = np.array([300.0, -200.0, 50.0])
    for X in (
        cga.point_pair(c, c + [1, 0, 0]),
        cga.circle_from_points(c, c + [1, 0, 0], c + [0, 1, 0]),
        cga.line_from_points(c, c + [0, 0, 1]),
        cga.up(c) ^ (cga.up(c) << (cga.e1 ^ cga.einf)),  # a tangent vector (a null blade)
    ):
        assert is_blade(X)


def test_is_versor():
    T, R = cga.translator([1.0, -2.0, 0.5]), cga.rotor([0, 0, 1], 0.7)
    a, b = cga.sphere([1, 0, 0], 2.0), cga.plane([0, 1, 0], 3.0)
    for V in (T, R, T * R, 1e6 * (T * R), a, a * b, cga.e1 * cga.e2, cga.E):
        assert is_versor(V), V
    rng = np.random.default_rng(3)
    assert is_versor(random_vector(rng) * random_vector(rng) * random_vector(rng))
    B = random_mv(rng).grade(2)  # a generic bivector is not simple: B ~B has a grade-4 part
    for V in (1 + cga.e1, cga.up([1, 2, 3]), cga.einf, cga.e1 + cga.e1 * cga.e2, B, Multivector(G, {})):
        assert not is_versor(V), V


# ----------------------------------------------------- projection, rejection
def test_projection_and_rejection_by_E_are_the_thesis_2_58_2_59():
    rng = np.random.default_rng(4)
    for _ in range(10):
        a = random_vector(rng)
        assert close(project(a, cga.E), (a | cga.E) * cga.E, 1e-13)  # (2.58), E^-1 = E
        assert close(reject(a, cga.E), (a ^ cga.E) * cga.E, 1e-13)  # (2.59)


@FAST
@given(SEEDS, st.integers(1, 4))
def test_projection_lies_in_B_and_rejection_is_orthogonal(seed, k):
    rng = np.random.default_rng(seed)
    x, B = random_vector(rng), random_blade(rng, k)
    P, Rj = project(x, B), reject(x, B)
    s = np.linalg.norm(x.to_array()) * np.linalg.norm(B.to_array())
    assert close(P + Rj, x, 1e-9)
    assert (P ^ B).iszero(1e-9 * s) and left_contraction(Rj, B).iszero(1e-9 * s)
    if k >= 2:
        A = random_blade(rng, 2)
        PA = project(A, B)
        for f in blade_factors(PA) if not PA.iszero(1e-12) else []:
            assert (f ^ B).iszero(1e-8 * np.linalg.norm(f.to_array()) * np.linalg.norm(B.to_array()))


def test_project_refuses_a_null_blade():
    with pytest.raises(DegenerateGeometryError, match="project: B: is a null blade"):
        project(cga.e1, cga.up([1, 2, 3]))
    with pytest.raises(DegenerateGeometryError, match="reject: B: is a null blade"):
        reject(cga.e1, cga.up([0, 0, 0]) ^ cga.e1)


# ------------------------------------------------------------- closed forms
@FAST
@given(SEEDS)
def test_plane_plane_is_the_line_along_n1_cross_n2(seed):
    rng = np.random.default_rng(seed)
    n1, n2 = unit(rng.normal(size=3)), unit(rng.normal(size=3))
    if np.linalg.norm(np.cross(n1, n2)) < 0.1:
        return
    d1, d2 = rng.uniform(-5, 5, size=2)
    P1, P2 = cga.plane(n1, d1), cga.plane(n2, d2)
    L = intersect(P1, P2)  # standard form, the thesis's L = P1 ^ P2 (table 2.1)
    assert close(L, P1 ^ P2, 1e-12)
    u = unit(np.cross(n1, n2))
    q = np.linalg.solve(np.array([n1, n2, u]), [d1, d2, 0.0])
    assert abs(abs(cga.line_direction(L) @ u) - 1.0) < 1e-12
    for x in (q, q + 3 * u):  # on the line: x ^ L* = 0 (2.76); point_line_distance is only sqrt(eps) accurate here
        assert (cga.up(x) ^ cga.dual_form(L)).iszero(1e-12 * (1 + x @ x))
    proportional(cga.dual_form(L), cga.line_from_points(q, q + u))
    assert classify(L, form="standard").name == "line"


@FAST
@given(SEEDS)
def test_line_plane_is_the_flat_point_at_the_crossing(seed):
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(-5, 5, size=(2, 3))
    n, d = unit(rng.normal(size=3)), float(rng.uniform(-3, 3))
    if abs(n @ unit(b - a)) < 0.1 or np.linalg.norm(b - a) < 0.1:
        return
    x = a + (d - n @ a) / (n @ (b - a)) * (b - a)
    F = intersect(cga.line_from_points(a, b), cga.plane(n, d))  # mixed forms: dual form back
    proportional(F, cga.einf ^ cga.up(x), 1e-9)
    k = classify(F)
    assert (k.kind, k.dimension, k.name) == ("flat", 0, "flat point")
    ea = unit(np.cross(n, rng.normal(size=3)))
    F2 = meet(cga.line_from_points(a, b), cga.plane_from_points(x, x + ea, x + np.cross(n, ea)))  # both dual forms
    proportional(F2, cga.einf ^ cga.up(x), 1e-9)


@FAST
@given(SEEDS)
def test_sphere_sphere_is_the_circle_of_elementary_geometry(seed):
    rng = np.random.default_rng(seed)
    c1, c2 = rng.uniform(-3, 3, size=(2, 3))
    r1, r2 = rng.uniform(0.2, 3, size=2)
    dist = float(np.linalg.norm(c2 - c1))
    t = (dist**2 + r1**2 - r2**2) / (2 * dist)
    rho2 = r1**2 - t**2  # < 0: imaginary circle (d > r1 + r2 or one inside the other)
    if dist < 0.1 or abs(rho2) < 1e-3:
        return
    s1, s2 = cga.sphere(c1, r1), cga.sphere(c2, r2)
    z = intersect(s1, s2)
    assert close(z, s1 ^ s2, 1e-12)  # (2.79)
    k = classify(z, form="standard")
    assert k.kind == "round" and k.dimension == 1 and k.imaginary == (rho2 < 0)
    assert math.isclose(k.radius2, rho2, rel_tol=1e-8, abs_tol=1e-9)
    assert (float((s1 ^ s2) ** 2) < 0) == (rho2 > 0)  # Theorem 2.4.1
    if rho2 > 0:
        centre, radius, normal = cga.circle_center_radius(z)
        u = (c2 - c1) / dist
        assert np.allclose(centre, c1 + t * u, atol=1e-9) and math.isclose(radius, math.sqrt(rho2), rel_tol=1e-9)
        assert abs(abs(normal @ u) - 1) < 1e-9
        assert classify(cga.dual_form(z), form="dual") == BladeKind("round", 1, False, 3, "dual", k.radius2)


@FAST
@given(SEEDS)
def test_sphere_line_is_the_point_pair_of_the_quadratic(seed):
    rng = np.random.default_rng(seed)
    c, p = rng.uniform(-3, 3, size=(2, 3))
    u, r = unit(rng.normal(size=3)), float(rng.uniform(0.5, 3))
    half_b, cc = u @ (p - c), (p - c) @ (p - c) - r**2  # s^2 + 2 half_b s + cc = 0
    disc = half_b**2 - cc  # the squared half distance of the two points, negative when the line misses
    if abs(disc) < 1e-3:
        return
    PP = intersect(cga.line_from_points(p, p + u), cga.sphere(c, r))
    k = classify(PP)
    assert (k.kind, k.dimension, k.imaginary) == ("round", 0, disc < 0)
    assert math.isclose(k.radius2, disc, rel_tol=1e-8, abs_tol=1e-9)
    if disc > 0:
        s = -half_b + np.array([-1, 1]) * math.sqrt(disc)
        expected = sorted([tuple(p + si * u) for si in s])
        got = sorted(tuple(x) for x in cga.point_pair_endpoints(PP))
        assert np.allclose(got, expected, atol=1e-8)


def test_circle_plane_and_circle_sphere():
    Z = cga.circle_from_points([1, 0, 0], [0, 1, 0], [-1, 0, 0])
    for h in (0.0, 0.3, -0.8):
        PP = intersect(Z, cga.plane([1, 0, 0], h))
        got = sorted(tuple(x) for x in cga.point_pair_endpoints(PP))
        y = math.sqrt(1 - h * h)
        assert np.allclose(got, [(h, -y, 0), (h, y, 0)], atol=1e-12)
    k = classify(intersect(Z, cga.plane([1, 0, 0], 2.0)))
    assert (k.name, round(k.radius2, 12)) == ("imaginary point pair", -3.0)  # 1 - h^2
    assert classify(intersect(Z, cga.sphere([1, 0, 0], 1.0))).name == "point pair"
    proportional(intersect(Z, cga.plane([0, 0, 1], 0.0)), Z)  # the circle lies in the plane: itself


def test_three_spheres_give_the_thesis_point_pair():
    s1, s2, s3 = cga.sphere([0, 0, 0], 1.0), cga.sphere([1, 0, 0], 1.0), cga.sphere([0, 1, 0], 1.0)
    PP = intersect(intersect(s1, s2), s3, forms=("standard", "standard"))
    assert close(PP, s1 ^ s2 ^ s3, 1e-13)  # table 2.1: PP = s1 ^ s2 ^ s3
    got = sorted(tuple(x) for x in cga.point_pair_endpoints(PP))
    h = math.sqrt(0.5)
    assert np.allclose(got, [(0.5, 0.5, -h), (0.5, 0.5, h)], atol=1e-12)


def test_degenerate_positions_are_named_not_refused():
    P1, P2 = cga.plane([0, 0, 1], 0.0), cga.plane([0, 0, 1], 1.0)
    assert classify(intersect(P1, P2), form="standard").name == "free bivector"  # parallel planes
    proportional(intersect(P1, P2), cga.e3 ^ cga.einf)
    assert classify(intersect(P1, 3 * P1), form="standard").name == "plane"  # coincident
    L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])
    assert classify(intersect(L1, P2)).name == "free vector"  # line parallel to a plane
    proportional(intersect(L1, P1), L1)  # line in the plane
    skew = meet(L1, cga.line_from_points([0, 1, 1], [0, 2, 1]))
    proportional(skew, cga.einf)
    assert classify(skew, form="dual").name == "point at infinity"
    F = meet(L1, cga.line_from_points([2, -1, 0], [2, 1, 0]))  # coplanar lines: the join is their plane
    proportional(F, cga.einf ^ cga.up([2, 0, 0]))
    assert classify(meet(L1, cga.line_from_points([0, 1, 0], [1, 1, 0]))).name == "free vector"
    s = cga.sphere([0, 0, 0], 1.0)
    assert classify(intersect(s, cga.sphere([3, 0, 0], 2.0)), form="standard").name == "tangent bivector"
    assert classify(intersect(cga.line_from_points([-2, 1, 0], [2, 1, 0]), s)).name == "tangent vector"
    assert classify(intersect(s, cga.sphere([0, 0, 0], 2.0)), form="standard").name == "dual flat point"
    x = cga.up([0.0, 0.0, 0.0])  # two tangent vectors at one point: a null join, met in the Euclidean metric
    proportional(meet(x ^ cga.e1, x ^ cga.e2), x)
    assert classify(meet(x ^ cga.e1, x ^ cga.e2)).name == "point"
    assert classify(intersect(cga.up([1, 0, 0]), s, forms=("dual", "standard"))).name == "point"
    assert classify(meet(cga.point_pair([0, 0, 0], [1, 0, 0]), cga.point_pair([0, 2, 0], [0, 3, 0]))).kind == "scalar"


def test_classify_the_entities_of_table_2_1():
    a, b, c, d = [1.0, 0, 0], [0, 1.0, 0], [-1.0, 0, 0], [0, 0, 1.0]
    cases = [
        (cga.up([1, 2, 3]), "auto", "point", 0, 0.0),
        (cga.einf, "auto", "direction", 0, None),
        (cga.point_pair(a, c), "auto", "round", 0, 1.0),
        (cga.circle_from_points(a, b, c), "auto", "round", 1, 1.0),
        (cga.sphere_from_points(a, b, c, d), "auto", "round", 2, 1.0),
        (cga.sphere([1, 2, 3], 1.5), "auto", "round", 2, 2.25),
        (cga.sphere([1, 2, 3], 0.0), "auto", "point", 0, 0.0),
        (cga.standard_form(cga.circle_from_points(a, b, c)), "standard", "round", 1, 1.0),
        (cga.einf ^ cga.up(a), "auto", "flat", 0, None),
        (cga.line_from_points(a, b), "auto", "flat", 1, None),
        (cga.plane_from_points(a, b, d), "auto", "flat", 2, None),
        (cga.plane([0, 0, 1], 2.0), "auto", "flat", 2, None),
        (cga.up(a) ^ cga.e2, "auto", "tangent", 1, 0.0),
        (cga.einf ^ cga.e1 ^ cga.e2, "auto", "direction", 2, None),
        (cga.e1 ^ cga.e2, "dual", "dual flat", 1, None),
    ]
    for X, form, kind, dim, r2 in cases:
        k = classify(X, form=form)
        assert (k.kind, k.dimension) == (kind, dim), (X, k)
        assert (k.radius2 is None) == (r2 is None) and (r2 is None or math.isclose(k.radius2, r2, abs_tol=1e-12))
    assert classify(2.0).kind == "scalar" and classify(cga.Ic).kind == "pseudoscalar"
    assert classify(cga.Ic, form="standard").kind == "scalar"
    k = classify(cga.point_pair(a, c))
    assert k.name == "point pair" and not k.imaginary and k.grade == 2 and k.form == "dual"


def test_classify_small_rounds_and_the_tangent_tolerance():
    x = np.array([6.0, -3.0, 2.0])
    k = classify(cga.point_pair(x, x + [0, 0.01, 0]))
    assert k.kind == "round" and math.isclose(k.radius2, 0.005**2, rel_tol=1e-5)
    tiny = cga.point_pair([0.5, 0, 0], [0.5, 1e-6, 0])
    assert classify(tiny).kind == "tangent"  # |X X^| / |X|^2 ~ 1e-13, below the default tangent_tol
    k = classify(tiny, tangent_tol=1e-20)
    assert k.kind == "round" and math.isclose(k.radius2, 0.25e-12, rel_tol=1e-3)


# ------------------------------------------------------------------- errors
ALL_BINARY = [left_contraction, right_contraction, scalar_product, regressive_product, join, meet, project, reject]


@pytest.mark.parametrize("func", ALL_BINARY)
def test_bad_input_names_the_function_and_the_argument(func):
    name = func.__name__
    with pytest.raises(InvalidInputError, match=f"{name}: A: expected a Multivector"):
        func("e1", cga.e1)
    with pytest.raises(InvalidInputError, match=f"{name}: B: contains NaN or inf"):
        func(cga.e1, Multivector(G, {1: float("nan")}))  # e1 * nan: the product itself refuses NaN
    with pytest.raises(InvalidInputError, match=f"{name}: A: a batch"):
        func(cga.up(np.zeros((2, 3))), cga.e1)
    with pytest.raises(InvalidInputError, match=f"{name}: A: numeric coefficients only"):
        func(cga.e1 * sympy.Symbol("t"), cga.e1)
    with pytest.raises(InvalidInputError, match=f"{name}: B: a multivector of Algebra"):
        func(cga.e1, Algebra(3).basis_vectors()[0])


@pytest.mark.parametrize("func", [join, meet, project, reject])
def test_non_blades_and_zero_are_refused(func):
    name = func.__name__
    with pytest.raises(InvalidInputError, match=f"{name}: A: not a blade"):
        func(cga.e1 * cga.e2 + cga.e3 * cga.ep, cga.e1)
    with pytest.raises(InvalidInputError, match=f"{name}: B: not a blade \\(mixed grades"):
        func(cga.e1, 1 + cga.e1)
    with pytest.raises(DegenerateGeometryError, match=f"{name}: B: is zero"):
        func(cga.e1, cga.e1 - cga.e1)


def test_other_bad_input():
    with pytest.raises(InvalidInputError, match="dual: A: contains NaN"):
        dual(Multivector(G, {1: float("inf")}))
    with pytest.raises(InvalidInputError, match="undual: A: expected a Multivector"):
        undual(None)
    with pytest.raises(InvalidInputError, match="blade_factors: A: a scalar has no vector factors"):
        blade_factors(Multivector(G, {0: 2.0}))
    with pytest.raises(InvalidInputError, match="classify: form: form must be one of"):
        classify(cga.e1, form="opn")
    with pytest.raises(InvalidInputError, match="intersect: out: must be one of"):
        intersect(cga.e1, cga.e2, out="x")
    with pytest.raises(InvalidInputError, match="intersect: forms: expected a pair"):
        intersect(cga.e1, cga.e2, forms="dual")
    with pytest.raises(InvalidInputError, match="intersect: Y: not a blade"):
        intersect(cga.e1, cga.e1 * cga.e2 + cga.e3 * cga.ep)
    with pytest.raises(InvalidInputError, match="is_versor: V: expected a Multivector"):
        is_versor([1, 2])
    with pytest.raises(InvalidInputError, match="is_blade: A: expected a Multivector"):
        is_blade("A")
