"""Accuracy of exp (2.37) against independent truths, over every kind of bivector of G(4,1).

Truths, none of which uses the closed form of :mod:`cga_lessons.algebra.exponential`:

* ``_series_exp``: the series (2.37) summed with scaling and squaring,
  ``exp(B) = exp(B/2^k)^(2^k)``, in 40-digit decimal arithmetic, the product
  taken from a table of the public ``Multivector *`` on the basis blades;
* ``_mpmath_exp``: mpmath's ``expm`` of the 32x32 matrix of left
  multiplication by B (built from ``B * blade``), at 40 digits; slower, so it
  only checks the series truth and a few cases;
* for screws, the NumPy rigid motion: a rotation by theta about the axis
  through a point, then a slide d along it (2.110).

Errors are measured relative to the largest coefficient of the exact result.
"""

import math
from decimal import Decimal, localcontext
from functools import cache

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra, InvalidInputError, Multivector, exp
from cga_lessons.conformal import motor_log

G41 = cga.G41
BIV = G41.grade_blades[2]
DIGITS = 40


# ------------------------------------------------------------------ truths
@cache
def _even_table(alg):
    """Even blades of ``alg`` and their product table [(index of a b, sign)], from the public product."""
    even = [b for b in alg.blade_order if alg.grades[b] % 2 == 0]
    idx = {b: i for i, b in enumerate(even)}
    table = []
    for a in even:
        row = []
        for b in even:
            prod = Multivector(alg, {a: 1.0}) * Multivector(alg, {b: 1.0})
            ((c, v),) = prod.coeffs.items() if prod.coeffs else ((0, 0.0),)
            row.append((idx[c], int(v)))
        table.append(row)
    return even, table


def _mul(x, y, table):
    out = [Decimal(0)] * len(x)
    for i, xi in enumerate(x):
        if not xi:
            continue
        row = table[i]
        for j, yj in enumerate(y):
            if yj:
                c, sign = row[j]
                if sign:
                    out[c] += xi * yj if sign > 0 else -(xi * yj)
    return out


def _series_exp(B: Multivector) -> np.ndarray:
    """exp(B) on the even blades, by the series (2.37) with scaling and squaring, in 40 digits."""
    even, table = _even_table(B.algebra)
    with localcontext() as ctx:
        ctx.prec = DIGITS
        x = [Decimal(float(B.coeffs.get(b, 0.0))) for b in even]  # exact: every float is a decimal
        size, k = sum(abs(v) for v in x), 0
        while size > Decimal("0.25"):
            size, k = size / 2, k + 1
        X = [v / Decimal(2**k) for v in x]
        total = [Decimal(1)] + [Decimal(0)] * (len(x) - 1)
        term = list(total)
        tiny = Decimal(10) ** -(DIGITS + 2)
        for n in range(1, 80):
            term = [v / n for v in _mul(X, term, table)]
            total = [a + b for a, b in zip(total, term)]
            if max(abs(v) for v in term) < tiny:
                break
        for _ in range(k):
            total = _mul(total, total, table)
        return np.array([float(v) for v in total])


def _mpmath_exp(B: Multivector) -> np.ndarray:
    """exp(B) on the even blades, as mpmath's expm of the 32x32 matrix of left multiplication by B."""
    order = G41.blade_order
    L = mpmath.zeros(32, 32)
    for j, b in enumerate(order):
        prod = B * Multivector(G41, {b: 1.0})  # exact: each coefficient is +-1 times one of B's
        for i, c in enumerate(order):
            if c in prod.coeffs:
                L[i, j] = mpmath.mpf(float(prod.coeffs[c]))
    with mpmath.workdps(DIGITS):
        E = mpmath.expm(L)
        col = {c: float(E[i, 0]) for i, c in enumerate(order)}
    even, _ = _even_table(G41)
    assert all(abs(col[c]) == 0 for c in order if G41.grades[c] % 2)  # exp of a bivector is even
    return np.array([col[c] for c in even])


