"""Anchored entities under the versors that are no isometry (cga_lessons.conformal.anchored_versors): a dilation and
the similarities it makes with a motor or a reflection, an inversion times a motor, an inversion in a small sphere
far out; and the honest square of a far sphere in its inverse (cga_lessons.algebra.inverse.vector_square).

Truth: exact rationals (fractions.Fraction) as in test_entities_at_scale.py: the entity's points are the floats
handed to the library, their images under the exact map (the dilation's own centre and factor, the motor's own
(R, t), the plane and the sphere as stored) are exact, the circumsphere and circumcircle of the images by Cramer's
rule, square roots in mpmath.  Properties within 1e-9 of their size, positions besides within a few ulp of the
coordinates involved (``close_pos``).  The global coefficients are those of the plain apply, bit for bit.

Before: apply of these dropped the frame (the global blade 1e6 out holds a unit sphere's radius to ~1e-4; a
dilated sphere read as imaginary), and a unit sphere 1e6 out was refused as having no inverse, or its V ~V was
garbage (-4e6 for a squared radius of 0.66): the tables sum the squares of its 5e11-sized e+/e- coefficients.
"""

from fractions import Fraction as Fr

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from test_anchored import NEAR, about_anchor, entities, floats, invert_exact, reflect_exact, same_bits, size
from test_entities_at_scale import EPS, REL, close_pos, cross, dot, fr, fsqrt, layout, one_blade, solve3, sub

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, Multivector
from cga_lessons.conformal.anchored import Anchored, frame

G41 = cga.G41


# ------------------------------------------------------------------------- exact geometry
def sphere_through(pts):
    """Centre and squared radius of the sphere through four exact points (Cramer's rule)."""
    a = pts[0]
    rows = [[2 * (x - y) for x, y in zip(q, a)] for q in pts[1:]]
    c = solve3(rows, [dot(q, q) - dot(a, a) for q in pts[1:]])
    return c, dot(sub(a, c), sub(a, c))


def circle_through(pts):
    """Centre and squared radius of the circle through three exact points."""
    a, b, c = pts
    n = cross(sub(b, a), sub(c, a))
    rows = [[2 * (x - y) for x, y in zip(b, a)], [2 * (x - y) for x, y in zip(c, a)], n]
    centre = solve3(rows, [dot(b, b) - dot(a, a), dot(c, c) - dot(a, a), dot(n, a)])
    return centre, dot(sub(a, centre), sub(a, centre))


def rigid_exact(V):
    """The exact map x -> R x + t of a motor's own (R, t) (2.102), read by the library as floats."""
    R, t = G41.rigid_motion(V)
    Rf, tf = [[Fr(float(v)) for v in row] for row in R], [Fr(float(v)) for v in t]
    return lambda x: [sum(Rf[i][k] * x[k] for k in range(3)) + tf[i] for i in range(3)]


def dilation_exact(centre, s):
    d, s = fr(centre), Fr(s)
    return lambda x: [a + s * (b - a) for a, b in zip(d, x)]


def check_images(V, pts, image, far):
    """apply(V, X) of the sphere, circle and point pair through ``pts`` keeps the frame, gives the plain bits and
    the exact images' centre, radius and ends (``image``: the exact point map)."""
    S, Z, PP = cga.sphere_from_points(*pts), cga.circle_from_points(*pts[:3]), cga.point_pair(*pts[:2])
    imgs = [image(fr(p)) for p in pts]
    for X in (S, Z, PP):
        Y = cga.apply(V, X)
        assert type(Y) is Anchored and frame(Y)[0] is not None
        assert same_bits(Y, cga.apply(V, X.plain()))  # the global coefficients: the plain apply's
    tc, tr2 = sphere_through(imgs)
    centre, radius = cga.sphere_center_radius(cga.apply(V, S))
    rho = fsqrt(tr2)
    assert close_pos(centre, floats(tc), rho, far) and abs(radius - rho) <= REL * rho
    cc, cr2 = circle_through(imgs[:3])
    centre, radius, _ = cga.circle_center_radius(cga.apply(V, Z))
    rho = fsqrt(cr2)
    assert close_pos(centre, floats(cc), rho, far) and abs(radius - rho) <= REL * rho
    ends = cga.point_pair_endpoints(cga.apply(V, PP))
    want = [floats(v) for v in imgs[:2]]
    sep = float(np.linalg.norm(want[0] - want[1]))
    if not close_pos(ends[0], want[0], sep, far):
        ends = ends[::-1]
    assert close_pos(ends[0], want[0], sep, far) and close_pos(ends[1], want[1], sep, far)


