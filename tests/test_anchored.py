"""Anchored entities (cga_lessons.conformal.anchored, anchored_ops): rounds and lines that carry their local frame.

What is checked: which constructors anchor and which do not; that ``local`` is the entity translated by -anchor
(2.100), checked against the library's own translator near the origin; that every translation-covariant operation
(products, sums, scaling, the involutions, inverse, dual, the blades functions, join, meet, intersect) with
anchored operands or invariant ones (numbers, e ^ A, Ic: each claim checked against the sandwich) keeps it, its
local blade the same operation on the local blades (the second moved into the first one's frame) and its global
coefficients the plain operation's, bit for bit, a plain conformal point counting as anchored at itself
(``point_wedges``); that an operation with anything else drops it and gives the plain bits; that the dual forms,
``apply`` of a motor (2.102) and ``batch_item`` keep it; that an anchored entity cannot be changed in place.
Accuracy far from the origin against exact truth is in ``test_entities_at_scale.py``; here the properties of moved
entities (and of the circle where a moved sphere meets another) are held to 1e-9 against the exact image of the
exact answer under the motor's own (R, t).
"""

import copy
from fractions import Fraction as Fr

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from test_entities_at_scale import (
    EPS,
    REL,
    circle_of,
    circumcircle,
    circumsphere,
    close_pos,
    cross,
    fr,
    fsqrt,
    layout,
    one_blade,
    sub,
    unit,
)

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


