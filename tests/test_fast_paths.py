"""Fast paths of the algebra core (issue 8): batched versors as matrices, compiled and tabled products.

Every fast result is checked against an independent truth: a naive geometric product written here from the
axioms (2.10), kingdon's sandwich with array coefficients, the compound matrices of the grade-1 matrix
(a versor's outermorphism), Rodrigues' rotation formula and the inversion formula (2.88).
"""

import itertools

import numpy as np
import pytest
import sympy as sp

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra, InvalidInputError, Multivector
from cga_lessons.algebra.versor_matrices import stack_rows
from cga_lessons.conformal import G41, versors

RNG_SEED = 20240807


# ------------------------------------------------------------------ independent reference product
def blade_sign(alg, a: int, b: int) -> int:
    """Sign of e_a e_b from the axioms (2.10): count the swaps, then contract equal factors."""
    swaps = sum(bin(a >> (i + 1)).count("1") for i in range(alg.n) if b >> i & 1)
    s = -1 if swaps % 2 else 1
    for i in range(alg.n):
        if a >> i & 1 and b >> i & 1:
            s *= alg.metric[i]
    return s


def naive_gp(A: Multivector, B: Multivector) -> Multivector:
    alg = A.algebra
    out: dict = {}
    for a, x in A.coeffs.items():
        for b, y in B.coeffs.items():
            s = blade_sign(alg, a, b)
            if s:
                out[a ^ b] = out.get(a ^ b, 0) + s * x * y
    return Multivector(alg, out)


