"""Raw wedges of plain conformal points (cga_lessons.conformal.point_wedges): ``up(a) ^ up(b) ^ up(c) ^ up(d)``, the
thesis's sphere (table 2.1, 2.75), and the other entities written with ``^``, ``+`` and ``-`` of plain points, carry
the points' local frame and are exact at any distance from the origin.

Truth: as in ``test_entities_at_scale.py``, the property from elementary geometry in exact rationals
(fractions.Fraction) on the very floats handed to ``up``, square roots in mpmath; shapes of size 0.1-100 up to 1e6
from the origin; every property to 1e-9 relative (positions besides to a few ulp of the coordinates).  Also: the
global coefficients are the plain operators' (without the hook) bit for bit; which vectors are read as points (the
routes a point takes, and spheres that must not be); the frame through anchored entities, sums and batches.
"""

from fractions import Fraction as Fr

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from test_entities_at_scale import (
    CONFIGS,
    EPS,
    FAST,
    REL,
    circumcircle,
    circumsphere,
    close_pos,
    cross,
    dot,
    flt,
    fr,
    fsqrt,
    layout,
    sub,
    unit,
)

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra, InvalidInputError, Multivector
from cga_lessons.conformal.anchored import Anchored, frame
from cga_lessons.conformal.anchored_points import point_frame
from cga_lessons.conformal.point_wedges import framed_points

MOTOR = cga.motor([0.3, -0.2, 0.9], 0.7, [1.0, 2.0, -0.5])


def plain_wedge(*Xs):
    """The outer product of Xs without the operation hook: the plain coefficients (what the operator gave before)."""
    out = Xs[0]
    for X in Xs[1:]:
        out = out.plain_operation("^", X)
    return out


def same_bits(X, Y) -> bool:
    return X.coeffs.keys() == Y.coeffs.keys() and all(np.array_equal(X.coeffs[k], Y.coeffs[k]) for k in X.coeffs)


# ------------------------------------------------------------- the entities, far out
@FAST
@given(CONFIGS)
def test_raw_sphere_and_circle_far_eq_2_75_2_80(cfg):
    """``up(a) ^ up(b) ^ up(c) ^ up(d)`` is the sphere through the four points (2.75), ``up(a) ^ up(b) ^ up(c)`` the
    circle (2.80), read exactly at any distance; their coefficients are the plain wedge's, bit for bit."""
    c, size, pts = layout(*cfg)
    U = [cga.up(p) for p in pts]
    S, Z = U[0] ^ U[1] ^ U[2] ^ U[3], U[0] ^ U[1] ^ U[2]
    assert type(S) is Anchored and same_bits(S, plain_wedge(*U))
    assert type(Z) is Anchored and same_bits(Z, plain_wedge(*U[:3]))
    assert np.array_equal(S.anchor, pts[0])  # anchored at its first point: the data itself
    tc, tr2 = circumsphere(pts)
    centre, radius = cga.sphere_center_radius(S)
    assert close_pos(centre, flt(tc), fsqrt(tr2), c) and abs(radius - fsqrt(tr2)) <= REL * fsqrt(tr2)
    cc, cr2, cn = circumcircle(pts[:3])
    centre, radius, normal = cga.circle_center_radius(Z)
    assert close_pos(centre, flt(cc), fsqrt(cr2), c) and abs(radius - fsqrt(cr2)) <= REL * fsqrt(cr2)
    assert min(np.linalg.norm(normal - unit(cn)), np.linalg.norm(normal + unit(cn))) <= REL


