"""Tests of the symbolic derivations of chapter 2 (cga_lessons.symbolic).

Each derivation compares the thesis's printed steps with what the algebra
computes from symbols; a test asserts that every correct step holds, that
every printed erratum fails, and that each equation it claims is checked.
"""

from __future__ import annotations

from functools import cache

import pytest
import sympy as sp

from cga_lessons import conformal as cga
from cga_lessons import symbolic
from cga_lessons.conformal.points import up
from cga_lessons.equations import REGISTRY, check_registry
from cga_lessons.equations.registry import ch2_derivations, ch2_derivations_entities
from cga_lessons.symbolic.core import Ring, const, dot3, euclid, proportional, same


@cache
def derivation(name: str):
    return symbolic.DERIVATIONS[name]()


def assert_derivation(name: str, labels):
    d = derivation(name)
    bad = [(c.name, c.holds, c.expected) for c in d.failures()]
    assert not bad, f"{name}: checks not as expected: {bad}"
    assert d.holds
    for label in labels:
        assert d.for_label(label), f"{name}: no check of ({label})"
    for c in d.checks:
        if c.expected:
            assert c.holds, c.name
        else:
            assert not c.holds, f"printed erratum {c.name!r} unexpectedly holds"
    return d


def _labels(a, b):
    return [f"2.{i}" for i in range(a, b + 1)]


# ------------------------------------------------------------ the checker
def test_checker_detects_wrong_identities():
    """The comparison machinery must be able to say 'no' (else no test here could fail)."""
    c = const()
    x, y = sp.symbols("x y", real=True)
    X = up([x, y, sp.Integer(0)])
    assert same(X * X, 0) and not same(X * X, 1)
    assert not same(X | c.einf, 1)
    assert same((x + y) ** 2, x**2 + 2 * x * y + y**2) and not same((x + y) ** 2, x**2 + y**2)
    assert same(1 / (x + 1) - 1 / (x + 1), 0) and not same(x / (x + 1), 1)
    assert proportional(X * 3, X) and not proportional(X, X + c.einf)
    ring = Ring([x, y], [x**2 + y**2 - 1])
    assert same(x**4 + 2 * x**2 * y**2 + y**4, 1, ring) and not same(x**2, 1, ring)
    v = euclid([x, y, 0])
    assert same(ring.lift(v) * ring.lift(v), 1, ring) and not same(ring.lift(v) * ring.lift(v), -1, ring)
    assert dot3([x, y, 1], [1, 1, 1]) == x + y + 1


# ------------------------------------------------------------ derivations
def test_clifford_product_plane():
    d = assert_derivation("clifford_product_plane", _labels(1, 8))
    q1, q2, k = sp.symbols("q1 q2 k")
    assert d.values["rules"] == [{q1: 1, q2: 1, k: 0}]


def test_basis_and_product_axioms():
    assert_derivation("basis_and_product_axioms", ["2.9", "2.10"])


def test_stereographic_projection():
    d = assert_derivation("stereographic_projection", _labels(38, 51))
    x = sp.Symbol("x", real=True, nonzero=True)
    a, b = d.values["a"], d.values["b"]
    # independent truth: the projected point is on the unit circle and on the line through n and x
    assert sp.simplify(a**2 + b**2 - 1) == 0
    assert sp.simplify(b - (1 - a / x)) == 0
    assert len(d.values["roots"]) == 2


def test_minkowski_plane():
    d = assert_derivation("minkowski_plane", _labels(52, 56))
    assert d["2.55 E := e0 ^ e = e+ e- (printed)"].holds is False
    assert d["2.56 e0 E = -e0 (corrected)"].holds


