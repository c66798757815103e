"""Versors far from the origin that are no motor: similarities (a dilation, its products with a motor or a reflection),
reflections in far planes (2.89-2.91), the dilator about a far centre, spheres (2.84-2.88); issue 16.

Truth: for points, the exact maps of the factors (a plane's reflection x -> x - 2 (n . x - delta) n, the dilation
x -> c + s (x - c), a motor's own (R, t)) composed in rationals (fractions.Fraction) on the floats handed to the
library; for matrices and coefficients, the versor as stored (its float coefficients as exact SymPy rationals)
applied exactly, ``V X^ V^-1`` (2.82) with ``V^-1 = ~V / (V ~V)`` (V ~V an exact scalar for those, checked).  Points
within 1e-9 of the truth relative to the size of the points involved.

Before: ``_rigid_affine`` took a reflection times a dilation 1e6 out for an isometry (its tolerance scaled with the
|t|^2-sized entries of the 5x5 matrix): ``apply_to_points(dilator(10) * plane(e3, 1e6), [1, 2, 3])`` returned
(1, 2, 2.0008e6) for 10 (1, 2, 2e6 - 3); ``rigid_motion`` weighed the E = e+e- part of ``T_t D_s`` against the
largest coefficient (|t|/2) and passed it for a motor up to s = 1.02 1e6 out; ``dilator(1.0, c)`` was off the
identity by up to 1.2e-4 1e6 out (round-off of the product T_c D ~T_c); ``versor_matrix`` of a sphere 1e3 out
divided by the tables' ``V ~V``, 1 % off.
"""

from fractions import Fraction as Fr

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from test_entities_at_scale import EPS, REL

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector

G41 = cga.G41


# ------------------------------------------------------------------------------------ exact truth
def exact(V: Multivector) -> Multivector:
    """The multivector with V's float coefficients as exact rationals."""
    return Multivector(G41, {b: sp.Rational(Fr(float(v))) for b, v in V.coeffs.items()})


def exact_action(V: Multivector):
    """``X -> V X^ V^-1`` (2.82) in exact rationals for the stored V (V ~V an exact non-zero scalar)."""
    Vx = exact(V)
    VV = (Vx * ~Vx).coeffs
    assert set(k for k, v in VV.items() if v != 0) == {0}, "V ~V is no exact scalar"
    inv = ~Vx * (1 / VV[0])
    odd = all(G41.grades[b] % 2 for b in V.coeffs)

    def act(X: Multivector) -> Multivector:
        Xx = exact(X)
        return Vx * (Xx.involute() if odd else Xx) * inv

    return act


def close(got, want, xs) -> bool:
    scale = max(np.abs(want).max(), np.abs(xs).max(), 1.0)
    return float(np.abs(np.asarray(got) - want).max()) <= REL * scale


def unit(rng):
    u = rng.normal(size=3)
    return u / np.linalg.norm(u)


# ---------------------------------------------------------------------------------- item 1: points
KINDS = ["D0 P", "P D0", "Dc", "T D0", "D0 T", "R Dc", "Dc R", "P", "P M", "M P", "P D0 M"]


def plane_map(P):
    """The exact reflection in the stored plane ``n + delta e`` (2.89, 2.90): x -> x - 2 (n . x - delta) n / n^2."""
    n = [Fr(float(P.coeffs.get(b, 0.0))) for b in (1, 2, 4)]
    delta, nn = Fr(float(P.coeffs[8])), sum(v * v for v in n)
    return lambda x: [xi - 2 * (sum(a * b for a, b in zip(n, x)) - delta) * ni / nn for xi, ni in zip(x, n)]


def dilation_map(s, c=(0.0, 0.0, 0.0)):
    cf, sf = [Fr(float(v)) for v in c], Fr(s)
    return lambda x: [a + sf * (b - a) for a, b in zip(cf, x)]


def rigid_map(V):
    """The exact map x -> R x + t of a motor's own (R, t) (2.102, read by rigid_motion as floats)."""
    R, t = G41.rigid_motion(V)
    Rf, tf = [[Fr(float(v)) for v in row] for row in R], [Fr(float(v)) for v in t]
    return lambda x: [sum(Rf[i][k] * x[k] for k in range(3)) + tf[i] for i in range(3)]