def _rel_error(B: Multivector, truth: np.ndarray) -> float:
    even, _ = _even_table(B.algebra)
    got = exp(B).to_array(even)
    return float(np.max(np.abs(got - truth)) / np.max(np.abs(truth)))


def _bivector(coeffs) -> Multivector:
    return Multivector(G41, {b: float(v) for b, v in zip(BIV, coeffs) if v != 0})


def _screw_bivector(n, point, angle, slide) -> Multivector:
    """-angle/2 (l + e m) with l = n I_E and m = point . l - (slide/angle) n (2.110), built in floats."""
    l = cga.vector(n) * cga.IE
    m = (cga.vector(point) | l) - cga.vector(n) * (slide / angle)
    return ((l + cga.einf * m) * (-angle / 2)).grade(2)


def _rigid_screw(n, point, angle, slide, x):
    """The screw motion on points x (N, 3): rotate by angle about the line (point, n), slide along n."""
    K = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    R = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * (K @ K)
    return (x - point) @ R.T + point + slide * n


def _unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


# ----------------------------------------------------- the truths themselves
def test_series_truth_agrees_with_mpmath_expm():
    """The two truths agree to far below the tolerance, and exp meets both (a small angle, a long slide too)."""
    rng = np.random.default_rng(11)
    cases = [
        _bivector(rng.normal(size=10)),
        _screw_bivector(_unit([1.0, -2.0, 0.5]), [700.0, 650.0, 240.0], 1.8e-5, 3.0),
        G41.blade("e12", 1.3) + G41.blade("e3-", 0.8) + G41.blade("e1+", -0.4),  # loxodromic
    ]
    for B in cases:
        series, matrix = _series_exp(B), _mpmath_exp(B)
        assert np.max(np.abs(series - matrix)) <= 1e-25 * np.max(np.abs(matrix))
        assert _rel_error(B, matrix) < 1e-12


# ------------------------------------------------------- against the series
@settings(deadline=None, max_examples=150)
@given(
    coeffs=st.lists(st.floats(-1.0, 1.0), min_size=10, max_size=10),
    log_scale=st.floats(-6.0, 1.3),
)
def test_exp_of_general_bivectors_matches_series(coeffs, log_scale):
    """Any bivector of G(4,1) (rotations, boosts, transversions, dilations mixed), norms 1e-6 to 60."""
    B = _bivector(np.array(coeffs) * 10**log_scale)
    if not B.coeffs:
        return
    assert _rel_error(B, _series_exp(B)) < 1e-12


@settings(deadline=None, max_examples=150)
@given(
    axis=st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3).filter(lambda v: np.linalg.norm(v) > 0.1),
    point=st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3),
    log_angle=st.floats(-12.0, math.log10(math.pi)),
    log_size=st.floats(0.0, 7.0),
    slide=st.floats(-1.0, 1.0),
    off_null=st.floats(-1.0, 1.0),
)
def test_exp_of_screws_matches_series(axis, point, log_angle, log_size, slide, off_null):
    """Screws (2.110): angles 1e-12..pi, translations up to 1e7, some with a small o-part (not exactly a screw)."""
    size = 10**log_size
    B = _screw_bivector(_unit(axis), np.array(point) * size, 10**log_angle, slide * size)
    B = B + (cga.eo * cga.vector(np.array(point) * off_null * 1e-9)).grade(2)
    assert _rel_error(B, _series_exp(B)) < 1e-12