# ------------------------------------------- operations: the frame follows the covariant ones
T = cga.translator([0.3, -1.2, 2.5])  # invariant: translations commute
KEEP = {  # f(X, Y, P, Q): X, Y anchored (anchors f != g), P, Q their plain copies
    "X * 2": lambda X, Y: X * 2.0,
    "2 * X": lambda X, Y: 2.0 * X,
    "X * int": lambda X, Y: X * 3,
    "X / 2": lambda X, Y: X / 2.0,
    "-X": lambda X, Y: -X,
    "X + 1": lambda X, Y: X + 1.0,
    "2 - X": lambda X, Y: 2.0 - X,
    "1 / X": lambda X, Y: 1.0 / X,
    "X + Y": lambda X, Y: X + Y,
    "X - Y": lambda X, Y: X - Y,
    "X * Y": lambda X, Y: X * Y,
    "Y * X": lambda X, Y: Y * X,
    "X ^ Y": lambda X, Y: X ^ Y,
    "X | Y": lambda X, Y: X | Y,
    "X << Y": lambda X, Y: X << Y,
    "X / Y": lambda X, Y: X / Y,
    "X >> Y": lambda X, Y: X >> Y,
    "X.inner(Y)": lambda X, Y: X.inner(Y),
    "X.left_contraction(Y)": lambda X, Y: X.left_contraction(Y),
    "X ^ einf": lambda X, Y: X ^ cga.einf,
    "einf ^ X": lambda X, Y: cga.einf ^ X,
    "X | einf": lambda X, Y: X | cga.einf,
    "einf << X": lambda X, Y: cga.einf << X,
    "X * Ic": lambda X, Y: X * cga.Ic,
    "Ic * X": lambda X, Y: cga.Ic * X,
    "X * (e ^ e1)": lambda X, Y: X * (cga.einf ^ cga.e1),
    "T * X": lambda X, Y: T * X,
    "T >> X": lambda X, Y: T >> X,
    "X >> T": lambda X, Y: X >> T,
    "~X": lambda X, Y: ~X,
    "reverse": lambda X, Y: X.reverse(),
    "involute": lambda X, Y: X.involute(),
    "conjugate": lambda X, Y: X.conjugate(),
    "grade": lambda X, Y: X.grade(*X.grades_present()),
    "even + odd": lambda X, Y: X.even() + X.odd(),
    "dual": lambda X, Y: X.dual(),
    "undual": lambda X, Y: X.undual(),
    "X ** 2": lambda X, Y: X**2,
    "X ** -1": lambda X, Y: X**-1,
    "inv": lambda X, Y: X.inv(),
    "normalized": lambda X, Y: X.normalized(),
    "left_contraction(X, Y)": lambda X, Y: cga.left_contraction(X, Y),
    "right_contraction(X, Y)": lambda X, Y: cga.right_contraction(X, Y),
    "blades.dual": lambda X, Y: cga.blades.dual(X),
    "blades.undual": lambda X, Y: cga.blades.undual(X),
    "regressive_product": lambda X, Y: cga.regressive_product(X, Y),
    "join": lambda X, Y: cga.join(X, Y),
    "meet": lambda X, Y: cga.meet(X, Y),
    "project": lambda X, Y: cga.project(X, Y),
    "reject": lambda X, Y: cga.reject(X, Y),
    "intersect": lambda X, Y: cga.intersect(X, Y),
    "standard_form": lambda X, Y: cga.standard_form(X),
    # a plain conformal point is anchored at itself (w up(x) = T_x (w e0) ~T_x, point_wedges): the frame follows
    "X * eo": lambda X, Y: X * cga.eo,
    "X ^ eo": lambda X, Y: X ^ cga.eo,
    "eo | X": lambda X, Y: cga.eo | X,
    "X + up(p)": lambda X, Y: X + cga.up([1.0, 2.0, 3.0]),
    "up(p) ^ X": lambda X, Y: cga.up([1.0, 2.0, 3.0]) ^ X,
    "X ^ apply(M, up(p))": lambda X, Y: X ^ cga.apply(cga.motor([0, 0, 1], 0.3, [1, 2, 3]), cga.up([1.0, 2.0, 3.0])),
    "X * (e + 1e-10 eo)": lambda X, Y: X * (cga.einf + 1e-10 * cga.eo),  # an (imaginary) sphere: anchored too
}
DROP = {  # a multivector that translations change (and not a point), or an operation that is not covariant
    "X * e1": lambda X, Y: X * cga.e1,
    "e1 * X": lambda X, Y: cga.e1 * X,
    "X * Q (plain)": lambda X, Y: X * plain(Y),
    "Q * X (plain)": lambda X, Y: plain(Y) * X,
    "X ^ (plain sphere)": lambda X, Y: X ^ plain(cga.sphere([1.0, 2.0, 3.0], 0.5)),  # not null: no point
    "X ^ (plain e + 1e-10 eo)": lambda X, Y: X ^ Multivector(cga.G41, {8: 1.0 - 0.5e-10, 16: 1.0 + 0.5e-10}),
    "X ^ (up(p) / 3, 1e7 out)": lambda X, Y: X ^ (cga.up([1e7, 2.0, 3.0]) / 3.0),  # its weight is not resolved
    "X * E": lambda X, Y: X * cga.E,
    "X * rotor": lambda X, Y: X * cga.rotor([0, 0, 1], 0.3),
    "M >> X": lambda X, Y: cga.motor([0, 0, 1], 0.3, [1, 2, 3]) >> X,
    "map": lambda X, Y: X.map(lambda v: v),
    "simplify": lambda X, Y: X.simplify(),
    "apply an inversion times a reflection": lambda X, Y: cga.apply(
        cga.sphere([0.5, 0, 1], 2.0) * cga.plane([0, 0, 1], 3.0), X
    ),  # even and moves e: no similarity, no inversion times a motor
    "meet with a plane": lambda X, Y: cga.meet(X, cga.dual_form(cga.plane([0, 0, 1], 3.0))),
}
OTHER = cga.sphere(NEAR[1] + [0.3, -0.2, 0.1], 0.8)  # a second entity, its anchor not X's


def outcomes(op, X, Y):
    """``(got, want)``: the operation on the anchored entities and on their plain copies; None when both refuse
    (with the same error)."""
    P, Q = X.plain(), Y.plain()
    try:
        want = op(P, Q)
    except (ValueError, ArithmeticError) as exc:
        with pytest.raises(type(exc)):
            op(X, Y)
        return None
    return op(X, Y), want


def size(X: Multivector) -> float:
    return max((float(np.max(np.abs(v))) for v in X.coeffs.values()), default=0.0)