def versor_of(kind, rng, off, s):
    """A versor with one factor ``off`` out (a plane, a translation or a dilation's centre), the others about the
    origin or near it (the float product of two factors that both reach far rounds its coefficients by
    eps |t1| |t2|, test_anchored_versors.py: no longer the versor meant), and its exact point map, the factors'
    maps composed (the right factor acts first)."""
    P = cga.plane(unit(rng), off)  # n + delta e, 2.89
    c = off * unit(rng)
    D0, Dc = cga.dilator(s), cga.dilator(s, c)
    T = cga.translator(off * unit(rng))  # 2.100
    R = cga.rotor(unit(rng), rng.uniform(-3, 3))
    M = cga.motor(unit(rng), rng.uniform(-3, 3), rng.normal(size=3))  # 2.102
    maps = {"P": plane_map(P), "D0": dilation_map(s), "Dc": dilation_map(s, c), "T": rigid_map(T)}
    maps.update(R=rigid_map(R), M=rigid_map(M))
    versors = {"P": P, "D0": D0, "Dc": Dc, "T": T, "R": R, "M": M}
    names = kind.split()
    V = versors[names[0]]
    for n in names[1:]:
        V = V * versors[n]

    def image(x):
        y = [Fr(float(v)) for v in x]
        for n in reversed(names):
            y = maps[n](y)
        return np.array([float(v) for v in y])

    return V, image


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(3.0, 6.0), st.floats(-3.0, 3.0), st.sampled_from(KINDS))
def test_apply_to_points_of_far_similarities_and_reflections_is_exact(seed, log_off, log_s, kind):
    """A similarity (x -> s R x + t) or an odd isometry 1e3 to 1e6 out, s in [1e-3, 1e3]: apply_to_points within
    1e-9 of the exact image (the factors' maps: 2.89-2.91, 2.100, 2.102 and the dilator), for points near the
    origin and near the far factor; it is no motor (rigid_motion refuses it)."""
    rng = np.random.default_rng(seed)
    off = 10.0**log_off
    s = 10.0**log_s
    V, image = versor_of(kind, rng, off, s)
    xs = np.vstack([rng.normal(size=(2, 3)), off * unit(rng) + rng.normal(size=(2, 3))])
    want = np.array([image(x) for x in xs])
    assert close(cga.apply_to_points(V, xs), want, xs), kind
    assert close(cga.apply_to_points(V, xs[0]), want[0], xs), kind
    assert G41.rigid_motion(V) is None or (s == 1.0 and "P" not in kind)  # s = 1: a motor


def test_the_reported_reflection_times_dilation():
    """The case of the issue: a dilation by 10 after the reflection in the plane z = 1e6 (2.89, 2.90)."""
    V = cga.dilator(10.0) * cga.plane([0, 0, 1], 1e6)
    want = 10.0 * np.array([1.0, 2.0, 2e6 - 3.0])
    got = cga.apply_to_points(V, [1.0, 2.0, 3.0])
    assert np.abs(got - want).max() <= REL * np.abs(want).max()
    # the anchored sphere keeps its frame: its image read exactly
    centre, radius = cga.sphere_center_radius(cga.apply(V, cga.sphere([1.0, 2.0, 3.0], 0.5)))
    assert np.abs(centre - want).max() <= REL * np.abs(want).max() and abs(radius - 5.0) <= REL * 5.0


@pytest.mark.parametrize("off", [1e3, 1e6])
@pytest.mark.parametrize("s", [1.001, 1.000001, 0.999, 2.0])
def test_a_translated_dilation_is_no_motor(off, s):
    """``T_t D_s`` (2.100 times the dilator) has an E = e+e- part ``rho |R|`` (rho = (s - 1) / (s + 1)) at any
    distance: rigid_motion weighs it against the rotor, so it is no motor; motor_to_matrix and motor_log refuse
    it, and apply_to_points maps by ``x -> s x + t`` (before: a motor, x -> x + t', up to s = 1.02 1e6 out)."""
    t = off * np.array([0.6, -0.48, 0.64])
    x = np.array([[1.0, 2.0, 3.0], [-4.0, 0.5, 2.0]]) + t
    for V, want in ((cga.translator(t) * cga.dilator(s), s * x + t), (cga.dilator(s) * cga.translator(t), s * (x + t))):
        assert G41.rigid_motion(V) is None
        with pytest.raises(InvalidInputError, match="^motor_to_matrix: M: "):
            cga.motor_to_matrix(V)
        with pytest.raises(InvalidInputError, match="^motor_log: M: not a motor"):
            cga.motor_log(V)
        assert np.abs(cga.apply_to_points(V, x) - want).max() <= 1e-12 * np.abs(want).max()