def test_minkowski_properties_2_56_each_E():
    """Every property of (2.56) is checked under both signs of E; report which fail."""
    d = derivation("minkowski_plane")
    names = [p[0] for p in symbolic.MINKOWSKI_PROPERTIES]
    assert len(names) == 10
    for name in names:
        assert d[f"2.56 {name} [E = e+e-]"].ok and d[f"2.56 {name} [E = e0^e]"].ok
    assert d.values["fails_with_E_ep_em"] == ["e0 E = e0"]
    fails = d.values["fails_with_E_e0_wedge_e"]
    assert "e0 E = e0" not in fails and len(fails) == 6
    # flipping the sign of E changes exactly the properties that are odd in E
    assert set(fails) == {"E e = -e", "e+ E = e-", "e- E = e+", "e+ e = 1 + E", "e- e = -(1 + E)", "e ^ e- = E"}


def test_projection_rejection():
    d = assert_derivation("projection_rejection", _labels(57, 60))
    a4, a5 = sp.symbols("a4 a5", real=True)
    sol = d.values["alpha_beta"][0]
    alpha, beta = sp.symbols("alpha beta")
    assert sp.simplify(sol[alpha] - (a5 - a4)) == 0 and sp.simplify(sol[beta] - (a4 + a5) / 2) == 0


def test_null_cone_points():
    d = assert_derivation("null_cone_points", _labels(61, 68) + ["table 2.1"])
    assert d["2.63 middle line (printed)"].holds is False
    assert d["2.63 middle line (corrected)"].holds


def test_sphere_and_plane():
    d = assert_derivation("sphere_and_plane", _labels(70, 77) + ["table 2.1"])
    w = sp.symbols("w1:4", real=True)
    rho = sp.Symbol("rho", positive=True)
    alpha = sp.Symbol("alpha")
    assert sp.simplify(d.values["recovered"][0][alpha] - (dot3(w, w) - rho**2) / 2) == 0


def test_circle_properties():
    d = assert_derivation("circle_properties", ["2.78", "2.79", "2.80", "table 2.1"] + _labels(119, 124))
    assert d.values["radius2"] == sp.Symbol("r", positive=True) ** 2


def test_line_properties():
    assert_derivation("line_properties", ["2.81", "table 2.1"] + _labels(125, 130))


def test_conformal_transformations():
    d = assert_derivation("conformal_transformations", _labels(82, 93) + ["table 2.2"])
    assert d["2.92 = 1 + t e/2 (printed)"].holds is False
    assert d["2.92 T x ~T = up(x + t): moves by +t"].holds


def test_point_pair_extraction():
    d = assert_derivation("point_pair_extraction", _labels(131, 134) + ["table 2.1"])
    a = sp.symbols("a1:4", real=True)
    b = sp.symbols("b1:4", real=True)
    assert same(d.values["p1"], up(list(a))) and same(d.values["p2"], up(list(b)))
    assert d.values["sphere_scale"] == -1


def test_rotors_and_motors():
    assert_derivation("rotors_and_motors", _labels(135, 145))


# ------------------------------------------------------------ errata
@pytest.mark.parametrize(
    "err", symbolic.ERRATA, ids=[f"{e.label.replace(' ', '')}-{i}" for i, e in enumerate(symbolic.ERRATA)]
)
def test_errata(err):
    """Each printed form fails and its correction holds, in the derivation named."""
    d = derivation(err.decided_by.rsplit(".", 1)[1])
    assert d[err.printed_check].expected is False
    assert d[err.printed_check].holds is False
    assert d[err.correct_check].holds is True
    assert err.printed and err.correct and err.printed != err.correct


def test_every_printed_failure_is_listed_as_erratum():
    """A check expected to fail is an erratum in ERRATA, or one of its stated consequences."""
    listed = {(e.decided_by.rsplit(".", 1)[1], e.printed_check) for e in symbolic.ERRATA}
    consequences = {
        # the other (2.56) properties under the printed E = e0 ^ e of (2.55)
        *((("minkowski_plane", f"2.56 {p[0]} [E = e0^e]")) for p in symbolic.MINKOWSKI_PROPERTIES),
        # (2.122) unsquared, next to the squared form that is listed
        ("circle_properties", "2.122 rho = z^2 / (e ^ z)^2 (printed)"),
    }
    for name in symbolic.DERIVATIONS:
        for c in derivation(name).errata():
            assert (name, c.name) in listed | consequences, f"{name}: {c.name!r} fails but is not in ERRATA"