def unit_vector(rng):
    u = rng.normal(size=3)
    return u / np.linalg.norm(u)


# ---------------------------------------------------------------- dilations and similarities
KINDS = ["D", "D R", "R D", "D0 M", "M D0", "P D0", "D0 P"]


@settings(max_examples=60, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.floats(3.0, 6.0),
    st.floats(-1.0, 2.0),
    st.floats(-1.0, 1.0),  # s = 1 included: dilator(1.0, c) is 1 exactly (closed form, test_versors_far.py)
    st.sampled_from(KINDS),
)
def test_a_dilation_and_its_similarities_keep_the_frame_far_out(seed, log_off, log_size, log_s, kind):
    """A sphere, circle and point pair 1e3 to 1e6 out (sizes 0.1-100) under a dilation by 0.1-10 (the dilator:
    not numbered in the thesis; D = exp(-ln(s)/2 E), E of 2.55) about a centre near them or about the origin, and
    under its products with a motor (2.102) or a reflection in a plane (2.89-2.91): the images' centres, radii and
    ends within 1e-9 of the exact ones.  A factor with a far centre times one about the origin: the float product
    of two versors that both move the origin by |t1| and |t2| rounds its coefficients by eps |t1| |t2| (e e = 0
    summed as e+ e+ + e- e-), which turns its rotation part by that much, moving points |x| out by eps |t1| |t2|
    |x|: that versor itself no longer holds the motion to 1e-9."""
    c, size, pts = layout(seed, log_off, log_size)
    rng = np.random.default_rng(seed + 1)
    s = 10.0**log_s
    rot = cga.rotor(unit_vector(rng), rng.uniform(-3, 3))
    far_motor = cga.motor(unit_vector(rng), rng.uniform(-3, 3), unit_vector(rng) * 10 ** rng.uniform(3, 6))
    a, b, d = (c + size * rng.uniform(-2, 2, size=3) for _ in range(3))
    Pd = cga.plane_from_points(a, b, d)
    P = cga.standard_form(Pd)
    near = c + size * rng.uniform(0.5, 3.0) * unit_vector(rng)
    if kind == "D R":  # the dilation's centre near the turned entity
        near = floats(rigid_exact(rot)(fr(c))) + size * rng.uniform(0.5, 3.0) * unit_vector(rng)
    D, D0 = cga.dilator(s, near), cga.dilator(s)
    dil, dil0 = dilation_exact(near, s), dilation_exact([0.0, 0.0, 0.0], s)
    mirror = lambda x: reflect_exact(Pd, x)  # noqa: E731
    V, image = {
        "D": (D, dil),
        "D R": (D * rot, lambda x: dil(rigid_exact(rot)(x))),
        "R D": (rot * D, lambda x: rigid_exact(rot)(dil(x))),
        "D0 M": (D0 * far_motor, lambda x: dil0(rigid_exact(far_motor)(x))),
        "M D0": (far_motor * D0, lambda x: rigid_exact(far_motor)(dil0(x))),
        "P D0": (P * D0, lambda x: mirror(dil0(x))),
        "D0 P": (D0 * P, lambda x: dil0(mirror(x))),
    }[kind]
    far = 4 * (np.linalg.norm(c) + np.linalg.norm(floats(image(fr(c)))) + size)
    check_images(V, pts, image, far)