@pytest.mark.parametrize(
    "blades",
    [
        {"e12": 0.7},  # rotation (2.94)
        {"e1+": 1.1},  # e1 e+ squares to -1: a rotation too
        {"e1-": 2.5},  # e1 e- squares to +1: a boost
        {"e+-": -1.5},  # E = e+ e- squares to +1: a dilation
        {"e1+": 3.0, "e1-": 3.0},  # translator (2.100), B^2 = 0
        {"e1+": -3.0, "e1-": 3.0, "e12": 0.2},  # transversion and rotation
        {"e12": 2.0, "e3+": 2.0},  # two rotation planes of equal angle (repeated root)
        {"e12": 2.0, "e3+": 2.0 * (1 + 1e-9), "e1-": 1e-4},  # nearly repeated root
        {"e12": 0.3, "e3+": 0.3 * (1 + 1e-6), "e2-": 1e-3},  # nearly repeated, small
        {"e12": 1.5, "e3-": 1.5},  # rotation and boost of equal size (loxodromic)
        {"e12": 1e-7, "e3-": 1e-7, "e1+": 1e-8},  # tiny
        {"e12": 30.0, "e3+": 29.0, "e1-": 0.5},  # large rotations
        {"e1-": 300.0, "e23": 2.0},  # a large boost
        {"e12": 1e-9, "e1+": 4e6, "e1-": 4e6, "e3+": -2e6, "e3-": -2e6},  # tiny turn, very long slide
    ],
)
def test_exp_special_bivectors_match_series(blades):
    B = sum((G41.blade(k, v) for k, v in blades.items()), G41.scalar(0.0)).grade(2)
    assert _rel_error(B, _series_exp(B)) < 1e-12


def test_scalar_part_multiplies():
    B = G41.scalar(0.7) + G41.blade("e12", 0.4) + G41.blade("e3-", 0.9)
    truth = _series_exp(B.grade(2)) * math.exp(0.7)
    assert _rel_error(B, truth) < 1e-13


# ----------------------------------------------------- the reported failure
def test_reproduction_small_angle_long_slide():
    """The report: a motor of angle 1.8e-5 with |t| ~ 1e3; exp(motor_log(M)) raised 'not invertible'."""
    n = _unit([1.0310601652090412, -1.7383210989009736, -0.03926821095340596])
    angle, t = 1.7964222211712104e-05, np.array([714.9305341608075, 656.3599565057399, 240.96875071329404])
    M = cga.motor(n, angle, t)
    B = motor_log(M)
    X = exp(B)  # no raise
    assert _rel_error(B, _series_exp(B)) < 1e-13
    # the log in closed form (versor_log's module docstring), computed here from n, angle and t
    half = angle / 2
    t_par = (t @ n) * n
    w = 0.5 * (t_par + half / math.tan(half) * (t - t_par) - half * np.cross(n, t))
    exact = exp(((cga.vector(n) * cga.IE) * (-half) + cga.einf * cga.vector(w)).grade(2))
    scale = np.linalg.norm(t)
    assert np.max(np.abs((exact - M).to_array())) < 1e-12 * scale
    assert np.max(np.abs((X - M).to_array())) < 1e-10 * scale


def test_reproduction_round_trip_to_1e_12():
    n = _unit([1.0310601652090412, -1.7383210989009736, -0.03926821095340596])
    t = np.array([714.9305341608075, 656.3599565057399, 240.96875071329404])
    M = cga.motor(n, 1.7964222211712104e-05, t)
    assert np.max(np.abs((exp(motor_log(M)) - M).to_array())) < 1e-12 * np.linalg.norm(t)