@FAST
@given(CONFIGS)
def test_raw_point_pair_line_and_plane_far_eq_2_68_2_77_2_81(cfg):
    """``up(a) ^ up(b)`` (2.68: its ends and its sphere, 2.131, 2.134), ``up(a) ^ up(b) ^ e`` (the line, 2.81) and
    ``e ^ up(a) ^ up(b) ^ up(c)`` (the plane, 2.77), exact at any distance."""
    c, size, pts = layout(*cfg, k=3)
    a, b, x = pts
    A, B, X = fr(a), fr(b), fr(x)
    PP = cga.up(a) ^ cga.up(b)
    p1, p2 = cga.point_pair_endpoints(PP)  # never refused: read about a
    s = float(np.linalg.norm(a - b))
    assert close_pos(p1, a, s, c) and close_pos(p2, b, s, c)
    centre, radius = cga.sphere_center_radius(cga.point_pair_sphere(PP))
    half2 = dot(sub(A, B), sub(A, B)) / 4
    assert close_pos(centre, (a + b) / 2, s, c) and abs(radius - fsqrt(half2)) <= REL * fsqrt(half2)
    d = sub(B, A)
    for L in (cga.up(a) ^ cga.up(b) ^ cga.einf, cga.einf ^ cga.up(a) ^ cga.up(b)):
        assert type(L) is Anchored
        r = cga.line_direction(L)
        assert min(np.linalg.norm(r - unit(d)), np.linalg.norm(r + unit(d))) <= REL  # (2.127)
        cr = cross(sub(X, A), d)
        dist = fsqrt(dot(cr, cr) / dot(d, d))
        assert abs(cga.point_line_distance(x, L) - dist) <= REL * dist  # (2.130)
    nv = cross(sub(B, A), sub(X, A))
    P = cga.einf ^ cga.up(a) ^ cga.up(b) ^ cga.up(x)
    n, dist = cga.plane_normal_distance(P)
    assert min(np.linalg.norm(n - unit(nv)), np.linalg.norm(n + unit(nv))) <= REL
    offset = dot(nv, A) / fsqrt(dot(nv, nv))  # the signed distance of the plane along nv
    assert close_pos([abs(dist)], [abs(offset)], max(abs(offset), size), c)


@FAST
@given(CONFIGS)
def test_sums_of_points_far_eq_2_72(cfg):
    """``up(c) - rho^2 e / 2`` is the sphere of centre c (2.72), ``up(c) + rho^2 e / 2`` the imaginary one, and
    ``up(a) - up(b)`` the plane between a and b (its normal a - b, its distance (a + b) . n / 2): exact far out."""
    c, size, pts = layout(*cfg, k=2)
    a, b = pts
    S = cga.up(c) - (0.5 * size * size) * cga.einf
    assert type(S) is Anchored and np.array_equal(S.anchor, c)
    centre, radius = cga.sphere_center_radius(S)
    assert close_pos(centre, c, size, c) and abs(radius - size) <= REL * size
    Si = cga.up(c) + (0.5 * size * size) * cga.einf  # imaginary: rho^2 = -size^2
    k = cga.classify(Si, form="standard")
    assert k.name == "imaginary sphere" and abs(k.radius2 + size * size) <= REL * size * size
    n, dist = cga.plane_normal_distance(cga.up(a) - cga.up(b))
    A, B = fr(a), fr(b)
    nv = sub(A, B)
    assert np.linalg.norm(n - unit(nv)) <= REL
    want = (dot(A, A) - dot(B, B)) / 2 / fsqrt(dot(nv, nv))  # (a^2 - b^2) / (2 |a - b|) = (a + b) . n / 2
    assert close_pos([dist], [want], size, c)


@FAST
@given(CONFIGS)
def test_anchored_entities_take_points_as_operands(cfg):
    """An anchored entity and a plain point: the frame follows now (``circle_from_points(a, b, c) ^ up(d)`` is the
    sphere, ``point_pair(a, b) ^ up(c)`` the circle), anchored at the entity's anchor; and a raw wedge moved by a
    motor (2.102) stays exact."""
    c, size, pts = layout(*cfg)
    tc, tr2 = circumsphere(pts)
    Z = cga.circle_from_points(*pts[:3])
    for S in (Z ^ cga.up(pts[3]), cga.point_pair(*pts[:2]) ^ cga.up(pts[2]) ^ cga.up(pts[3])):
        assert type(S) is Anchored
        centre, radius = cga.sphere_center_radius(S)
        assert close_pos(centre, flt(tc), fsqrt(tr2), c) and abs(radius - fsqrt(tr2)) <= REL * fsqrt(tr2)
    assert np.array_equal((Z ^ cga.up(pts[3])).anchor, Z.anchor)
    S = cga.apply(MOTOR, cga.up(pts[0]) ^ cga.up(pts[1]) ^ cga.up(pts[2]) ^ cga.up(pts[3]))
    assert abs(cga.sphere_center_radius(S)[1] - fsqrt(tr2)) <= REL * fsqrt(tr2)  # a motor keeps the radius


