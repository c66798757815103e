"""The conformal package's one checks module, composed from :mod:`cga_lessons.checks` (its ``fail``,
``degenerate``, ``real``, ``batch``, ``magnitude``, ``instance``) and the algebra's
:func:`~cga_lessons.algebra.finite_multivector`.

* :func:`check_points`: Euclidean point(s) (3,) or (N, 3), or three SymPy expressions, with :data:`COORD_LIMIT`;
* :func:`multivector`, :func:`check_vector`: an entity or versor argument: a multivector of G(4,1), finite real
  coefficients (single, numeric, non-zero, a vector when asked);
* :func:`mv_is_finite`, :func:`result_finite`, :func:`input_error`: a result that came out NaN or inf is
  refused, naming the input with NaN or inf or, for finite inputs, the overflow (the words of
  ``checks.finite_result``, with the arguments named).

Internal to :mod:`cga_lessons.conformal` (not re-exported by its facade).
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, Multivector, finite_multivector, is_sympy

from .model import G41

__all__ = [
    "COORD_LIMIT",
    "COORD_WHY",
    "check_points",
    "multivector",
    "check_vector",
    "mv_is_finite",
    "result_finite",
    "input_error",
]

#: Largest coordinate a conformal point can hold: up(x) stores x^2 / 2, which overflows a float beyond ~1.3e154.
COORD_LIMIT = 1e153
COORD_WHY = "a conformal point stores x^2 / 2, which overflows a float beyond ~1.3e154"


def check_points(x, func: str, name: str = "x", *, limit: bool = False):
    """Euclidean point(s) through the checks layer: ``(array (3,) or (N, 3), False)``, or ``(list, True)`` for
    three SymPy expressions (a list or a 3x1 matrix with at least one of them symbolic).

    Refuses a Multivector (a conformal point wants :func:`down` first), wrong shapes, NaN/inf and complex
    numbers; with ``limit`` also coordinates beyond :data:`COORD_LIMIT`, whose squares overflow.
    """
    if isinstance(x, Multivector):
        raise checks.fail(func, name, "expected Euclidean coordinates, got a Multivector (use down() first)")
    if isinstance(x, (list, tuple)) and len(x) == 3 and any(is_sympy(c) for c in x):
        return list(x), True
    if checks.is_symbolic(x) and _is_sympy_matrix(x):
        return [x[i] for i in range(3)], True
    arr, single = checks.batch(x, func, name, (3,), limit=COORD_LIMIT if limit else None, why=COORD_WHY)
    return (arr[0] if single else arr), False


def _is_sympy_matrix(x) -> bool:
    try:
        import sympy

        return isinstance(x, sympy.MatrixBase) and len(x) == 3
    except ImportError:  # pragma: no cover
        return False


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

    ``single``: no batch (array coefficients); ``numeric``: no SymPy coefficients (nor object arrays of them);
    ``nonzero``: the zero multivector is refused (:class:`DegenerateGeometryError`); ``finite=False`` lets NaN and
    inf through.  The check of the conformal package's public functions that take an entity or a versor: one pass
    over the (at most 32) coefficients for their kinds, then the algebra's
    :func:`~cga_lessons.algebra.finite_multivector`.
    """
    checks.instance(X, func, name, Multivector, what)
    if algebra is not None and X.algebra is not algebra:
        raise checks.fail(func, name, f"a multivector of {X.algebra!r}, not of the conformal G(4,1)")
    for v in X._c.values():
        t = type(v)
        if t is float or t is int or t is np.float64:
            continue
        if t is np.ndarray and v.dtype.kind in "fiuO":
            if single and v.ndim:
                raise checks.fail(func, name, f"a batch of shape {v.shape}; pass one at a time")
            if v.dtype.kind == "O" and (numeric or not all(is_sympy(e) or _real(e) for e in v.flat)):
                raise checks.fail(func, name, "numeric coefficients only, got an array of objects")
        elif is_sympy(v):
            if numeric:
                raise checks.fail(func, name, "numeric coefficients only, got SymPy ones")
        elif not _real(v):
            raise checks.fail(func, name, f"coefficients must be real numbers, got {type(v).__name__}")
        elif finite:
            checks.real(v, func, name)  # NaN and inf, in the usual words
    if finite:
        finite_multivector(X, func, name)
    if nonzero and not X._c:
        raise checks.degenerate(func, name, "is the zero multivector")
    return X


def _real(v) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_))


def check_vector(X, func: str, name: str) -> Multivector:
    """A finite multivector of G(4,1) of grade 1 (a point, sphere or plane in standard form)."""
    multivector(X, func, name, nonzero=False)
    gs = X.grades_present()
    if gs != [1]:
        raise checks.fail(func, name, f"expected a conformal point or sphere (a vector, grade 1), got grades {gs}")
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


def result_finite(result: Multivector, func: str, /, **inputs) -> Multivector:
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
