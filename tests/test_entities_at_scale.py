"""Entities far from the origin (section 2.4, 2.111-2.130): properties against exact geometry, offsets up to 1e6.

Truth: the same property from elementary geometry (circumsphere by Cramer's rule, circumcircle, plane through three
points, point-line distance) in exact rational arithmetic (fractions.Fraction) on the very floats handed to the
library, square roots in mpmath at 50 digits.  Shapes are well conditioned (a jittered regular tetrahedron, rotated,
of size 0.1-100) and placed at up to 1e6 from the origin.

Every property of the entities the constructors build is held to 1e-9 relative; positions get besides a floor of a
few ulp of the coordinates themselves (``close_pos``).  The rounds (spheres, circles, point pairs) and lines carry
their local frame (:mod:`cga_lessons.conformal.anchored`) and are read from it, as do raw wedges of plain points
(:mod:`cga_lessons.conformal.point_wedges`, tested in ``test_point_wedges.py``); the float64 e+/e- storage of a
plain blade holds a round's squared size only to about eps (|c|^2 + size^2 + 1) absolute (see
:mod:`cga_lessons.conformal.entities_frame`): ``test_plain_blades_keep_the_storage_limit`` checks that limit, and
that it is real.
"""

from fractions import Fraction as Fr

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector

mpmath.mp.dps = 50
EPS = float(np.finfo(float).eps)
REL = 1e-9
FAST = settings(max_examples=30, deadline=None)
# seed, log10 of the offset (0.1 .. 1e6), log10 of the size (0.1 .. 100)
CONFIGS = st.tuples(st.integers(0, 2**32 - 1), st.floats(-1.0, 6.0), st.floats(-1.0, 2.0))
TETRA = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]]) / np.sqrt(3)


def layout(seed, log_off, log_size, k=4):
    """k points of a jittered regular tetrahedron of circumradius ~size, rotated, centred ~10**log_off out."""
    rng = np.random.default_rng(seed)
    c = rng.normal(size=3)
    c *= 10.0**log_off / np.linalg.norm(c)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    size = 10.0**log_size
    return c, size, c + size * (TETRA[:k] + rng.uniform(-0.1, 0.1, size=(k, 3))) @ q.T


# ------------------------------------------------------------- exact truth
def fr(v):
    return [Fr(float(x)) for x in v]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def solve3(rows, rhs):
    """Cramer's rule, exactly."""
    det = dot(rows[0], cross(rows[1], rows[2]))
    out = []
    for i in range(3):
        m = [list(r) for r in rows]
        for k in range(3):
            m[k][i] = rhs[k]
        out.append(dot(m[0], cross(m[1], m[2])) / det)
    return out


def fsqrt(x: Fr) -> float:
    return float(mpmath.sqrt(mpmath.mpf(x.numerator) / x.denominator))


def flt(v):
    return np.array([float(x) for x in v])


def unit(v):
    n = mpmath.sqrt(sum(mpmath.mpf(x.numerator) / x.denominator for x in (y * y for y in v)))
    return np.array([float(mpmath.mpf(x.numerator) / x.denominator / n) for x in v])


def circumsphere(pts):
    a = fr(pts[0])
    rows, rhs = [], []
    for q in pts[1:]:
        q = fr(q)
        rows.append([2 * (x - y) for x, y in zip(q, a)])
        rhs.append(dot(q, q) - dot(a, a))
    c = solve3(rows, rhs)
    return c, dot(sub(a, c), sub(a, c))


def circumcircle(pts):
    a, b, c = (fr(p) for p in pts)
    n = cross(sub(b, a), sub(c, a))
    rows = [[2 * (x - y) for x, y in zip(b, a)], [2 * (x - y) for x, y in zip(c, a)], n]
    centre = solve3(rows, [dot(b, b) - dot(a, a), dot(c, c) - dot(a, a), dot(n, a)])
    return centre, dot(sub(a, centre), sub(a, centre)), n


def close_pos(got, truth, scale, c):
    """A position within 1e-9 of its scale, or 8 ulp of the coordinates' size (their own resolution)."""
    return np.linalg.norm(np.asarray(got) - truth) <= REL * scale + 8 * EPS * (np.linalg.norm(c) + scale)


# ----------------------------------------------------------------- spheres
@FAST
@given(CONFIGS)
def test_sphere_from_points_far_eq_2_75_2_115_2_117(cfg):
    c, size, pts = layout(*cfg)
    tc, tr2 = circumsphere(pts)
    p, rho = flt(tc), fsqrt(tr2)
    centre, radius = cga.sphere_center_radius(cga.sphere_from_points(*pts))
    assert close_pos(centre, p, rho, c)
    assert abs(radius - rho) <= REL * rho