def test_batches_of_points_wedge_exactly():
    """``up`` of (N, 3) arrays wedged (with each other, or with one point) is a batch of anchored spheres, each
    member's radius exact 1e6 out, and the member's coefficients those of the single wedge."""
    rng = np.random.default_rng(7)
    base = 1e6 * rng.normal(size=(6, 1, 3)) / np.sqrt(3) + rng.normal(size=(6, 4, 3))
    a, b, c, d = (np.ascontiguousarray(base[:, i]) for i in range(4))
    S = cga.up(a) ^ cga.up(b) ^ cga.up(c) ^ cga.up(d)
    assert type(S) is Anchored and S.shape == (6,) and np.array_equal(S.anchor, a)
    radii = cga.sphere_center_radius(S)[1]
    near = a[0] + rng.normal(size=(3, 6, 3))  # one point with batches of points near it
    one = cga.up(a[0]) ^ cga.up(near[0]) ^ cga.up(near[1]) ^ cga.up(near[2])
    assert type(one) is Anchored and one.anchor.shape == (6, 3)
    for i in range(6):
        _, tr2 = circumsphere([a[i], b[i], c[i], d[i]])
        assert abs(radii[i] - fsqrt(tr2)) <= REL * fsqrt(tr2)
        single = cga.up(a[i]) ^ cga.up(b[i]) ^ cga.up(c[i]) ^ cga.up(d[i])
        assert same_bits(S.batch_item(i), single)
    for i, radius in enumerate(cga.sphere_center_radius(one)[1]):
        _, tr2 = circumsphere([a[0], near[0, i], near[1, i], near[2, i]])
        assert abs(radius - fsqrt(tr2)) <= REL * fsqrt(tr2)


def test_raw_wedges_as_the_storage_limit_table():
    """The numbers of point_wedges' docstring: rho^2 of a unit sphere from a raw wedge, through the frame, within a
    few eps at 1e2, 1e3 and 1e6 (the plain wedge: up to ~1e-6 at 1e2, ~0.1 at 1e3, refused or meaningless at 1e6)."""
    for off in (2.0, 3.0, 6.0):
        worst = 0.0
        for seed in range(20):
            _, _, pts = layout(seed, off, 0.0)
            _, tr2 = circumsphere(pts)
            S = cga.up(pts[0]) ^ cga.up(pts[1]) ^ cga.up(pts[2]) ^ cga.up(pts[3])
            worst = max(worst, abs(cga.sphere_center_radius(S)[1] ** 2 - float(tr2)) / float(tr2))
        assert worst <= 16 * EPS, off


# ---------------------------------------------------------------- which vectors are points
@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(-3.0, 7.0))
def test_points_of_every_route_are_read_at_down(seed, log_off):
    """``up(x)`` is recognised at x itself, weight 1 (its coefficients are the bits ``up`` stores for x), at any
    distance; a point of another route (``apply`` of a motor, ``up(down(X))``, ``2 up(x)``, ``-up(x)``) is
    recognised whenever its weight ``-e . X`` (2.111) holds ``s w = E^2`` to 8 eps, always from 1e3 out (where the
    weight is stored exactly), and anchored at ``down(X)`` (2.114)."""
    rng = np.random.default_rng(seed)
    x = rng.normal(size=3)
    x *= 10.0**log_off / np.linalg.norm(x)
    X = cga.up(x)
    anchor, weight = point_frame(X)
    assert np.array_equal(anchor, x) and weight == 1.0
    for Y, w in ((cga.apply(MOTOR, X), 1.0), (cga.up(cga.down(X)), 1.0), (2.0 * X, 2.0), (-X, -1.0)):
        got = point_frame(Y)
        xp, xm = Fr(Y["e+"]), Fr(Y["e-"])
        E = [Fr(Y[b]) for b in ("e1", "e2", "e3")]
        sw_q = abs((xp + xm) * (xm - xp) - sum(v * v for v in E))  # s w - E^2, exactly
        bound = 8 * Fr(EPS) * (abs(xm - xp) * (abs(xp) + abs(xm)) + sum(v * v for v in E))
        assert (got is not None) == (sw_q <= bound + 4 * Fr(EPS) * bound)  # the test, to the rounding of its terms
        if log_off >= 3.0:
            assert got is not None
        if got is not None:
            up_bits = Y.coeffs == cga.up(cga.euclidean(Y)).coeffs  # up(E) itself: at E, weight 1
            assert np.array_equal(got[0], cga.euclidean(Y) if up_bits else cga.down(Y))
            assert abs(got[1] - w) <= 16 * EPS * max(1.0, float(x @ x)) * abs(w)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(-3.0, 6.0), st.floats(0.0, 6.0))
