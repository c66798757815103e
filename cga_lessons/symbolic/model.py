"""Symbolic derivations of sections 2.3-2.3.3: the stereographic projection, the Minkowski plane and conformal
points, Eqs. (2.38)-(2.68) (the Clifford product and the axioms, 2.1-2.10, are in
:mod:`cga_lessons.symbolic.axioms`).

Each function returns a :class:`~cga_lessons.symbolic.core.Derivation`;
``d.holds`` is asserted by ``tests/test_symbolic.py``.
"""

from __future__ import annotations

import sympy as sp

from cga_lessons.algebra import Algebra, Multivector
from cga_lessons.conformal import up

from .axioms import exact_basis
from .core import const, dot3, euclid, inverse
from .records import Derivation, derivation

__all__ = [
    "stereographic_projection",
    "minkowski_plane",
    "MINKOWSKI_PROPERTIES",
    "projection_rejection",
    "null_cone_points",
]

ONE = sp.Integer(1)
HALF = sp.Rational(1, 2)


# --------------------------------------------------------------- 2.38 - 2.51
@derivation
def stereographic_projection() -> Derivation:
    """Stereographic projection in 1D, Eqs. (2.38)-(2.51), solved with SymPy.

    The point x e1 (2.38) is joined to the north pole n = e+ by a line
    f(a) = m a + q whose coefficients are *solved* from f(0) = 1 and f(x) = 0
    (2.39); the line is intersected with the unit circle a^2 + f(a)^2 = 1
    (2.40) by ``sympy.solve`` (2.41-2.44).  The non-trivial root is compared
    with (2.45) and (2.47), the point with (2.48), its homogeneous forms with
    (2.49)-(2.51), and (2.51) with ``up`` restricted to one dimension
    (x e1 + x^2 e / 2 + e0), a null vector.

    Returns
    -------
    Derivation
        values: ``line`` (f as an expression in a), ``roots`` (all solutions
        for a), ``a``, ``b`` (the projected point's coordinates),
        ``x1 x2 x3`` (the points of 2.48, 2.49, 2.50-2.51).
    """
    d = Derivation("Stereographic projection (1D)", tuple(f"2.{i}" for i in range(38, 52)))
    x = sp.Symbol("x", real=True, nonzero=True)
    a, m, q = sp.symbols("a m q", real=True)
    G2 = Algebra(2, labels=["1", "+"])
    e1, ep = exact_basis(G2)
    d.add("2.38 x = x e1 + 0 e+ is on the e1 axis", "2.38", (e1 * x) | ep, 0)
    # (2.39) the line through the north pole (0, 1) and (x, 0), solved
    coef = sp.solve([m * 0 + q - 1, m * x + q], [m, q], dict=True)[0]
    f = coef[m] * a + coef[q]
    d.values["line"] = f
    d.add("2.39 line through n and x: f(a) = -a/x + 1", "2.39", f, -a / x + 1)
    circle = a**2 + f**2 - 1  # (2.40)
    d.add("2.40 n = (0, 1) is on the circle", "2.40", circle.subs(a, 0), 0)
    d.add("2.41 substituted", "2.41", circle, a**2 + (-a / x + 1) ** 2 - 1)
    d.add("2.42 expanded", "2.42", sp.expand(circle), a**2 + a**2 / x**2 - 2 * a / x)
    d.add("2.43 factored", "2.43", sp.expand(circle), a * (a + a / x**2 - 2 / x))
    roots = sp.solve(circle, a)
    d.values["roots"] = roots
    d.add_bool("2.43 two roots", "2.43", len(roots) == 2, lhs=roots)
    trivial = [r for r in roots if sp.simplify(r) == 0]
    other = [r for r in roots if sp.simplify(r) != 0]
    d.add_bool("2.43 a = 0 is the north pole", "2.43", len(trivial) == 1 and f.subs(a, 0) == 1, lhs=trivial)
    a_s = sp.simplify(other[0]) if other else sp.nan
    d.add("2.44 a (1 + 1/x^2) = 2/x", "2.44", a_s * (1 + 1 / x**2), 2 / x)
    d.add("2.45 a = 2x/(x^2+1)", "2.45", a_s, 2 * x / (x**2 + 1))
    b_s = sp.simplify(f.subs(a, a_s))
    d.values["a"], d.values["b"] = a_s, b_s
    d.add("2.46 f(a) substituted", "2.46", b_s, -(1 / x) * (2 * x / (x**2 + 1)) + 1)
    d.add("2.47 f(a) = (x^2-1)/(x^2+1)", "2.47", b_s, (x**2 - 1) / (x**2 + 1))
    _projected_point(d, a_s, b_s, e1, ep, x)
    return d