@FAST
@given(CONFIGS)
def test_sphere_centre_radius_far_eq_2_72_2_73(cfg):
    c, size, _ = layout(*cfg)
    s = cga.sphere(c, size)
    assert float(-(s | cga.einf)) == 1.0  # the weight (2.74) is stored exactly
    centre, radius = cga.sphere_center_radius(s)
    assert close_pos(centre, c, size, c)
    assert abs(radius - size) <= REL * size
    for k in (0.5, 1 - 1e-8, 1 + 1e-8, 1.5):  # (2.118) on either side, 1e-8 of the radius off the surface too
        x = c + k * size * np.array([0.6, 0.0, 0.8])
        assert cga.point_sphere_side(x, s, atol=0.0) == (1 if k < 1 else -1)


@FAST
@given(CONFIGS)
def test_point_sphere_side_far_eq_2_118(cfg):
    c, size, pts = layout(*cfg)
    tc, tr2 = circumsphere(pts)
    S = cga.sphere_from_points(*pts)
    rng = np.random.default_rng(cfg[0])
    xs = flt(tc) + rng.uniform(0.3, 1.7, size=(8, 1)) * size * rng.normal(size=(8, 3)) / 1.7
    u = rng.normal(size=(8, 3))
    near = flt(tc) + (1 + rng.choice([-4e-9, 4e-9], size=(8, 1))) * flt([fsqrt(tr2)] * 3)[:1] * u / np.linalg.norm(
        u, axis=1, keepdims=True
    )  # 4e-9 of the radius off the surface (before the rounding of their coordinates)
    xs = np.vstack([xs, near])
    sides = cga.point_sphere_side(xs, S, atol=0.0)
    limit = REL * float(tr2)  # the power rho^2 - |x - p|^2 is right to 1e-9 of rho^2
    for x, side in zip(xs, sides):
        power = tr2 - dot(sub(fr(x), tc), sub(fr(x), tc))  # rho^2 - |x - p|^2, exactly
        if abs(float(power)) > limit:
            assert side == (1 if power > 0 else -1)


# ----------------------------------------------------------------- circles
@FAST
@given(CONFIGS)
def test_circle_far_eq_2_80_2_119_to_2_124(cfg):
    c, size, pts = layout(*cfg, k=3)
    tc, tr2, tn = circumcircle(pts)
    p, rho = flt(tc), fsqrt(tr2)
    for Z in (cga.circle_from_points(*pts), cga.standard_form(cga.circle_from_points(*pts))):
        centre, radius, normal = cga.circle_center_radius(Z)
        assert close_pos(centre, p, rho, c)
        assert abs(radius - rho) <= REL * rho
        assert np.linalg.norm(normal - unit(tn)) <= REL


# ------------------------------------------------------------------ planes
@FAST
@given(CONFIGS)
def test_plane_far_eq_2_77_2_89(cfg):
    c, size, pts = layout(*cfg, k=3)
    nv = cross(sub(fr(pts[1]), fr(pts[0])), sub(fr(pts[2]), fr(pts[0])))
    delta = dot(nv, fr(pts[0]))
    d_true = (
        float(
            mpmath.sign(delta)
            * mpmath.sqrt(
                mpmath.mpf((delta * delta / dot(nv, nv)).numerator) / (delta * delta / dot(nv, nv)).denominator
            )
        )
        if delta
        else 0.0
    )
    n, d = cga.plane_normal_distance(cga.plane_from_points(*pts))
    assert np.linalg.norm(n - unit(nv)) <= REL
    assert close_pos([d], [d_true], max(abs(d_true), size), c)


# ------------------------------------------------------------------- lines
@FAST
@given(CONFIGS)
def test_line_far_eq_2_81_2_125_to_2_130(cfg):
    c, size, pts = layout(*cfg, k=3)
    a, b, x = pts
    A, B, X = fr(a), fr(b), fr(x)
    d = sub(B, A)
    r = unit(d)
    L = cga.line_from_points(a, b)
    assert np.linalg.norm(cga.line_direction(L) - r) <= REL  # (2.127)
    m_true = flt(cross(A, d)) / fsqrt(dot(d, d))  # the moment a x r = (a x d) / |d|
    assert close_pos(cga.line_moment(L), m_true, np.linalg.norm(m_true), c)  # (2.128)
    t = dot(sub([Fr(0)] * 3, A), d) / dot(d, d)
    closest = flt([ai + t * di for ai, di in zip(A, d)])
    assert close_pos(cga.line_closest_point(L), closest, np.linalg.norm(closest), c)  # (2.129)
    cr = cross(sub(X, A), d)
    dist = fsqrt(dot(cr, cr) / dot(d, d))
    assert abs(cga.point_line_distance(x, L) - dist) <= REL * dist  # (2.130), about the line's anchor
    assert close_pos([cga.point_line_distance(cga.up(x) * 3.0, cga.standard_form(L))], [dist], dist, c)  # down(X)
    got = cga.point_line_distance(np.stack([x, a, b]), L)
    assert close_pos(got[:1], [dist], dist, c) and np.all(got[1:] <= 16 * EPS * (np.linalg.norm(c) + size))