def test_a_dilation_far_out_was_the_storage_limit():
    """The plain blade of a dilated unit-size sphere 1e6 out reads as an imaginary sphere or off by far more than
    1e-9: what the frame removes."""
    c = np.array([0.6e6, -0.48e6, 0.64e6]) + [0.1234567, 0.7654321, -0.3141592]
    X = cga.sphere(c + [3.0, 0.0, 0.0], 0.5)
    Y = cga.apply(cga.dilator(2.0, c), X)
    centre, radius = cga.sphere_center_radius(Y)
    assert np.linalg.norm(centre - (c + [6.0, 0.0, 0.0])) <= 8 * EPS * 1e6 and abs(radius - 1.0) <= 4 * EPS
    try:
        _, plain_radius = cga.sphere_center_radius(Y.plain())
        assert abs(plain_radius - 1.0) > 1e-6
    except DegenerateGeometryError:  # s^2 < 0: read as imaginary
        pass


# -------------------------------------------------------------------- an inversion times a motor
#: rotors with small integer coefficients (1, e12, e13, e23): with coordinates on a grid of 1/4, the products
#: S M and M S are exact in floats, so the versor holds its geometry exactly (checked) and the truth is exact.
ROTORS = [(1, 0, 0, 0), (1, 1, 0, 0), (1, 0, 1, 0), (0, 0, 0, 1), (1, 1, 1, 1), (1, -1, 0, 1), (0, 1, -1, 0)]


def rotation_exact(r):
    """The rotation matrix (Fractions) of the rotor ``r0 + r12 e12 + r13 e13 + r23 e23`` (2.96: the quaternion
    (w, x, y, z) = (r0, -r23, r13, -r12)), divided by its squared norm."""
    w, x, y, z = (Fr(v) for v in (r[0], -r[3], r[2], -r[1]))
    n = w * w + x * x + y * y + z * z
    return [
        [(w * w + x * x - y * y - z * z) / n, 2 * (x * y - z * w) / n, 2 * (x * z + y * w) / n],
        [2 * (x * y + z * w) / n, (w * w - x * x + y * y - z * z) / n, 2 * (y * z - x * w) / n],
        [2 * (x * z - y * w) / n, 2 * (y * z + x * w) / n, (w * w - x * x - y * y + z * z) / n],
    ]


def on_grid(v, g=0.25):
    return np.rint(np.asarray(v) / g) * g


def exact_product(A, B):
    """The product of two float multivectors in exact rationals (SymPy), as a dict blade -> Rational."""
    ex = [Multivector(G41, {k: sp.Rational(Fr(float(v))) for k, v in X.coeffs.items()}) for X in (A, B)]
    return {k: v for k, v in (ex[0] * ex[1]).coeffs.items() if v != 0}


