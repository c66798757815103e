"""Shared machinery of the symbolic derivations (:mod:`cga_lessons.symbolic`).

A derivation is a function that builds the thesis's objects with SymPy
coefficients (exact constants, :func:`cga_lessons.conformal.model.exact_constants`),
compares each printed step with what the algebra computes, and returns a
:class:`Derivation`: the list of :class:`Check` objects (one per equation or
step, with both sides kept for display) and a dictionary of named values
(solved coordinates, intermediate multivectors).

A check compares two sides, each a SymPy expression, a :class:`Multivector`, a
SymPy matrix or a list of these.  Two sides are equal when their difference
expands (or cancels, or reduces modulo the relations of a
:class:`Ring`) to zero.  A check carries ``expected``: ``True`` for an
identity the thesis states correctly, ``False`` for a printed form that is an
erratum and must *fail*.  ``Derivation.holds`` is true when every check comes
out as expected.
"""

from __future__ import annotations

import math
import numbers

import sympy as sp
from sympy.polys.polyerrors import PolynomialError
from sympy.polys.rings import PolyElement

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, GeometryError, Multivector
from cga_lessons.conformal import G41, ModelConstants, exact_constants, up

__all__ = [
    "Ring",
    "const",
    "euclid",
    "is_zero",
    "same",
    "proportional",
    "inverse",
    "dot3",
    "cross3",
    "add3",
    "sub3",
    "scale3",
    "sphere_from_center",
]


def const() -> ModelConstants:
    """The exact constants ``e1 e2 e3 ep em einf eo E IE Ic`` of G(4,1) (SymPy rationals, as fields of one
    :class:`~cga_lessons.conformal.ModelConstants`)."""
    return exact_constants()


def euclid(v) -> Multivector:
    """The Euclidean vector v1 e1 + v2 e2 + v3 e3 of G(4,1) from three SymPy expressions."""
    v = [sp.sympify(c) for c in v]
    return Multivector(G41, {1: v[0], 2: v[1], 4: v[2]}, _prune=True)


def dot3(a, b):
    """Euclidean dot product of two length-3 sequences."""
    return sum(sp.sympify(x) * y for x, y in zip(a, b))


def cross3(a, b) -> list:
    """Cross product of two length-3 sequences."""
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def add3(a, b) -> list:
    """a + b for coordinate lists."""
    return [x + y for x, y in zip(a, b)]


def sub3(a, b) -> list:
    """a - b for coordinate lists."""
    return [x - y for x, y in zip(a, b)]


def scale3(k, a) -> list:
    """k a for a coordinate list."""
    return [k * x for x in a]


def sphere_from_center(center, radius2) -> Multivector:
    """Standard-form sphere up(p) - rho^2 e / 2 (2.72), given the squared radius (exact)."""
    return up([sp.sympify(v) for v in center]) - exact_constants().einf * (sp.sympify(radius2) / 2)


