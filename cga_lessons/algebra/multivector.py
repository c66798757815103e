"""The Multivector type of :mod:`cga_lessons.algebra` and its operators.

A :class:`Multivector` is a sparse map ``blade bitmap -> coefficient`` over
one :class:`~cga_lessons.algebra.Algebra`.  The coefficient may be a
Python/NumPy float, a NumPy array (a *batch*: one multivector per element,
e.g. one conformal point per row of a point cloud) or a SymPy expression; see
:mod:`cga_lessons.algebra.coefficients`.  The products behind the operators
are the algebra's (:mod:`cga_lessons.algebra.products`), the fast sandwich of
a versor is its matrices per grade (:mod:`cga_lessons.algebra.versor_matrices`); the
norms and the inverse (2.19) live in :mod:`cga_lessons.algebra.inverse`, the
text/LaTeX display and the SymPy helpers in :mod:`cga_lessons.algebra.display`.

The operators and the thesis's notation for each are tabled in :mod:`cga_lessons.algebra`.

Import these names from :mod:`cga_lessons.algebra`, their public home.
"""

from __future__ import annotations

import numbers
from typing import TYPE_CHECKING

import numpy as np

from cga_lessons.errors import InvalidInputError

from .coefficients import absmax, is_real_batch, is_real_single, is_sympy, is_zero
from .display import DisplayMixin
from .inverse import NormsAndInverseMixin

if TYPE_CHECKING:
    from .core import Algebra

__all__ = ["Multivector", "commutator"]


