"""Anchored entities (cga_lessons.conformal.anchored): rounds and lines that carry their local frame.

What is checked: which constructors anchor and which do not; that ``local`` is the entity translated by -anchor
(2.100), checked against the library's own translator near the origin; that every operation drops the frame and
gives the plain multivector's result bit for bit; that the dual forms, ``apply`` of a motor (2.102) and
``batch_item`` keep it; that an anchored entity cannot be changed in place.  Accuracy far from the origin against
exact truth is in ``test_entities_at_scale.py``; here the properties of moved entities are held to 1e-9 against
the exact image of the exact answer under the motor's own (R, t).
"""

import copy
from fractions import Fraction as Fr

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from test_entities_at_scale import EPS, REL, circumcircle, circumsphere, close_pos, fr, fsqrt, layout

from cga_lessons import conformal as cga
from cga_lessons.algebra import InvalidInputError, Multivector
from cga_lessons.conformal.anchored import Anchored, frame, plain

RNG = np.random.default_rng(16)
TETRA = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]) / np.sqrt(3)


def entities(pts):
    """Every anchored entity of the constructors, through the points ``pts`` (4 of them), by name."""
    a, b, c, d = pts
    return {
        "sphere": cga.sphere(a, 0.7),
        "sphere_from_points": cga.sphere_from_points(a, b, c, d),
        "circle_from_points": cga.circle_from_points(a, b, c),
        "point_pair": cga.point_pair(a, b),
        "line_from_points": cga.line_from_points(a, b),
        "point_pair_sphere": cga.point_pair_sphere(cga.point_pair(a, b)),
        "standard_form(circle)": cga.standard_form(cga.circle_from_points(a, b, c)),
        "standard_form(pair)": cga.standard_form(cga.point_pair(a, b)),
    }


NEAR = 3.0 + 0.9 * TETRA @ np.linalg.qr(RNG.normal(size=(3, 3)))[0]
FAR = 1e6 * np.array([0.6, -0.48, 0.64]) + 0.9 * TETRA @ np.linalg.qr(RNG.normal(size=(3, 3)))[0]


def same_bits(X: Multivector, Y: Multivector) -> bool:
    if set(X.coeffs) != set(Y.coeffs):
        return False
    return all(np.array_equal(np.asarray(X.coeffs[k]), np.asarray(Y.coeffs[k])) for k in X.coeffs)


# ------------------------------------------------------------- what is anchored
def test_the_rounds_and_lines_are_anchored_flats_points_and_sympy_are_not():
    for name, X in entities(FAR).items():
        assert type(X) is Anchored, name
        assert np.array_equal(X.anchor, X.anchor) and X.local.shape == X.shape, name
    a, b, c, _ = FAR
    assert type(cga.sphere_from_points(*FAR)) is Anchored  # the dual form keeps the frame
    for X in (cga.plane_from_points(a, b, c), cga.plane([0, 0, 1], 2.0), cga.up(a), cga.up(FAR)):
        assert type(X) is Multivector
    R = sp.Rational
    assert type(cga.point_pair([R(1), R(2), R(3)], [R(0), R(1), R(0)])) is Multivector
    assert type(cga.sphere([R(1), R(2), R(3)], R(2))) is Multivector


def test_the_anchor_is_the_data_point_nearest_the_origin():
    a, b, c, d = FAR
    near = FAR[np.argmin(np.sum(FAR * FAR, axis=1))]
    assert np.array_equal(cga.sphere_from_points(a, b, c, d).anchor, near)
    assert np.array_equal(cga.sphere(b, 2.0).anchor, b)  # a sphere from its centre: the centre
    assert np.array_equal(cga.point_pair(a, b).anchor, a if a @ a < b @ b else b)


@pytest.mark.parametrize("name", list(entities(NEAR)))
def test_local_is_the_entity_translated_by_minus_the_anchor_eq_2_100(name):
    """Near the origin the translator of the library (2.100) is exact enough to check ``local`` against."""
    X = entities(NEAR)[name]
    moved = cga.apply(cga.translator(-X.anchor), X.plain())
    scale = max(abs(v) for v in X.local.coeffs.values())
    assert moved.isclose(X.local, rtol=0.0, atol=1e-13 * scale), name