def test_products_of_motors_near_the_origin_are_still_motors():
    """The tolerance for round-off in the E and e+/e- parts of a product of motors (2.99) now scales with the
    rotor, not with the largest coefficient: products up to 1e3 out stay motors (test_versors_at_scale.py)."""
    rng = np.random.default_rng(3)
    for scale in (1.0, 1e2, 1e3):
        for _ in range(20):
            Ms = [cga.motor(unit(rng), rng.uniform(-3, 3), rng.normal(size=3) * scale) for _ in range(4)]
            assert G41.rigid_motion(Ms[0] * Ms[1] * Ms[2] * Ms[3]) is not None


# -------------------------------------------------------------------------- item 2: the dilator
@settings(max_examples=80, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 6.0), st.floats(-3.0, 3.0), st.floats(-2.0, 3.0))
def test_the_dilator_about_a_far_centre_is_exact(seed, log_c, log_s, log_size):
    """``D_c = a - b E - b e ^ c`` (T_c D ~T_c written out; the dilator is not numbered in the thesis, Dorst,
    Fontijne & Mann 2007, ch. 16; T of 2.100): apply_to_points within 1e-9 of ``c + s (x - c)`` (exact) for |c| up
    to 1e6, s in [1e-3, 1e3], points near c and near the origin; its scalar and E parts are those of the dilator
    about the origin, bit for bit (no |c|^2-sized terms), and its e+ and e- parts equal (it fixes e)."""
    rng = np.random.default_rng(seed)
    c, s, size = 10.0**log_c * unit(rng), 10.0**log_s, 10.0**log_size
    D = cga.dilator(s, c)
    xs = np.vstack([c + size * rng.normal(size=(3, 3)), rng.normal(size=(1, 3))])
    cf, sf = [Fr(float(v)) for v in c], Fr(s)
    want = np.array([[float(a + sf * (Fr(float(b)) - a)) for a, b in zip(cf, x)] for x in xs])
    assert close(cga.apply_to_points(D, xs), want, xs)
    D0 = cga.dilator(s)
    assert D.coeffs[0] == D0.coeffs[0] and D.coeffs.get(24, 0.0) == D0.coeffs.get(24, 0.0)
    assert all(D.coeffs.get(b | 8, 0.0) == D.coeffs.get(b | 16, 0.0) for b in (1, 2, 4))


@pytest.mark.parametrize("c", [[123456.7, -234567.8, 345678.9], [1e6, 2e5, -3e5], [-5.7e5, 6.1e5, 5.5e5]])
def test_the_dilator_by_one_is_the_identity_anywhere(c):
    """dilator(1.0, c) is 1 exactly (b = 0), wherever c is (before: about 1 - 1.2e-4 for some c 1e6 out)."""
    D = cga.dilator(1.0, c)
    assert D.coeffs == {0: 1.0}
    x = np.array([c, [1.0, 2.0, 3.0]])
    assert np.array_equal(cga.apply_to_points(D, x), x)


def test_random_far_centres_gave_no_identity_before():
    """The case the report could not find: c of random direction 1e6 out (the product T_c ~T_c rounds)."""
    rng = np.random.default_rng(1)
    for _ in range(8):
        c = unit(rng) * 1e6
        x = rng.normal(size=3) * 1e6
        assert np.array_equal(cga.apply_to_points(cga.dilator(1.0, c), x), x)


# ----------------------------------------------------------- item 3: versor_matrix, versor_matrices, >>
def exact_matrix(V, grade):
    act = exact_action(V)
    blades = G41.grade_blades[grade]
    cols = [act(Multivector(G41, {b: 1.0})).coeffs for b in blades]
    return [[sp.Rational(col.get(r, 0)) for col in cols] for r in blades]