def about_anchor(Z: Anchored) -> Multivector:
    """The global blade translated by -anchor with the library's translator (2.100): exact enough near the origin
    to check the local blade against (as ``test_local_is_the_entity_translated_by_minus_the_anchor``)."""
    return cga.apply(cga.translator(-Z.anchor), Z.plain())


@pytest.mark.parametrize("op", list(KEEP))
def test_covariant_operations_keep_the_frame_and_give_the_plain_bits(op):
    """Every covariant operation of anchored entities (or of one and a number or an invariant multivector) gives
    the plain operation's global coefficients bit for bit, anchored: its local blade is the result about the
    anchor (2.100), the anchor that of its first anchored operand."""
    kept = 0
    for name, X in entities(NEAR).items():
        for Y in (OTHER, X):
            if Y is X and op in ("meet", "join", "project", "reject", "intersect"):
                continue
            got = outcomes(KEEP[op], X, Y)
            if got is None:
                continue
            got, want = got
            assert same_bits(got, want), (op, name)
            if not want.coeffs:  # zero (X ^ X): plain
                assert type(got) is Multivector
                continue
            if size(want) <= 1e-12 * size(plain(X)) * size(plain(Y)):  # zero but for round-off (X ^ X of a pair)
                continue
            assert type(got) is Anchored, (op, name)
            f, L = frame(got)
            if f is None:  # the local blade could not be built (e.g. no inverse about the anchor): read as plain
                continue
            kept += 1
            first = Y if op in ("Y * X",) else X
            assert np.array_equal(f, first.anchor), (op, name)
            scale = max(size(L), size(want))  # near the origin: the round-off of the global coefficients
            assert about_anchor(got).isclose(L, rtol=0.0, atol=1e-11 * scale), (op, name)
    assert kept > 0, op


@pytest.mark.parametrize("op", list(DROP))
def test_other_operations_drop_the_frame_and_give_the_plain_bits(op):
    for name, X in entities(NEAR).items():
        got = outcomes(DROP[op], X, OTHER)
        if got is None:
            continue
        got, want = got
        assert type(got) is Multivector, (op, name)
        assert same_bits(got, want), (op, name)


def test_the_local_blade_is_the_operation_on_the_local_blades_eq_2_100():
    """``(X o Y).local = X.local o (T_{g-f} Y.local ~T_{g-f})`` about X's anchor f (g: Y's), the definition."""
    from cga_lessons.conformal.anchored_ops import translated

    X, Y = cga.sphere_from_points(*FAR), cga.sphere(FAR[0] + [0.5, 0.25, -0.125], 0.75)
    Xs = cga.standard_form(X)
    for Z, want in (
        (Xs ^ Y, Xs.local ^ translated(Y.local, Y.anchor - Xs.anchor)),
        (Y ^ Xs, Y.local ^ translated(Xs.local, Xs.anchor - Y.anchor)),
        (2.0 * Y - Xs, 2.0 * Y.local - translated(Xs.local, Xs.anchor - Y.anchor)),
    ):
        assert same_bits(Z.local, want)
    assert np.array_equal((Xs ^ Y).anchor, Xs.anchor) and np.array_equal((Y ^ Xs).anchor, Y.anchor)