# --------------------------------------------------------- operations drop it
OPS = {
    "X * 2": lambda X, P: X * 2.0,
    "2 * X": lambda X, P: 2.0 * X,
    "X / 2": lambda X, P: X / 2.0,
    "-X": lambda X, P: -X,
    "X + P": lambda X, P: X + P,
    "X - P": lambda X, P: X - P,
    "X * P": lambda X, P: X * P,
    "X ^ einf": lambda X, P: X ^ cga.einf,
    "X | einf": lambda X, P: X | cga.einf,
    "einf << X": lambda X, P: cga.einf << X,
    "~X": lambda X, P: ~X,
    "reverse": lambda X, P: X.reverse(),
    "involute": lambda X, P: X.involute(),
    "conjugate": lambda X, P: X.conjugate(),
    "grade": lambda X, P: X.grade(*X.grades_present()),
    "even + odd": lambda X, P: X.even() + X.odd(),
    "dual": lambda X, P: X.dual(),
    "X ** 2": lambda X, P: X**2,
    "M >> X": lambda X, P: cga.motor([0, 0, 1], 0.3, [1, 2, 3]) >> X,
    "map": lambda X, P: X.map(lambda v: v),
    "reflect_in_plane": lambda X, P: cga.reflect_in_plane(cga.plane([0, 0, 1], 2.0), X),
    "invert_in_sphere": lambda X, P: cga.invert_in_sphere(cga.sphere([0, 0, 1], 2.0), X),
    "meet with a plane": lambda X, P: cga.meet(X, cga.dual_form(cga.plane([0, 0, 1], 3.0))),
}


@pytest.mark.parametrize("op", list(OPS))
def test_operations_drop_the_frame_and_give_the_plain_bits(op):
    for name, X in entities(NEAR).items():
        P = X.plain()
        assert type(P) is Multivector and same_bits(P, X)
        try:
            want = OPS[op](P, P)
        except (ValueError, ArithmeticError) as exc:  # the plain one refuses: so must the anchored one
            with pytest.raises(type(exc)):
                OPS[op](X, P)
            continue
        got = OPS[op](X, P)
        assert type(got) is Multivector, (op, name)
        assert same_bits(got, want), (op, name)


def test_a_batch_item_keeps_the_frame():
    base = 1e5 * RNG.normal(size=(5, 1, 3)) + RNG.normal(size=(5, 4, 3))
    a, b, c, d = (base[:, i] for i in range(4))
    for one, batch in (
        (lambda i: cga.sphere_from_points(a[i], b[i], c[i], d[i]), cga.sphere_from_points(a, b, c, d)),
        (lambda i: cga.circle_from_points(a[i], b[i], c[i]), cga.circle_from_points(a, b, c)),
        (lambda i: cga.point_pair(a[i], b[i]), cga.point_pair(a, b)),
        (lambda i: cga.sphere(a[i], 2.0), cga.sphere(a, 2.0)),
    ):
        assert type(batch) is Anchored and batch.anchor.shape == (5, 3)
        for i, item in enumerate(batch):
            X = one(i)
            assert type(item) is Anchored
            assert same_bits(item, X) and same_bits(item.local, X.local) and np.array_equal(item.anchor, X.anchor)
        assert type(batch.batch_item(slice(1, 3))) is Anchored


def test_one_centre_with_several_radii_shares_the_anchor():
    S = cga.sphere(FAR[0], [1.0, 2.0])
    assert S.anchor.shape == (2, 3) and np.array_equal(S.anchor[1], FAR[0])
    assert np.array_equal(cga.sphere_center_radius(S)[1], [1.0, 2.0])


# ------------------------------------------------------------ apply keeps it
MOTORS = st.builds(
    lambda axis, angle, t, e: cga.motor(axis, angle, np.array(t) / np.linalg.norm(t) * 10.0**e),
    st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.05),
    st.floats(-np.pi, np.pi),
    st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.05),
    st.floats(-2, 6),
)


def image_exact(M, p):
    """The exact image (Fractions) of an exact point under the motor's own (R, t)."""
    R, t = cga.G41.rigid_motion(M)
    return [sum(Fr(float(R[i, k])) * p[k] for k in range(3)) + Fr(float(t[i])) for i in range(3)]


def image(M, p):
    """The exact image of an exact point under the motor's own (R, t) (2.102), as floats."""
    R, t = cga.G41.rigid_motion(M)
    return np.array([float(sum(Fr(float(R[i, k])) * p[k] for k in range(3)) + Fr(float(t[i]))) for i in range(3)])


