"""The checks of the conformal package's public functions that take multivectors, composed from
:mod:`cga_lessons.checks` (its ``fail``, ``degenerate``, ``real``, ``array``, ``instance``).

* :func:`multivector`: an entity or versor argument: a multivector of G(4,1), finite real coefficients (single,
  numeric, non-zero when asked);
* :func:`mv_is_finite`, :func:`finite_multivector`, :func:`input_error`: a result that came out NaN or inf is
  refused, naming the input with NaN or inf or, for finite inputs, the overflow (the words of
  ``checks.finite_result``, with the arguments named).

Internal to :mod:`cga_lessons.conformal` (not re-exported by its facade).
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, Multivector, all_finite, is_sympy

from .model import G41

__all__ = ["multivector", "mv_is_finite", "finite_multivector", "input_error"]


def multivector(
    X,
    func: str,
    name: str,
    *,
    what: str = "a multivector of G(4,1)",
    single: bool = False,
    numeric: bool = False,
    algebra=G41,
    nonzero: bool = True,
    finite: bool = True,
) -> Multivector:
    """``X`` if it is a multivector of ``algebra`` (G41; None: any) with finite real coefficients; else the error
    ``"func: name: problem"`` of :mod:`cga_lessons.checks`.

    ``single``: no batch (array coefficients); ``numeric``: no SymPy coefficients; ``nonzero``: the zero
    multivector is refused (:class:`DegenerateGeometryError`); ``finite=False`` lets NaN and inf through.
    The check of the conformal package's public functions that take an entity or a versor: one pass over
    the (at most 32) coefficients, and one :func:`~cga_lessons.algebra.all_finite` per coefficient array
    of a batch.
    """
    checks.instance(X, func, name, Multivector, what)
    if algebra is not None and X.algebra is not algebra:
        raise checks.fail(func, name, f"a multivector of {X.algebra!r}, not of the conformal G(4,1)")
    for v in X._c.values():
        t = type(v)
        if t is float or t is int or t is np.float64:
            if finite and not math.isfinite(v):
                raise checks.fail(func, name, "contains NaN or inf")
        elif t is np.ndarray and v.dtype.kind in "fiu":
            if single and v.ndim:
                raise checks.fail(func, name, f"a batch of shape {v.shape}; pass one at a time")
            if finite and not all_finite(v):
                raise checks.fail(func, name, "contains NaN or inf")
        elif is_sympy(v):
            if numeric:
                raise checks.fail(func, name, "numeric coefficients only, got SymPy ones")
        elif isinstance(v, (bool, np.bool_, complex, np.complexfloating)) or not isinstance(v, numbers.Real):
            raise checks.fail(func, name, f"coefficients must be real numbers, got {type(v).__name__}")
        elif finite:
            checks.real(v, func, name)  # NaN and inf, in the usual words
    if nonzero and not X._c:
        raise checks.degenerate(func, name, "is the zero multivector")
    return X


def mv_is_finite(Y: Multivector, batches: bool = True) -> bool:
    """Whether the coefficients of a result are finite (SymPy ones count as finite).

    One ``fsum`` of the coefficients of a single multivector (about 0.2 us); for a batch one dot product per
    coefficient array, or, with ``batches=False``, none: a batch counts as finite (the choice of the algebra's
    own products for the hot paths, whose batches are checked where they are made: ``up``, the constructors).
    """
    c = Y._c
    try:
        if math.isfinite(math.fsum(c.values())):
            return True
    except (OverflowError, ValueError):  # terms of 1e308 (finite) or inf - inf: look at each
        pass
    except TypeError:  # arrays (a batch) or SymPy coefficients
        pass
    for v in c.values():
        if type(v) is np.ndarray:
            if not batches and v.ndim:
                continue
            if v.dtype == np.float64 and v.ndim == 1:
                # a dot product is finite exactly when v is, unless |v| > 1e154: then look at each entry
                with np.errstate(over="ignore", invalid="ignore"):
                    if math.isfinite(v @ v):
                        continue
            if v.dtype.kind in "fc" and not np.all(np.isfinite(v)):
                return False
        elif not is_sympy(v):
            try:
                if not math.isfinite(v):
                    return False
            except (TypeError, OverflowError):  # not a real number
                return False
    return True


def finite_multivector(result: Multivector, func: str, /, **inputs) -> Multivector:
    """``result`` if its coefficients are finite (:func:`mv_is_finite`); else :func:`input_error`."""
    if mv_is_finite(result):
        return result
    raise input_error(func, inputs)


def input_error(func: str, inputs: dict, exc: Exception | None = None) -> Exception:
    """The error for a result that came out NaN or inf (or an operation that refused to make one, ``exc``):
    it names the input with NaN or inf (raised from here), or, when the inputs are finite, all of them: the
    computation overflowed (``checks.finite_result``'s words, with the arguments named)."""
    for name, X in inputs.items():
        if isinstance(X, Multivector):
            multivector(X, func, name, algebra=None, nonzero=False)
        elif X is not None and not is_sympy(X):
            checks.array(X, func, name, np.shape(X))
    names = ", ".join(inputs)
    why = f" ({exc})" if exc is not None else ""
    if isinstance(exc, DegenerateGeometryError):
        return checks.degenerate(func, names, f"no finite result{why}")
    return checks.fail(func, names, f"the result overflows a float (the inputs' magnitudes are too large){why}")