FAR_VERSORS = {
    "sphere 1e3 out, radius 0.3": cga.sphere([1e3, -2e3, 5e2], 0.3).plain(),
    "sphere 1e6 out": cga.sphere([1e6, 2e5, -3e5], 1.0).plain(),
    "sphere 1e4 out, dual form": cga.dual_form(cga.sphere([1e4, 3e3, -2e3], 2.0)).plain(),
    "dilation times a plane 1e6 out": cga.dilator(10.0) * cga.plane([0, 0, 1], 1e6),
    "plane 1e4 out": cga.plane([0.0, 0.6, 0.8], 1e4),
    "dilator about a centre 1e5 out": cga.dilator(7.0, [3e4, -2e4, 8e4]),
}


@pytest.mark.parametrize("name", list(FAR_VERSORS))
@pytest.mark.parametrize("grade", [1, 2])
def test_versor_matrix_of_far_versors_against_exact(name, grade):
    """versor_matrix (2.82) of a versor whose V ~V the tables cannot resolve: every column within 1e-12 of its
    largest exact entry (before: the tables' V ~V, 0.0908 for 0.09 for the sphere 1e3 out, garbage 1e6 out).
    Algebra.versor_matrices returns None for it (no matrices divided by a V ~V lost to round-off)."""
    V = FAR_VERSORS[name]
    got = cga.versor_matrix(V, grade)
    want = exact_matrix(V, grade)
    for j in range(len(want)):
        col = [abs(Fr(float(got[i][j])) - Fr(str(want[i][j]))) for i in range(len(want))]
        size = max(abs(Fr(str(want[i][j]))) for i in range(len(want)))
        assert max(col) <= Fr(1e-12) * size, (name, j)
    assert G41.versor_matrices(V, (grade,)) is None


def test_near_the_origin_versor_matrices_are_the_tables():
    """Where the tables resolve V ~V nothing changed: versor_matrix is the tables' matrix."""
    for V in (cga.sphere([1.0, 2.0, -0.5], 1.3), cga.dilator(3.0, [0.5, 0.2, 0.1]), cga.plane([0, 0, 1], 2.0)):
        assert np.array_equal(cga.versor_matrix(V, 1), G41.versor_matrices(V, (1,))[1])


@pytest.mark.parametrize("name", list(FAR_VERSORS))
def test_the_sandwich_operator_is_v_x_rev_v_to_its_round_off(name):
    """``V >> X = V X ~V`` (2.98, 2.101, 2.103, as documented): it never divides by ``V ~V``, so a versor far out
    gives the product to the round-off of its terms, ``eps |V|^2 |X|`` (the plain product where V ~V rounds to
    0); apply is the normalised action, by the versor's factors."""
    V = FAR_VERSORS[name]
    Vx = exact(V)
    for X in (cga.up([1.0, 2.0, 3.0]), cga.line_from_points([0.0, 1.0, 0.0], [1.0, 1.0, 2.0]).plain()):
        got, want = V >> X, Vx * exact(X) * ~Vx
        size = sum(float(v) ** 2 for v in V.coeffs.values()) * max(abs(float(v)) for v in X.coeffs.values())
        keys = set(got.coeffs) | set(want.coeffs)
        err = max(abs(Fr(float(got.coeffs.get(b, 0.0))) - Fr(str(want.coeffs.get(b, 0)))) for b in keys)
        assert err <= Fr(64 * EPS) * Fr(size), name


@pytest.mark.parametrize("name", list(FAR_VERSORS))
def test_apply_of_far_versors_against_exact_coefficients(name):
    """apply (2.82) of a far versor to plain entities near the origin: the coefficients within 1e-12 of the largest
    exact one (the tables' garbage V ~V scaled them by up to 4e-3 for the dilation times the plane 1e6 out).  Down
    of a plain result with a weight other than 1 keeps the storage limit (eps |y|^2 of the weight)."""
    V = FAR_VERSORS[name]
    act = exact_action(V)
    for X in (cga.up([1.0, 2.0, 3.0]), cga.line_from_points([0.0, 1.0, 0.0], [1.0, 1.0, 2.0]).plain()):
        got, want = cga.apply(V, X), act(X)
        keys = set(got.coeffs) | set(want.coeffs)
        size = max(abs(Fr(str(v))) for v in want.coeffs.values())
        err = max(abs(Fr(float(got.coeffs.get(b, 0.0))) - Fr(str(want.coeffs.get(b, 0)))) for b in keys)
        assert err <= Fr(1e-12) * size, name