@settings(max_examples=80, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.floats(3.0, 6.0),
    st.floats(-1.0, 2.0),
    st.booleans(),
    st.sampled_from(["home", "turn", "far"]),
)
def test_an_inversion_times_a_motor_keeps_the_frame_far_out(seed, log_off, log_size, motor_first, where):
    """V = S M (the motor first) or M S, with S a sphere near the entity's image (2.72, 2.84-2.88) and M a motor
    (2.102) that carries the entity 1e3-1e6 out to near the origin (``home``), turns it about the origin with a
    small translation (``turn``) or carries it as far elsewhere (``far``): the images' centres, radii and ends within
    1e-9 of the exact ones.  V is exact in floats (checked), and the truth is the exact map of its own factors; a
    float product of a sphere and a motor that both reach 1e6 is not (e e = 0 summed as e+ e+ + e- e- rounds
    |c|^3-sized terms, and its e0 part, the rotor, is held to eps |c|^2 only): those cases are left out."""
    c, size, pts = layout(seed, log_off, log_size)
    rng = np.random.default_rng(seed + 11)
    rot = ROTORS[rng.integers(len(ROTORS))]
    Rx = rotation_exact(rot)
    turn = lambda x: [sum(Rx[i][k] * x[k] for k in range(3)) for i in range(3)]  # noqa: E731
    target = {
        "home": rng.uniform(-5, 5, size=3),
        "turn": floats(turn(fr(c))) + rng.uniform(-5, 5, size=3),
        "far": unit_vector(rng) * 10**log_off,
    }[where]
    t = on_grid(target - floats(turn(fr(c))))
    M = cga.translator(t) * Multivector(G41, {b: float(v) for b, v in zip((0, 3, 5, 6), rot) if v})
    assert np.allclose(G41.rigid_motion(M)[0], np.array(Rx, dtype=float), rtol=0, atol=1e-15)
    motion = lambda x: [a + Fr(float(b)) for a, b in zip(turn(x), t)]  # noqa: E731
    centre_at = floats(motion(fr(c))) if motor_first else c
    p = on_grid(centre_at + max(size * rng.uniform(2.5, 4.0), 1.0) * unit_vector(rng))
    r2 = max(float(on_grid(size * size * rng.uniform(0.25, 4.0), 1 / 16)), 1 / 16)
    beta = 0.5 * (p @ p - r2)
    S = Multivector(G41, {1: p[0], 2: p[1], 4: p[2], 8: beta - 0.5, 16: beta + 0.5})
    V = S * M if motor_first else M * S
    exact = exact_product(S, M) if motor_first else exact_product(M, S)
    assume({k: Fr(float(v)) for k, v in V.coeffs.items() if v} == {k: Fr(v.p, v.q) for k, v in exact.items()})
    fp, fr2 = fr(p), Fr(r2)
    if motor_first:
        image = lambda x: invert_exact(fp, fr2, motion(x))  # noqa: E731
    else:
        image = lambda x: motion(invert_exact(fp, fr2, x))  # noqa: E731
    far = 4 * (np.linalg.norm(c) + np.linalg.norm(p) + np.linalg.norm(t) + np.linalg.norm(floats(image(fr(c)))))
    check_images(V, pts, image, far)


# ------------------------------------------------------------------ near the origin: the frame is the blade's
def products():
    """The new versors near NEAR, by name: dilations, similarities, an inversion times a motor."""
    M = cga.motor([0.3, 1, -0.2], 0.8, [1.0, -2.0, 0.5])
    D = cga.dilator(1.7, NEAR[0] + [0.5, -0.2, 0.3])
    S = cga.sphere(NEAR[0] + [1.5, -0.5, 0.4], 1.3)
    P = cga.standard_form(cga.plane_from_points(NEAR[0] + [1, 0, 0], NEAR[0] + [0, 1.2, 0.3], NEAR[0] + [0.2, 0, 1]))
    return {
        "dilation": D,
        "dilation about the origin": cga.dilator(0.6),
        "dilation * motor": D * M,
        "motor * dilation": 2.0 * M * D,
        "plane * dilation": P * D,
        "dilation * plane * motor": D * P * M,
        "sphere * motor": S.plain() * M,
        "motor * sphere": M * S.plain(),
        "imaginary sphere * motor": (cga.up(NEAR[1]) + 0.8 * cga.einf) * M,
    }


@pytest.mark.parametrize("name", list(products()))
def test_the_new_versors_keep_the_frame_and_give_the_plain_bits(name):
    """As for the reflections and inversions in test_anchored.py: the global coefficients are the plain apply's,
    bit for bit; the anchor is the image of X's anchor, the local blade the result about it (2.100); the dual form,
    a motion that follows, and a batch keep it."""
    V = products()[name]
    M = cga.motor([1, 0, 0], 0.4, [0.5, 0.2, -1.0])
    for xname, X in entities(NEAR).items():
        Y = cga.apply(V, X)
        assert type(Y) is Anchored, (name, xname)
        assert same_bits(Y, cga.apply(V, X.plain())), (name, xname)
        # apply_to_points of an inversion goes through the tables' product, round-off ~1e-11 here
        assert np.allclose(Y.anchor, cga.apply_to_points(V, X.anchor), rtol=0, atol=1e-10), (name, xname)
        for Z in (Y, cga.dual_form(Y), cga.apply(M, Y), cga.apply(V, cga.apply(M, X))):
            assert type(Z) is Anchored and frame(Z)[0] is not None, (name, xname)
            scale = max(size(Z.local), size(Multivector(G41, dict(Z.coeffs))))
            assert about_anchor(Z).isclose(Z.local, rtol=0.0, atol=1e-11 * scale), (name, xname)
    Xs = cga.sphere(NEAR, [0.3, 0.4, 0.5, 0.6])
    Y = cga.apply(V, Xs)
    for i in range(4):
        Yi = cga.apply(V, Xs.batch_item(i))
        assert Y.batch_item(i).isclose(Yi) and Y.local.batch_item(i).isclose(Yi.local, atol=1e-13)
        assert np.allclose(Y.anchor[i], Yi.anchor, rtol=0, atol=1e-13)


