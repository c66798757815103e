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


def is_real_single(M) -> bool:
    """True when every coefficient of ``M`` is one real number (no batch, no SymPy)."""
    real = REAL_TYPES
    for v in M._c.values():
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
    for v in M._c.values():
        if type(v) is np.ndarray:
            if v.dtype.kind not in "fiu" or not v.ndim:
                return False
            seen = True
        elif type(v) not in real:
            return False
    return seen


def any_sympy(*mvs) -> bool:
    return any(is_sympy(v) for m in mvs for v in m._c.values())


def absmax(v) -> float:
    """max |v| of a real coefficient, a number or an array, as a float (NaN stays NaN)."""
    t = type(v)
    if t is float or t is np.float64 or t is int:
        return float(abs(v))
    return float(np.max(np.abs(v)))


def all_finite(arr: np.ndarray) -> bool:
    """``np.isfinite(arr).all()`` for a float array, screened cheaply first.

    For a large contiguous float64 array the dot product ``a . a`` is finite
    exactly when no element is NaN or inf, unless the squares overflow (only
    for |a| > 1e154), in which case the full test decides.
    """
    if arr.size <= 8:
        return all(map(math.isfinite, arr.ravel().tolist()))
    if arr.dtype == np.float64 and arr.size > 512 and arr.flags.c_contiguous:
        flat = arr.reshape(-1)
        with np.errstate(over="ignore", invalid="ignore"):
            if np.isfinite(flat @ flat):
                return True
    return bool(np.isfinite(arr).all())
