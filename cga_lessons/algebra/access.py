"""Reading and comparing a multivector: coefficients by blade name, its blades, batches, arrays, its scalar part,
``isclose`` and ``==``.

``X["e12"]`` reads a coefficient (``X["e21"]`` is ``-X["e12"]``, zero where absent), :func:`blades` and
:func:`items` list the non-zero ones in the order of (2.9), :func:`batch_item` takes one multivector out of a batch
and :func:`to_array` writes the coefficients as an array.

Plain functions of a multivector X, each one of the methods of :class:`~cga_lessons.algebra.multivector.Multivector`
(``X["e12"]`` is :func:`coefficient`, ``X == Y`` :func:`equals`, ``X.blades()`` :func:`blades`, ...).  They read X's
``algebra`` and ``_c``, and its ``_operand``, ``_plus`` and ``_mismatch``.
"""

from __future__ import annotations

import numbers

import numpy as np

from cga_lessons.checks import fail, real

from .coefficients import absmax, is_sympy
from .operands import BladeIndexError, blade_bitmaps


def coefficient(X, name):
    """The coefficient of a blade, by name (``X["e12"]``, any factor order) or by bitmap (``X[3]``)."""
    alg = X.algebra
    if type(name) is str:
        hit = alg._name_to_blade.get(name)
        b, s = hit if hit is not None else alg._parse(name, "Multivector[]", "name")
    elif isinstance(name, numbers.Integral) and not isinstance(name, (bool, np.bool_)):
        b, s = int(name), 1
        if not 0 <= b < alg.dim:
            raise BladeIndexError(f"Multivector[]: name: blade bitmap {b} outside 0..{alg.dim - 1}")
    else:
        raise fail("Multivector[]", "name", f"expected a blade name such as 'e12' or a bitmap, got {name!r}")
    v = X._c.get(b, 0.0)
    return v if s == 1 else -v


def blades(X) -> list[str]:
    """Names of the blades with a non-zero coefficient, in the order of (2.9)."""
    order = X.algebra.blade_order
    return [X.algebra.blade_names[b] for b in order if b in X._c]


def items(X):
    """(blade name, coefficient) pairs in the order of (2.9)."""
    return [(X.algebra.blade_names[b], X._c[b]) for b in X.algebra.blade_order if b in X._c]


def coeffs(X) -> dict:
    """The raw sparse map ``{bitmap: coefficient}`` (read only by convention)."""
    return X._c


def shape(X) -> tuple:
    """Batch shape: () for a single multivector, (N,) for N of them."""
    for v in X._c.values():
        if isinstance(v, np.ndarray):
            return v.shape
    return ()


def length(X):
    shape = X.shape
    if not shape:
        raise TypeError("a single multivector has no len(); use .shape for batches")
    return shape[0]


def iterate(X):
    """The items of a batch, one multivector each; a single multivector is not iterable."""
    shape = X.shape
    if not shape:
        raise TypeError("a single multivector is not iterable; use .items() for its blades")
    return (X.batch_item(i) for i in range(shape[0]))


def no_attribute(X, name):
    # blade access as attributes is deliberately not offered: X["e12"] is explicit.
    raise AttributeError(name)


def batch_item(X, index):
    """One multivector of a batch, ``X.batch_item(3)`` (``(i, j)`` for a 2-D batch; a slice gives a sub-batch)."""
    shape = X.shape
    func = "Multivector.batch_item"
    if not shape:
        raise fail(func, "self", "is a single multivector, not a batch")
    if index is None or isinstance(index, (bool, np.bool_, float, complex, str, bytes)):
        raise fail(func, "index", f"expected an integer, a slice or a tuple of them, got {index!r}")
    try:
        out = {b: v[index] if isinstance(v, np.ndarray) else v for b, v in X._c.items()}
    except (IndexError, TypeError) as exc:
        raise fail(func, "index", f"{exc} (the batch has shape {shape})") from None
    return type(X)(X.algebra, out, _prune=True)


def to_array(X, blades=None) -> np.ndarray:
    """Coefficients as an array, last axis over ``blades`` (default all, order of (2.9))."""
    alg = X.algebra
    if blades is None:
        blades = alg.blade_order
    else:
        blades = list(blades) if isinstance(blades, (list, tuple, range)) else blades
        dim = alg.dim
        if not (type(blades) is list and all(type(b) is int and 0 <= b < dim for b in blades)):
            blades = blade_bitmaps(blades, "Multivector.to_array", "blades", dim)
    shape = X.shape
    out = np.zeros(shape + (len(blades),))
    try:
        for i, b in enumerate(blades):
            if b in X._c:
                out[..., i] = X._c[b]
    except (TypeError, ValueError):
        raise fail("Multivector.to_array", "self", "has coefficients that are not real numbers") from None
    return out


def grades_present(X) -> list[int]:
    return sorted({X.algebra.grades[b] for b in X._c})


def scalar(X):
    """The scalar part <M>_0 as a coefficient (an array of zeros for a batch without one)."""
    if 0 in X._c:
        return X._c[0]
    shape = X.shape
    return np.zeros(shape) if shape else 0.0


def to_float(X):
    scale = max((absmax(v) for v in X._c.values() if not is_sympy(v)), default=0.0)
    extra = [
        X.algebra.blade_names[b]
        for b, v in X._c.items()
        if b != 0 and (is_sympy(v) or absmax(v) > 1e-10 * max(scale, 1e-300))
    ]
    if extra:
        raise fail("float", "self", f"the multivector is not a scalar (has blades {extra})")
    v = X._c.get(0, 0.0)
    if isinstance(v, np.ndarray):
        if v.size != 1:
            raise fail("float", "self", f"a batch of {v.size} scalars is not one float")
        return float(v.reshape(-1)[0])
    return float(v)


# -------------------------------------------------------- comparisons
def isclose(X, other, rtol: float = 1e-9, atol: float = 1e-12) -> bool:
    """True when every coefficient agrees within ``atol + rtol*|other|`` (numeric)."""
    func = "Multivector.isclose"
    rtol = real(rtol, func, "rtol", low=0)
    atol = real(atol, func, "atol", low=0)
    other = X._operand(other, func)
    for b in set(X._c) | set(other._c):
        try:
            a = np.asarray(X._c.get(b, 0.0), dtype=float)
            c = np.asarray(other._c.get(b, 0.0), dtype=float)
        except (TypeError, ValueError):
            raise fail(func, "other", "compares numeric coefficients only (a SymPy symbol is not a number)") from None
        try:
            if not np.allclose(a, c, rtol=rtol, atol=atol):
                return False
        except ValueError as exc:
            raise X._mismatch(func, other, exc) from None
    return True


def equals(X, other, func: str = "Multivector =="):
    if isinstance(other, type(X)):
        if other.algebra is not X.algebra:
            raise fail(func, "other", f"is a multivector of {other.algebra}, not of {X.algebra}")
    elif isinstance(other, (numbers.Number, np.ndarray)) or is_sympy(other):
        other = type(X)(X.algebra, {0: other}, _prune=True)
    else:
        return NotImplemented
    diff = X._plus(-other)
    for v in diff._c.values():
        if is_sympy(v):
            import sympy

            if sympy.simplify(v) != 0:
                return False
        elif np.any(np.asarray(v) != 0):
            return False
    return True


def not_equals(X, other):
    eq = equals(X, other, "Multivector !=")
    return eq if eq is NotImplemented else not eq


def iszero(X, atol: float = 1e-12) -> bool:
    atol = real(atol, "Multivector.iszero", "atol", low=0)
    return X.isclose(0.0, rtol=0.0, atol=atol)
