"""The Multivector type of :mod:`cga_lessons.algebra` and its operators.

A :class:`Multivector` is a sparse map ``blade bitmap -> coefficient`` over
one :class:`~cga_lessons.algebra.Algebra`.  The coefficient may be a
Python/NumPy float, a NumPy array (a *batch*: one multivector per element,
e.g. one conformal point per row of a point cloud) or a SymPy expression; see
:mod:`cga_lessons.algebra.coefficients`.  The products behind the operators
are the algebra's (:mod:`cga_lessons.algebra.products`), the fast sandwich of
a versor is its matrices per grade (:mod:`cga_lessons.algebra.versor_matrices`); the
grades, involutions and dual live in :mod:`cga_lessons.algebra.involutions`, the
norms and the inverse (2.19) in :mod:`cga_lessons.algebra.inverse`, the
text/LaTeX display and the SymPy helpers in :mod:`cga_lessons.algebra.display`.

The operators and the thesis's notation for each are tabled in :mod:`cga_lessons.algebra`.

Import these names from :mod:`cga_lessons.algebra`, their public home.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cga_lessons.checks import fail, instance, integer, short
from cga_lessons.errors import DegenerateGeometryError, GeometryError

from . import access, display, inverse, involutions
from .coefficients import is_real_batch, is_real_single, is_zero
from .operands import AlgebraKind, finite_multivector, finite_out, no_inverse, not_finite, scalar_operand

if TYPE_CHECKING:
    from .core import Algebra

__all__ = ["Multivector", "commutator"]


def _hooked(out, op: str, A, B):
    """``out = A op B`` of an operator, passed to the algebra's operation hook (:meth:`Algebra.set_operation_hook
    <cga_lessons.algebra.Algebra.set_operation_hook>`) when there is one and B is a multivector."""
    hook = A.algebra.operation_hook
    return out if hook is None or not isinstance(B, Multivector) else hook(out, op, A, B)


class Multivector:
    """A multivector of an :class:`~cga_lessons.algebra.Algebra`: a sparse map blade -> coefficient.

    Coefficients are floats, NumPy arrays (a batch, all of one shape) or SymPy
    expressions.  Read a coefficient by blade name, ``X["e12"]`` (zero where
    absent; ``X["e21"]`` is ``-X["e12"]``); :meth:`blades` lists the non-zero
    ones.  The constructor takes the map ``{blade bitmap: coefficient}`` as it
    is (it is the building block of every operation); make multivectors from
    checked input with :meth:`Algebra.vector <cga_lessons.algebra.Algebra.vector>`,
    :meth:`~cga_lessons.algebra.Algebra.blade`, :meth:`~cga_lessons.algebra.Algebra.from_array` ...

    The operators refuse what they cannot combine with a clear error
    (``"Multivector *: other: ..."``): a NaN or inf number or array, a
    multivector of another algebra, a division by zero or by a multivector
    without inverse, and (for single multivectors) NaN or inf coefficients
    and results that overflow; see :mod:`cga_lessons.algebra.operands`.

    The operators are defined here; the other methods are plain functions of :mod:`~cga_lessons.algebra.access`
    (coefficients, comparisons), :mod:`~cga_lessons.algebra.involutions` (grades, involutions, dual),
    :mod:`~cga_lessons.algebra.inverse` (norms, inverse 2.19) and :mod:`~cga_lessons.algebra.display`.
    """

    __slots__ = ("algebra", "_c")
    __array_priority__ = 1000  # so that ndarray * Multivector defers to us
    __array_ufunc__ = None

    def __init__(self, algebra: Algebra, coeffs: dict | None = None, _prune: bool = False):
        if not isinstance(algebra, AlgebraKind):
            raise fail("Multivector", "algebra", f"expected an Algebra, got {type(algebra).__name__}")
        c = {} if coeffs is None else coeffs
        if type(c) is not dict:
            if not isinstance(c, dict):
                raise fail("Multivector", "coeffs", f"expected a dict {{blade bitmap: coefficient}}, got {c!r:.40}")
            c = dict(c)
        if _prune:
            c = {k: v for k, v in c.items() if not is_zero(v)}
        self.algebra = algebra
        self._c = c

    def _sympy_(self):
        # Tell SymPy a multivector is not one of its expressions, so that
        # ``sympy_expr * X`` falls back to Multivector.__rmul__.
        import sympy

        raise sympy.SympifyError(self)

    # ---------------------------------------------------------- arithmetic
    def _coerce(self, other, func: str):
        """``other`` as a multivector of this algebra; NotImplemented for a type of someone else's."""
        if isinstance(other, Multivector):
            if other.algebra is not self.algebra:
                raise fail(func, "other", f"is a multivector of {other.algebra}, not of {self.algebra}")
            return other
        other = scalar_operand(other, func)
        if other is NotImplemented:
            return other
        return Multivector(self.algebra, {0: other}, _prune=True)

    def _operand(self, other, func: str):
        """:meth:`_coerce` for a method, where no reflected operation can take over: refuses every other type."""
        got = self._coerce(other, func)
        if got is NotImplemented:
            raise fail(func, "other", f"expected a Multivector or a real number, got {type(other).__name__}")
        return got

    def _mismatch(self, func: str, other, exc: Exception):
        """The error for a NumPy failure inside an operation: batches of shapes that do not combine."""
        if isinstance(exc, GeometryError):
            return exc
        shape = getattr(other, "shape", ())
        return fail(func, "other", f"cannot combine a batch of shape {self.shape} with shape {shape} ({exc})")

    def _plus(self, other):
        """``self + other`` (a multivector of the same algebra), unchecked."""
        out = dict(self._c)
        for b, v in other._c.items():
            out[b] = out[b] + v if b in out else v
        return Multivector(self.algebra, out, _prune=True)

    def _binary(self, other, kind: str, func: str, reflected: bool = False):
        """The product ``kind`` of self and other (other first if ``reflected``), checked."""
        other = self._coerce(other, func)
        if other is NotImplemented:
            return NotImplemented
        try:
            out = (
                self.algebra._products.product(other, self, kind)
                if reflected
                else self.algebra._products.product(self, other, kind)
            )
        except ValueError as exc:
            raise self._mismatch(func, other, exc) from None
        return finite_out(out, func)

    # The operators +, - and ^ call the algebra's operation hook after their plain routine when both operands are
    # multivectors (_hooked).
    def _add(self, other):
        """``self + other`` without the operation hook."""
        other = self._coerce(other, "Multivector +")
        if other is NotImplemented:
            return NotImplemented
        try:
            return finite_out(self._plus(other), "Multivector +")
        except ValueError as exc:
            raise self._mismatch("Multivector +", other, exc) from None

    def __add__(self, other):
        """Sum; a number is a scalar."""
        return _hooked(self._add(other), "+", self, other)

    __radd__ = _add

    def __neg__(self):
        return Multivector(self.algebra, {b: -v for b, v in self._c.items()})

    def __pos__(self):
        return self

    def _sub(self, other):
        """``self - other`` without the operation hook."""
        other = self._coerce(other, "Multivector -")
        if other is NotImplemented:
            return NotImplemented
        try:
            return finite_out(self._plus(-other), "Multivector -")
        except ValueError as exc:
            raise self._mismatch("Multivector -", other, exc) from None

    def __sub__(self, other):
        """Difference; a number is a scalar."""
        return _hooked(self._sub(other), "-", self, other)

    def __rsub__(self, other):
        other = self._coerce(other, "Multivector -")
        if other is NotImplemented:
            return NotImplemented
        try:
            return finite_out(other._plus(-self), "Multivector -")
        except ValueError as exc:
            raise self._mismatch("Multivector -", other, exc) from None

    def _scale(self, k):
        return Multivector(self.algebra, {b: v * k for b, v in self._c.items()}, _prune=True)

    def __mul__(self, other):
        """Geometric product (2.11)."""
        if isinstance(other, Multivector):  # the hot path, written out
            if other.algebra is not self.algebra:
                self._coerce(other, "Multivector *")  # raises: another algebra
            try:
                out = self.algebra._products.product(self, other, "gp")
            except ValueError as exc:
                raise self._mismatch("Multivector *", other, exc) from None
            return finite_out(out, "Multivector *")
        k = scalar_operand(other, "Multivector *")
        if k is NotImplemented:
            return NotImplemented
        try:
            return finite_out(self._scale(k), "Multivector *")
        except ValueError as exc:
            raise self._mismatch("Multivector *", other, exc) from None

    def __rmul__(self, other):
        k = scalar_operand(other, "Multivector *")
        if k is NotImplemented:
            return NotImplemented
        try:
            out = Multivector(self.algebra, {b: k * v for b, v in self._c.items()}, _prune=True)
        except ValueError as exc:
            raise self._mismatch("Multivector *", other, exc) from None
        return finite_out(out, "Multivector *")

    def __truediv__(self, other):
        """Division: by a scalar, or right multiplication by the inverse (2.19)."""
        func = "Multivector /"
        if isinstance(other, Multivector):
            other = self._coerce(other, func)
            return self._binary(self._inverse_of(other, func, "other"), "gp", func)
        k = scalar_operand(other, func, divisor=True)
        if k is NotImplemented:
            return NotImplemented
        try:
            return finite_out(Multivector(self.algebra, {b: v / k for b, v in self._c.items()}), func)
        except ValueError as exc:
            raise self._mismatch(func, other, exc) from None

    def __rtruediv__(self, other):
        func = "Multivector /"
        other = self._coerce(other, func)
        if other is NotImplemented:
            return NotImplemented
        return other._binary(self._inverse_of(self, func, "self"), "gp", func)

    def _inverse_of(self, X, func: str, name: str):
        """``X.inv()`` for an operator: NaN or inf coefficients and a missing inverse named as its operand."""
        bad = not_finite(X)
        if bad is not None:
            raise fail(func, name, f"coefficient of {bad} is NaN or inf")
        try:
            return X.inv()
        except DegenerateGeometryError as exc:
            raise no_inverse(func, name, exc) from None

    def _xor(self, other):
        """``self ^ other`` without the operation hook."""
        return self._binary(other, "op", "Multivector ^")

    def __xor__(self, other):
        """Outer product (2.14, 2.30); a scalar factor just scales (2.20)."""
        return _hooked(self._xor(other), "^", self, other)

    def __rxor__(self, other):
        return self._binary(other, "op", "Multivector ^", reflected=True)

    def __or__(self, other):
        """The thesis's inner product (2.21-2.29): <A_r B_s>_|r-s|, zero with a scalar (2.28)."""
        return self._binary(other, "ip", "Multivector |")

    def __ror__(self, other):
        return self._binary(other, "ip", "Multivector |", reflected=True)

    def __lshift__(self, other):
        """Left contraction A _| B: <A_r B_s>_{s-r} (zero when r > s)."""
        return self._binary(other, "lc", "Multivector <<")

    def plain_operation(self, op: str, other):
        """``self op other`` for ``op`` one of ``"+"``, ``"-"``, ``"^"`` (other a multivector or a number), computed
        and checked as the operator does it, without the algebra's operation hook (:meth:`Algebra.set_operation_hook
        <cga_lessons.algebra.Algebra.set_operation_hook>`): what a layer that adds to the operators' results computes
        its own parts with.  NotImplemented where the operator would defer to other."""
        plain = _PLAIN.get(op) if type(op) is str else None
        if plain is None:
            raise fail("Multivector.plain_operation", "op", f"expected one of '+', '-', '^', got {short(op)}")
        return plain(self, other)

    def __rshift__(self, other):
        """Sandwich ``V >> X = V X ~V`` (2.98, 2.101, 2.103).

        A single numeric versor V (``V ~V`` a non-zero scalar, one parity, in
        an algebra of dimension at most 5) on a numeric X, one entity or a
        batch, takes the fast path: the matrix of ``X -> V X ~V`` on each grade
        of X, built once in closed form (:meth:`Algebra.versor_matrices`),
        times X's coefficients.  A versor keeps grades (2.82), so the result
        has X's grades only, where the plain product adds round-off in the
        others.  Anything else is the plain product ``V * X * ~V``.  It never
        divides by ``V ~V`` (it scales by it), so a versor whose ``V ~V`` is
        lost to round-off (a sphere far from the origin) still gives ``V X ~V``
        to the round-off of its terms, ``eps |V|^2 |X|`` (by the tables, or by
        the plain product where ``V ~V`` rounds to 0); the normalised action
        ``V X^ V^-1`` of such a versor is :func:`cga_lessons.conformal.apply`.
        """
        func = "Multivector >>"
        other = self._coerce(other, func)
        if other is NotImplemented:
            return NotImplemented
        alg = self.algebra
        if other._c and (is_real_single(other) or is_real_batch(other)):
            info = alg._versors.info(self, tuple(other.grades_present()))
            if info is not None:
                return finite_out(alg._versors.apply_unchecked(info[2], other), func)
        try:
            return finite_out(alg._products.product(alg._products.product(self, other, "gp"), ~self, "gp"), func)
        except ValueError as exc:
            raise self._mismatch(func, other, exc) from None

    def inner(self, other):
        """The thesis's inner product (2.21-2.29), same as ``self | other``."""
        return self._binary(self._operand(other, "Multivector.inner"), "ip", "Multivector.inner")

    def left_contraction(self, other):
        """Left contraction, same as ``self << other``."""
        return self._binary(self._operand(other, "Multivector.left_contraction"), "lc", "Multivector.left_contraction")

    def scalar_product(self, other):
        """<A B>_0 as a coefficient (float, array or SymPy)."""
        func = "Multivector.scalar_product"
        return self._binary(self._operand(other, func), "sp", func)._c.get(0, 0.0)

    def __pow__(self, k):
        func = "Multivector **"
        k = integer(k, func, "k")
        bad = not_finite(self)
        if bad is not None:
            raise fail(func, "self", f"coefficient of {bad} is NaN or inf")
        base = self
        if k < 0:
            base, k = self._inverse_of(self, func, "self"), -k
        alg = self.algebra
        out = Multivector(alg, {0: 1.0})
        while k:
            if k & 1:
                out = alg._products.product(out, base, "gp")
            k >>= 1
            if k:
                base = alg._products.product(base, base, "gp")
                if not_finite(base) is not None:
                    break  # overflowed: the check below names it
        return finite_out(out if not k else base, func, "k")

    # ------------------------------------------- methods that are plain functions of other modules
    # reading and comparing (access.py)
    __getitem__ = access.coefficient
    blades = access.blades
    items = access.items
    coeffs = property(access.coeffs)
    shape = property(access.shape)
    __len__ = access.length
    __iter__ = access.iterate
    __getattr__ = access.no_attribute  # blade access as attributes is deliberately not offered: X["e12"] is explicit
    batch_item = access.batch_item
    to_array = access.to_array
    grades_present = access.grades_present
    scalar = access.scalar
    __float__ = access.to_float
    isclose = access.isclose
    __eq__ = access.equals
    __ne__ = access.not_equals
    __hash__ = None
    iszero = access.iszero
    # grades, involutions, dual (involutions.py)
    __invert__ = reverse = involutions.reverse
    involute = involutions.involute
    conjugate = involutions.conjugate
    grade = involutions.grade
    even = involutions.even
    odd = involutions.odd
    dual = involutions.dual
    undual = involutions.undual
    # norms and the inverse (inverse.py)
    norm2 = inverse.norm2
    norm = inverse.norm
    normalized = inverse.normalized
    inv = inverse.inv
    # display and SymPy helpers (display.py)
    simplify = display.simplify
    expand = display.expand
    subs = display.subs
    map = display.map_coefficients
    __repr__ = display.text
    _repr_latex_ = display.latex


_PLAIN = {"+": Multivector._add, "-": Multivector._sub, "^": Multivector._xor}  # the operators' plain routines


def mv_from_dict(algebra, coeffs: dict):
    """A Multivector from a dict that is already pruned (no checks, no copy)."""
    m = object.__new__(Multivector)
    m.algebra = algebra
    m._c = coeffs
    return m


def mv_from_pairs(algebra, keys, values):
    """A Multivector from parallel keys and values, dropping exact zeros."""
    out = {}
    for k, v in zip(keys, values):
        t = type(v)
        if t is float or t is np.float64 or t is int:
            if v != 0:
                out[k] = v
        elif not is_zero(v):
            out[k] = v
    m = object.__new__(Multivector)
    m.algebra = algebra
    m._c = out
    return m


def commutator(A: Multivector, B: Multivector) -> Multivector:
    """Commutator product A x B = (AB - BA)/2 (2.36)."""
    for name, X in (("A", A), ("B", B)):
        finite_multivector(instance(X, "commutator", name, Multivector, "a Multivector"), "commutator", name)
    if B.algebra is not A.algebra:
        raise fail("commutator", "B", f"is a multivector of {B.algebra}, not of A's {A.algebra}")
    alg = A.algebra
    try:
        diff = alg._products.product(A, B, "gp")._plus(-alg._products.product(B, A, "gp"))
    except ValueError as exc:
        raise fail("commutator", "A, B", f"batches of shapes {A.shape} and {B.shape} do not combine ({exc})") from None
    return finite_out(Multivector(alg, {b: v / 2 for b, v in diff._c.items()}), "commutator", "A, B")