# ------------------------------------------------------------ registry
OWN_LABELS = {f"2.{i}" for i in [*range(1, 11), *range(38, 78), *range(82, 94), *range(131, 146)]}


def test_registry_entries():
    labels = [e.label for e in ch2_derivations.ENTRIES + ch2_derivations_entities.ENTRIES]
    assert len(labels) == len(set(labels)) and set(labels) == OWN_LABELS
    problems = [p for p in check_registry() if p.split(":")[0] in OWN_LABELS]
    assert problems == []
    for label in OWN_LABELS:
        entry = REGISTRY[label]
        assert entry.status in ("symbolic", "erratum", "definition")
        if entry.status == "erratum":
            assert any(e.label == label for e in symbolic.ERRATA)
    for err in symbolic.ERRATA:
        if err.label in OWN_LABELS:
            assert REGISTRY[err.label].status == "erratum"


def test_down_of_a_symbolic_point_is_exact():
    """(2.114) on SymPy coefficients: missing components are the integer 0, never the float 0.0."""
    x = sp.Symbol("x", real=True)
    got = cga.down(cga.up([x, 0, 0]))
    assert got == sp.Matrix([x, 0, 0])
    assert not any(isinstance(v, sp.Float) for v in got.atoms(sp.Number))


def test_symbolic_point_pairs_and_circles_stay_exact_and_refuse_collinear_points():
    """(2.131) on SymPy pairs in general position, mixed integer/symbol input kept exact, (2.80) refusing a line."""
    x, y = sp.symbols("x y", real=True)
    p1, p2 = cga.point_pair_endpoints(cga.point_pair([x, y, 0], [x + 1, y, 0]))
    assert {tuple(p1), tuple(p2)} == {(x, y, 0), (x + 1, y, 0)}
    q1, q2 = cga.point_pair_endpoints(cga.point_pair([1, 2, 3], [sp.Integer(4), 5, 6]))
    assert {tuple(q1), tuple(q2)} == {(1, 2, 3), (4, 5, 6)}
    assert all(isinstance(v, sp.Integer) for v in tuple(q1) + tuple(q2))
    with pytest.raises(cga.DegenerateGeometryError, match="circle_from_points: a, b, c: the 3 points are collinear"):
        cga.circle_from_points([0, 0, 0], [1, 0, 0], [sp.Integer(2), 0, 0])


def test_derivations_are_computed_once_and_returned_as_copies():
    """A second call costs nothing and returns a Derivation of its own (adding to it leaves the next call's alone)."""
    first = symbolic.minkowski_plane()
    first.add_bool("a note of mine", "2.56", True)
    second = symbolic.minkowski_plane()
    assert "a note of mine" not in second.names() and second.names() == first.names()[:-1]
    assert second.checks[0] is first.checks[0]  # the checks themselves are shared (frozen)


def test_the_machinery_refuses_bad_input_clearly():
    d = symbolic.minkowski_plane()
    with pytest.raises(KeyError, match=r"Derivation\[\]: name: .*no check named 'nope'"):
        d["nope"]
    with pytest.raises(cga.InvalidInputError, match="Derivation.for_label: label: '2.999' is not an equation"):
        d.for_label("2.999")
    with pytest.raises(cga.InvalidInputError, match="Derivation.add: name: check .* recorded twice"):
        d.add(d.names()[0], "2.56", 1, 1)
    with pytest.raises(cga.InvalidInputError, match="basis_and_product_axioms: signatures: must be <= 10"):
        symbolic.basis_and_product_axioms([(11, 0, 0)])
    with pytest.raises(cga.InvalidInputError, match="Ring: symbols: expected SymPy symbols"):
        Ring(["x"])
    with pytest.raises(cga.InvalidInputError, match="is_zero: rel: expected a Ring or None"):
        symbolic.is_zero(sp.Integer(0), rel="text")