@settings(max_examples=30, deadline=None)
@given(MOTORS, st.integers(0, 2**32 - 1), st.floats(-1.0, 2.0), st.sampled_from([1.0, -3.0]))
def test_apply_of_a_motor_keeps_the_frame_eq_2_102(M, seed, log_size, scale):
    c, size, pts = layout(seed, 6.0, log_size)
    tc, tr2 = circumsphere(pts)
    cc, cr2, _ = circumcircle(pts[:3])
    V = scale * M  # a scaled motor is the same motion (V X V^-1)
    S, Z, PP = cga.sphere_from_points(*pts), cga.circle_from_points(*pts[:3]), cga.point_pair(*pts[:2])
    for X in (S, Z, PP, cga.line_from_points(*pts[:2])):
        Y = cga.apply(V, X)
        assert type(Y) is Anchored
        assert same_bits(Y, cga.apply(V, X.plain()))  # the global coefficients are those of the plain apply
        assert np.abs(Y.anchor - cga.apply_to_points(V, X.anchor)).max() <= 4 * EPS * np.abs(Y.anchor).max()
    far = np.linalg.norm(c) + np.linalg.norm(cga.G41.rigid_motion(M)[1])
    centre, radius = cga.sphere_center_radius(cga.apply(V, S))
    rho = fsqrt(tr2)
    assert close_pos(centre, image(M, tc), rho, far) and abs(radius - rho) <= REL * rho
    centre, radius, _ = cga.circle_center_radius(cga.apply(V, Z))
    rho = fsqrt(cr2)
    assert close_pos(centre, image(M, cc), rho, far) and abs(radius - rho) <= REL * rho
    p1, p2 = cga.point_pair_endpoints(cga.apply(V, PP))
    s = float(np.linalg.norm(pts[0] - pts[1]))
    assert close_pos(p1, image(M, fr(pts[0])), s, far) and close_pos(p2, image(M, fr(pts[1])), s, far)


def test_motions_wait_until_read_and_compose():
    """apply leaves the motion pending (moving an anchored batch costs what moving a plain one does); a chain of
    motors composes, and the dual forms carry the pending motion along."""
    Z = cga.circle_from_points(*FAR[:3])
    cc, cr2, _ = circumcircle(FAR[:3])
    f0 = frame(Z, settle=False)[0]
    Ms = [
        cga.motor([0.3, -0.2, 0.9], 0.7, [10.0, -20.0, 5.0]),
        cga.translator([1e5, 0, -3e5]),
        cga.rotor([1, 1, 0], 2.0),
    ]
    Y, want = Z, list(cc)
    for M in Ms:
        Y = cga.apply(M, Y)
        want = image_exact(M, want)
    assert frame(Y, settle=False)[0] is f0  # nothing computed yet
    S = cga.standard_form(Y)
    assert type(S) is Anchored and frame(S, settle=False)[0] is f0
    centre, radius, _ = cga.circle_center_radius(S)
    rho = fsqrt(cr2)
    assert abs(radius - rho) <= REL * rho
    assert close_pos(centre, np.array([float(v) for v in want]), rho, 2e6)


def test_a_local_blade_that_cannot_be_built_drops_the_frame():
    """Should the local blade not be storable (translated data that overflow where the data did not), the entity
    is read as a plain blade."""
    from cga_lessons.algebra import GeometryError
    from cga_lessons.conformal import entities_frame
    from cga_lessons.conformal.anchored import from_points

    def fails(*rel):
        raise GeometryError("overflows")

    X = from_points(entities_frame.point_pair, "point_pair", FAR[0], FAR[1], local=fails)
    assert type(X) is Anchored and frame(X, settle=False)[0] is not None
    f, L = frame(X)
    assert f is None and L is X
    assert X.anchor is None and X.local is None
    assert same_bits(cga.point_pair_sphere(X), cga.point_pair_sphere(X.plain()))  # read from the global blade


def test_apply_of_other_versors_drops_the_frame():
    X = cga.sphere_from_points(*FAR)
    for V in (cga.plane([0, 0, 1], 2.0), cga.sphere([0, 0, 0], 3.0), cga.dilator(2.0)):  # not motors
        assert type(cga.apply(V, X)) is Multivector


# ----------------------------------------------------------------- readers
def test_classify_reads_the_local_blade_far_out():
    Z = cga.circle_from_points(*FAR[:3])
    _, r2, _ = circumcircle(FAR[:3])
    k = cga.classify(Z)
    assert k.name == "circle" and abs(k.radius2 - float(r2)) <= REL * float(r2)
    kp = cga.classify(Z.plain())  # the plain blade, 1e6 out, reads as a tangent (radius2 0): the storage limit
    assert kp.name != "circle" or abs(kp.radius2 - float(r2)) > REL * float(r2)


