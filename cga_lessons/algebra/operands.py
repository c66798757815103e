"""The checks of the algebra's operands: numbers, arrays, blades, grades and multivectors given to its methods.

Built on :mod:`cga_lessons.checks` (the one checking layer): every error reads ``"func: arg: problem"``, where
``func`` is what the user wrote: ``"Multivector *"`` for an operator (the class and the operator),
``"Multivector.grade"`` or ``"Algebra.vector"`` for a method.  The operators call these at their entry, and
:func:`finite_out` on their result, so that a NaN or inf operand, or a product that overflows, raises instead of
leaving NaN or inf coefficients; the inner product routes (:mod:`cga_lessons.algebra.products`) trust their operands.

What is checked where, and why (the products are benchmarked against NumPy):

* a number or array operand (``X * s``, ``X + s``, ``X / s``): finite, real, and for ``/`` non-zero, on every call;
* a single multivector (float coefficients): the result of every operator is screened with one ``sum`` of its
  coefficients (NaN and inf propagate through a sum; only when the sum is not finite are the coefficients looked
  at one by one), so that NaN or inf operands and overflow are refused at a cost of a few hundred nanoseconds;
* a batch (array coefficients) is checked where it is made (:meth:`Algebra.vector`, :meth:`Algebra.from_array`,
  :func:`cga_lessons.conformal.up` ...), not rescanned by every product: a product of batches is the inner loop of
  every batch computation, and a scan of its coefficients would cost as much as a sandwich.  Its number or array
  operands are checked as above.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons.checks import array, degenerate, fail, instance, integer, is_symbolic, real, short
from cga_lessons.errors import InvalidInputError

from .coefficients import all_finite, is_sympy

#: Operand types that are never a multivector's, a number's or an array's: refused with a clear error (Python's
#: reflected operation would fail for them too), where other unknown types get NotImplemented (their own reflected
#: operation may know a Multivector).
FOREIGN = (type(None), str, bytes, list, tuple, dict, set, frozenset, complex, bool, np.bool_)


class BladeNameError(InvalidInputError, KeyError):
    """Not a blade name of the algebra (also a ``KeyError``, as a missing key of a mapping)."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class BladeIndexError(InvalidInputError, IndexError):
    """A blade bitmap outside the algebra (also an ``IndexError``)."""


class AlgebraKind:
    """Base of :class:`~cga_lessons.algebra.Algebra`, so that a Multivector can check its algebra without a cycle."""


_BIG = 1 << 1000  # ints below this convert to a float
_F64, _NDARRAY = np.float64, np.ndarray  # looked up once: finite_out runs on every operator's result


def scalar_operand(value, func: str, name: str = "other", *, divisor: bool = False):
    """``value`` (unchanged) if it is a finite real number, a finite real array or a SymPy expression.

    Returns NotImplemented for a type this package does not know (its reflected operation may); ``divisor``
    refuses zero.  An int or SymPy number keeps its exact type (``X * 2`` of SymPy coefficients stays exact).
    """
    t = type(value)
    if t is float or t is np.float64:
        if value - value != 0.0:
            raise fail(func, name, f"is NaN or inf ({value!r})")
        if divisor and value == 0.0:
            raise fail(func, name, "division by zero")
        return value
    if t is np.ndarray:
        return _array_operand(value, func, name, divisor)
    if t is int and -_BIG < value < _BIG:
        if divisor and value == 0:
            raise fail(func, name, "division by zero")
        return value
    if isinstance(value, FOREIGN):
        raise fail(func, name, f"expected a Multivector, a real number or an array, got {t.__name__} {short(value)}")
    if is_sympy(value) or is_symbolic(value):
        if divisor and value == 0:
            raise fail(func, name, "division by zero")
        return value
    if isinstance(value, numbers.Number):
        x = real(value, func, name)
        if divisor and x == 0.0:
            raise fail(func, name, "division by zero")
        return value
    return NotImplemented


def _array_operand(a: np.ndarray, func: str, name: str, divisor: bool) -> np.ndarray:
    kind = a.dtype.kind
    if kind == "O":  # SymPy entries, say: exact, not checked
        return a
    if kind not in "biuf":
        raise fail(func, name, f"must be real numbers, got an array of {a.dtype}")
    if kind == "f" and not all_finite(a):
        raise fail(func, name, "contains NaN or inf")
    if divisor and not np.all(a):
        raise fail(func, name, "division by zero (the array has a zero)")
    return a


def not_finite(out) -> str | None:
    """The name of a blade of ``out`` whose coefficient is NaN or inf (single multivectors only), else None."""
    c = out._c
    if not c:
        return None
    t = type(next(iter(c.values())))
    if t is not float and t is not np.float64 and t is not int:
        return None  # a batch (checked where it is made) or SymPy (exact)
    try:  # NaN and inf propagate through the sum; arrays and SymPy symbols raise TypeError
        if math.isfinite(math.fsum(c.values())):
            return None
    except (TypeError, ValueError, OverflowError):  # an array, a symbol, inf - inf, finite values beyond float range
        pass
    for b, v in c.items():
        t = type(v)
        if (t is float or t is np.float64) and not math.isfinite(v):
            return out.algebra.blade_names[b]
    return None