def test_which_multivectors_are_translation_invariant():
    """K is invariant (T K ~T = K for every translator, 2.100) exactly when it commutes with e e1, e e2, e e3: the
    scalars, e ^ A for Euclidean A, and Ic.  Each claim checked against the sandwich with a few translators."""
    from cga_lessons.conformal.anchored_ops import invariant

    Ts = [cga.translator(t) for t in ([1.0, 0, 0], [0, -2.0, 0], [0, 0, 0.5], [0.3, 0.7, -1.1])]

    def moved_by_some(K):
        return any(not (V * K * ~V).isclose(K, rtol=0.0, atol=1e-12) for V in Ts)

    yes = [cga.einf, 2.5 * cga.einf, cga.Ic, cga.einf ^ cga.e1, cga.einf ^ cga.e1 ^ cga.e3, cga.einf ^ cga.IE, T,
           3.0 + cga.einf, cga.G41.scalar(2.0), cga.einf * cga.e2 - 4.0 * cga.Ic]  # fmt: skip
    no = [cga.eo, cga.e1, cga.ep, cga.em, cga.E, cga.IE, cga.up([1.0, 2.0, 3.0]), cga.rotor([0, 0, 1], 0.3),
          cga.motor([1, 0, 0], 0.2, [1, 2, 3]), cga.einf + 1e-10 * cga.eo, cga.E * cga.e1,
          cga.einf ^ cga.eo]  # fmt: skip
    for K in yes:
        assert invariant(K) and not moved_by_some(K), K
    for K in no:
        assert not invariant(K), K
        assert moved_by_some(K), K
    batch = {1: np.zeros(2), 8: np.array([1.0, 2.0]), 16: np.array([1.0, 2.0])}  # e, 2 e (zeros are no part)
    assert invariant(Multivector(cga.G41, batch)) and not invariant(Multivector(cga.G41, {**batch, 1: np.ones(2)}))


def test_a_long_chain_of_results_is_built_when_read_without_deep_recursion():
    """A sum of 500 anchored spheres, none of the partial sums read: their local blades are built when the last
    is read, never more than MAX_DEPTH levels deep (the operands of a deeper result are built at once)."""
    from cga_lessons.conformal.anchored_ops import MAX_DEPTH

    centres = FAR[0] + 1e-3 * np.random.default_rng(1).normal(size=(500, 3))
    spheres = [cga.sphere(p, 1.0) for p in centres]
    total, plain_total = spheres[0], spheres[0].plain()
    for S in spheres[1:]:
        total, plain_total = total + S, plain_total + S.plain()
    assert frame(total, settle=False)[1].depth <= MAX_DEPTH
    assert same_bits(total, plain_total)
    centre, _ = cga.sphere_center_radius(total)  # a sphere of the pencil, of weight 500: centred at the mean
    assert np.linalg.norm(centre - np.mean(centres, axis=0)) <= 1e-9 * 1e-3 + 8 * EPS * np.linalg.norm(FAR[0])


def test_an_operand_whose_frame_is_dropped_drops_the_results_frame():
    from cga_lessons.algebra import GeometryError
    from cga_lessons.conformal import entities_frame
    from cga_lessons.conformal.anchored import from_points

    def fails(*rel):
        raise GeometryError("overflows")

    X = from_points(entities_frame.point_pair, "point_pair", FAR[0], FAR[1], local=fails)
    Y = X * 2.0 + cga.point_pair(FAR[1], FAR[2])
    assert type(Y) is Anchored and frame(Y) == (None, Y)
    assert same_bits(Y, X.plain() * 2.0 + cga.point_pair(FAR[1], FAR[2]).plain())


def test_a_batch_keeps_the_frame_through_operations():
    """A batch of anchored spheres (one anchor each) with one sphere: each item is what the single entities give."""
    rng = np.random.default_rng(2)
    base = 1e5 * rng.normal(size=(5, 1, 3)) + rng.normal(size=(5, 4, 3))
    S = cga.sphere(base[:, 0], 1.5)
    s1 = cga.sphere(base[0, 1], 2.0)
    Z, Zd = S ^ s1, 3.0 * cga.dual_form(S) - cga.dual_form(cga.sphere(base[:, 2], 1.0))
    assert type(Z) is Anchored and Z.anchor.shape == (5, 3) and Z.local.shape == (5,)
    for i in range(5):
        one = cga.sphere(base[i, 0], 1.5) ^ s1
        assert same_bits(Z.batch_item(i), one) and Z.batch_item(i).local.isclose(one.local, rtol=1e-13, atol=1e-13)
        two = 3.0 * cga.dual_form(cga.sphere(base[i, 0], 1.5)) - cga.dual_form(cga.sphere(base[i, 2], 1.0))
        assert same_bits(Zd.batch_item(i), two)
        assert Zd.batch_item(i).local.isclose(two.local, rtol=1e-13, atol=1e-13)
    s2 = cga.sphere(base[1, 1], 2.0) ^ S  # a single anchor first: the result's anchor broadcast to the batch
    assert np.array_equal(s2.anchor, np.broadcast_to(base[1, 1], (5, 3)))