def test_a_product_of_far_motors_raises_instead_of_answering():
    """Three motors 1e6 out multiplied in floats (2.99) round their rotor by eps |t|^2 (~1e-4): no motor, and no
    versor to working precision (its V ~V lost to round-off): apply and apply_to_points raise, naming V, instead of
    the silently wrong map of the tables or the 32x32 solve."""
    rng = np.random.default_rng(7)
    M = cga.motor(unit(rng), 1.0, 1e6 * unit(rng))
    for _ in range(2):
        M = M * cga.motor(unit(rng), 1.0, 1e6 * unit(rng))
    with pytest.raises(InvalidInputError, match=r"^apply: V: V ~V = .* lost to the round-off"):
        cga.apply(M, cga.up([1.0, 2.0, 3.0]))
    with pytest.raises(InvalidInputError, match=r"^apply_to_points: V: V ~V = .* lost to the round-off"):
        cga.apply_to_points(M, [1.0, 2.0, 3.0])


@pytest.mark.parametrize("s", [1.001, 0.999, 2.0])
def test_decompose_motor_refuses_a_far_similarity(s):
    """A translator 1e6 out times a dilator (T_t D_s, a similarity: x -> s x + t) is no motor: decompose_motor
    (2.140-2.145) raises instead of the rigid part it read before (t = 999500 for s = 1.001, the truth's x being
    1.001e6 after the scaling), and why_not_motor names the dilation's E part, as rigid_motion weighs it (against
    the rotor's norm, not the largest coefficient that grows with t)."""
    M = cga.translator([1e6, 0.0, 0.0]) * cga.dilator(s)
    assert cga.G41.rigid_motion(M) is None
    why = cga.why_not_motor(M)
    assert "E = e+e- part" in why and "dilation" in why
    with pytest.raises(InvalidInputError, match=r"^decompose_motor: M: not a motor"):
        cga.decompose_motor(M)


def test_why_not_motor_agrees_with_rigid_motion_on_far_products_of_motors():
    """Products of four motors translating by up to 1e4 (their e+/e- round-off grows like eps |t|^2): why_not_motor
    and rigid_motion accept and refuse the same ones."""
    rng = np.random.default_rng(3)
    for size in (10.0, 1e3, 1e4):
        for _ in range(20):
            Ms = [cga.motor(unit(rng), rng.uniform(0, 3), size * unit(rng)) for _ in range(4)]
            M = Ms[0] * Ms[1] * Ms[2] * Ms[3]
            assert (cga.why_not_motor(M) == "") == (cga.G41.rigid_motion(M) is not None)


def exact_inversion(c, r2, x):
    """x inverted in the sphere of centre c and squared radius r2 (2.84-2.88), in exact rationals."""
    d = [Fr(float(a)) - Fr(float(b)) for a, b in zip(x, c)]
    dd = sum(v * v for v in d)
    return [Fr(float(ci)) + Fr(r2) * v / dd for ci, v in zip(c, d)]


@settings(max_examples=60, deadline=None)
@given(
    far=st.sampled_from([0.0, 1e3, 1e4, 1e6]),
    seed=st.integers(0, 10_000),
    radius=st.floats(0.1, 100.0),
    imaginary=st.booleans(),
    dual=st.booleans(),
)
def test_apply_to_points_inverts_far_points_in_closed_form(far, seed, radius, imaginary, dual):
    """apply_to_points of a sphere (2.84-2.88; imaginary: r2 < 0, standard or dual form) on points near it, up to
    1e6 from the origin: within 1e-9 of |x - c| of the exact image (the conformal round trip lost up to 13 |x - c|
    1e6 out, 2e-8 at 1e3: the weight of a far conformal point), the rounding of the coordinates besides."""
    rng = np.random.default_rng(seed)
    c = far * unit(rng)
    r2 = -radius * radius if imaginary else radius * radius
    S = cga.sphere(c, radius)
    if imaginary:  # p + rho^2 e / 2 (2.72 with r2 = -rho^2); a sum with e keeps the sphere's frame
        S = S + (radius * radius) * cga.einf
    V = cga.dual(S) if dual else S
    x = c + rng.normal(size=(4, 3)) * radius * 3
    y = cga.apply_to_points(V, x)
    for xi, yi in zip(x, y):
        want = exact_inversion(c, r2, xi)
        size = np.linalg.norm(xi - c)
        err = max(abs(Fr(float(a)) - b) for a, b in zip(yi, want))
        assert err <= Fr(1e-9) * Fr(float(size)) + Fr(4 * EPS) * Fr(float(np.abs(yi).max())), (far, seed)


