"""The exponential of a bivector (2.37), summed in closed form.

``exp(B)`` is how the thesis writes rotors (2.94-2.96), translators (2.100) and
screws (2.110): a bivector whose square is a scalar gives cosh/sinh
(or cos/sin, or ``1 + B``) directly, and a general bivector of G(4,1) splits
into two commuting simple ones.  The same code takes float, batched and SymPy
coefficients.  Import :func:`exp` from :mod:`cga_lessons.algebra`.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from .algebra_coefficients import _any_sympy, _is_sympy, _is_zero
from .algebra_errors import InvalidInputError
from .multivector import Multivector

__all__ = ["exp"]


@cache
def _sympy():
    import sympy

    return sympy


def _cosh_sinhc(lam):
    """cosh(sqrt(lam)) and sinh(sqrt(lam))/sqrt(lam), real for real lam of any sign."""
    if _is_sympy(lam):
        sp = _sympy()
        if lam == 0:
            return sp.Integer(1), sp.Integer(1)
        if lam.is_negative or (-lam).is_positive:
            a = sp.sqrt(-lam)
            return sp.cos(a), sp.sin(a) / a
        if lam.is_positive:
            a = sp.sqrt(lam)
            return sp.cosh(a), sp.sinh(a) / a
        # sign unknown: give the form for a negative square (rotations), the common case
        a = sp.sqrt(-lam)
        return sp.cos(a), sp.sin(a) / a
    lam = np.asarray(lam, dtype=float)
    a = np.sqrt(np.abs(lam))
    pos = lam > 0
    c = np.where(pos, np.cosh(a), np.cos(a))
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.where(pos, np.sinh(a) / np.where(a == 0, 1, a), np.sin(a) / np.where(a == 0, 1, a))
    s = np.where(a < 1e-8, 1.0 + lam / 6.0, s)
    if c.ndim == 0:
        return float(c), float(s)
    return c, s


def _exp_simple(B: Multivector, lam):
    """exp of a bivector with a scalar square ``lam`` (2.37 summed in closed form)."""
    c, s = _cosh_sinhc(lam)
    return B * s + c


def exp(B: Multivector) -> Multivector:
    """Exponential of a bivector (2.37), summed in closed form.

    A bivector whose square is a scalar ``lam`` is simple and
    ``exp(B) = cosh(sqrt(lam)) + B sinh(sqrt(lam))/sqrt(lam)`` (cos/sin for a
    rotation plane, ``1 + B`` for a null bivector such as ``e t/2`` of a
    translator, 2.100).  A general bivector of G(4,1) (a screw, 2.110) splits
    into two commuting simple bivectors B = B1 + B2, with squares the roots of
    ``l^2 - <B^2>_0 l + (<B^2>_4)^2/4 = 0``; then exp(B) = exp(B1) exp(B2).
    A scalar part, if present, multiplies by its ordinary exponential.
    """
    alg = B.algebra
    grades = set(B.grades_present())
    if not grades <= {0, 2}:
        raise InvalidInputError(f"exp: closed form needs a bivector (plus scalar), got grades {sorted(grades)}")
    scal = B.scalar()
    B = B.grade(2)
    factor = None
    if not _is_zero(scal):
        factor = _sympy().exp(scal) if _is_sympy(scal) else np.exp(scal)
    if not B._c:
        out = Multivector(alg, {0: 1.0})
        return out * factor if factor is not None else out
    sq = B * B
    lam0 = sq.scalar()
    four = sq.grade(4)
    symbolic = _any_sympy(B)
    if symbolic:
        four = four.simplify()
    numeric_small = (not symbolic) and four.iszero(atol=1e-14 * max(1.0, float(np.max(np.abs(lam0)))))
    if (symbolic and not four._c) or numeric_small:
        out = _exp_simple(B, lam0)
    else:
        q = (four * four).scalar()
        if symbolic:
            sp = _sympy()
            disc = sp.sqrt(lam0**2 - q)
            l1, l2 = (lam0 + disc) / 2, (lam0 - disc) / 2
        else:
            disc = np.sqrt(np.maximum(np.asarray(lam0) ** 2 - q, 0.0))
            l1, l2 = (lam0 + disc) / 2, (lam0 - disc) / 2
            if np.any(disc < 1e-10 * np.maximum(1.0, np.abs(lam0))):
                return _exp_series(B) * (factor if factor is not None else 1.0)
        half = four * 0.5 if not symbolic else four / 2
        Binv = B.inv()
        B1 = (Binv * (half + l1)).grade(2)
        B2 = B - B1
        out = _exp_simple(B1, l1) * _exp_simple(B2, l2)
        if symbolic:
            out = out.simplify()
    return out * factor if factor is not None else out


def _exp_series(B: Multivector, terms: int = 30) -> Multivector:
    """exp by scaling and squaring of the series (2.37), for the rare repeated-root case."""
    norm = np.max(np.abs(B.to_array()))
    k = int(max(0, np.ceil(np.log2(max(norm, 1e-300))) + 1)) if norm > 0.5 else 0
    X = B * (0.5**k)
    out = Multivector(B.algebra, {0: 1.0})
    term = Multivector(B.algebra, {0: 1.0})
    for i in range(1, terms):
        term = term * X * (1.0 / i)
        out = out + term
    for _ in range(k):
        out = out * out
    return out