def test_join_and_meet_in_part_overlapping_spans_match_the_global_weight():
    """Two coplanar lines 1e6 out: their join is their plane (a partial overlap: the join weights it with a
    Euclidean-orthonormal basis of the coefficient space, which depends on the frame) and their meet a flat point.
    The local blades are scaled to be the global ones (one blade, one orientation); the plane reads exactly."""
    from cga_lessons.conformal.anchored_ops import translated

    a, b, c = FAR[0], FAR[1], FAR[2]
    J, M = cga.join(cga.line_from_points(a, b), cga.line_from_points(a, c)), cga.meet(
        cga.line_from_points(a, b), cga.line_from_points(a, c)
    )
    assert J.grades_present() == [4] and M.grades_present() == [2]
    for X in (J, M):
        f, L = frame(X)
        assert f is not None
        W, G = translated(L, f).to_array(), X.plain().to_array()
        assert np.linalg.norm(W - G) <= 1e-9 * np.linalg.norm(G)  # flats 1e6 out: stored to round-off
    assert cga.classify(M).name == "flat point"
    n, d = cga.plane_normal_distance(J)
    A = fr(a)
    nv = cross(sub(fr(b), A), sub(fr(c), A))
    u = unit(nv)
    sign = 1.0 if n @ u > 0 else -1.0
    assert np.linalg.norm(n - sign * u) <= REL
    d_true = float(np.dot(u, a))  # n . a, exact to rounding: |a| eps
    assert abs(d - sign * d_true) <= REL * np.linalg.norm(b - a) + 8 * EPS * np.linalg.norm(a)


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


@settings(max_examples=30, deadline=None)
@given(MOTORS, st.integers(0, 2**32 - 1), st.floats(-1.0, 6.0), st.floats(-1.0, 2.0))
def test_a_moved_sphere_meets_another_in_the_exact_circle(M, seed, log_off, log_size):
    """A sphere through four points (offsets up to 1e6, sizes 0.1-100), moved by a motor (2.102), met with a sphere
    near it: the circle (centre, radius, normal) against the exact circle of the exact image (2.79).  The moved
    anchor is rounded to its coordinates (``R f + t``, a few ulp of ``far``), an error of the moved sphere's position
    that reaches the circle through the distance D of the centres: its radius by ``|a (D - a)| / (rho D)`` times
    it (a the distance from the first centre to the circle's plane), its normal by ``1 / D``."""
    c, size, pts = layout(seed, log_off, log_size)
    tc, tr2 = circumsphere(pts)
    S = cga.apply(M, cga.sphere_from_points(*pts))
    mc = image_exact(M, tc)
    rng = np.random.default_rng(seed + 3)
    u = rng.normal(size=3)
    c3 = np.array([float(v) for v in mc]) + size * rng.uniform(0.5, 1.2) * u / np.linalg.norm(u)
    r3 = size * rng.uniform(0.8, 1.2)
    pc, rho2, d, k = circle_of(mc, tr2, fr(c3), Fr(r3) ** 2)
    assume(rho2 > 0)
    rho, D = fsqrt(rho2), float(np.sqrt(float(sum(x * x for x in d))))
    a = float(k) * D
    far = np.linalg.norm(c) + np.linalg.norm(cga.G41.rigid_motion(M)[1])
    ulps = 16 * EPS * far  # the moved anchor's rounding
    for Z in (cga.standard_form(S) ^ cga.sphere(c3, r3), cga.intersect(S, cga.sphere(c3, r3), tol=1e-15)):
        centre, radius, normal = cga.circle_center_radius(Z)
        assert np.linalg.norm(centre - np.array([float(v) for v in pc])) <= REL * rho + 2 * ulps
        assert abs(radius - rho) <= REL * rho + ulps * abs(a * (D - a)) / (rho * D)
        n = unit(d)
        assert min(np.linalg.norm(normal - n), np.linalg.norm(normal + n)) <= REL + ulps / D
        assert one_blade(Z)


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
    """A versor without a frame of its own that no closed form reads (an inversion times a reflection: a plane
    carries no frame, so the product is plain) drops it; two inversions in anchored spheres keep it (applied in
    the versor's frame), as do dilations, similarities and an inversion times a motor (test_anchored_versors.py)."""
    X = cga.sphere_from_points(*FAR)
    assert type(cga.apply(cga.sphere([0, 0, 0], 3.0) * cga.plane([0, 0, 1], 3.0), X)) is Multivector
    Y = cga.apply(cga.sphere([0, 0, 0], 3.0) * cga.sphere([1, 0, 0], 2.0), X)
    assert type(Y) is Anchored and frame(Y)[0] is not None