def test_near_the_origin_an_inversion_keeps_the_tables_bits():
    """Where the tables resolve V ~V (within 1e-12 of it) apply is what it was: the product with the tables'
    matrices, bit for bit; far out it is the product of the factors."""
    for V in (products()["sphere * motor"], products()["motor * sphere"], cga.sphere(NEAR[0], 1.3)):
        for X in entities(NEAR).values():
            X = X.plain()
            want = G41.apply_matrices(G41.versor_matrices(V, X.grades_present()), X)
            assert same_bits(cga.apply(V, X), want)


# ------------------------------------------------------------------------- a small sphere far out
def far_scene(off):
    c = off * np.array([0.6, -0.48, 0.64]) + [0.1234567, 0.7654321, -0.3141592]
    return c, cga.sphere(c, 1.0), cga.sphere(c + [3.0, 0.0, 0.0], 0.5)


@pytest.mark.parametrize("off", [1e3, 1e4, 1e5, 1e6])
def test_a_unit_sphere_far_out_inverts_plain_or_anchored(off):
    """A unit sphere 1e3-1e6 out (2.84-2.88), anchored or plain, standard or dual form: apply never refuses it.
    Anchored: the image of an anchored sphere exact (1e-9), its global blade the local one translated back (one
    entity: the factors' product, no garbage scale); plain: the image as exact as the plain sphere holds its
    radius (eps |c|^2)."""
    c, S, X = far_scene(off)
    a, b = 1 / 2.5, 1 / 3.5  # the images of c + 2.5 e1 and c + 3.5 e1, the sphere's ends on its axis
    want, rho = c + [(a + b) / 2, 0.0, 0.0], (a - b) / 2
    for V in (S, cga.dual_form(S), S.plain(), cga.dual_form(S).plain()):
        for act in (cga.apply, cga.invert_in_sphere):
            Y = act(V, X)
            assert type(Y) is Anchored and same_bits(Y, act(V, X.plain()))
            assert one_blade(Y)
            centre, radius = cga.sphere_center_radius(Y)
            tol = REL if type(V) is Anchored else REL + 64 * EPS * off**2
            assert close_pos(centre, want, tol * rho, 4 * off) and abs(radius - rho) <= tol * rho
    Y = cga.apply(S.plain(), cga.up(c + np.array([[2.5, 0.0, 0.0], [0.0, 2.0, 0.0]])))  # plain points: no refusal
    assert np.all(np.isfinite(Y.to_array()))


@pytest.mark.parametrize("off", [1.0, 1e3, 1e6])
def test_a_sphere_of_radius_zero_has_no_inverse(off):
    """A null sphere (a point, 2.62) is no versor, near or far, anchored or plain, either form: the package's
    DegenerateGeometryError (a ValueError), naming the function and the argument."""
    c, _, X = far_scene(off)
    for V in (cga.sphere(c, 0.0), cga.sphere(c, 0.0).plain(), cga.up(c), cga.dual_form(cga.sphere(c, 0.0))):
        with pytest.raises(DegenerateGeometryError, match=r"^apply: V: has no inverse"):
            cga.apply(V, X)
        with pytest.raises(ValueError, match=r"^invert_in_sphere: S: has no inverse"):
            cga.invert_in_sphere(V, X)
    if off == 1.0:  # far out the float product of a point and a motor rounds to a non-null versor, taken as stored
        with pytest.raises(DegenerateGeometryError, match=r"^apply: V: has no inverse"):
            cga.apply(cga.up(c) * cga.motor([0, 0, 1], 0.3, [1.0, 2.0, 3.0]), X)