class Ring:
    """Exact polynomial arithmetic modulo relations, for the heavy identities.

    Coefficients become elements of SymPy's sparse polynomial ring
    ``QQ[symbols]`` (:func:`sympy.ring`, lex order), which multiply far faster
    than expressions; the :class:`Multivector` code path is unchanged.
    ``relations`` (e.g. ``c^2 + s^2 - 1`` for cos and sin of a half-angle,
    ``n . n - 1`` for a unit axis) are turned into a Groebner basis; a
    polynomial whose remainder is zero lies in their ideal, so it vanishes
    wherever the relations hold.
    ``subs`` replaces functions by symbols first (``cos(theta/2) -> c``).

    Parameters
    ----------
    symbols : sequence of sympy.Symbol
        Every symbol that appears (the ring's generators).
    relations : sequence of expressions
        Polynomials that vanish (``== 0``).
    subs : sequence of (expression, expression) pairs
        Substitutions applied to expressions before conversion.
    """

    def __init__(self, symbols, relations=(), subs=()):
        self.symbols = _symbols(symbols)
        self.subs = _pairs(subs)
        self.R, *gens = sp.ring(self.symbols, sp.QQ, order="lex")
        self.gens = dict(zip(self.symbols, gens))
        rels = [sp.expand(side(r, "Ring", "relations", allow_none=False)) for r in _sequence(relations, "relations")]
        try:
            basis = sp.groebner(rels, *self.symbols, order="lex").exprs if rels else []
            self.basis = [self.R.from_expr(g) for g in basis]
        except (PolynomialError, ValueError, TypeError) as exc:
            raise checks.fail("Ring", "relations", f"must be polynomials in symbols {self.symbols} ({exc})") from None

    def element(self, v):
        """A ring element from a polynomial expression (or a ring element)."""
        if isinstance(v, PolyElement):
            return v
        v = sp.sympify(v)
        if v.is_zero:
            return self.R.zero
        if self.subs:
            v = v.subs(self.subs)
        return self.R.from_expr(sp.expand(v))

    def lift(self, X: Multivector) -> Multivector:
        """X with ring-element coefficients."""
        return Multivector(X.algebra, {b: self.element(v) for b, v in X.coeffs.items()}, _prune=True)

    def scalar(self, v) -> Multivector:
        """The scalar multivector v (a Multivector cannot be scaled by a ring element directly)."""
        return Multivector(G41, {0: self.element(v)}, _prune=True)

    def vector(self, v) -> Multivector:
        """The Euclidean vector of three polynomial expressions, lifted."""
        return self.lift(euclid(v))

    def up(self, y: Multivector) -> Multivector:
        """The conformal point y + y^2 e / 2 + e0 (2.62) of a lifted Euclidean vector y."""
        c = exact_constants()
        y2 = (y * y).scalar()
        return y + self.lift(c.einf) * self.scalar(self.element(y2) * sp.Rational(1, 2)) + self.lift(c.eo)

    def divide(self, X: Multivector, den) -> Multivector:
        """X / den, for a polynomial den that divides every coefficient exactly."""
        den = self.element(den)
        out = {}
        for blade, v in X.coeffs.items():
            (q,), rem = self.element(v).div([den])
            if rem != 0:
                raise checks.fail("Ring.divide", "den", f"{den} does not divide the coefficient {v}")
            out[blade] = q
        return Multivector(X.algebra, out, _prune=True)

    def reduce(self, v):
        """Normal form of v modulo the relations (v a ring element or an expression)."""
        if not isinstance(v, PolyElement):
            v = sp.sympify(v)
            if self.subs:
                v = v.subs(self.subs)
            num, _den = sp.fraction(sp.together(v))
            v = self.element(num)
        return v.rem(self.basis) if self.basis else v

    def to_expr(self, X: Multivector, back=None) -> Multivector:
        """X with SymPy expression coefficients again; ``back`` maps symbols back (``c -> cos(theta/2)``)."""
        out = {}
        for b, v in X.coeffs.items():
            ex = v.as_expr() if isinstance(v, PolyElement) else sp.sympify(v)
            out[b] = ex.subs(back) if back else ex
        return Multivector(X.algebra, out, _prune=True)


def _sequence(value, name: str) -> list:
    if isinstance(value, (str, bytes, dict)) or not hasattr(value, "__iter__"):
        raise checks.fail("Ring", name, f"expected a sequence, got {value!r:.40}")
    return list(value)


def _symbols(symbols) -> tuple:
    """The ring's generators: distinct SymPy symbols, at least one."""
    out = tuple(_sequence(symbols, "symbols"))
    if not out or not all(isinstance(v, sp.Symbol) for v in out):
        raise checks.fail("Ring", "symbols", f"expected SymPy symbols (at least one), got {out!r:.60}")
    if len(set(out)) != len(out):
        raise checks.fail("Ring", "symbols", f"lists a symbol twice: {out!r:.60}")
    return out


def _pairs(subs) -> dict:
    """The substitutions (expression, expression) applied before conversion, as a dict."""
    pairs = list(subs.items()) if isinstance(subs, dict) else _sequence(subs, "subs")
    for pair in pairs:
        if isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise checks.fail("Ring", "subs", f"expected (expression, expression) pairs, got {pair!r:.40}")
        for v in pair:
            side(v, "Ring", "subs", allow_none=False)
    return dict(pairs)


#: What one side of a comparison may be (besides lists, tuples and dicts of them, and None where allowed).
_SIDE_TYPES = (bool, numbers.Number, Multivector, PolyElement, sp.Basic, sp.MatrixBase, list, tuple, dict)