def mirrors():
    """Reflections (a plane and its dual form, a plane times a motor) and inversions (a sphere, its dual form, an
    imaginary sphere) near NEAR, by name."""
    S = cga.sphere(NEAR[0] + [1.5, -0.5, 0.4], 1.3)
    P = cga.plane_from_points(NEAR[0] + [1, 0, 0], NEAR[0] + [0, 1.2, 0.3], NEAR[0] + [0.2, 0.1, 1])
    return {
        "plane": cga.standard_form(P),
        "dual plane": P,
        "reflect_in_plane": P,
        "motor * plane": cga.motor([0.3, 1, -0.2], 0.8, [1.0, -2.0, 0.5]) * cga.standard_form(P),
        "sphere": S,
        "dual sphere": cga.dual_form(S),
        "invert_in_sphere": S,
        "plain sphere": S.plain(),
        "imaginary sphere": cga.up(NEAR[0] + [1.5, -0.5, 0.4]) + 0.8 * cga.einf,
    }


@pytest.mark.parametrize("name", list(mirrors()))
def test_reflections_and_inversions_keep_the_frame_and_give_the_plain_bits(name):
    """apply of a reflection in a plane (2.89-2.91, also a plane's dual form and its product with a motor) or of an
    inversion in a sphere (2.84-2.88) keeps the frame of every anchored entity: the global coefficients are the
    plain ones, bit for bit; the anchor is the image of X's anchor, the local blade the result about it (2.100), and
    a dual form or a motion that follows keeps it too (a pending reflection involutes the local blade)."""
    V = mirrors()[name]
    act = {"reflect_in_plane": cga.reflect_in_plane, "invert_in_sphere": cga.invert_in_sphere}.get(name, cga.apply)
    M = cga.motor([1, 0, 0], 0.4, [0.5, 0.2, -1.0])
    for xname, X in entities(NEAR).items():
        Y = act(V, X)
        assert type(Y) is Anchored, (name, xname)
        assert same_bits(Y, act(V, X.plain())), (name, xname)
        assert np.allclose(Y.anchor, cga.apply_to_points(V, X.anchor), rtol=0, atol=1e-11), (name, xname)
        for Z in (Y, cga.dual_form(Y), cga.apply(M, Y), cga.apply(V, cga.apply(M, X))):
            assert type(Z) is Anchored, (name, xname)
            scale = max(size(Z.local), size(plain(Z)))
            assert about_anchor(Z).isclose(Z.local, rtol=0.0, atol=1e-11 * scale), (name, xname)
    Xs = cga.sphere(NEAR[:, :], [0.3, 0.4, 0.5, 0.6])  # a batch keeps it, element by element
    Y = act(V, Xs)
    for i in range(4):
        Yi = act(V, Xs.batch_item(i))
        assert Y.batch_item(i).isclose(Yi) and Y.local.batch_item(i).isclose(Yi.local, atol=1e-13)
        assert np.allclose(Y.anchor[i], Yi.anchor, rtol=0, atol=1e-13)