def _projected_point(d: Derivation, a_s, b_s, e1, ep, x):
    """(2.48)-(2.51): the projected point on the unit circle, made homogeneous and null: up(x) in 1D."""
    x1 = e1 * a_s + ep * b_s
    d.values["x1"] = x1
    d.add(
        "2.48 x' = 2x/(x^2+1) e1 + (x^2-1)/(x^2+1) e+",
        "2.48",
        x1,
        e1 * (2 * x / (x**2 + 1)) + ep * ((x**2 - 1) / (x**2 + 1)),
    )
    d.add("2.48 x' is on the unit circle", "2.48", x1 * x1, 1)
    G21 = Algebra(2, 1, labels=["1", "+", "-"])
    f1, fp, fm = exact_basis(G21)
    x2 = f1 * a_s + fp * b_s + fm
    d.values["x2"] = x2
    d.add("2.49 x'' = x' + e-", "2.49", x2, f1 * (2 * x / (x**2 + 1)) + fp * ((x**2 - 1) / (x**2 + 1)) + fm)
    d.add("2.49 x'' is null", "2.49", x2 * x2, 0)
    x3 = x2 * ((x**2 + 1) / 2)
    x3 = x3.map(sp.cancel)
    d.values["x3"] = x3
    d.add(
        "2.50 x''' = x e1 + (x^2-1)/2 e+ + (x^2+1)/2 e-",
        "2.50",
        x3,
        f1 * x + fp * ((x**2 - 1) / 2) + fm * ((x**2 + 1) / 2),
    )
    f_inf, f_0 = fm + fp, (fm - fp) / 2
    d.add("2.51 x''' = x e1 + x^2/2 (e- + e+) + (e- - e+)/2", "2.51", x3, f1 * x + f_inf * (x**2 / 2) + f_0)
    X = up([x, 0, 0])
    d.add(
        "2.51 equals up(x e1) restricted to 1D",
        "2.51",
        [X["e1"], X["e+"], X["e-"], X - const().e1 * X["e1"] - const().ep * X["e+"] - const().em * X["e-"]],
        [x3["e1"], x3["e+"], x3["e-"], 0],
    )
    d.add("2.51 x''' is null", "2.51", x3 * x3, 0)
    d.add("2.51 x''' . e = -1", "2.51", x3 | f_inf, -1)


# --------------------------------------------------------------- 2.52 - 2.56
#: The ten properties printed in (2.56), as functions of (E, e, e0, e+, e-):
#: (name, lhs, rhs, holds with E = e+ e-, holds with E = e0 ^ e).
MINKOWSKI_PROPERTIES = (
    ("E^2 = 1", lambda E, e, o, p, m: E * E, lambda E, e, o, p, m: 1, True, True),
    ("~E = -E", lambda E, e, o, p, m: ~E, lambda E, e, o, p, m: -E, True, True),
    ("E e = -e", lambda E, e, o, p, m: E * e, lambda E, e, o, p, m: -e, True, False),
    ("e0 E = e0", lambda E, e, o, p, m: o * E, lambda E, e, o, p, m: o, False, True),
    ("e+ E = e-", lambda E, e, o, p, m: p * E, lambda E, e, o, p, m: m, True, False),
    ("e- E = e+", lambda E, e, o, p, m: m * E, lambda E, e, o, p, m: p, True, False),
    ("e+ e = 1 + E", lambda E, e, o, p, m: p * e, lambda E, e, o, p, m: 1 + E, True, False),
    ("e- e = -(1 + E)", lambda E, e, o, p, m: m * e, lambda E, e, o, p, m: -(1 + E), True, False),
    ("e ^ e- = E", lambda E, e, o, p, m: e ^ m, lambda E, e, o, p, m: E, True, False),
    ("e+ . e = 1", lambda E, e, o, p, m: p | e, lambda E, e, o, p, m: 1, True, True),
)


