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

from dataclasses import dataclass, field

import sympy as sp
from sympy.polys.rings import PolyElement

from cga_lessons.algebra import DegenerateGeometryError, Multivector
from cga_lessons.conformal import G41, exact_constants, up

__all__ = [
    "Check",
    "Derivation",
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


def const() -> dict:
    """The exact constants ``e1 e2 e3 ep em einf eo E IE Ic`` of G(4,1) (SymPy rationals)."""
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
    return up([sp.sympify(v) for v in center]) - exact_constants()["einf"] * (sp.sympify(radius2) / 2)


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
        self.symbols = tuple(symbols)
        self.subs = dict(subs)
        self.R, *gens = sp.ring(self.symbols, sp.QQ, order="lex")
        self.gens = dict(zip(self.symbols, gens))
        rels = [sp.expand(r) for r in relations]
        basis = sp.groebner(rels, *self.symbols, order="lex").exprs if rels else []
        self.basis = [self.R.from_expr(g) for g in basis]

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
        return y + self.lift(c["einf"]) * self.scalar(self.element(y2) * sp.Rational(1, 2)) + self.lift(c["eo"])

    def divide(self, X: Multivector, den) -> Multivector:
        """X / den, for a polynomial den that divides every coefficient exactly."""
        den = self.element(den)
        out = {}
        for blade, v in X.coeffs.items():
            (q,), rem = self.element(v).div([den])
            if rem != 0:
                raise ValueError(f"Ring.divide: {den} does not divide the coefficient {v}")
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
    if isinstance(x, bool):
        return not x
    if isinstance(x, Multivector):
        return all(_scalar_is_zero(v, rel) for v in x.coeffs.values())
    if isinstance(x, sp.MatrixBase):
        return all(_scalar_is_zero(v, rel) for v in x)
    if isinstance(x, (list, tuple)):
        return all(is_zero(v, rel) for v in x)
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
    return is_zero(_diff(a, b), rel)


def proportional(X: Multivector, Y: Multivector, rel: Ring | None = None) -> bool:
    """True when X and Y are non-zero and X = k Y for a scalar k (homogeneous equality).

    Tests that every 2x2 minor ``X_i Y_j - X_j Y_i`` of the coefficient
    vectors vanishes; entities of the conformal model are defined up to scale.
    """
    if is_zero(X, rel) or is_zero(Y, rel):
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


def _display(x):
    """x with ring elements turned back into SymPy expressions (for display)."""
    if isinstance(x, PolyElement):
        return x.as_expr()
    if isinstance(x, Multivector) and any(isinstance(v, PolyElement) for v in x.coeffs.values()):
        return Multivector(x.algebra, {b: _display(v) for b, v in x.coeffs.items()}, _prune=True)
    if isinstance(x, list):
        return [_display(v) for v in x]
    return x


@dataclass(frozen=True)
class Check:
    """One step of a derivation: ``lhs == rhs`` and whether it holds.

    Attributes
    ----------
    name : str
        Short key, e.g. ``"2.56 e0 E = e0 (printed)"``.
    label : str
        The thesis's equation number, e.g. ``"2.56"`` (``"table 2.2"`` for a table).
    raw_lhs, raw_rhs
        The two sides as computed (SymPy expressions, multivectors, or ring
        elements of a :class:`Ring`); the properties ``lhs`` and ``rhs``
        give them with SymPy coefficients, for display.
    holds : bool
        Whether ``lhs == rhs`` identically.
    expected : bool
        ``True`` for a correct statement, ``False`` for a printed erratum
        (which must then fail).
    note : str
        What the step says, in words.
    """

    name: str
    label: str
    raw_lhs: object
    raw_rhs: object
    holds: bool
    expected: bool = True
    note: str = ""

    @property
    def lhs(self):
        """Left side, with SymPy coefficients (converted from ring elements on access)."""
        return _display(self.raw_lhs)

    @property
    def rhs(self):
        """Right side, with SymPy coefficients."""
        return _display(self.raw_rhs)

    @property
    def ok(self) -> bool:
        """True when the check came out as expected (identity holds, erratum fails)."""
        return self.holds == self.expected


@dataclass
class Derivation:
    """Result of a derivation: the checks of its steps and its named values.

    ``holds`` is true when every correct identity holds and every printed
    erratum fails.  Index by check name: ``d["2.45"].holds``.
    """

    title: str
    labels: tuple
    checks: list = field(default_factory=list)
    values: dict = field(default_factory=dict)

    def add(self, name, label, lhs, rhs, expected=True, note="", rel=None) -> Check:
        """Compare ``lhs`` with ``rhs`` and record the result as a :class:`Check`."""
        if any(c.name == name for c in self.checks):
            raise ValueError(f"check {name!r} recorded twice")
        chk = Check(name, label, lhs, rhs, same(lhs, rhs, rel), expected, note)
        self.checks.append(chk)
        return chk

    def add_bool(self, name, label, value: bool, expected=True, note="", lhs=None, rhs=None) -> Check:
        """Record a check decided elsewhere (proportionality, a set of solutions)."""
        if any(c.name == name for c in self.checks):
            raise ValueError(f"check {name!r} recorded twice")
        chk = Check(name, label, lhs, rhs, bool(value), expected, note)
        self.checks.append(chk)
        return chk

    @property
    def holds(self) -> bool:
        return all(c.ok for c in self.checks)

    def __getitem__(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(f"{self.title}: no check named {name!r}; have {[c.name for c in self.checks]}")

    def names(self) -> list:
        return [c.name for c in self.checks]

    def for_label(self, label: str) -> list:
        """The checks of one equation."""
        return [c for c in self.checks if c.label == label]

    def errata(self) -> list:
        """The checks of printed forms that are wrong (expected to fail)."""
        return [c for c in self.checks if not c.expected]

    def failures(self) -> list:
        """Checks that did not come out as expected (empty when ``holds``)."""
        return [c for c in self.checks if not c.ok]

    def table(self) -> str:
        """The checks as a Markdown table (for notebooks)."""
        rows = [f"**{self.title}** (Eqs. {', '.join(self.labels)})", "", "| eq. | step | result |", "|---|---|---|"]
        for c in self.checks:
            if c.expected:
                res = "holds" if c.holds else "**FAILS**"
            else:
                res = "printed form fails (erratum)" if not c.holds else "**printed form holds?**"
            name = c.name.replace("|", "\\|")  # a literal | would split the Markdown cell
            rows.append(f"| {c.label} | {name} | {res} |")
        return "\n".join(rows)

    def _repr_markdown_(self) -> str:
        return self.table()

    def __repr__(self) -> str:
        n_err = len(self.errata())
        status = "holds" if self.holds else f"{len(self.failures())} unexpected result(s)"
        return f"<Derivation {self.title!r}: {len(self.checks)} checks, {n_err} errata, {status}>"