class Multivector(NormsAndInverseMixin, DisplayMixin):
    """A multivector of an :class:`~cga_lessons.algebra.Algebra`: a sparse map blade -> coefficient.

    Coefficients are floats, NumPy arrays (a batch, all of one shape) or SymPy
    expressions.  Read a coefficient by blade name, ``X["e12"]`` (zero where
    absent; ``X["e21"]`` is ``-X["e12"]``); :meth:`blades` lists the non-zero
    ones.

    The norms and the inverse (2.19) come from
    :class:`~cga_lessons.algebra.inverse.NormsAndInverseMixin`, the display and
    the SymPy helpers from :class:`~cga_lessons.algebra.display.DisplayMixin`.
    """

    __slots__ = ("algebra", "_c")
    __array_priority__ = 1000  # so that ndarray * Multivector defers to us
    __array_ufunc__ = None

    def __init__(self, algebra: Algebra, coeffs: dict | None = None, _prune: bool = False):
        self.algebra = algebra
        c = coeffs or {}
        if _prune:
            c = {k: v for k, v in c.items() if not is_zero(v)}
        self._c = c

    def _sympy_(self):
        # Tell SymPy a multivector is not one of its expressions, so that
        # ``sympy_expr * X`` falls back to Multivector.__rmul__.
        import sympy

        raise sympy.SympifyError(self)

    # -------------------------------------------------------------- access
    def __getitem__(self, name):
        if isinstance(name, str):
            b, s = self.algebra.parse_blade(name)
        else:
            b, s = int(name), 1
            if not 0 <= b < self.algebra.dim:
                raise IndexError(f"blade bitmap {b} outside 0..{self.algebra.dim - 1}")
        v = self._c.get(b, 0.0)
        return v if s == 1 else -v

    def blades(self) -> list[str]:
        """Names of the blades with a non-zero coefficient, in the order of (2.9)."""
        order = self.algebra.blade_order
        return [self.algebra.blade_names[b] for b in order if b in self._c]

    def items(self):
        """(blade name, coefficient) pairs in the order of (2.9)."""
        return [(self.algebra.blade_names[b], self._c[b]) for b in self.algebra.blade_order if b in self._c]

    @property
    def coeffs(self) -> dict:
        """The raw sparse map ``{bitmap: coefficient}`` (read only by convention)."""
        return self._c

    @property
    def shape(self) -> tuple:
        """Batch shape: () for a single multivector, (N,) for N of them."""
        for v in self._c.values():
            if isinstance(v, np.ndarray):
                return v.shape
        return ()

    def __len__(self):
        shape = self.shape
        if not shape:
            raise TypeError("a single multivector has no len(); use .shape for batches")
        return shape[0]

    def __iter__(self):
        """The items of a batch, one multivector each; a single multivector is not iterable."""
        shape = self.shape
        if not shape:
            raise TypeError("a single multivector is not iterable; use .items() for its blades")
        return (self.batch_item(i) for i in range(shape[0]))

    def __getattr__(self, name):
        # blade access as attributes is deliberately not offered: X["e12"] is explicit.
        raise AttributeError(name)

    def batch_item(self, index) -> Multivector:
        """One multivector (or a sub-batch) of a batch: ``X.batch_item(3)``."""
        out = {}
        for b, v in self._c.items():
            out[b] = v[index] if isinstance(v, np.ndarray) else v
        return Multivector(self.algebra, out, _prune=True)

    def to_array(self, blades=None) -> np.ndarray:
        """Coefficients as an array, last axis over ``blades`` (default all, order of (2.9))."""
        alg = self.algebra
        blades = alg.blade_order if blades is None else blades
        shape = self.shape
        out = np.zeros(shape + (len(blades),))
        for i, b in enumerate(blades):
            if b in self._c:
                out[..., i] = self._c[b]
        return out

    def grades_present(self) -> list[int]:
        return sorted({self.algebra.grades[b] for b in self._c})

    # ---------------------------------------------------------- arithmetic
    def _coerce(self, other) -> Multivector:
        if isinstance(other, Multivector):
            if other.algebra is not self.algebra:
                raise InvalidInputError(f"cannot combine multivectors of {self.algebra} and {other.algebra}")
            return other
        if isinstance(other, np.ndarray) or isinstance(other, numbers.Number) or is_sympy(other):
            return Multivector(self.algebra, {0: other}, _prune=True)
        return NotImplemented

    def __add__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        out = dict(self._c)
        for b, v in other._c.items():
            out[b] = out[b] + v if b in out else v
        return Multivector(self.algebra, out, _prune=True)

    __radd__ = __add__

    def __neg__(self):
        return Multivector(self.algebra, {b: -v for b, v in self._c.items()})

    def __pos__(self):
        return self

    def __sub__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self + (-other)

    def __rsub__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return other + (-self)

    def _scale(self, k):
        return Multivector(self.algebra, {b: v * k for b, v in self._c.items()}, _prune=True)

    def __mul__(self, other):
        """Geometric product (2.11)."""
        if isinstance(other, Multivector):
            return self.algebra._product(self, self._coerce(other), "gp")
        if isinstance(other, (numbers.Number, np.ndarray)) or is_sympy(other):
            return self._scale(other)
        return NotImplemented

    def __rmul__(self, other):
        if isinstance(other, (numbers.Number, np.ndarray)) or is_sympy(other):
            return Multivector(self.algebra, {b: other * v for b, v in self._c.items()}, _prune=True)
        return NotImplemented

    def __truediv__(self, other):
        """Division: by a scalar, or right multiplication by the inverse (2.19)."""
        if isinstance(other, Multivector):
            return self * other.inv()
        if isinstance(other, (numbers.Number, np.ndarray)) or is_sympy(other):
            return Multivector(self.algebra, {b: v / other for b, v in self._c.items()})
        return NotImplemented

    def __rtruediv__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return other * self.inv()

    def __xor__(self, other):
        """Outer product (2.14, 2.30); a scalar factor just scales (2.20)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "op")

    def __rxor__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(other, self, "op")

    def __or__(self, other):
        """The thesis's inner product (2.21-2.29): <A_r B_s>_|r-s|, zero with a scalar (2.28)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "ip")

    def __ror__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(other, self, "ip")

    def __lshift__(self, other):
        """Left contraction A _| B: <A_r B_s>_{s-r} (zero when r > s)."""
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        return self.algebra._product(self, other, "lc")

    def __rshift__(self, other):
        """Sandwich ``V >> X = V X ~V`` (2.98, 2.101, 2.103).

        A single numeric versor V (``V ~V`` a non-zero scalar, one parity, in
        an algebra of dimension at most 5) on a numeric X, one entity or a
        batch, takes the fast path: the matrix of ``X -> V X ~V`` on each grade
        of X, built once in closed form (:meth:`Algebra.versor_matrices`),
        times X's coefficients.  A versor keeps grades (2.82), so the result
        has X's grades only, where the plain product adds round-off in the
        others.  Anything else is the plain product ``V * X * ~V``.
        """
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        if other.algebra is self.algebra and other._c and (is_real_single(other) or is_real_batch(other)):
            info = self.algebra._versor_info(self, tuple(other.grades_present()))
            if info is not None:
                return self.algebra.apply_matrices(info[2], other)
        return self * other * ~self

    def inner(self, other):
        """The thesis's inner product (2.21-2.29), same as ``self | other``."""
        return self | other

    def left_contraction(self, other):
        """Left contraction, same as ``self << other``."""
        return self << other

    def scalar_product(self, other):
        """<A B>_0 as a coefficient (float, array or SymPy)."""
        return self.algebra._product(self, self._coerce(other), "sp")._c.get(0, 0.0)

    def __pow__(self, k):
        if not isinstance(k, numbers.Integral):
            raise InvalidInputError(f"power: exponent must be an integer, got {k!r}")
        if k < 0:
            return self.inv() ** (-k)
        out = Multivector(self.algebra, {0: 1.0})
        base = self
        while k:
            if k & 1:
                out = out * base
            base = base * base
            k >>= 1
        return out

    # ----------------------------------------------------------- involutions
    def __invert__(self):
        """Reverse (2.32-2.33): grade k gets the sign (-1)^(k(k-1)/2)."""
        flip = self.algebra._rev_flip
        return mv_from_dict(self.algebra, {b: (-v if flip[b] else v) for b, v in self._c.items()})

    def reverse(self):
        return ~self

    def involute(self):
        """Grade involution (2.35): grade k gets the sign (-1)^k."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: (-v if g[b] & 1 else v) for b, v in self._c.items()})

    def conjugate(self):
        """Clifford conjugate: reverse of the grade involution."""
        return (~self).involute()

    def grade(self, *ks):
        """Grade projection <M>_k (2.18); several grades give their sum."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] in ks})

    def even(self):
        """Even part (2.16)."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] % 2 == 0})

    def odd(self):
        """Odd part (2.17)."""
        g = self.algebra.grades
        return Multivector(self.algebra, {b: v for b, v in self._c.items() if g[b] % 2 == 1})

    def dual(self):
        """Dual M* = M I^-1 (2.31)."""
        alg = self.algebra
        I = alg.pseudoscalar()
        return self * I.inv()

    def undual(self):
        """Inverse of :meth:`dual`: M I."""
        return self * self.algebra.pseudoscalar()

    def scalar(self):
        """The scalar part <M>_0 as a coefficient (an array of zeros for a batch without one)."""
        if 0 in self._c:
            return self._c[0]
        shape = self.shape
        return np.zeros(shape) if shape else 0.0

    def __float__(self):
        scale = max((absmax(v) for v in self._c.values() if not is_sympy(v)), default=0.0)
        extra = [
            self.algebra.blade_names[b]
            for b, v in self._c.items()
            if b != 0 and (is_sympy(v) or absmax(v) > 1e-10 * max(scale, 1e-300))
        ]
        if extra:
            raise InvalidInputError(f"float(): multivector is not a scalar (has blades {extra})")
        v = self._c.get(0, 0.0)
        if isinstance(v, np.ndarray):
            if v.size != 1:
                raise InvalidInputError(f"float(): a batch of {v.size} scalars is not one float")
            return float(v.reshape(-1)[0])
        return float(v)

    # -------------------------------------------------------- comparisons
    def isclose(self, other, rtol: float = 1e-9, atol: float = 1e-12) -> bool:
        """True when every coefficient agrees within ``atol + rtol*|other|`` (numeric)."""
        other = self._coerce(other)
        for b in set(self._c) | set(other._c):
            a = np.asarray(self._c.get(b, 0.0), dtype=float)
            c = np.asarray(other._c.get(b, 0.0), dtype=float)
            if not np.allclose(a, c, rtol=rtol, atol=atol):
                return False
        return True

    def __eq__(self, other):
        other = self._coerce(other)
        if other is NotImplemented:
            return NotImplemented
        diff = self - other
        for v in diff._c.values():
            if is_sympy(v):
                import sympy

                if sympy.simplify(v) != 0:
                    return False
            elif np.any(np.asarray(v) != 0):
                return False
        return True

    def __ne__(self, other):
        eq = self.__eq__(other)
        return eq if eq is NotImplemented else not eq

    __hash__ = None

    def iszero(self, atol: float = 1e-12) -> bool:
        return self.isclose(0.0, rtol=0.0, atol=atol)


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
    return (A * B - B * A) / 2