@derivation
def minkowski_plane() -> Derivation:
    """The Minkowski plane R^{1,1} and its null basis, Eqs. (2.52)-(2.56).

    Builds e+, e- from the basis of G(4,1) (2.52), the null basis
    e0 = (e- - e+)/2, e = e- + e+ (2.53), checks (2.54), the three printed
    forms of E (2.55), and each of the ten properties of (2.56) twice: with
    E = e+ e- (the model's convention, = e ^ e0) and with E = e0 ^ e as
    printed in (2.55).  ``MINKOWSKI_PROPERTIES`` records which properties we
    claim hold under each; the checks confirm the claims.

    Returns
    -------
    Derivation
        values: ``fails_with_E_ep_em`` and ``fails_with_E_e0_wedge_e``, the
        names of the (2.56) properties that fail under each definition.
    """
    d = Derivation("Minkowski plane and null basis", ("2.52", "2.53", "2.54", "2.55", "2.56"))
    c = const()
    ep, em = c.ep, c.em
    d.add("2.52 e+^2 = 1", "2.52", ep * ep, 1)
    d.add("2.52 e-^2 = -1", "2.52", em * em, -1)
    d.add("2.52 e+ . e- = 0", "2.52", ep | em, 0)
    e0 = (em - ep) * HALF
    e = em + ep
    d.add("2.53 model e0 = (e- - e+)/2", "2.53", c.eo, e0)
    d.add("2.53 model e = e- + e+", "2.53", c.einf, e)
    d.add("2.54 e0^2 = 0", "2.54", e0 * e0, 0)
    d.add("2.54 e^2 = 0", "2.54", e * e, 0)
    d.add("2.54 e . e0 = -1", "2.54", e | e0, -1)
    d.add("2.55 e+ ^ e- = e+ e-", "2.55", ep ^ em, ep * em)
    d.add(
        "2.55 E := e0 ^ e = e+ e- (printed)",
        "2.55",
        e0 ^ e,
        ep * em,
        expected=False,
        note="e0 ^ e = -e+ e-: the printed definition has the wrong sign",
    )
    d.add("2.55 E = e ^ e0 = e+ e- (corrected)", "2.55", e ^ e0, ep * em)
    d.add("2.55 model E = e+ e-", "2.55", c.E, ep * em)
    variants = (("E = e+e-", ep * em, 3), ("E = e0^e", e0 ^ e, 4))
    for tag, E, col in variants:
        fails = []
        for prop in MINKOWSKI_PROPERTIES:
            name, lhs, rhs = prop[0], prop[1](E, e, e0, ep, em), prop[2](E, e, e0, ep, em)
            chk = d.add(f"2.56 {name} [{tag}]", "2.56", lhs, rhs, expected=prop[col])
            if not chk.holds:
                fails.append(name)
        d.values["fails_with_E_ep_em" if col == 3 else "fails_with_E_e0_wedge_e"] = fails
    E = ep * em
    d.add("2.56 e0 E = -e0 (corrected)", "2.56", e0 * E, -e0)
    d.add("2.56 E e0 = e0 (corrected, other order)", "2.56", E * e0, e0)
    return d


# --------------------------------------------------------------- 2.57 - 2.60
@derivation
def projection_rejection() -> Derivation:
    """Projection onto and rejection from the Minkowski plane, Eqs. (2.57)-(2.60).

    For a general vector a of R^{4,1} (five symbols): ``P_E(a) = (a . E) E``
    is the e+, e- part, written ``alpha e0 + beta e`` with alpha, beta
    *solved* (2.58); ``P_E^perp(a) = (a . E*) ~E* = (a ^ E) E`` is the
    Euclidean part (2.59); they sum to a (2.57).  ``I_c = e_{+-123} = E I_E``
    (2.60) is the pseudoscalar of G(4,1), squaring to -1.
    """
    d = Derivation("Projection and rejection, Ic", ("2.57", "2.58", "2.59", "2.60"))
    c = const()
    E, Ic, IE = c.E, c.Ic, c.IE
    s = sp.symbols("a1:6", real=True)
    basis = [c.e1, c.e2, c.e3, c.ep, c.em]
    a = sum((b * si for si, b in zip(s, basis)), basis[0] * 0)
    P = (a | E) * E
    Pp = (a ^ E) * E
    d.add("2.57 P_E(a) + P_E^perp(a) = a", "2.57", P + Pp, a)
    d.add("2.58 P_E(a) is the e+, e- part", "2.58", P, c.ep * s[3] + c.em * s[4])
    al, be = sp.symbols("alpha beta")
    eqs = [(c.eo * al + c.einf * be - P)[k] for k in ("e+", "e-")]
    sol = sp.solve(eqs, [al, be], dict=True)
    d.values["alpha_beta"] = sol
    d.add_bool("2.58 alpha, beta solved uniquely", "2.58", len(sol) == 1, lhs=sol)
    if sol:
        d.add("2.58 P_E(a) = alpha e0 + beta e", "2.58", c.eo * sol[0][al] + c.einf * sol[0][be], P)
    Es = E * inverse(Ic)
    d.add("2.59 (a ^ E) E is the Euclidean part", "2.59", Pp, c.e1 * s[0] + c.e2 * s[1] + c.e3 * s[2])
    d.add("2.59 (a . E*) ~E* = (a ^ E) E", "2.59", (a | Es) * ~Es, Pp)
    d.add("2.60 Ic = e+-123", "2.60", Ic, Ic.algebra.blade("e+-123", ONE))
    d.add("2.60 Ic = E IE", "2.60", Ic, E * IE)
    d.add(
        "2.60 Ic = e1 e2 e3 e+ e- (pseudoscalar of G41)", "2.60", Ic, Multivector(Ic.algebra, {Ic.algebra.dim - 1: ONE})
    )
    d.add("2.60 Ic^2 = -1", "2.60", Ic * Ic, -1)
    return d