def finite_out(out, func: str, name: str = "other"):
    """``out`` if none of its coefficients is NaN or inf (single multivectors), else the error naming ``name``.

    The operand ``name`` either had NaN or inf coefficients or was so large that the result overflowed.  The
    common case (float coefficients, all finite) costs one ``sum``: NaN and inf propagate through it, and only
    when it is not a finite float (or the coefficients are not all floats) are they looked at one by one.
    """
    c = out._c
    for v in c.values():
        t = type(v)
        if t is float or t is _F64:
            s = sum(c.values())
            if type(s) is _NDARRAY or s - s != 0.0:  # a batch after a float, or NaN/inf (or a sum that overflows)
                bad = not_finite(out)
                if bad is not None:
                    raise fail(
                        func,
                        name,
                        f"the result has a NaN or inf coefficient (on {bad}): an operand has NaN or inf "
                        "coefficients, or the result overflows a float",
                    )
        break
    return out


def finite_multivector(X, func: str, name: str):
    """``X`` (a multivector) if none of its coefficients (floats or arrays) is NaN or inf; for functions' entries.

    ``func`` and ``name`` are the caller's: the error names the public function and the argument that held ``X``.
    """
    coeffs = getattr(X, "_c", None)
    if not isinstance(coeffs, dict):
        raise fail(func, name, f"expected a Multivector, got {type(X).__name__}")
    for b, v in coeffs.items():
        t = type(v)
        if t is float or t is np.float64:
            ok = math.isfinite(v)
        elif t is np.ndarray:
            ok = v.dtype.kind not in "fc" or all_finite(v)
        else:
            continue
        if not ok:
            raise fail(func, name, f"contains NaN or inf (the coefficient of {X.algebra.blade_names[b]})")
    return X


def same_algebra(X, algebra, func: str, name: str, mv_type):
    """``X`` if it is a multivector (``mv_type``) of ``algebra``, else the error."""
    instance(X, func, name, mv_type, "a Multivector")
    if X.algebra is not algebra:
        raise fail(func, name, f"is a multivector of {X.algebra}, not of {algebra}")
    return X


def blade_bitmaps(blades, func: str, name: str, dim: int) -> list:
    """``blades`` as a list of blade bitmaps (ints in 0..dim-1)."""
    if isinstance(blades, (str, bytes)) or not hasattr(blades, "__iter__"):
        raise fail(func, name, f"expected a sequence of blade bitmaps (ints 0..{dim - 1}), got {short(blades)}")
    out = [integer(b, func, name, low=0, high=dim - 1) for b in blades]
    if not out:
        raise fail(func, name, "expected at least one blade")
    if len(set(out)) != len(out):
        raise fail(func, name, f"lists a blade twice: {out}")
    return out


def coefficient(value, func: str, name: str):
    """One coefficient given by a user: a finite real number (kept as given), a finite real array or SymPy."""
    if is_sympy(value) or is_symbolic(value):
        return value
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "O":
            return value
        if value.dtype.kind not in "biuf":
            raise fail(func, name, f"must be real numbers, got an array of {value.dtype}")
        if not all_finite(value.astype(float, copy=False)):
            raise fail(func, name, "contains NaN or inf")
        return value
    real(value, func, name)
    return value


def coefficient_array(value, func: str, name: str, length: int, per: str = "") -> np.ndarray:
    """``value`` as a finite float array whose last axis has ``length`` entries (one item or a batch of any shape)."""
    ndim = value.ndim if isinstance(value, np.ndarray) else np.asarray(value, dtype=object).ndim  # ragged: lists
    a = array(value, func, name, (None,) * ndim, finite=False)  # numbers, real, rows of one length
    if a.ndim == 0 or a.shape[-1] != length:
        raise fail(func, name, f"the last axis must have length {length}{per}, got shape {a.shape}")
    if not all_finite(a):
        raise fail(func, name, "contains NaN or inf")
    return a


def nonnegative(value, func: str, name: str, *, positive: bool = False):
    """``value`` (a real number or a real array) if finite and >= 0 (> 0 if ``positive``), else the error."""
    if not isinstance(value, np.ndarray):
        return real(value, func, name, low=0.0, strict_low=positive)
    if value.dtype.kind not in "iuf":
        raise fail(func, name, f"must be real numbers, got an array of {value.dtype}")
    if not all_finite(value):
        raise fail(func, name, "contains NaN or inf")
    if value.size and (value.min() <= 0 if positive else value.min() < 0):
        raise fail(func, name, f"must be {'>' if positive else '>='} 0 everywhere, got {value.min():.6g}")
    return value


def matrices_per_grade(mats, grade_blades: list, func: str) -> dict:
    """``mats`` if it is ``{grade: k x k finite real matrix}`` (k blades of that grade), else the error."""
    if not isinstance(mats, dict) or not mats:
        raise fail(func, "mats", f"expected {{grade: matrix}} (from versor_matrices), got {short(mats)}")
    for g, m in mats.items():
        g = integer(g, func, "mats", low=0, high=len(grade_blades) - 1)
        k = len(grade_blades[g])
        if not isinstance(m, np.ndarray) or m.shape != (k, k) or m.dtype.kind not in "iuf":
            raise fail(func, "mats", f"grade {g} needs a real {k} x {k} matrix, got {short(m)}")
        if not np.all(np.isfinite(m)):
            raise fail(func, "mats", f"the matrix of grade {g} contains NaN or inf")
    return mats


def no_inverse(func: str, name: str, exc: Exception):
    """The error for dividing by (or raising to a negative power) a multivector that has no inverse."""
    return degenerate(func, name, f"has no inverse ({str(exc).split(': ', 2)[-1]})")
