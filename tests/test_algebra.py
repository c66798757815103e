"""The algebra core G(p,q,r): axioms, products, involutions, exp; cross-checked against kingdon."""

import copy
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons.algebra import Algebra, DegenerateGeometryError, InvalidInputError, Multivector, commutator, exp

G41 = Algebra(4, 1, labels=["1", "2", "3", "+", "-"])
G3 = Algebra(3)

coeff = st.floats(min_value=-3, max_value=3, allow_nan=False, allow_infinity=False)


def mv_strategy(alg, max_blades=6, grades=None):
    blades = [b for b in range(alg.dim) if grades is None or alg.grades[b] in grades]
    return st.dictionaries(st.sampled_from(blades), coeff, max_size=max_blades).map(lambda d: Multivector(alg, d))


def random_mv(alg, rng, grades=None, k=None):
    blades = [b for b in range(alg.dim) if grades is None or alg.grades[b] in grades]
    k = len(blades) if k is None else k
    chosen = rng.choice(blades, size=min(k, len(blades)), replace=False)
    return Multivector(alg, {int(b): float(rng.normal()) for b in chosen})


# ------------------------------------------------------------------ axioms (2.10)
@pytest.mark.parametrize("p,q,r", [(3, 0, 0), (4, 1, 0), (2, 0, 1), (1, 1, 0), (0, 2, 0)])
def test_basis_squares_and_anticommutation(p, q, r):
    """(2.10): e_i^2 = +1, -1, 0 by signature and e_i e_j = -e_j e_i = e_ij."""
    alg = Algebra(p, q, r)
    es = alg.basis_vectors()
    expected = [1] * p + [-1] * q + [0] * r
    for i, ei in enumerate(es):
        assert (ei * ei).scalar() == expected[i]
        for j, ej in enumerate(es):
            if i != j:
                assert ei * ej == -(ej * ei)
                assert (ei * ej) == (ei ^ ej)


def test_clifford_product_in_R2_eq_2_8():
    """(2.5)-(2.8): ab = a.b + a^b with the closed forms of the thesis."""
    G2 = Algebra(2)
    a1, a2, b1, b2 = 1.5, -2.0, 0.25, 3.0
    a = G2.vector([a1, a2])
    b = G2.vector([b1, b2])
    ab = a * b
    assert ab.scalar() == pytest.approx(a1 * b1 + a2 * b2)
    assert ab["e12"] == pytest.approx(a1 * b2 - a2 * b1)
    assert (a ^ b) == -(b ^ a)  # (2.7)
    assert float(a * a) == pytest.approx(a1**2 + a2**2)  # (2.1)-(2.2)
    e1, e2 = G2.basis_vectors()
    assert float((e1 * e2) ** 2) == -1.0


def test_blade_names_and_access():
    X = G41.blade("e31", 2.0) + G41.blade("e+-", 1.0)
    assert X["e13"] == -2.0 and X["e31"] == 2.0
    assert X["e12"] == 0.0
    assert X.blades() == ["e13", "e+-"]
    assert G41.blade("e123+-") == G41.pseudoscalar()
    assert float(G41.scalar(3.5)) == 3.5
    with pytest.raises(InvalidInputError):
        float(X)
    with pytest.raises(KeyError):
        G41.parse_blade("e9")


def test_repr_and_latex():
    X = G41.blade("e12", 2.0) - G41.blade("e+", 0.5) + 1.0
    assert repr(X) == "1 - 0.5 e+ + 2 e12"  # grade, then index: the order of (2.9)
    assert "\\mathbf{e}_{12}" in X._repr_latex_()
    x = sp.Symbol("x")
    Y = G41.blade("e1", x + 1)
    assert repr(Y) == "(x + 1) e1"