# --------------------------------------------------------------- 2.61 - 2.68
@derivation
def null_cone_points() -> Derivation:
    """Conformal points, the null cone and the distance identity, Eqs. (2.61)-(2.68).

    For symbolic points x, a, b of R^3: ``up(x)`` is null with ``x . e = -1``
    (2.61) and equals ``x + x^2 e/2 + e0`` (2.62); the expansion in e+, e-
    (2.63) as printed (middle line) and corrected; ``X / (-X . e0)`` (2.64)
    and its limit e along any ray; the product of two points (2.65), their
    inner product (2.66), (2.67), and their outer product, the point pair (2.68).

    Returns
    -------
    Derivation
        values: ``X``, ``A``, ``B`` and ``limit`` (the limit of 2.64).
    """
    d = Derivation("Conformal points and distances", tuple(f"2.{i}" for i in range(61, 69)))
    c = const()
    e, e0, E, ep, em = c.einf, c.eo, c.E, c.ep, c.em
    xs = sp.symbols("x1:4", real=True)
    a_s = sp.symbols("a1:4", real=True)
    b_s = sp.symbols("b1:4", real=True)
    X = up(list(xs))
    x = euclid(xs)
    x2 = dot3(xs, xs)
    d.values["X"] = X
    d.add("2.61 x^2 = 0", "2.61", X * X, 0)
    d.add("2.61 x . e = -1", "2.61", X | e, -1)
    d.add("2.62 up(x) = x + x^2 e / 2 + e0", "2.62", X, x + e * (x2 / 2) + e0)
    d.add("2.62 x = 0 gives e0", "2.62", up([sp.Integer(0)] * 3), e0)
    d.add(
        "2.63 middle line (printed)",
        "2.63",
        X,
        x + (em - ep) * (x2 / 2) + (em + ep) * HALF,
        expected=False,
        note="the expansions of e and e0 are swapped",
    )
    d.add("2.63 middle line (corrected)", "2.63", X, x + (em + ep) * (x2 / 2) + (em - ep) * HALF)
    d.add("2.63 final line", "2.63", X, x + ep * ((x2 - 1) / 2) + em * ((x2 + 1) / 2))
    ratio = (X * (1 / (-(X | e0).scalar()))).map(sp.cancel)
    d.add("2.64 -x . e0 = x^2/2", "2.64", -(X | e0), x2 / 2)
    d.add("2.64 x / (-x . e0) = e + 2 (x + e0)/x^2", "2.64", ratio, e + (x + e0) * (2 / x2))
    s = sp.Symbol("s", positive=True)
    ray = ratio.subs({xi: s * xi for xi in xs})
    limit = ray.map(lambda v: sp.limit(v, s, sp.oo))
    d.values["limit"] = limit
    d.add("2.64 limit along a ray x = s u, s -> oo, is e", "2.64", limit, e)
    A, B = up(list(a_s)), up(list(b_s))
    a, b = euclid(a_s), euclid(b_s)
    a2, b2 = dot3(a_s, a_s), dot3(b_s, b_s)
    d.values["A"], d.values["B"] = A, B
    printed65 = a * b + (a - b) * e0 - ((b * a2 - a * b2) * e + E * (b2 - a2) + (a2 + b2)) * HALF
    d.add("2.65 ab expanded", "2.65", A * B, printed65)
    dist2 = dot3([p - q for p, q in zip(a_s, b_s)], [p - q for p, q in zip(a_s, b_s)])
    d.add("2.66 a . b = -(a - b)^2 / 2", "2.66", A | B, -dist2 / 2)
    d.add("2.66 = a.b - (a^2 + b^2)/2", "2.66", A | B, dot3(a_s, b_s) - (a2 + b2) / 2)
    d.add("2.66 a . b = scalar part of (2.65)", "2.66", A | B, printed65.grade(0))
    d.add("2.67 (a - b)^2 = -2 a . b", "2.67", (A - B) * (A - B), -2 * (A | B))
    d.add("2.67 (a - b)^2 = |a - b|^2", "2.67", (A - B) * (A - B), dist2)
    printed68 = (a ^ b) + ((a - b) ^ e0) - (((b * a2 - a * b2) ^ e) + E * (b2 - a2)) * HALF
    d.add("2.68 a ^ b expanded", "2.68", A ^ B, printed68)
    d.add("2.68 a ^ b = bivector part of (2.65)", "2.68", A ^ B, printed65.grade(2))
    d.add(
        "table 2.1 point dual x* = (-E x - x^2 e/2 + e0) I_E",
        "table 2.1",
        X * inverse(c.Ic),
        (e0 - E * x - e * (x2 / 2)) * c.IE,
    )
    return d