def side(value, func: str, name: str, *, allow_none: bool = True):
    """``value`` if it can be one side of a comparison: a SymPy expression or matrix, a Multivector, a ring element,
    a finite number, a bool, or a list, tuple or dict of them (``None`` if ``allow_none``)."""
    if value is None and allow_none:
        return value
    if not isinstance(value, _SIDE_TYPES) or isinstance(value, complex):
        raise checks.fail(
            func, name, f"expected a SymPy expression, a Multivector, a number or a list of them, got {value!r:.40}"
        )
    if isinstance(value, float) and not math.isfinite(value):
        raise checks.fail(func, name, f"is NaN or inf ({value!r})")
    if isinstance(value, Multivector):
        for b, v in value.coeffs.items():
            if isinstance(v, float) and not math.isfinite(v):
                raise checks.fail(func, name, f"coefficient of {value.algebra.blade_names[b]} is NaN or inf")
    return value


def ring_or_none(rel, func: str):
    """``rel`` if it is None or a :class:`Ring`."""
    if rel is not None and not isinstance(rel, Ring):
        raise checks.fail(func, "rel", f"expected a Ring or None, got {type(rel).__name__} {rel!r:.40}")
    return rel


def signature_list(signatures, func: str) -> tuple:
    """``signatures`` as distinct ``(p, q, r)`` triples of ints with 1 <= p + q + r <= 10."""
    if isinstance(signatures, (str, bytes)) or not hasattr(signatures, "__iter__"):
        raise checks.fail(func, "signatures", f"expected a sequence of (p, q, r), got {signatures!r:.40}")
    out = []
    for sig in signatures:
        if isinstance(sig, (str, bytes)) or not hasattr(sig, "__len__") or len(sig) != 3:
            raise checks.fail(func, "signatures", f"each signature is (p, q, r), got {sig!r:.40}")
        p, q, r = (checks.integer(v, func, "signatures", low=0, high=10) for v in sig)
        if not 1 <= p + q + r <= 10:
            raise checks.fail(func, "signatures", f"G({p},{q},{r}) must have dimension 1 to 10")
        out.append((p, q, r))
    if not out or len(set(out)) != len(out):
        raise checks.fail(func, "signatures", f"expected distinct signatures, at least one, got {out}")
    return tuple(out)


def _scalar_is_zero(e, rel: Ring | None) -> bool:
    if rel is not None:
        return rel.reduce(e) == 0
    if isinstance(e, PolyElement):
        return e == 0
    e = sp.sympify(e)
    if e.is_zero is True:  # also Float(0.0), which SymPy does not call == 0
        return True
    has_den = any(p.exp.is_negative and p.base.free_symbols for p in e.atoms(sp.Pow))
    num = sp.fraction(sp.together(e))[0] if has_den else e
    if sp.expand(num) == 0:
        return True
    if e.has(sp.sin, sp.cos, sp.acos, sp.Abs, sp.sqrt):
        return sp.simplify(e) == 0
    return False


def is_zero(x, rel: Ring | None = None) -> bool:
    """True when x (expression, Multivector, matrix, list, bool) is identically zero.

    Exact: a polynomial or rational difference is zero only if it expands
    (or cancels, or reduces modulo the relations of ``rel``) to 0.
    """
    return _is_zero(side(x, "is_zero", "x", allow_none=False), ring_or_none(rel, "is_zero"))


def _is_zero(x, rel: Ring | None) -> bool:
    if isinstance(x, bool):
        return not x
    if isinstance(x, Multivector):
        return all(_scalar_is_zero(v, rel) for v in x.coeffs.values())
    if isinstance(x, sp.MatrixBase):
        return all(_scalar_is_zero(v, rel) for v in x)
    if isinstance(x, (list, tuple)):
        return all(_is_zero(v, rel) for v in x)
    return _scalar_is_zero(x, rel)