@pytest.mark.parametrize("motor_first", [True, False])
def test_apply_to_points_of_an_inversion_times_a_motor(motor_first):
    """S M (the motor first) and M S 100 out: the closed form composed with the motor's own (R, t) (2.102), within
    1e-9 of the exact map of V's own factors; near the origin the same points as the conformal round trip (2.62,
    2.65).  (The float product of a sphere and a motor both |c| out holds its rotor only to eps |c|^2: further
    out it is refused as lost to round-off, tested above.)"""
    rng = np.random.default_rng(5)
    for far, tol in ((0.0, 1e-12), (100.0, 1e-9)):
        c = far * unit(rng)
        M = cga.motor(unit(rng), 0.8, c + rng.normal(size=3))
        S = cga.sphere(c + rng.normal(size=3), 1.5)
        V = S * M if motor_first else M * S
        x = c + rng.normal(size=(5, 3)) * 3
        y = cga.apply_to_points(V, x)
        R, t = cga.G41.rigid_motion(M)
        p, r2 = np.array(cga.sphere_center_radius(S)[0]), cga.sphere_center_radius(S)[1] ** 2
        scale = Fr(float(np.abs(x - p).max() + np.abs(y - p).max()))
        for xi, yi in zip(x, y):
            if motor_first:
                want = exact_inversion(p, r2, R @ xi + t)
            else:
                w = exact_inversion(p, r2, xi)
                want = [sum(Fr(float(R[i, k])) * w[k] for k in range(3)) + Fr(float(t[i])) for i in range(3)]
            err = max(abs(Fr(float(a)) - b) for a, b in zip(yi, want))
            assert err <= Fr(tol) * scale + Fr(8 * EPS) * Fr(float(np.abs(yi).max()))
        if far == 0.0:
            assert np.allclose(y, cga.down(cga.apply(V, cga.up(x))), rtol=0, atol=1e-12)


def test_apply_to_points_refuses_the_inverting_spheres_centre():
    """The centre goes to infinity (2.84): a degenerate-geometry error naming x, not inf or NaN."""
    S = cga.sphere([1e6, 2.0, 3.0], 2.0)
    with pytest.raises(DegenerateGeometryError, match=r"^apply_to_points: x: V sends a point to infinity"):
        cga.apply_to_points(S, [1e6, 2.0, 3.0])


@pytest.mark.parametrize("weight", [1 / 3, -0.7, 2.5, 1e-3, 7.0])
def test_down_of_a_weighted_point_far_out_eq_2_111_2_114(weight):
    """``down(w up(x)) = x`` (2.111, 2.114) for any weight w, one point and a batch: within 2^11 eps of |x| near
    the origin (the weight read as the difference ``X_- - X_+``, its rounding eps x^2 / 2 relative, below
    ``SUM_OVER_WEIGHT``), within a few eps far out (read as ``|X_E|^2 / (X_+ + X_-)``).  As the difference
    ``down(up(x) / 3)`` 1e6 out was 3e-5 off (30 m)."""
    rng = np.random.default_rng(7)
    for scale, tol in ((1e-3, 8 * EPS), (1.0, 8 * EPS), (30.0, 2048 * EPS), (1e3, 8 * EPS), (1e6, 8 * EPS)):
        xs = rng.normal(size=(200, 3)) * scale
        batch = cga.down(cga.up(xs) * weight)
        assert np.all(np.abs(batch - xs).max(axis=1) <= tol * np.abs(xs).max(axis=1))
        for x in xs[:40]:
            assert np.abs(cga.down(cga.up(x) * weight) - x).max() <= tol * np.abs(x).max()
    assert cga.down(cga.up(np.zeros((0, 3)))).shape == (0, 3)  # an empty batch reads as one