def test_point_sphere_side_is_exact_to_a_tiny_fraction_of_the_radius_far_out():
    S = cga.sphere(FAR[0], 1.0)
    n = np.array([0.6, 0.0, 0.8])
    for k, side in ((1 - 1e-9, 1), (1 + 1e-9, -1)):
        assert cga.point_sphere_side(FAR[0] + k * n, S, atol=0.0) == side


# ---------------------------------------------------------- no change in place
def test_anchored_entities_cannot_be_changed_in_place():
    X = cga.point_pair(FAR[:2], FAR[2:])  # a batch
    with pytest.raises(InvalidInputError, match=r"^Anchored: coeffs: .*read-only"):
        X.coeffs[1] = np.zeros(2)
    for write in (lambda: X.coeffs.update({1: 0.0}), lambda: X.coeffs.pop(24), lambda: X.local.coeffs.clear()):
        with pytest.raises(InvalidInputError):
            write()
    with pytest.raises(ValueError, match="read-only"):
        X.coeffs[24][0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        X.anchor[0, 0] = 1.0
    with pytest.raises(AttributeError):
        X.anchor = np.zeros((2, 3))
    assert copy.copy(X) is X and copy.deepcopy(X) is X
    P = X.plain()
    P.coeffs[24][0] = 1.0  # a plain copy is writable, and a copy
    assert X.coeffs[24][0] != 1.0
    assert dict(X.coeffs).keys() == X.coeffs.keys()


def test_it_prints_and_compares_as_its_global_coefficients():
    for X in entities(FAR).values():
        P = X.plain()
        assert repr(X) == repr(P) and X == P and P == X and not (X != P)
        assert X != 2.0 * P


def test_the_class_refuses_an_inconsistent_frame():
    S = cga.sphere(FAR[0], 1.0)
    assert type(Anchored(cga.G41, {1: 1.0})) is Multivector  # without a frame: what the operations build
    with pytest.raises(InvalidInputError, match=r"^Anchored: anchor, local: "):
        Anchored(cga.G41, dict(S.coeffs), anchor=[0.0, 0.0], local=S.local)
    with pytest.raises(InvalidInputError, match=r"^Anchored: local: grades \[2\]"):
        Anchored(cga.G41, dict(S.coeffs), anchor=S.anchor, local=cga.e1 * cga.e2)
    with pytest.raises(InvalidInputError, match=r"^Anchored: local: expected a Multivector"):
        Anchored(cga.G41, dict(S.coeffs), anchor=S.anchor, local=None)
    with pytest.raises(InvalidInputError, match=r"^Anchored: anchor, local: "):
        Anchored(cga.G41, dict(S.coeffs), anchor=[np.nan, 0.0, 0.0], local=S.local)
    P = S.plain()
    assert frame(S)[0] is S.anchor and frame(S)[1] is S.local
    assert frame(P)[0] is None and frame(P)[1] is P
    assert plain(P) is P and type(plain(S)) is Multivector and same_bits(plain(S), S)


def test_the_short_local_forms_are_the_closed_forms_eq_2_68_2_72():
    """The local blades of spheres and pairs are written directly; they are the closed forms of entities_frame
    (a sphere's bit for bit, a pair's but for the rounding of a - b onto its grid, which the direct form skips)."""
    from cga_lessons.conformal import entities_frame as F
    from cga_lessons.conformal.anchored import pair_about_an_end, sphere_local

    c, r2 = RNG.normal(size=(6, 3)) * 10.0 ** RNG.uniform(-2, 3, size=(6, 1)), RNG.uniform(0, 9, size=6)
    assert same_bits(sphere_local(c, r2), F.sphere_std(c, F.dot(c, c) - r2, 1.0, "sphere", "center, radius"))
    for i in range(6):
        assert same_bits(sphere_local(c[i], r2[i]), F.sphere_std(c[i], c[i] @ c[i] - r2[i], 1.0, "s", "c, r"))
    y, z = c, np.zeros((6, 3))
    a, b = np.where(np.arange(6)[:, None] % 2 == 0, y, z), np.where(np.arange(6)[:, None] % 2 == 0, z, y)
    P, Q = pair_about_an_end(a, b), F.point_pair(a, b, "point_pair")
    assert set(P.coeffs) == set(Q.coeffs)
    assert all(np.allclose(P.coeffs[k], Q.coeffs[k], rtol=4 * EPS, atol=0) for k in P.coeffs)