def _diff(a, b):
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        if len(a) != len(b):
            return [sp.Integer(1)]
        return [_diff(x, y) for x, y in zip(a, b)]
    if isinstance(a, sp.MatrixBase) or isinstance(b, sp.MatrixBase):
        return sp.Matrix(a) - sp.Matrix(b)
    if isinstance(a, Multivector) and isinstance(b, PolyElement):
        b = Multivector(a.algebra, {0: b}, _prune=True)
    if isinstance(b, Multivector) and isinstance(a, PolyElement):
        a = Multivector(b.algebra, {0: a}, _prune=True)
    if isinstance(b, Multivector) and not isinstance(a, Multivector):
        return -(b - a)
    return a - b


def _lift_any(x, rel: Ring):
    """x with ring coefficients (raises ValueError for a non-polynomial expression)."""
    if isinstance(x, Multivector):
        return rel.lift(x)
    if isinstance(x, (list, tuple)):
        return [_lift_any(v, rel) for v in x]
    if isinstance(x, sp.MatrixBase):
        return [_lift_any(v, rel) for v in x]
    return rel.element(x)


def same(a, b, rel: Ring | None = None) -> bool:
    """True when the two sides are identically equal (see :func:`is_zero`).

    With a :class:`Ring`, polynomial sides are compared in the ring; sides
    with denominators are compared as expressions (numerator reduced).
    """
    side(a, "same", "a", allow_none=False)
    side(b, "same", "b", allow_none=False)
    ring_or_none(rel, "same")
    try:
        return _same(a, b, rel)
    except (TypeError, AttributeError, sp.SympifyError, GeometryError) as exc:
        raise checks.fail("same", "a, b", f"cannot be compared ({type(exc).__name__}: {exc})") from None


def _same(a, b, rel: Ring | None) -> bool:
    if isinstance(a, bool) or isinstance(b, bool):
        return bool(a) == bool(b)
    if rel is not None:
        try:
            a, b = _lift_any(a, rel), _lift_any(b, rel)
        except ValueError:
            pass
        else:
            if isinstance(a, Multivector) and isinstance(b, PolyElement):
                b = rel.scalar(b)
            elif isinstance(b, Multivector) and isinstance(a, PolyElement):
                a = rel.scalar(a)
    return _is_zero(_diff(a, b), rel)


def proportional(X: Multivector, Y: Multivector, rel: Ring | None = None) -> bool:
    """True when X and Y are non-zero and X = k Y for a scalar k (homogeneous equality).

    Tests that every 2x2 minor ``X_i Y_j - X_j Y_i`` of the coefficient
    vectors vanishes; entities of the conformal model are defined up to scale.
    """
    for name, M in (("X", X), ("Y", Y)):
        side(checks.instance(M, "proportional", name, Multivector, "a Multivector"), "proportional", name)
    ring_or_none(rel, "proportional")
    if _is_zero(X, rel) or _is_zero(Y, rel):
        return False
    blades = sorted(set(X.coeffs) | set(Y.coeffs))
    xs = [X.coeffs.get(b, 0) for b in blades]
    ys = [Y.coeffs.get(b, 0) for b in blades]
    pivot = next(i for i, v in enumerate(ys) if not _scalar_is_zero(v, rel))
    return all(_scalar_is_zero(xs[i] * ys[pivot] - xs[pivot] * ys[i], rel) for i in range(len(blades)))


def inverse(X: Multivector) -> Multivector:
    """Inverse ~X / (X ~X) of a blade or versor with SymPy coefficients (2.19).

    Expands ``X ~X`` before testing that it is a scalar, so a symbolic blade
    never falls back to the general 32x32 linear solve.
    """
    X = X.expand()
    rev = ~X
    mm = (X * rev).expand()
    if set(mm.coeffs) - {0}:
        raise DegenerateGeometryError(f"inverse: X ~X is not a scalar (blades {mm.blades()}); not a versor")
    d = mm.scalar()
    if d == 0:
        raise DegenerateGeometryError("inverse: X ~X = 0, X is null and has no inverse")
    if d.is_number:
        return rev * (1 / d)
    return rev.map(lambda v: v / d)


def display(x):
    """x with ring elements turned back into SymPy expressions (for display)."""
    if isinstance(x, PolyElement):
        return x.as_expr()
    if isinstance(x, Multivector) and any(isinstance(v, PolyElement) for v in x.coeffs.values()):
        return Multivector(x.algebra, {b: display(v) for b, v in x.coeffs.items()}, _prune=True)
    if isinstance(x, list):
        return [display(v) for v in x]
    return x