# ------------------------------------------------------------------ products
@settings(max_examples=60, deadline=None)
@given(mv_strategy(G41), mv_strategy(G41), mv_strategy(G41))
def test_associativity_and_distributivity(A, B, C):
    assert ((A * B) * C).isclose(A * (B * C), atol=1e-9)
    assert (A * (B + C)).isclose(A * B + A * C, atol=1e-9)
    assert ((A ^ B) ^ C).isclose(A ^ (B ^ C), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(mv_strategy(G41), mv_strategy(G41))
def test_reverse_of_product_eq_2_34(A, B):
    assert (~(A * B)).isclose(~B * ~A, atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(mv_strategy(G41, grades={1}), mv_strategy(G41, grades={1}))
def test_inner_outer_of_vectors_eq_2_13_2_14(a, b):
    ab, ba = a * b, b * a
    assert (a | b).isclose((ab + ba) * 0.5, atol=1e-9)  # (2.13)
    assert (a ^ b).isclose((ab - ba) * 0.5, atol=1e-9)  # (2.14)
    assert (a * b).isclose((a | b) + (a ^ b), atol=1e-9)  # (2.11)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5), st.integers(1, 5), st.data())
def test_grade_selection_eq_2_29_2_30(r, s, data):
    """(2.29)-(2.30) on random blades (outer products of random vectors)."""
    vecs = data.draw(st.lists(mv_strategy(G41, grades={1}, max_blades=5), min_size=r + s, max_size=r + s))
    A = vecs[0]
    for v in vecs[1:r]:
        A = A ^ v
    B = vecs[r]
    for v in vecs[r + 1 :]:
        B = B ^ v
    assert (A | B).isclose((A * B).grade(abs(r - s)), atol=1e-8)
    assert (A ^ B).isclose((A * B).grade(r + s), atol=1e-8)


def test_inner_product_with_scalar_is_zero_eq_2_28():
    A = G41.blade("e12", 2.0)
    assert not (A | 3.0)._c
    assert not (G41.scalar(2.0) | A)._c
    # the left contraction differs: scalar _| A = scalar A
    assert (G41.scalar(2.0) << A) == A * 2.0


def test_inner_vector_bivector_eq_2_24():
    rng = np.random.default_rng(1)
    a, b, c = (G41.vector(rng.normal(size=5)) for _ in range(3))
    lhs = a | (b ^ c)
    rhs = (b * (a | b).scalar()) * 0 + c * (a | b).scalar() - b * (a | c).scalar()
    assert lhs.isclose(rhs, atol=1e-12)


def test_left_contraction_vs_thesis_inner_differ_when_grade_higher_on_left():
    """The thesis inner product of a bivector with a vector is nonzero; the left contraction is zero."""
    e1, e2 = G3.basis_vectors()[:2]
    B = e1 ^ e2
    assert (B | e1) == -e2 * 1.0 or (B | e1) == e2 * -1.0
    assert not (B << e1)._c


def test_involutions_eq_2_33_2_35():
    rng = np.random.default_rng(2)
    M = random_mv(G41, rng)
    for k in range(6):
        Mk = M.grade(k)
        assert (~M).grade(k) == Mk * (-1) ** (k * (k - 1) // 2)
        assert M.involute().grade(k) == Mk * (-1) ** k
    assert M.even() + M.odd() == M  # (2.16)-(2.18)


def test_dual_and_pseudoscalar_eq_2_31():
    I = G41.pseudoscalar()
    assert float(I * I) == -1.0
    rng = np.random.default_rng(3)
    X = random_mv(G41, rng, grades={2})
    assert set(X.dual().grades_present()) == {3}  # dual of a 2-blade is an (n-2)-blade
    assert X.dual().undual().isclose(X)


def test_inverse_of_vector_eq_2_19_and_general():
    a = G41.vector([1.0, 2.0, 0.5, 1.0, 0.3])
    assert (a * a.inv()).isclose(1.0)
    assert a.inv().isclose(a * (1.0 / float(a * a)))
    rng = np.random.default_rng(4)
    M = random_mv(G41, rng)
    assert (M * M.inv()).isclose(1.0, atol=1e-9)
    assert (M.inv() * M).isclose(1.0, atol=1e-9)
    null = G41.blade("e+") + G41.blade("e-")
    with pytest.raises(DegenerateGeometryError):
        null.inv()


def test_commutator_eq_2_36():
    rng = np.random.default_rng(5)
    A, B = random_mv(G41, rng), random_mv(G41, rng)
    assert commutator(A, B).isclose((A * B - B * A) * 0.5)
    assert commutator(A, B).isclose(-commutator(B, A))


def _series_exp(B, terms=40):
    out = G41.scalar(1.0)
    term = G41.scalar(1.0)
    for i in range(1, terms):
        term = term * B * (1.0 / i)
        out = out + term
    return out


@pytest.mark.parametrize(
    "blades",
    [
        {"e12": 0.7},  # rotation plane: B^2 < 0
        {"e1+": 0.2, "e1-": 0.2},  # null: translator (2.100)
        {"e+-": 0.4},  # boost: B^2 > 0
        {"e12": 0.6, "e3+": 0.3, "e3-": 0.3},  # screw (2.110)
        {"e12": 0.5, "e13": -0.2, "e1+": 0.3, "e2-": 0.1, "e+-": 0.2},  # general bivector
    ],
)
def test_exp_closed_form_matches_series_eq_2_37(blades):
    B = sum((G41.blade(k, v) for k, v in blades.items()), G41.scalar(0.0))
    assert exp(B).isclose(_series_exp(B), atol=1e-10)


def test_exp_batched_and_symbolic():
    th = np.array([0.1, 1.0, 2.5])
    B = G41.blade("e12", th)
    R = exp(B)
    assert np.allclose(R.scalar(), np.cos(th)) and np.allclose(R["e12"], np.sin(th))
    t = sp.Symbol("theta", positive=True)
    Rs = exp(G41.blade("e12", -t / 2))
    assert sp.simplify(Rs.scalar() - sp.cos(t / 2)) == 0
    assert sp.simplify(Rs["e12"] + sp.sin(t / 2)) == 0


# ------------------------------------------------------ three kinds of number
def test_batch_matches_loop():
    rng = np.random.default_rng(6)
    A = Multivector(G41, {b: rng.normal(size=7) for b in (1, 3, 8, 24, 31)})
    B = Multivector(G41, {b: rng.normal(size=7) for b in (2, 6, 16)})
    P = A * B
    for i in range(7):
        assert P.batch_item(i).isclose(A.batch_item(i) * B.batch_item(i))


def test_symbolic_matches_numeric():
    x, y = sp.symbols("x y", real=True)
    A = G41.blade("e1", x) + G41.blade("e2+", y)
    B = G41.blade("e1-", y) + G41.blade("e+", 2 * x)
    P = (A * B).expand()
    num = A.subs({x: 0.3, y: -1.2}) * B.subs({x: 0.3, y: -1.2})
    assert P.subs({x: 0.3, y: -1.2}).map(float).isclose(num.map(float))


def test_invalid_algebra_and_mixing():
    with pytest.raises(InvalidInputError, match="Algebra: p: must be >= 0"):
        Algebra(-1)
    with pytest.raises(InvalidInputError, match=r"Multivector \*: other: is a multivector of Algebra\(3, 0, 0\)"):
        G41.blade("e1") * G3.blade("e1")
    with pytest.raises(InvalidInputError, match="Algebra.vector: coeffs: the last axis must have length 5"):
        G41.vector([1.0, 2.0])


def test_operators_refuse_bad_operands_clearly():
    """Division by zero, NaN/inf operands, overflow and foreign types: a clear error naming the operator."""
    X = G3.vector([1.0, 2.0, 3.0]) + 1.0
    with pytest.raises(InvalidInputError, match="Multivector /: other: division by zero"):
        X / 0.0
    for bad in (math.nan, math.inf, np.array([1.0, math.nan])):
        with pytest.raises(InvalidInputError, match=r"Multivector \*: other: (is|contains) NaN or inf"):
            X * bad
        with pytest.raises(InvalidInputError, match=r"Multivector \+: other: (is|contains) NaN or inf"):
            X + bad
    nan_coefficients = Multivector(G3, {1: math.nan})  # the constructor takes the map as it is
    with pytest.raises(InvalidInputError, match=r"Multivector \^: other: the result has a NaN or inf coefficient"):
        X ^ nan_coefficients
    with pytest.raises(InvalidInputError, match="overflows a float"):
        G3.vector([1e200, 0.0, 0.0]) * 1e200
    with pytest.raises(DegenerateGeometryError, match="Multivector /: other: has no inverse"):
        X / (X * 0.0)
    for call in (lambda: X + None, lambda: X * "text", lambda: X.scalar_product(None), lambda: X.isclose([1.0])):
        with pytest.raises(InvalidInputError, match="other: expected a Multivector"):
            call()
    with pytest.raises(TypeError):  # a type of someone else's: Python's protocol (NotImplemented), not ours
        X * object()
    with pytest.raises(InvalidInputError, match="Multivector.grade: k: must be >= 0"):
        X.grade(-1)
    with pytest.raises(KeyError, match="Multivector\\[\\]: name: 'e4' is not a blade name"):
        X["e4"]


def test_reflected_operations_equality_and_copies_still_work():
    X = G3.vector([1.0, 2.0, 3.0])
    t = sp.Symbol("t")
    assert (t * X)["e1"] == 1.0 * t and (X * 2)["e3"] == 6 and (np.float64(2.0) * X)["e2"] == 4.0
    assert (np.array([1.0, 2.0]) * X).shape == (2,) and (2.0 / G3.scalar(4.0)).scalar() == 0.5
    assert (X == None) is False and (X != "text") is True  # noqa: E711 (== None must not raise)
    assert not (X == Multivector(G3, {1: math.nan}))
    Y = copy.deepcopy(X)
    assert Y.algebra is G3 and Y == X and (Y + X) == 2 * X


# ------------------------------------------------------------------ kingdon
def test_random_products_agree_with_kingdon():
    """Geometric, outer and reverse in G(4,1) against kingdon (same bitmap order: e4 = e+, e5 = e-)."""
    kingdon = pytest.importorskip("kingdon")
    K = kingdon.Algebra(4, 1)
    rng = np.random.default_rng(7)

    def to_k(M):
        return K.multivector(
            {f"e{''.join(str(i + 1) for i in range(5) if b >> i & 1)}" if b else "e": v for b, v in M.coeffs.items()}
        )

    def from_k(km):
        return Multivector(G41, {int(k): float(v) for k, v in zip(km.keys(), km.values())})

    for _ in range(25):
        A, B = random_mv(G41, rng, k=int(rng.integers(1, 12))), random_mv(G41, rng, k=int(rng.integers(1, 12)))
        assert (A * B).isclose(from_k(to_k(A) * to_k(B)), atol=1e-12)
        assert (A ^ B).isclose(from_k(to_k(A) ^ to_k(B)), atol=1e-12)
        assert (~A).isclose(from_k(~to_k(A)), atol=1e-12)


def test_math_is_used_consistently():
    assert math.isclose(float(exp(G41.blade("e12", math.pi / 2)).scalar()), 0.0, abs_tol=1e-15)


def test_outer_with_scalar_eq_2_20():
    A = G41.blade("e13", 2.0) + G41.blade("e2", 1.0)
    assert (A ^ 3.0) == A * 3.0 and (3.0 ^ A) == A * 3.0


def test_inner_product_expansions_eq_2_21_to_2_27():
    """(2.22)/(2.23)/(2.25) expansion of a vector with a blade, (2.26)-(2.27) nesting."""
    rng = np.random.default_rng(8)
    x, b1, b2, b3, a1, a2 = (G41.vector(rng.normal(size=5)) for _ in range(6))
    B = b1 ^ b2 ^ b3
    expansion = (b2 ^ b3) * (x | b1).scalar() - (b1 ^ b3) * (x | b2).scalar() + (b1 ^ b2) * (x | b3).scalar()
    assert (x | B).isclose(expansion, atol=1e-10)  # (2.23), (2.25)
    assert (B | x).isclose(expansion * ((-1) ** (3 - 1)), atol=1e-10)  # (2.22): B . x = (-1)^(r-1) x . B
    assert ((a1 ^ a2) | B).isclose(a1 | (a2 | B), atol=1e-10)  # (2.26)
    B4 = B ^ G41.vector(rng.normal(size=5))
    assert ((a1 ^ a2 ^ x) | B4).isclose(a1 | (a2 | (x | B4)), atol=1e-9)  # (2.27)


def test_reverse_of_blade_eq_2_32():
    rng = np.random.default_rng(9)
    a1, a2, a3 = (G41.vector(rng.normal(size=5)) for _ in range(3))
    assert (~(a1 ^ a2 ^ a3)).isclose(a3 ^ a2 ^ a1)


def test_sympy_expression_times_multivector():
    """A SymPy value on the left of a multivector scales it (SymPy must not try to float() it)."""
    x = sp.Symbol("x")
    e1 = G41.blade("e1", sp.Integer(1))
    assert (x * e1)["e1"] == x and (x + e1).scalar() == x


def test_batch_scalar_part_keeps_its_shape():
    X = G41.vector(np.ones((4, 5)))
    assert np.array_equal((X | G41.blade("e12")).scalar(), np.zeros(4))


def test_a_multivector_iterates_over_its_batch_and_never_forever():
    """list() of a single multivector raises (it used to loop for ever through __getitem__); a batch gives its items."""
    import numpy as np

    from cga_lessons import conformal as cga

    with pytest.raises(TypeError, match="not iterable"):
        list(cga.up([1.0, 2.0, 3.0]))
    pts = np.arange(12.0).reshape(4, 3)
    items = list(cga.up(pts))
    assert len(items) == 4 and all(cga.down(X).tolist() == p.tolist() for X, p in zip(items, pts))
    with pytest.raises(IndexError, match="outside 0..31"):
        cga.e1[32]