def test_an_inversion_of_an_anchor_at_its_centre_drops_the_frame():
    X = cga.point_pair(NEAR[0], NEAR[1])
    Y = cga.invert_in_sphere(cga.sphere(NEAR[1], 2.0), X)  # the anchor (NEAR[1], nearest the origin) goes to e
    if np.linalg.norm(NEAR[1]) < np.linalg.norm(NEAR[0]):
        assert type(Y) is Anchored and Y.anchor is None and Y.local is None


def reflect_exact(P, x):
    """The exact mirror image (Fractions) of an exact point in the plane P = n + delta e as stored (2.89)."""
    c = cga.standard_form(P).coeffs
    n = [Fr(float(c.get(b, 0.0))) for b in (1, 2, 4)]
    delta = (Fr(float(c.get(8, 0.0))) + Fr(float(c.get(16, 0.0)))) / 2
    k = 2 * (sum(a * b for a, b in zip(n, x)) - delta) / sum(a * a for a in n)
    return [a - k * b for a, b in zip(x, n)]


def invert_exact(p, r2, x):
    """The exact image (Fractions) of an exact point under the inversion in the sphere (p, r2) (2.88)."""
    d = [a - b for a, b in zip(x, p)]
    k = r2 / sum(a * a for a in d)
    return [b + k * a for a, b in zip(d, p)]


def floats(v):
    return np.array([float(x) for x in v])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(-1.0, 6.0), st.floats(-1.0, 2.0), st.booleans())
def test_a_reflection_in_a_plane_is_exact_far_out(seed, log_off, log_size, dual):
    """A sphere, circle and point pair through points 0.1 to 1e6 out (sizes 0.1-100) reflected in a plane near them
    (2.89-2.91; standard or dual form): centre, radius and ends within 1e-9 of the exact mirror images (Fractions)
    of the exact entity (its points reflected exactly in the plane as stored), where the plain result is garbage
    far out; the global coefficients are the plain ones."""
    c, size, pts = layout(seed, log_off, log_size)
    rng = np.random.default_rng(seed + 5)
    a, b, d = (c + size * rng.uniform(-2, 2, size=3) for _ in range(3))
    P = cga.plane_from_points(a, b, d)
    V = P if dual else cga.standard_form(P)
    far = 4 * (np.linalg.norm(c) + size)
    tc, tr2 = circumsphere(pts)
    cc, cr2, _ = circumcircle(pts[:3])
    S, Z, PP = cga.sphere_from_points(*pts), cga.circle_from_points(*pts[:3]), cga.point_pair(*pts[:2])
    for X in (S, Z, PP):
        assert same_bits(cga.apply(V, X), cga.apply(V, X.plain()))
    centre, radius = cga.sphere_center_radius(cga.reflect_in_plane(V, S))
    rho = fsqrt(tr2)
    assert close_pos(centre, floats(reflect_exact(P, tc)), rho, far) and abs(radius - rho) <= REL * rho
    centre, radius, _ = cga.circle_center_radius(cga.apply(V, Z))
    rho = fsqrt(cr2)
    assert close_pos(centre, floats(reflect_exact(P, cc)), rho, far) and abs(radius - rho) <= REL * rho
    ends = cga.point_pair_endpoints(cga.apply(V, PP))
    want = [floats(reflect_exact(P, fr(x))) for x in pts[:2]]
    s = float(np.linalg.norm(pts[0] - pts[1]))
    if not close_pos(ends[0], want[0], s, far):
        ends = ends[::-1]
    assert close_pos(ends[0], want[0], s, far) and close_pos(ends[1], want[1], s, far)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(-1.0, 6.0), st.floats(-1.0, 2.0))