def test_the_inverse_of_a_far_sphere_uses_its_honest_square():
    """``S.inv() = S / S^2`` (2.19): the square of a sphere 1e6 out summed from its squared coefficients is
    round-off (the e+/e- coefficients are 5e11); paired, (e+ - e-)(e+ + e-), it is the squared radius to the
    sphere's own accuracy, eps |c|^2.  A null vector (a point) still has no inverse; a batch likewise; near the
    origin the bits are those of the product."""
    c, S, _ = far_scene(1e6)
    for r in (1.0, 0.2):
        Sp = cga.sphere(c, r).plain()
        k = Sp.inv().coeffs[1] / Sp.coeffs[1]  # 1 / S^2
        assert abs(1 / k - r * r) <= 16 * EPS * 2e12
    with pytest.raises(DegenerateGeometryError, match="null and has no inverse"):
        cga.up(c).inv()
    B = cga.sphere(np.stack([c, 2 * c, c / 1e6]), [1.0, 2.0, 0.5]).plain()
    k = B.inv().coeffs[1] / B.coeffs[1]
    assert np.all(np.abs(1 / k - [1.0, 4.0, 0.25]) <= 16 * EPS * 8e12)
    with pytest.raises(DegenerateGeometryError, match="null and has no inverse"):
        cga.up(np.stack([c, c / 1e6])).inv()
    rng = np.random.default_rng(5)
    for _ in range(20):
        v = Multivector(G41, {b: rng.normal() for b in (1, 2, 4, 8, 16)})
        d = (v * ~v).coeffs[0]  # the product's square, sound here: the inverse as before (2.19), bit for bit
        assert same_bits(v.inv(), Multivector(G41, {b: x / d for b, x in (~v).coeffs.items()}))


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 3.0, 5.0, 6.0]), st.booleans())
def test_two_inversions_as_one_versor_are_exact_far_out(seed, log_off, plain_x):
    """S1 S2 (two anchored spheres multiplied: a conformal map that moves infinity, 2.84-2.88) applied to a sphere
    near them up to 1e6 out: the versor's global coefficients lose its scalar S1 . S2 there (a difference of
    |c|^4-sized terms; they read as a motor), so it is applied in its own frame (2.82, 2.100): the image's radius
    within 1e-9 of the exact one (the images of the four points under S2, then S1, in exact rationals), the frame
    kept.  Before: radius off by up to 4x 1e6 out (read as a motor); plain X (its coefficients moved into the
    versor's frame) gives a plain result, as accurate as X's own storage (checked at the origin only: further out
    the inversion magnifies that storage's limit)."""
    rng = np.random.default_rng(seed)
    far = 10.0**log_off if log_off else 0.0
    c = far * np.array([0.6, 0.8, 0.0])
    c1, c2 = c + rng.normal(size=3), c + rng.normal(size=3)
    r1, r2 = rng.uniform(0.5, 3.0, size=2)
    V = cga.sphere(c1, r1) * cga.sphere(c2, r2)
    pts = [c + rng.normal(size=3) * 3 for _ in range(4)]
    X = cga.sphere_from_points(*pts)
    q1, q2 = Fr(float(r1)) ** 2, Fr(float(r2)) ** 2
    imgs = [invert_exact(fr(c1), q1, invert_exact(fr(c2), q2, fr(p))) for p in pts]
    _, tr2 = sphere_through(imgs)
    plain_x = plain_x and far == 0.0
    Y = cga.apply(V, X.plain() if plain_x else X)
    rho = fsqrt(tr2)
    assert abs(cga.sphere_center_radius(Y)[1] - rho) <= REL * rho
    assert (type(Y) is Multivector) if plain_x else (type(Y) is Anchored and frame(Y)[0] is not None)
