"""The three kinds of coefficient a multivector holds, and cheap tests for them.

A coefficient is one real number (a Python float or int, a NumPy float), a
NumPy array (a *batch*: one multivector per element) or a SymPy expression.
The product routes and the versor fast paths of :mod:`cga_lessons.algebra`
choose their route by these tests, so they look at ``type(x)`` first and fall
back to ``isinstance`` only for the rare kinds.  The functions that take a
multivector ``M`` read only its sparse map ``M._c``.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons.checks import fail

PLAIN_TYPES = frozenset((float, int, np.float64, np.ndarray))


def is_sympy(x) -> bool:
    if type(x) in PLAIN_TYPES:
        return False
    return hasattr(x, "free_symbols") and not isinstance(x, np.ndarray)


def is_zero(c) -> bool:
    """True when a coefficient is exactly zero (float, array or SymPy)."""
    t = type(c)
    if t is float or t is int or t is np.float64:
        return c == 0
    if t is np.ndarray:
        if c.dtype.kind in "fiub":
            return not np.count_nonzero(c)  # NaN counts as non-zero, as in any()
        return not c.any()
    if isinstance(c, np.ndarray):
        return not np.any(c)
    if isinstance(c, numbers.Number):
        return c == 0
    if is_sympy(c):
        return c == 0 or c.is_zero is True
    return c == 0


#: Coefficient types of a single numeric multivector (the versor fast paths take only these).
REAL_TYPES = frozenset((float, np.float64, int))
#: ... and of the operands of a product sent through a float table (ints stay exact in the other routes).
FLOAT_TYPES = frozenset((float, np.float64))


def _not_a_multivector(M, func: str):
    return fail(func, "M", f"expected a Multivector, got {type(M).__name__}")


def is_real_single(M) -> bool:
    """True when every coefficient of ``M`` is one real number (no batch, no SymPy)."""
    real = REAL_TYPES
    try:
        values = M._c.values()
    except AttributeError:
        raise _not_a_multivector(M, "is_real_single") from None
    for v in values:
        if type(v) not in real:
            return False
    return True


def is_float_single(M) -> bool:
    """True when every coefficient of ``M`` is one float."""
    flt = FLOAT_TYPES
    for v in M._c.values():
        if type(v) not in flt:
            return False
    return True


def is_real_batch(M) -> bool:
    """True when ``M`` is a numeric batch: real arrays (at least one) and real numbers, no SymPy."""
    real = REAL_TYPES
    seen = False
    try:
        values = M._c.values()
    except AttributeError:
        raise _not_a_multivector(M, "is_real_batch") from None
    for v in values:
        if type(v) is np.ndarray:
            if v.dtype.kind not in "fiu" or not v.ndim:
                return False
            seen = True
        elif type(v) not in real:
            return False
    return seen


def any_sympy(*mvs) -> bool:
    """True when a coefficient of one of the multivectors ``mvs`` is a SymPy expression."""
    try:
        return any(is_sympy(v) for m in mvs for v in m._c.values())
    except AttributeError:
        bad = next(m for m in mvs if not hasattr(m, "_c"))
        raise fail("any_sympy", "mvs", f"expected Multivectors, got {type(bad).__name__}") from None


def absmax(v) -> float:
    """max |v| of a real coefficient, a number or an array, as a float (NaN stays NaN)."""
    t = type(v)
    if t is float or t is np.float64 or t is int:
        return float(abs(v))
    try:
        return float(np.max(np.abs(v)))
    except (TypeError, ValueError) as exc:
        raise fail("absmax", "v", f"expected a real number or a non-empty array of them ({exc})") from None


def all_finite(arr: np.ndarray) -> bool:
    """``np.isfinite(arr).all()`` for a float array, screened cheaply first.

    For a large contiguous float64 array the dot product ``a . a`` is finite
    exactly when no element is NaN or inf, unless the squares overflow (only
    for |a| > 1e154), in which case the full test decides.
    """
    if type(arr) is not np.ndarray:
        if arr is None or isinstance(arr, (str, bytes)):
            raise fail("all_finite", "arr", f"expected an array of numbers, got {arr!r:.40}")
        try:
            arr = np.asarray(arr)
        except ValueError as exc:
            raise fail("all_finite", "arr", f"expected an array of numbers ({exc})") from None
    kind = arr.dtype.kind
    if kind not in "fiub":
        if kind != "c":
            raise fail("all_finite", "arr", f"expected an array of numbers, got an array of {arr.dtype}")
        return bool(np.isfinite(arr).all())
    if arr.size <= 8:
        return all(map(math.isfinite, arr.ravel().tolist()))
    if arr.dtype == np.float64 and arr.size > 512 and arr.flags.c_contiguous:
        flat = arr.reshape(-1)
        with np.errstate(over="ignore", invalid="ignore"):
            if np.isfinite(flat @ flat):
                return True
    return bool(np.isfinite(arr).all())