def test_spheres_are_not_points(seed, log_off, log_margin):
    """A sphere ``up(c) -+ rho^2 e / 2`` (real or imaginary) whose rho^2 passes the storage's resolution of its
    e+/e- coefficients, ``8 eps (max(|c|^2, 1) + |c|^2)``, is never read as a point, so its wedges stay plain."""
    rng = np.random.default_rng(seed)
    c = rng.normal(size=3)
    c *= 10.0**log_off / np.linalg.norm(c)
    cc = float(c @ c)
    rho2 = 16 * EPS * (max(cc, 1.0) + cc) * 10.0**log_margin  # twice the documented threshold (8 eps) and beyond
    for sign in (-1.0, 1.0):
        shift = Multivector(cga.G41, {8: sign * rho2 / 2, 16: sign * rho2 / 2})
        S = Multivector(cga.G41, dict(cga.up(c).plain_operation("+", shift).coeffs))  # plain: no frame of its own
        assert point_frame(S) is None
        assert type(S ^ cga.up([1.0, 2.0, 3.0])) is Multivector
        assert type(cga.up([1.0, 2.0, 3.0]) ^ S) is Multivector


def test_what_is_not_a_point():
    """Not points: e (weight 0; invariant), ``e + 1e-10 e0`` (not null), a plain sphere, ``up(x) / 3`` 1e6 out (its
    weight is not resolved: to its coefficients a sphere of radius ~1e3), SymPy points (exact, never anchored), a
    multivector with other grades, and a vector whose e+/e- overflow; a sphere of radius 1e-3 1e6 out has the bits
    of ``up(c)`` (its radius is below the storage's resolution) and is one."""
    far = [1e6, 2.0, 3.0]
    for X in (
        cga.einf,
        Multivector(cga.G41, {8: 1.0 - 0.5e-10, 16: 1.0 + 0.5e-10}),
        cga.sphere(far, 1.0).plain(),
        cga.sphere([0.0, 0.0, 0.0], 1e-4).plain(),
        cga.up(far) / 3.0,
        cga.up(far) + cga.e1 * cga.e2,
        Multivector(cga.G41, {1: 1e200, 8: 1e300, 16: 1e300}),
    ):
        assert point_frame(X) is None
        assert type(X ^ cga.up([0.0, 1.0, 0.0])) is not Anchored or X is cga.einf
    assert type(cga.up(sp.symbols("x y z")) ^ cga.up([1, 2, 3])) is Multivector
    tiny = Multivector(cga.G41, dict(cga.up(far).coeffs)) - Multivector(cga.G41, {8: 0.5e-6, 16: 0.5e-6})
    assert same_bits(tiny, cga.up(far)) and point_frame(tiny) is not None


def test_up_over_three_far_out_is_not_resolved():
    """``up(x) / 3`` 1e6 out: ``X_- - X_+`` is 1/3 off by ~1e-5 of itself (each coefficient rounded to ~eps x^2);
    ``s w - E^2`` is then far beyond POINT_RTOL, as for a sphere of radius ~1e3: plain, not mis-read."""
    X = cga.up([1e6, 2.0, 3.0]) / 3.0
    w = Fr(X["e-"]) - Fr(X["e+"])
    assert abs(w - Fr(1, 3)) > Fr(1, 10**6)
    assert point_frame(X) is None and type(X ^ cga.up([1e6, 3.0, 3.0])) is Multivector


# ----------------------------------------------------------------- the hook and its layer
def test_the_hook_is_registered_on_g41_only_and_checked():
    """The conformal layer registers ``framed_points`` on G41; another algebra has none and its products are plain;
    the algebra refuses a hook that is not a function (a ValueError subclass of the checking layer)."""
    assert cga.G41.operation_hook is framed_points
    G3 = Algebra(3)
    assert G3.operation_hook is None
    with pytest.raises(InvalidInputError, match=r"^Algebra.set_operation_hook: hook: expected a function or None"):
        G3.set_operation_hook(42)
    e1, e2, _ = G3.basis_vectors()
    assert type(e1 ^ e2) is Multivector
    with pytest.raises(InvalidInputError, match=r"^Multivector.plain_operation: op: expected one of"):
        e1.plain_operation("*", e2)


def test_other_operators_and_operands_stay_plain():
    """The geometric and inner products are not hooked (the versors' hot path), nor an operand that is neither a
    point, anchored nor invariant (a motor, e1); numbers only scale (a scaled point is a plain point)."""
    a, b = cga.up([1e6, 2.0, 3.0]), cga.up([1e6, 3.0, 3.0])
    for Y in (a * b, a | b, a << b, MOTOR ^ a, a ^ cga.e1, cga.e1 ^ a, 2.5 * a, a * 2.0, a ^ 2.0):
        assert type(Y) is Multivector
    assert type(a ^ b) is Anchored and type(a + b) is Anchored and type(a - cga.einf) is Anchored
    assert frame(a ^ a)[0] is None  # zero: nothing to anchor