# ------------------------------------------------------------- point pairs
@FAST
@given(CONFIGS)
def test_point_pair_far_eq_2_68_2_131_2_134(cfg):
    c, size, pts = layout(*cfg, k=2)
    a, b = pts
    m, s = (a + b) / 2, float(np.linalg.norm(a - b))
    PP = cga.point_pair(a, b)
    p1, p2 = cga.point_pair_endpoints(PP)  # never refused: the accuracy guard is that of the local blade
    for got, want in ((p1, a), (p2, b)):
        assert np.linalg.norm(got - want) <= REL * s + 8 * EPS * np.linalg.norm(c)
    centre, radius = cga.sphere_center_radius(cga.point_pair_sphere(PP))  # (2.134)
    assert close_pos(centre, m, s, c)
    assert abs(radius - s / 2) <= REL * s / 2


def test_point_pair_spanning_far_and_near():
    """One end at 1e100, the other at 1: squares of 4th powers overflowed (NaN); now both ends within 1e-9."""
    a, b = np.array([1e100, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(a, b))
    assert np.linalg.norm(p1 - a) <= 1e-9 * 1e100 and np.linalg.norm(p2 - b) <= 1e-9


# ----------------------------------------------------- derived entities (anchored_ops)
def circle_of(c1, r1sq, c2, r2sq):
    """The exact circle where the spheres (c1, r1^2) and (c2, r2^2) meet (Fractions): centre, rho^2, the centres'
    difference d (the normal's direction) and a, the distance from c1 to the circle's plane (2.79)."""
    d = sub(c2, c1)
    D2 = dot(d, d)
    k = (D2 + r1sq - r2sq) / (2 * D2)
    return [x + k * y for x, y in zip(c1, d)], r1sq - k * k * D2, d, k


def one_blade(X):
    """The local blade, translated back by its anchor (2.100), is the global blade: one entity, one orientation,
    one weight.  To 1e-3 of the coefficient norm: the global coefficients of a product of rounds 1e6 out are the
    plain products' (|c|^2-sized terms cancel), good to ~1e-4 of their norm; a sign or a factor would be O(1)."""
    from cga_lessons.conformal.anchored_ops import translated

    W = translated(X.local, X.anchor)
    G = Multivector(cga.G41, dict(X.coeffs))
    return np.linalg.norm((W - G).to_array()) <= 1e-3 * np.linalg.norm(G.to_array())


def two_spheres(cfg):
    """A sphere through four points (anchored at one of them) and one from its centre (anchored there), centres
    0.5-1.2 sizes apart: they meet in a circle."""
    c, size, pts = layout(*cfg)
    rng = np.random.default_rng(cfg[0] + 1)
    u = rng.normal(size=3)
    c2 = c + size * rng.uniform(0.5, 1.2) * u / np.linalg.norm(u)
    r2 = size * rng.uniform(0.8, 1.2)
    return c, size, pts, c2, r2


@FAST
@given(CONFIGS)
def test_circle_where_two_spheres_meet_far_eq_2_79(cfg):
    """``s1 ^ s2`` (2.79), the regressive product, ``meet`` and ``intersect``: the circle of two anchored spheres
    as exact as the spheres (its local blade about the first one's anchor, the second moved in by 2.100).  ``meet``
    and ``intersect`` decide in the local frame, at the default ``tol`` as at a small one."""
    c, size, pts, c2, r2 = two_spheres(cfg)
    tc, tr2 = circumsphere(pts)
    pc, rho2, d, _ = circle_of(tc, tr2, fr(c2), Fr(r2) ** 2)
    assume(rho2 > 0)
    p, rho, u = flt(pc), fsqrt(rho2), unit(d)
    S1, S2 = cga.standard_form(cga.sphere_from_points(*pts)), cga.sphere(c2, r2)
    for Z in (
        S1 ^ S2,
        cga.regressive_product(cga.dual_form(S2), cga.dual_form(S1)),
        cga.meet(cga.dual_form(S1), cga.dual_form(S2)),
        cga.intersect(S1, S2),
        cga.intersect(S1, S2, tol=1e-15),
    ):
        centre, radius, normal = cga.circle_center_radius(Z)
        assert close_pos(centre, p, rho, c)
        assert abs(radius - rho) <= REL * rho
        assert min(np.linalg.norm(normal - u), np.linalg.norm(normal + u)) <= REL
        assert one_blade(Z)


@FAST
@given(CONFIGS)
def test_point_pair_where_a_line_cuts_a_sphere_far_table_2_1(cfg):
    """``intersect(L, s)`` and ``meet(L, s*)``: the point pair of an anchored line through an anchored sphere."""
    c, size, pts = layout(*cfg, k=2)
    rng = np.random.default_rng(cfg[0] + 2)
    S = cga.sphere(c, size)
    a = c + 0.5 * size * rng.uniform(-1, 1, size=3) / np.sqrt(3)  # within half the radius of the centre
    b = a + size * rng.normal(size=3)
    assume(np.linalg.norm(b - a) > 1e-3 * size)
    A, B, C = fr(a), fr(b), fr(c)
    dd, ac = sub(B, A), sub(A, C)
    qa, qb, qc = dot(dd, dd), dot(ac, dd), dot(ac, ac) - Fr(size) ** 2
    root = mpmath.sqrt(mpmath.mpf((qb * qb - qa * qc).numerator) / (qb * qb - qa * qc).denominator)
    ends = [
        np.array([float(mpmath.mpf(x.numerator) / x.denominator + s * y) for x, y in zip(A, dd)])
        for s in ((-mpmath.mpf(qb.numerator) / qb.denominator + r) / (mpmath.mpf(qa.numerator) / qa.denominator)
                  for r in (root, -root))
    ]  # fmt: skip
    sep = float(np.linalg.norm(ends[0] - ends[1]))
    L = cga.line_from_points(a, b)
    for PP in (cga.intersect(L, S), cga.meet(L, cga.dual_form(S))):
        p1, p2 = cga.point_pair_endpoints(PP)
        if np.linalg.norm(p1 - ends[0]) > np.linalg.norm(p1 - ends[1]):
            p1, p2 = p2, p1
        assert close_pos(p1, ends[0], sep, c) and close_pos(p2, ends[1], sep, c)
        assert one_blade(PP)


FAR_PAIR = ([0.6, -0.48, 0.64], 1.0, [0.5, 0.3, 0.1], 1.1)  # two unit-size spheres: their circle has rho ~ 0.87


def far_pair(offset):
    """Two anchored spheres ``offset`` out, centres 0.59 apart (FAR_PAIR)."""
    u, r1, d, r2 = FAR_PAIR
    c = offset * np.array(u)
    return c, cga.sphere(c, r1), cga.sphere(c + d, r2)


@pytest.mark.parametrize("offset", [1e5, 1e6])
def test_meet_of_far_anchored_spheres_decides_in_the_local_frame(offset):
    """1e5-1e6 out the 4-spaces of two unit spheres are ~1e-12 apart in the global coefficients, which the
    default ``tol = 1e-10`` takes for one subspace; their local blades (about the first sphere's anchor, the second
    moved in by 2.100) are well apart.  ``join``, ``meet`` and ``intersect`` of anchored blades decide there: the
    meet is the circle (grade 3, standard form grade 2), anchored, exact against the Fractions truth at the default
    ``tol``; its global coefficients are its local blade translated back by the anchor (``T_f L ~T_f``)."""
    from cga_lessons.conformal.anchored import frame
    from cga_lessons.conformal.anchored_ops import translated

    c, S1, S2 = far_pair(offset)
    _, r1, _, r2 = FAR_PAIR
    c2 = c + FAR_PAIR[2]
    pc, rho2, d, _ = circle_of(fr(c), Fr(r1) ** 2, fr(c2), Fr(r2) ** 2)
    p, rho, u = flt(pc), fsqrt(rho2), unit(d)
    A, B = cga.dual_form(S1), cga.dual_form(S2)
    M, Z, J = cga.meet(A, B), cga.intersect(S1, S2), cga.join(A, B)
    assert M.grades_present() == [3] and Z.grades_present() == [2] and J.grades_present() == [5]
    for X in (M, Z, J):
        f, L = frame(X)
        assert f is not None and L.grades_present() == X.grades_present()
        assert X == translated(L, f)  # the global coefficients: the local blade translated back, bit for bit
    for X in (M, Z):
        centre, radius, normal = cga.circle_center_radius(X)
        assert close_pos(centre, p, rho, c)
        assert abs(radius - rho) <= REL * rho
        assert min(np.linalg.norm(normal - u), np.linalg.norm(normal + u)) <= REL
    W = S1 ^ S2  # the thesis's circle (2.79): intersect's sign, the same local blade
    assert np.array_equal(frame(Z)[0], frame(W)[0]) and frame(Z)[1] == frame(W)[1]
    k = cga.classify(Z, form="standard")
    assert k.name == "circle" and abs(k.radius2 - rho * rho) <= REL * rho * rho


@pytest.mark.parametrize("offset", [1e5, 1e6])
def test_plain_blades_meet_as_before_far_out(offset):
    """Plain blades have only the global coefficients, and decide there, as before: 1e5-1e6 out the default ``tol``
    takes the 4-spaces of the two spheres for one subspace (the join is a sphere, the meet a grade-4 blade, the
    standard form a vector), the storage's limit.  A ``tol`` below the sines (1e-14) gives the circle."""
    _, S1, S2 = far_pair(offset)
    A, B = cga.dual_form(S1).plain(), cga.dual_form(S2).plain()
    assert cga.join(A, B).grades_present() == [4] and cga.meet(A, B).grades_present() == [4]
    assert cga.intersect(S1.plain(), S2.plain()).grades_present() == [1]
    assert cga.meet(A, B, 1e-14).grades_present() == [3]


@FAST
@given(CONFIGS)
def test_anchored_meet_keeps_the_plain_bits_where_the_frames_agree(cfg):
    """Where the local and the global blades decide the same (the same grade), ``join``, ``meet`` and ``intersect``
    of anchored blades return the plain routine's global coefficients, bit for bit, with the frame; where they
    differ (far out, small spheres) the anchored result is its local blade translated back."""
    from cga_lessons.conformal.anchored import frame
    from cga_lessons.conformal.anchored_ops import translated

    _, _, pts, c2, r2 = two_spheres(cfg)
    S1, S2 = cga.standard_form(cga.sphere_from_points(*pts)), cga.sphere(c2, r2)
    A, B = cga.dual_form(S1), cga.dual_form(S2)
    for fn, x, y in ((cga.join, A, B), (cga.meet, A, B), (cga.intersect, S1, S2)):
        X, P = fn(x, y), fn(x.plain(), y.plain())
        f, L = frame(X)
        assert f is not None
        if X.grades_present() == P.grades_present():
            assert X == P
        else:
            assert X == translated(L, f)


def test_anchored_meet_near_the_origin_is_the_plain_meet():
    """1e3 out both frames decide the circle: the anchored meet and intersect are the plain ones, bit for bit."""
    from cga_lessons.conformal.anchored import frame

    _, S1, S2 = far_pair(1e3)
    A, B = cga.dual_form(S1), cga.dual_form(S2)
    for X, P in (
        (cga.meet(A, B), cga.meet(A.plain(), B.plain())),
        (cga.intersect(S1, S2), cga.intersect(S1.plain(), S2.plain())),
        (cga.join(A, B), cga.join(A.plain(), B.plain())),
    ):
        assert X == P and frame(X)[0] is not None
        assert all(np.array_equal(X.coeffs[k], P.coeffs[k]) for k in P.coeffs) and X.coeffs.keys() == P.coeffs.keys()


@FAST
@given(CONFIGS)
def test_other_derived_entities_far(cfg):
    """A scaled and a negated sphere, the sum of two (a pencil member), a circle's plane (2.119), the line of a
    point pair (PP ^ e) and the sphere of a meet's point pair (2.134): read about their anchors."""
    c, size, pts = layout(*cfg)
    tc, tr2 = circumsphere(pts)
    p, rho = flt(tc), fsqrt(tr2)
    S = cga.sphere_from_points(*pts)
    for X in (2.5 * S, -S, S / 3.0, cga.standard_form(S) * 7.0):
        centre, radius = cga.sphere_center_radius(X)
        assert close_pos(centre, p, rho, c) and abs(radius - rho) <= REL * rho
    s1, s2 = cga.sphere(pts[0], size), cga.sphere(pts[1], size)  # s1 - s2: their radical plane, at the middle
    n, dist = cga.plane_normal_distance(s1 - s2)
    nv = sub(fr(pts[0]), fr(pts[1]))
    assert np.linalg.norm(n - unit(nv)) <= REL
    mid = [(x + y) / 2 for x, y in zip(fr(pts[0]), fr(pts[1]))]
    assert close_pos([dist], [float(np.dot(flt(mid), unit(nv)))], size, c)  # the radical plane of equal spheres
    Z = cga.circle_from_points(*pts[:3])
    nz, dz = cga.plane_normal_distance(cga.circle_plane(Z))
    _, _, tn = circumcircle(pts[:3])
    assert min(np.linalg.norm(nz - unit(tn)), np.linalg.norm(nz + unit(tn))) <= REL
    assert close_pos([abs(dz)], [abs(float(np.dot(pts[0], unit(tn))))], size, c)
    r = unit(sub(fr(pts[1]), fr(pts[0])))
    for L in (cga.point_pair(pts[0], pts[1]) ^ cga.einf, cga.point_pair(pts[1], pts[0]) ^ cga.einf):
        direction = cga.line_direction(L)
        assert min(np.linalg.norm(direction - r), np.linalg.norm(direction + r)) <= REL


# -------------------------------------------------------------- batches
def test_batches_match_single_entities_far_out():
    """A batch gives the bits of its single entities (the readers' squared sizes amplify any difference)."""
    rng = np.random.default_rng(3)
    base = 1e5 * rng.normal(size=(6, 1, 3)) + rng.normal(size=(6, 4, 3))
    a, b, c, d = (base[:, i] for i in range(4))
    batch = {
        "sphere": cga.sphere_center_radius(cga.sphere_from_points(a, b, c, d)),
        "circle": cga.circle_center_radius(cga.circle_from_points(a, b, c)),
        "plane": cga.plane_normal_distance(cga.plane_from_points(a, b, c)),
        "distance": (cga.point_line_distance(c, cga.line_from_points(a, b)),),
        "pair": cga.point_pair_endpoints(cga.point_pair(a, b), min_separation=0),
    }
    for i in range(6):
        one = {
            "sphere": cga.sphere_center_radius(cga.sphere_from_points(a[i], b[i], c[i], d[i])),
            "circle": cga.circle_center_radius(cga.circle_from_points(a[i], b[i], c[i])),
            "plane": cga.plane_normal_distance(cga.plane_from_points(a[i], b[i], c[i])),
            "distance": (cga.point_line_distance(c[i], cga.line_from_points(a[i], b[i])),),
            "pair": cga.point_pair_endpoints(cga.point_pair(a[i], b[i]), min_separation=0),
        }
        for key, values in one.items():
            assert all(np.array_equal(u[i], v) for u, v in zip(batch[key], values)), key


# ------------------------------------------------------------------ guards
UNIT = cga.sphere([0, 0, 0], 1.0)


def spoiled(X, value=np.nan):
    """X with every coefficient times ``value`` (NaN or inf), made directly: the algebra refuses ``X * nan``."""
    return Multivector(cga.G41, {k: v * value for k, v in X.coeffs.items()})


@pytest.mark.parametrize(
    "call, match",
    [
        (
            lambda: cga.point_pair([1e200, 0, 0], [0, 1, 0]),
            "^point_pair: a: magnitudes up to .*, beyond 1e\\+153: a conformal point stores x\\^2 / 2",
        ),
        (
            lambda: cga.point_pair([0, 1, 0], [0, 0, -1e160]),
            "^point_pair: b: magnitudes up to .*, beyond 1e\\+153: a conformal point stores x\\^2 / 2",
        ),
        (
            lambda: cga.sphere([0, 0, 0], 1e200),
            "^sphere: radius: magnitudes up to 1e\\+200, beyond 1e\\+153: its square overflows",
        ),
        (
            lambda: cga.sphere([1e155, 0, 0], 1.0),
            "^sphere: center: magnitudes up to .*, beyond 1e\\+153: a conformal point stores x\\^2 / 2",
        ),
        (
            lambda: cga.line_from_points([0, 0, 0], [0, 2e153, 0]),
            "^line_from_points: b: magnitudes up to .*, beyond 1e\\+153: a conformal point stores x\\^2 / 2",
        ),
        (
            lambda: cga.sphere_from_points(*(1e160 * TETRA)),
            "^sphere_from_points: a: magnitudes up to .*, beyond 1e\\+153: a conformal point stores x\\^2 / 2",
        ),
        (lambda: cga.circle_from_points([0, 0, 0], [1e100, 0, 0], [0, 1e100, 0]), "^circle_from_points: a, b, c: .*"),
        (lambda: cga.point_line_distance([1e200, 0, 0], cga.line_from_points([0, 0, 0], [1, 0, 0])), "^point_line_"),
        (lambda: cga.point_sphere_side([0, 0, 0.5], spoiled(UNIT)), "^point_sphere_side: S: .*NaN"),
        (lambda: cga.point_sphere_side(spoiled(cga.up([0, 0, 0.5])), UNIT), "^point_sphere_side: x: .*NaN"),
        (lambda: cga.sphere_center_radius(spoiled(UNIT, np.inf)), "^sphere_center_radius: S: .*NaN or inf"),
        (lambda: cga.point_pair_endpoints(spoiled(cga.point_pair([0, 0, 0], [1, 0, 0]))), "^point_pair_endpoints: PP"),
        (lambda: cga.circle_center_radius(spoiled(cga.circle_from_points(*TETRA[:3]))), "^circle_center_radius: Z"),
        (lambda: cga.plane_normal_distance(spoiled(cga.plane([0, 0, 1], 1.0))), "^plane_normal_distance: P: .*NaN"),
        (lambda: cga.line_direction(spoiled(cga.line_from_points([0, 0, 0], [1, 0, 0]))), "^line_direction: L: .*NaN"),
        (lambda: cga.down(spoiled(cga.up([1.0, 2.0, 3.0]))), "^down: X: .*NaN"),
        (lambda: cga.up([1.0 + 1j, 2.0, 3.0]), "^up: x: must be real numbers, got complex"),
        (lambda: cga.up(np.array([[1.0, 2.0, 3.0]], dtype=complex)), "^up: x: must be real numbers, got complex"),
        (lambda: cga.point_pair([0, 0, 0], [[1, 0, 0], [2, 0]]), "^point_pair: b: .*rows of different lengths"),
    ],
)
def test_overflow_and_nan_raise_invalid_input(call, match):
    with pytest.raises(InvalidInputError, match=match):
        call()


CIRCLE = cga.circle_from_points([1, 0, 0], [0, 1, 0], [-1, 0, 0])
SPHERE = cga.sphere([1, 2, 3], 1.0)
LINE = cga.line_from_points([0, 0, 0], [1, 0, 0])
PLANE = cga.plane([0, 0, 1], 2.0)


@pytest.mark.parametrize(
    "call, error, match",
    [
        (lambda: cga.line_direction(CIRCLE), InvalidInputError, "^line_direction: L: a circle"),
        (lambda: cga.line_moment(cga.standard_form(CIRCLE)), InvalidInputError, "^line_moment: L: a circle"),
        (lambda: cga.normalize_line(CIRCLE), InvalidInputError, "^normalize_line: L: a circle"),
        (lambda: cga.line_closest_point(CIRCLE), InvalidInputError, "^line_closest_point: L: a circle"),
        (lambda: cga.point_line_distance([0, 0, 1], CIRCLE), InvalidInputError, "^point_line_distance: L: a circle"),
        (lambda: cga.plane_normal_distance(SPHERE), InvalidInputError, "^plane_normal_distance: P: .*a sphere"),
        (lambda: cga.plane_normal_distance(cga.dual_form(SPHERE)), InvalidInputError, "^plane_normal_distance: P: "),
        (lambda: cga.sphere_center_radius(PLANE), DegenerateGeometryError, "^sphere_center_radius: S: .*a plane"),
        (lambda: cga.circle_center_radius(LINE), DegenerateGeometryError, "^circle_center_radius: Z: .*a line"),
        (lambda: cga.point_pair_endpoints(LINE ^ cga.up([0, 1, 0])), InvalidInputError, "^point_pair_endpoints: PP: "),
        (lambda: cga.sphere_center_radius(LINE), InvalidInputError, "^sphere_center_radius: S: expected a blade"),
        (lambda: cga.line_direction(cga.up([1, 2, 3])), InvalidInputError, "^line_direction: L: expected a blade"),
        (lambda: cga.circle_plane(LINE), DegenerateGeometryError, "^circle_plane: Z: .*a line"),
        (lambda: cga.circle_plane(cga.point_pair([0, 0, 0], [1, 0, 0])), DegenerateGeometryError, "^circle_plane: Z: "),
        (lambda: cga.point_pair_sphere(CIRCLE), DegenerateGeometryError, "^point_pair_sphere: PP: .*imaginary"),
        (lambda: cga.down(SPHERE), InvalidInputError, r"^down: X: X \. X != 0: a sphere"),
        (lambda: cga.down(cga.sphere(np.eye(3), 1.0)), InvalidInputError, r"^down: X: X \. X != 0: a sphere"),
        (lambda: cga.point_sphere_side(SPHERE, UNIT), InvalidInputError, "^point_sphere_side: x: .*a sphere"),
        (lambda: cga.point_line_distance(PLANE, LINE), DegenerateGeometryError, "^point_line_distance: x: "),
        (lambda: cga.point_weight(LINE), InvalidInputError, "^point_weight: X: expected a conformal point or sphere"),
        (lambda: cga.normalize_point(CIRCLE), InvalidInputError, "^normalize_point: X: expected a conformal point"),
    ],
)
def test_readers_reject_the_wrong_entity(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_nearly_coincident_pair_raises_with_both_separations():
    """A pair 1e-7 apart: its plain blade (the constructor's coefficients without the frame) resolves it to 1e-6
    only from 3e-5 on and is refused; the anchored pair of ``point_pair`` is read about its nearer end, exactly."""
    a, b = np.array([0.3, 0.3, 0.3]), np.array([0.3 + 1e-7, 0.3, 0.3])
    PP = Multivector(cga.G41, dict(cga.point_pair(a, b).coeffs))
    with pytest.raises(DegenerateGeometryError, match=r"^point_pair_endpoints: PP: the points are \S+ apart") as err:
        cga.point_pair_endpoints(PP)
    assert "resolve a separation to 1e-06 of itself from 3" in str(err.value)  # the resolvable one, 3.1e-05
    p1, _ = cga.point_pair_endpoints(PP, min_separation=0)  # unguarded: right to ~eps |m|^2 / separation
    assert np.linalg.norm(p1 - a) < 1e-8
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(a, b))
    assert np.linalg.norm(p1 - a) <= 1e-16 and np.linalg.norm(p2 - b) <= 1e-16


def test_sympy_input_stays_exact():
    R = sp.Rational
    pts = [[R(4), R(2), R(-1)], [R(1), R(5), R(-1)], [R(1), R(2), R(2)], [R(-2), R(2), R(-1)]]
    centre, radius = cga.sphere_center_radius(cga.sphere_from_points(*pts))
    assert list(centre) == [1, 2, -1] and radius == 3
    cc, rr, _ = cga.circle_center_radius(cga.circle_from_points(*pts[:3]))
    tc, tr2, _ = circumcircle([[float(v) for v in q] for q in pts[:3]])
    assert list(cc) == [sp.Rational(v.numerator, v.denominator) for v in tc]
    assert sp.simplify(rr**2 - sp.Rational(tr2.numerator, tr2.denominator)) == 0
    p1, p2 = cga.point_pair_endpoints(cga.point_pair(pts[0], pts[1]))
    assert list(p1) == pts[0] and list(p2) == pts[1]
    x = sp.symbols("x", real=True)
    dist = cga.point_line_distance([x, R(1), R(0)], cga.line_from_points(pts[0], pts[3]))
    assert sp.simplify(dist**2 - (1 + 1)) == 0  # the line y = 2, z = -1: distance^2 = 1 + 1


# ------------------------------------------------------------ plain blades
def test_plain_blades_keep_the_storage_limit():
    """Without its frame, the blade of an entity (its global coefficients) holds rho^2 to the storage limit of
    :mod:`cga_lessons.conformal.entities_frame`, 16 eps (|p|^2 + rho^2 + 1) absolute (a pair's half separation^2 to
    8 eps (|m|^2 + h^2)): 1e6 out that is far above 1e-9 of a unit round, and the error does reach beyond 1e-9.  A
    raw wedge of plain points, ``up(a) ^ up(b) ^ up(c) ^ up(d)``, carries the points' frame
    (:mod:`cga_lessons.conformal.point_wedges`): rho^2 of a unit sphere within a few eps at 1e2, 1e3 and 1e6; its
    coefficients alone, the frame dropped, carry the products' round-off besides: off by up to ~1e-6 at 100 and
    ~0.1 at 1000 from the origin (the docstring's numbers)."""
    worst, raw, dropped = 0.0, {2.0: 0.0, 3.0: 0.0, 6.0: 0.0}, {2.0: 0.0, 3.0: 0.0}
    for seed in range(20):
        for off in (0.0, 2.0, 3.0, 4.5, 6.0):
            c, size, pts = layout(seed, off, 0.0)
            tc, tr2 = circumsphere(pts)
            cc, cr2, _ = circumcircle(pts[:3])
            m, s2 = (pts[0] + pts[1]) / 2, dot(sub(fr(pts[0]), fr(pts[1])), sub(fr(pts[0]), fr(pts[1])))
            cases = (
                (cga.sphere_center_radius, cga.sphere_from_points(*pts), flt(tc), float(tr2), 16),
                (cga.circle_center_radius, cga.circle_from_points(*pts[:3]), flt(cc), float(cr2), 16),
                (lambda X: cga.sphere_center_radius(cga.point_pair_sphere(X)), cga.point_pair(*pts[:2]), m,
                 float(s2 / 4), 8),
            )  # fmt: skip
            for read, X, p, r2, k in cases:
                plain = Multivector(cga.G41, dict(X.coeffs))
                radius = read(plain)[1]
                err = abs(radius * radius - r2)
                assert err <= k * EPS * (p @ p + r2 + 1) + 4 * EPS * r2
                if off == 6.0:
                    worst = max(worst, err / r2)
            if off in raw:
                W = cga.up(pts[0]) ^ cga.up(pts[1]) ^ cga.up(pts[2]) ^ cga.up(pts[3])
                raw[off] = max(raw[off], abs(cga.sphere_center_radius(W)[1] ** 2 - float(tr2)) / float(tr2))
            if off in dropped:
                W = Multivector(cga.G41, dict(W.coeffs))  # the frame dropped: the plain wedge's coefficients
                dropped[off] = max(dropped[off], abs(cga.sphere_center_radius(W)[1] ** 2 - float(tr2)))
    assert worst > 1e3 * REL  # the limit is real: 1e6 out a plain unit round is off by more than 1e-6
    assert max(raw.values()) <= 16 * EPS  # through the points' frame: exact at every distance
    assert dropped[2.0] <= 1e-5 and 1e3 * REL < dropped[3.0] <= 1.0  # without it: the storage limit, and it is real