def test_an_inversion_in_a_sphere_is_exact_far_out(seed, log_off, log_size):
    """A sphere and a point pair 0.1 to 1e6 out (sizes 0.1-100) inverted in an anchored sphere near them (2.84-2.88):
    centre, radius and ends within 1e-9 of the exact images (Fractions) of the exact entities under the exact
    inversion (the sphere's own centre and squared radius).  Far out the tables' ``s ~s`` is round-off: apply
    takes the factors (anchored_versors.far_product) and never refuses; the global coefficients are the plain
    entity's result under the same sphere, bit for bit."""
    c, size, pts = layout(seed, log_off, log_size)
    rng = np.random.default_rng(seed + 7)
    u = rng.normal(size=3)
    p = c + size * rng.uniform(2.5, 4.0) * u / np.linalg.norm(u)
    r = size * rng.uniform(0.5, 2.0)
    V = cga.sphere(p, r)
    S, PP = cga.sphere_from_points(*pts), cga.point_pair(*pts[:2])
    for X in (S, PP):
        assert same_bits(cga.apply(V, X), cga.apply(V, X.plain()))
    fp, r2 = fr(p), Fr(r * r)
    far = 4 * (np.linalg.norm(c) + size)
    tc, tr2 = circumsphere(pts)
    dd = [a - b for a, b in zip(tc, fp)]
    k = sum(x * x for x in dd) - tr2
    centre, radius = cga.sphere_center_radius(cga.invert_in_sphere(V, S))
    rho = abs(r2 * fsqrt(tr2) / float(k))
    assert close_pos(centre, floats([b + r2 * a / k for a, b in zip(dd, fp)]), rho, far)
    assert abs(radius - rho) <= REL * rho
    ends = cga.point_pair_endpoints(cga.apply(V, PP))
    want = [floats(invert_exact(fp, r2, fr(x))) for x in pts[:2]]
    s = float(np.linalg.norm(want[0] - want[1]))
    if not close_pos(ends[0], want[0], s, far):
        ends = ends[::-1]
    assert close_pos(ends[0], want[0], s, far) and close_pos(ends[1], want[1], s, far)


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
    """A sphere's local blade is the closed form of entities_frame about its anchor, bit for bit; a pair's is
    written directly, the closed form but for the rounding of a - b onto its grid, which the direct form skips."""
    from cga_lessons.conformal import entities_frame as F
    from cga_lessons.conformal.anchored import pair_about_an_end, sphere_at

    c, r2 = RNG.normal(size=(6, 3)) * 10.0 ** RNG.uniform(-2, 3, size=(6, 1)), RNG.uniform(0, 9, size=6)
    f = np.array([3e5, -1e5, 2e5])
    local = sphere_at(f, c, r2, "sphere", "center, radius").local
    assert same_bits(local, F.sphere_std(c, F.dot(c, c) - r2, 1.0, "sphere", "center, radius"))
    for i in range(6):
        local = sphere_at(f, c[i], r2[i], "s", "c, r").local
        assert same_bits(local, F.sphere_std(c[i], c[i] @ c[i] - r2[i], 1.0, "s", "c, r"))
    y, z = c, np.zeros((6, 3))
    a, b = np.where(np.arange(6)[:, None] % 2 == 0, y, z), np.where(np.arange(6)[:, None] % 2 == 0, z, y)
    P, Q = pair_about_an_end(a, b), F.point_pair(a, b, "point_pair")
    assert set(P.coeffs) == set(Q.coeffs)
    assert all(np.allclose(P.coeffs[k], Q.coeffs[k], rtol=4 * EPS, atol=0) for k in P.coeffs)


def test_constructors_without_the_frame_give_the_plain_blade():
    """``frame=False``: the same coefficients, bit for bit, as a plain multivector (what a builder working near the
    origin uses); anything but a bool refused."""
    a, b = np.array([1e5, -2e5, 3.0]), np.array([1e5 + 0.4, -2e5 - 0.1, 2.5])
    for framed, plain_one in ((cga.point_pair(a, b), cga.point_pair(a, b, frame=False)),
                              (cga.sphere(a, 0.7), cga.sphere(a, 0.7, frame=False))):  # fmt: skip
        assert type(framed).__name__ == "Anchored" and type(plain_one) is Multivector
        assert dict(framed.coeffs) == dict(plain_one.coeffs)
    with pytest.raises(InvalidInputError, match="point_pair: frame"):
        cga.point_pair(a, b, frame="no")
    with pytest.raises(InvalidInputError, match="sphere: frame"):
        cga.sphere(a, 0.7, frame=None)