# ---------------------------------------------------------- rigid motions
def test_screws_move_points_like_the_rigid_motion():
    """Hundreds of screws, angles 1e-12..pi (and pi - 1e-12, pi), translations up to 1e7, batched and single."""
    rng = np.random.default_rng(2110)
    N = 300
    angles = np.concatenate(
        [10 ** rng.uniform(-12, math.log10(math.pi), N - 20), math.pi - 10 ** rng.uniform(-12, -2, 18), [math.pi] * 2]
    )
    sizes = 10 ** rng.uniform(0, 7, N)
    axes = rng.normal(size=(N, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    points = rng.normal(size=(N, 3)) * sizes[:, None]
    slides = rng.normal(size=N) * sizes
    x = rng.normal(size=(N, 4, 3)) * sizes[:, None, None]
    Bs = [_screw_bivector(axes[i], points[i], angles[i], slides[i]) for i in range(N)]
    batch = Multivector(G41, {b: np.array([B.coeffs.get(b, 0.0) for B in Bs]) for b in BIV}, _prune=True)
    Mb = exp(batch)
    worst = 0.0
    for i, B in enumerate(Bs):
        M = exp(B)
        Mi = Mb.batch_item(i)
        assert np.max(np.abs((Mi - M).to_array())) <= 1e-15 * max(1.0, np.max(np.abs(M.to_array())))
        got = cga.apply_to_points(M, x[i])
        want = _rigid_screw(axes[i], points[i], angles[i], slides[i], x[i])
        worst = max(worst, np.max(np.abs(got - want)) / sizes[i])
    assert worst < 1e-9


def test_screw_constructor_uses_exp():
    """versors.screw (2.110) at a small angle and a long slide, against the rigid motion."""
    n, c = _unit([0.3, -1.0, 2.0]), np.array([3e6, -1e6, 2e5])
    for angle in (1e-12, 1e-8, 1e-4, 0.5, math.pi):
        S = cga.screw(n, c, angle, 5e6)
        x = np.array([[1.0, 2.0, 3.0], [-4e6, 5e5, 1e6]])
        assert np.max(np.abs(cga.apply_to_points(S, x) - _rigid_screw(n, c, angle, 5e6, x))) < 1e-9 * 5e6


# ------------------------------------------------------ kinds of coefficient
def test_pure_translator_and_rotor_are_exact():
    t = cga.vector([3.0, -1.5, 1e7])
    B = cga.einf * t * 0.5
    assert exp(B) == 1 + B  # B^2 = 0: exactly 1 + B (2.100)
    R = exp(G41.blade("e12", -0.35))
    assert R.blades() == ["1", "e12"] and R.scalar() == math.cos(0.35) and R["e12"] == -math.sin(0.35)


def test_hyperbolic_planes():
    for name in ("e1-", "e2-", "e+-"):
        X = exp(G41.blade(name, 1.25))
        assert X.blades() == ["1", name]
        assert math.isclose(X.scalar(), math.cosh(1.25), rel_tol=1e-15)
        assert math.isclose(X[name], math.sinh(1.25), rel_tol=1e-15)


def test_batch_matches_single():
    rng = np.random.default_rng(37)
    coeffs = rng.normal(size=(25, 10)) * 10 ** rng.uniform(-6, 1, size=(25, 1))
    coeffs[:5, [0, 1, 3]] *= 1e-7  # small rotations
    batch = Multivector(G41, {b: coeffs[:, i] for i, b in enumerate(BIV)})
    X = exp(batch)
    assert X.shape == (25,)
    for i in range(25):
        single = exp(_bivector(coeffs[i]))
        assert np.max(np.abs((X.batch_item(i) - single).to_array())) <= 1e-14 * np.max(np.abs(single.to_array()))


def test_other_algebras():
    """G(4) e12 + e34 (repeated root), G(3), G(2,0,1) (a null plane), G(6) with three planes (the series)."""
    G4 = Algebra(4)
    c, s = math.cos(1.0), math.sin(1.0)
    X = exp(G4.blade("e12") + G4.blade("e34"))
    want = G4.scalar(c * c) + G4.blade("e12", c * s) + G4.blade("e34", c * s) + G4.blade("e1234", s * s)
    assert X.isclose(want, rtol=1e-15, atol=1e-15)
    G3 = Algebra(3)
    B3 = G3.blade("e12", 0.3) + G3.blade("e13", -1.1) + G3.blade("e23", 0.4)
    assert _rel_error(B3, _series_exp(B3)) < 1e-14
    G201 = Algebra(2, 0, 1)
    assert exp(G201.blade("e13", 0.8)) == 1 + G201.blade("e13", 0.8)
    G6 = Algebra(6)
    B6 = G6.blade("e12", 0.5) + G6.blade("e34", 0.7) + G6.blade("e56", 0.9)
    want6 = (
        (math.cos(0.5) + G6.blade("e12", math.sin(0.5)))
        * (math.cos(0.7) + G6.blade("e34", math.sin(0.7)))
        * (math.cos(0.9) + G6.blade("e56", math.sin(0.9)))
    )
    assert exp(B6).isclose(want6, rtol=1e-13, atol=1e-14)


# ------------------------------------------------------------------- SymPy
def _no_floats(X: Multivector) -> bool:
    return not any(sp.sympify(v).atoms(sp.Float) for v in X.coeffs.values())


def test_sympy_rotor_is_exact():
    theta = sp.Symbol("theta")
    e12 = cga.exact_constants().e1 * cga.exact_constants().e2
    R = exp(e12 * (-theta / 2))
    assert R.blades() == ["1", "e12"]
    assert R.scalar() == sp.cos(theta / 2) and R["e12"] == -sp.sin(theta / 2)
    assert _no_floats(R)
    Q = exp(e12 * (sp.pi / 4))
    assert Q.scalar() == sp.sqrt(2) / 2 and Q["e12"] == sp.sqrt(2) / 2


def test_sympy_translator_is_exact():
    c = cga.exact_constants()
    t = sp.symbols("t1 t2 t3", real=True)
    tv = c.e1 * t[0] + c.e2 * t[1] + c.e3 * t[2]
    B = c.einf * tv / 2
    X = exp(B)
    assert X.coeffs == (1 + B).coeffs and _no_floats(X)


def test_sympy_boost_and_screw():
    c = cga.exact_constants()
    a, d = sp.symbols("a d", real=True)
    X = exp(c.E * a)
    assert X.scalar() == sp.cosh(a) and X["e+-"] == sp.sinh(a)
    theta = sp.Symbol("theta", positive=True)
    B = (c.e1 * c.e2 + c.einf * c.e3 * d) * (-theta / 2)  # a screw along e3
    S = exp(B)
    assert _no_floats(S)
    values = {theta: 0.8, d: -1.7}
    numeric = exp(Multivector(G41, {b: float(v.subs(values)) for b, v in B.coeffs.items()}))
    assert S.subs(values).map(float).isclose(numeric, rtol=1e-14, atol=1e-14)


# ---------------------------------------------------------------- errors
@pytest.mark.parametrize(
    "B, match",
    [
        (G41.blade("e12", 1e300), "exp: B: rotation angle"),
        (G41.blade("e12", 2.0**53), "exp: B: rotation angle"),
        (G41.blade("e1-", 800.0), "exp: B: hyperbolic part"),
        (G41.blade("e+-", -1e200), "exp: B: hyperbolic part"),
        (Multivector(G41, {0b00011: float("nan")}), "exp: B: .*NaN or inf"),  # e12 (blade() refuses NaN)
        (Multivector(G41, {0b01001: float("inf")}), "exp: B: .*NaN or inf"),  # e1+
        (G41.scalar(800.0) + G41.blade("e12", 1.0), "exp: B: scalar part"),
        (G41.scalar(5.0) + G41.blade("e1-", 708.0), "exp: B: the result overflows"),
        (G41.blade("e12", np.array([0.5, 1e300])), "exp: B: rotation angle"),
        (Multivector(G41, {0b10001: np.array([0.5, np.nan])}), "exp: B: .*NaN or inf"),  # e1-
        (G41.blade("e1", 1.0), "exp: B: .*bivector"),
    ],
)
def test_overflow_and_bad_input_raise(B, match):
    with pytest.raises(InvalidInputError, match=match):
        exp(B)


def test_large_but_representable_arguments():
    """Up to the limits the results are finite; a huge translation alone is still 1 + B."""
    X = exp(G41.blade("e1-", 700.0))
    assert np.isfinite(X.scalar()) and math.isclose(X.scalar(), math.cosh(700.0), rel_tol=1e-13)
    R = exp(G41.blade("e12", 1e15))
    assert math.isclose(R.scalar() ** 2 + R["e12"] ** 2, 1.0, rel_tol=1e-15)
    T = cga.einf * cga.vector([1e200, -3e199, 0.0])
    assert exp(T) == 1 + T