def naive_reverse(A: Multivector) -> Multivector:
    return Multivector(
        A.algebra, {b: v * (-1) ** (bin(b).count("1") * (bin(b).count("1") - 1) // 2) for b, v in A.coeffs.items()}
    )


def naive_apply(V: Multivector, X: Multivector) -> Multivector:
    """V X^ V^-1 (2.82) with V^-1 = ~V / <V ~V>_0, projected on X's grades, all by the naive product."""
    odd = bin(next(iter(V.coeffs))).count("1") % 2
    Xi = Multivector(X.algebra, {b: -v if odd and bin(b).count("1") % 2 else v for b, v in X.coeffs.items()})
    Vr = naive_reverse(V)
    d = naive_gp(V, Vr).coeffs[0]
    return (naive_gp(naive_gp(V, Xi), Vr) / d).grade(*X.grades_present())


def close(A: Multivector, B: Multivector, atol=1e-10) -> bool:
    blades = set(A.coeffs) | set(B.coeffs)
    scale = max([1.0] + [float(np.max(np.abs(v))) for v in B.coeffs.values()])
    return all(np.allclose(A[b], B[b], rtol=0, atol=atol * scale) for b in blades)


# ------------------------------------------------------------------ versors and entities
def make_versors(rng):
    motor = cga.motor(rng.normal(size=3), 1.1, rng.normal(size=3))
    return {
        "motor": motor,
        "motor x 2.5 (not unit)": motor * 2.5,
        "rotor": cga.rotor(rng.normal(size=3), -0.6),
        "translator": cga.translator(rng.normal(size=3)),
        "screw": cga.screw(rng.normal(size=3), rng.normal(size=3), 0.9, 0.4),
        "reflection (odd)": cga.plane(rng.normal(size=3), 0.7),
        "inversion (odd)": cga.sphere(rng.normal(size=3), 1.3),
    }


def make_entities(rng, n=40):
    a, b, c, d = (rng.normal(size=(n, 3)) for _ in range(4))
    L = cga.line_from_points(a, b)
    return {
        "points (grade 1)": cga.up(a),
        "spheres (grade 1)": cga.sphere(a, rng.uniform(0.5, 2.0, size=n)),
        "point pairs (grade 2)": cga.point_pair(a, b),
        "lines, standard form (grade 2)": cga.standard_form(L),
        "lines (grade 3)": L,
        "circles (grade 3)": cga.circle_from_points(a, b, c),
        "planes (grade 4)": cga.plane_from_points(a, b, c),
        "spheres (grade 4)": cga.sphere_from_points(a, b, c, d),
        "mixed grades 0+2+5": Multivector(
            G41, {0: rng.normal(size=n), 6: rng.normal(size=n), 24: rng.normal(size=n), 31: rng.normal(size=n)}
        ),
    }


VERSOR_NAMES = list(make_versors(np.random.default_rng(0)))
ENTITY_NAMES = list(make_entities(np.random.default_rng(0)))


@pytest.mark.parametrize("vname", VERSOR_NAMES)
@pytest.mark.parametrize("ename", ENTITY_NAMES)
def test_batched_apply_takes_the_matrix_path_and_matches_the_sandwich(vname, ename, monkeypatch):
    """Eq. (2.82): apply(V, X) on a batch equals the plain sandwich V X^ V^-1 of every entity."""
    rng = np.random.default_rng(RNG_SEED)
    V = make_versors(rng)[vname]
    X = make_entities(rng)[ename]

    def no_sandwich(*args, **kwargs):
        raise AssertionError("the batch did not take the matrix path")

    monkeypatch.setattr(versors, "_apply_sandwich", no_sandwich)
    fast = cga.apply(V, X)
    monkeypatch.undo()
    assert fast.shape == X.shape
    assert set(fast.grades_present()) <= set(X.grades_present())
    for i in (0, 7, 39):
        assert close(fast.batch_item(i), naive_apply(V, X.batch_item(i)))
        assert close(fast.batch_item(i), versors._apply_sandwich(V, X.batch_item(i)))


@pytest.mark.parametrize("vname", VERSOR_NAMES)
def test_single_entity_apply_and_sandwich_operator_match_the_plain_product(vname):
    rng = np.random.default_rng(RNG_SEED + 1)
    V = make_versors(rng)[vname]
    for X in (cga.up(rng.normal(size=3)), cga.line_from_points(rng.normal(size=3), rng.normal(size=3))):
        assert close(cga.apply(V, X), naive_apply(V, X))
        # V >> X = V X ~V, no involution, no normalisation; a versor keeps the grade (round-off in others)
        plain = naive_gp(naive_gp(V, X), naive_reverse(V))
        fast = V >> X
        assert fast.grades_present() == X.grades_present()
        assert close(fast, plain.grade(*X.grades_present()))
        assert plain.grade(*[g for g in range(6) if g not in X.grades_present()]).iszero(atol=1e-10)


def test_sandwich_operator_on_a_non_versor_is_the_plain_product():
    rng = np.random.default_rng(3)
    A = Multivector(G41, {0: 1.0, 3: 0.5, 15: -0.7})  # even, but A ~A has a grade-4 part: not a versor
    assert not (A * ~A).grade(4).iszero()
    for X in (cga.up(rng.normal(size=3)), cga.up(rng.normal(size=(5, 3)))):
        got = A >> X
        want = naive_gp(naive_gp(A, X), naive_reverse(A))
        assert close(got, want, atol=1e-12)
        assert set(got.grades_present()) == set(want.grades_present())
    with pytest.raises(InvalidInputError, match="parity"):
        cga.apply(Multivector(G41, {0: 1.0, 1: 0.5}), cga.up([1.0, 2.0, 3.0]))
    # a non-versor in apply falls back to the sandwich with the general inverse
    X = cga.up(rng.normal(size=(4, 3)))
    assert close(cga.apply(A, X).batch_item(2), versors._apply_sandwich(A, X.batch_item(2)))


def test_batched_apply_matches_kingdon():
    """The same batches through kingdon's sandwich M >> X with array coefficients."""
    kingdon = pytest.importorskip("kingdon")
    K = kingdon.Algebra(4, 1)  # e4 = e+, e5 = e-: the same bitmaps as G41

    def name(b):
        return "e" + "".join(str(i + 1) for i in range(5) if b >> i & 1) if b else "e"

    def to_k(M):
        return K.multivector({name(b): v for b, v in M.coeffs.items()})

    rng = np.random.default_rng(RNG_SEED + 2)
    n = 60
    pts = rng.normal(size=(n, 3))
    entities = [
        cga.up(pts),
        cga.line_from_points(pts, rng.normal(size=(n, 3))),
        cga.point_pair(pts, rng.normal(size=(n, 3))),
    ]
    vs = make_versors(rng)
    for V in (vs[k] for k in ("motor", "motor x 2.5 (not unit)", "reflection (odd)", "inversion (odd)")):
        d = float((V * ~V).scalar())
        odd = V.grades_present()[0] % 2
        for X in entities:
            kv, kX = to_k(V), to_k(X)
            spelled = kv * kX * ~kv  # V X ~V = d (-1)^(g odd(V)) apply(V, X) on grade g
            swapped = kv >> kX if abs(d - 1.0) < 1e-12 else None  # kingdon's sandwich: V X^ V^-1 for unit V
            got = cga.apply(V, X)
            for b in range(32):
                g = bin(b).count("1")
                if g not in X.grades_present():
                    continue
                sign = -1.0 if odd and g % 2 else 1.0
                want = np.broadcast_to(np.asarray(getattr(spelled, name(b)), float), (n,))
                assert np.allclose(d * sign * np.asarray(got[b]), want, atol=1e-9 * max(1.0, abs(d)))
                if swapped is not None:
                    want = np.broadcast_to(np.asarray(getattr(swapped, name(b)), float), (n,))
                    assert np.allclose(np.asarray(got[b]), want, atol=1e-9)


# ------------------------------------------------------------------ outermorphism: grade k = k-th compound
@pytest.mark.parametrize("vname", VERSOR_NAMES)
def test_versor_matrices_are_the_compounds_of_the_grade_1_matrix(vname):
    """A versor's action is an outermorphism, f(a ^ b) = f(a) ^ f(b): on grade k its matrix is the k-th
    compound of the 5x5 matrix (determinants of k x k minors), in the blade order of (2.9)."""
    V = make_versors(np.random.default_rng(RNG_SEED + 3))[vname]
    A = cga.versor_matrix(V, 1)
    # the 5x5 matrix itself, column by column from naive sandwiches of the basis vectors
    cols = [naive_apply(V, Multivector(G41, {1 << j: 1.0})) for j in range(5)]
    assert np.allclose(A, np.array([[c[1 << i] for c in cols] for i in range(5)], dtype=float), atol=1e-12)
    for k in range(6):
        blades = G41.grade_blades[k]
        idx = [[i for i in range(5) if b >> i & 1] for b in blades]
        compound = np.array([[np.linalg.det(A[np.ix_(I, J)]) if k else 1.0 for J in idx] for I in idx])
        got = cga.versor_matrix(V, k)
        assert got.shape == (len(blades), len(blades))
        assert np.allclose(got, compound, atol=1e-10 * max(1.0, np.abs(compound).max()))


def test_versor_matrix_is_a_private_copy_and_the_cache_is_read_only():
    M = cga.motor([0.0, 0.0, 1.0], 0.5, [1.0, 0.0, 0.0])
    X = cga.up(np.random.default_rng(5).normal(size=(10, 3)))
    before = cga.apply(M, X).to_array()
    A = cga.versor_matrix(M, 1)
    A[:] = 0.0  # must not leak into the cache
    assert np.array_equal(cga.apply(M, X).to_array(), before)
    with pytest.raises(ValueError):
        G41.versor_matrices(M, (1,))[1][0, 0] = 1.0
    with pytest.raises(InvalidInputError):
        cga.versor_matrix(M, 7)


# ------------------------------------------------------------------ points: the 3x4 affine
def rodrigues(axis, angle):
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * np.outer(n, n)


def test_apply_to_points_is_the_rigid_affine_map():
    rng = np.random.default_rng(RNG_SEED + 4)
    axis, angle, t = rng.normal(size=3), 2.3, rng.normal(size=3) * 5
    M = cga.motor(axis, angle, t)
    pts = rng.normal(size=(2000, 3)) * 10
    truth = pts @ rodrigues(axis, angle).T + t
    got = cga.apply_to_points(M, pts)
    assert got.shape == (2000, 3)
    assert np.allclose(got, truth, atol=1e-11)
    assert np.allclose(cga.apply_to_points(M, pts[3]), truth[3], atol=1e-11)
    assert np.allclose(cga.apply_to_points(M, pts.tolist()), truth, atol=1e-11)
    # the same result through the conformal batch and down()
    assert np.allclose(cga.down(cga.apply(M, cga.up(pts))), truth, atol=1e-9)


def test_apply_to_points_of_an_inversion_uses_the_conformal_route():
    """Eq. (2.88): g(x) = rho^2 (x - p) / |x - p|^2 + p is not affine; the fast affine must not be used."""
    rng = np.random.default_rng(RNG_SEED + 5)
    p, rho = rng.normal(size=3), 1.7
    pts = rng.normal(size=(300, 3)) + 3.0
    diff = pts - p
    truth = rho**2 * diff / np.sum(diff**2, axis=1, keepdims=True) + p
    assert np.allclose(cga.apply_to_points(cga.sphere(p, rho), pts), truth, atol=1e-10)


def test_apply_to_points_validates_large_inputs():
    M = cga.motor([1.0, 0.0, 0.0], 0.3, [0.0, 1.0, 0.0])
    pts = np.random.default_rng(6).normal(size=(100_000, 3))
    for bad in (np.nan, np.inf, -np.inf):
        x = pts.copy()
        x[54_321, 1] = bad
        with pytest.raises(InvalidInputError, match="apply_to_points: x: contains NaN or inf"):
            cga.apply_to_points(M, x)
    huge = pts * 1e200  # the squares overflow, the values do not: no false alarm
    assert np.allclose(cga.apply_to_points(M, huge) / 1e200, cga.apply_to_points(M, pts) - [0.0, 1.0, 0.0])


# ------------------------------------------------------------------ batch layout
def test_conformal_batches_are_rows_of_one_block_and_are_not_copied():
    pts = np.random.default_rng(7).normal(size=(1000, 3))
    X = cga.up(pts)
    rows = [X.coeffs[b] for b in (1, 2, 4, 8, 16)]
    block = stack_rows(rows, (1000,))
    assert block.shape == (5, 1000) and all(np.shares_memory(block, r) for r in rows)
    M = cga.motor([0.2, 0.5, -0.1], 0.4, [1.0, 2.0, 3.0])
    Y = cga.apply(M, X)
    assert np.shares_memory(stack_rows([Y.coeffs[b] for b in (1, 2, 4, 8, 16)], (1000,)), Y.coeffs[1])
    # the same points stored column-wise (not a block) give the same numbers
    Xc = G41.from_array(X.to_array([1, 2, 4, 8, 16]), blades=[1, 2, 4, 8, 16])
    assert not np.shares_memory(stack_rows([Xc.coeffs[b] for b in (1, 2, 4, 8, 16)], (1000,)), Xc.coeffs[1])
    assert np.allclose(cga.apply(M, Xc).to_array(), Y.to_array(), rtol=0, atol=1e-14)
    # swapped rows are not mistaken for the block order
    swapped = [rows[1], rows[0], rows[2], rows[3], rows[4]]
    assert np.array_equal(stack_rows(swapped, (1000,))[0], rows[1])


def test_batches_of_any_shape():
    rng = np.random.default_rng(13)
    M = cga.motor(rng.normal(size=3), 0.8, rng.normal(size=3))
    L = Multivector(G41, {b: rng.normal(size=(4, 6)) for b in G41.grade_blades[3]})
    got = cga.apply(M, L)
    assert got.shape == (4, 6)
    for i, j in ((0, 0), (3, 5), (2, 1)):
        assert close(got.batch_item((i, j)), naive_apply(M, L.batch_item((i, j))))
    assert close((M >> L).batch_item((1, 2)), naive_gp(naive_gp(M, L.batch_item((1, 2))), naive_reverse(M)).grade(3))


def test_batches_with_constant_coefficients_and_batches_of_versors():
    rng = np.random.default_rng(8)
    M = cga.motor(rng.normal(size=3), 0.8, rng.normal(size=3))
    X = Multivector(G41, {1: rng.normal(size=6), 2: 0.5, 8: rng.normal(size=6), 16: 2.0})  # floats broadcast
    got = cga.apply(M, X)
    for i in range(6):
        assert close(got.batch_item(i), naive_apply(M, X.batch_item(i)))
    Ms = cga.motor(rng.normal(size=(6, 3)), rng.normal(size=6), rng.normal(size=(6, 3)))  # a batch of motors
    x = cga.up(rng.normal(size=3))
    moved = cga.apply(Ms, x)
    for i in range(6):
        assert close(moved.batch_item(i), naive_apply(Ms.batch_item(i), x))


# ------------------------------------------------------------------ products: compiled, tabled, interpreted
ALGEBRAS = [Algebra(3), Algebra(4, 1), Algebra(2, 0, 1), Algebra(1, 3)]


def random_mv(alg, rng, k, batch=None):
    blades = rng.choice(alg.dim, size=min(k, alg.dim), replace=False)
    return Multivector(
        alg, {int(b): (float(rng.normal()) if batch is None else rng.normal(size=batch)) for b in blades}
    )


@pytest.mark.parametrize("alg", ALGEBRAS, ids=str)
def test_every_product_route_agrees_with_the_naive_product(alg):
    rng = np.random.default_rng(9)
    for _ in range(15):
        ka, kb = (int(k) for k in rng.integers(1, alg.dim + 1, size=2))
        A, B = random_mv(alg, rng, ka), random_mv(alg, rng, kb)
        first, second, third = A * B, A * B, A * B  # interpreted, then compiled (or a table of signs)
        want = naive_gp(A, B)
        for got in (first, second, third):
            assert close(got, want, atol=1e-13)
        # arrays go through the same compiled code, element by element the naive product
        Ab, Bb = random_mv(alg, rng, ka, batch=4), random_mv(alg, rng, kb, batch=4)
        for P in (Ab * Bb, Ab * Bb):
            for i in range(4):
                assert close(P.batch_item(i), naive_gp(Ab.batch_item(i), Bb.batch_item(i)), atol=1e-13)


def test_compiled_and_interpreted_products_are_identical_for_floats_and_sympy():
    """The compiled code sums each result in the interpreted loop's order: the same bits, the same expressions."""
    x, y, z = sp.symbols("x y z", real=True)
    alg = Algebra(3)
    A = Multivector(alg, {0: x, 3: y, 5: sp.Integer(2) * z, 7: x * y})
    B = Multivector(alg, {1: y, 6: z - 1, 7: sp.Rational(1, 2)})
    runs = [(A * B)._c for _ in range(3)]
    assert runs[0] == runs[1] == runs[2]
    want = naive_gp(A, B)
    assert all(sp.expand(runs[1].get(b, 0) - want[b]) == 0 for b in range(8))
    # floats with few terms (compiled code): bit for bit the interpreted result
    rng = np.random.default_rng(10)
    G = Algebra(4, 1)
    a, b = random_mv(G, rng, 3), random_mv(G, rng, 4)
    assert (a * b)._c == (a * b)._c == (a * b)._c
    # integers stay integers (exact arithmetic is not sent through the float table)
    I = Multivector(G, {b: 1 for b in range(32)})
    assert all(type(v) is int for v in (I * I)._c.values())


def test_float_table_route_for_large_products():
    """A motor (12 blades) times a point (5 blades) has 60 terms: float singles take one small matrix product."""
    rng = np.random.default_rng(11)
    M = cga.motor(rng.normal(size=3), 0.7, rng.normal(size=3))
    X = cga.up(rng.normal(size=3))
    assert len(M.coeffs) * len(X.coeffs) >= G41._products.TABLE_TERMS
    for _ in range(3):
        assert close(M * X, naive_gp(M, X), atol=1e-14)
        assert close(M * X * ~M, naive_gp(naive_gp(M, X), naive_reverse(M)), atol=1e-13)


def test_products_of_many_blade_sets_stay_correct_when_the_caches_fill():
    rng = np.random.default_rng(12)
    alg = Algebra(4, 1)
    alg._products.cache_limit = 8
    try:
        for ka, kb in itertools.product((1, 3, 9), (2, 5, 11)):
            A, B = random_mv(alg, rng, ka), random_mv(alg, rng, kb)
            for _ in range(2):
                assert close(A * B, naive_gp(A, B), atol=1e-13)
        assert len(alg._products.cache) <= 8
    finally:
        alg._products.cache_limit = 1024


def test_batched_down_is_the_single_point_route_and_the_affine_map():
    """The one-pass ``down`` of a batch (2.111, 2.114) against the single-point route and the 4x4 matrix."""
    rng = np.random.default_rng(31)
    pts = rng.normal(scale=20.0, size=(500, 3))
    M = cga.motor(rng.normal(size=3), 1.1, rng.normal(size=3))
    got = cga.down(cga.apply(M, cga.up(pts)))
    H = cga.motor_to_matrix(M)
    np.testing.assert_allclose(got, pts @ H[:3, :3].T + H[:3, 3], rtol=0, atol=1e-11 * 400)
    Y = cga.apply(M, cga.up(pts))
    for i in (0, 17, 499):
        np.testing.assert_allclose(got[i], cga.down(Y.batch_item(i)), rtol=1e-14, atol=1e-13)
    grid = Multivector(G41, {b: v.reshape(4, 5) for b, v in cga.up(pts[:20]).coeffs.items()})  # any batch shape
    np.testing.assert_allclose(cga.down(grid), pts[:20].reshape(4, 5, 3), atol=1e-12)
    scaled = Multivector(G41, {b: 3.0 * v for b, v in cga.up(pts[:5]).coeffs.items()})  # weights other than 1
    np.testing.assert_allclose(cga.down(scaled), pts[:5], atol=1e-12)


def test_batched_down_refuses_what_is_not_a_finite_point():
    pts = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    X = cga.up(pts)
    at_infinity = Multivector(G41, {1: np.ones(2), 8: np.ones(2), 16: np.array([1.0, 2.0])})  # first one: X . e = 0
    with pytest.raises(cga.DegenerateGeometryError, match="down: X: X . e = 0"):
        cga.down(at_infinity)
    with pytest.raises(cga.InvalidInputError, match="down: X: a conformal point is a vector"):
        cga.down(X + cga.e1 * cga.e2 * np.ones(2))
    with pytest.raises(cga.GeometryError, match="down:"):
        cga.down(Multivector(G41, {**X.coeffs, 1: np.array([np.nan, 1.0])}))
    with pytest.raises(cga.GeometryError, match="down:"):
        cga.down(Multivector(G41, {**X.coeffs, 16: np.array([np.inf, 1.0])}))


def test_single_point_down_agrees_with_the_batch_and_refuses_the_same_inputs():
    rng = np.random.default_rng(32)
    pts = rng.normal(scale=50.0, size=(20, 3))
    X = cga.apply(cga.motor(rng.normal(size=3), 0.4, rng.normal(size=3)), cga.up(pts))
    batch = cga.down(X)
    for i in range(20):
        np.testing.assert_allclose(cga.down(X.batch_item(i)), batch[i], rtol=1e-15, atol=0)
    with pytest.raises(cga.DegenerateGeometryError, match="down: X: X . e = 0"):
        cga.down(cga.einf + cga.e1)
    with pytest.raises(cga.InvalidInputError, match="down: X: a conformal point is a vector"):
        cga.down(cga.up([1.0, 2.0, 3.0]) + cga.e1 * cga.e2)
    with pytest.raises(cga.GeometryError, match="down:"):  # (float("nan") * cga.e1 is refused by the operator)
        cga.down(Multivector(G41, {**cga.up([1.0, 2.0, 3.0]).coeffs, 1: float("nan")}))


def test_up_refuses_coordinates_whose_squares_overflow():
    with pytest.raises(cga.InvalidInputError, match="up: x: magnitudes up to 1e\\+200, beyond 1e\\+153: "):
        cga.up([1e200, 0.0, 0.0])
    with pytest.raises(cga.InvalidInputError, match="up: x:"):
        cga.up(np.array([[1.0, 2.0, 3.0], [0.0, -1e160, 0.0]]))
    np.testing.assert_allclose(cga.apply_to_points(cga.translator([1.0, 0.0, 0.0]), [1e200, 0.0, 0.0]), [1e200, 0, 0])
