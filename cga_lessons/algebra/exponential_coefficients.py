"""The scalar coefficients of the closed-form exponential of a bivector (2.37).

For :mod:`cga_lessons.algebra.exponential`.

With ``B^2 = s + F`` (F the grade-4 part), ``exp(B) = C1 C2 + alpha B + (S1 S2 / 2) F + (h / 2) F B``, where
``lam1``, ``lam2`` are the roots of ``lam^2 - s lam + F^2/4``, ``Ci = cosh(sqrt(lam_i))``,
``Si = sinh(sqrt(lam_i)) / sqrt(lam_i)`` (cos and sin(x)/x for a negative root), ``h`` the divided difference
``(C1 S2 - C2 S1) / (lam1 - lam2)`` and ``alpha = C2 S1 - lam2 h``.  This module computes those scalars for one
bivector or a batch, without cancellation: ``h`` by a series when both roots are small, by a ``sinh(z)/z`` form when
they are close, by the quotient otherwise; overflow of the hyperbolic part raises.  See
:mod:`cga_lessons.algebra.exponential` for the derivation and references.
"""

from __future__ import annotations

import cmath
import math
from fractions import Fraction
from functools import cache

import numpy as np

from cga_lessons.errors import InvalidInputError

from .coefficients import is_sympy
from .multivector import Multivector

__all__ = ["sympy_module", "cosh_sinhc", "exp_simple", "exp_coefficients_one", "exp_coefficients"]

#: Largest rotation angle (rad) exp accepts: at 2**52 the spacing of floats is 1 rad.
_MAX_ANGLE = 2.0**52
#: Largest rapidity of a hyperbolic part: cosh overflows a float beyond about 710.
_MAX_RAPIDITY = 710.5
#: The three regimes of the divided difference h (see the module docstring).
_SMALL = 0.5  # both |lam| <= _SMALL: the series
_NEAR = 0.5  # |lam1 - lam2| < _NEAR * max|lam|: the shc form
_SERIES_ORDER = 12


@cache
def sympy_module():
    import sympy

    return sympy


# ------------------------------------------------------------ one plane
def _sympy_root(x):
    """A square root of the SymPy expression x without a sqrt when there is one, else None.

    Any root will do: every function used on it here (cos, sin(r)/r, cosh,
    sinh(r)/r) is even, so ``sqrt(theta**2)`` may be taken as ``theta``.
    """
    sp = sympy_module()
    r = sp.powdenest(sp.sqrt(x), force=True)
    if any(p.exp.is_Rational and not p.exp.is_Integer for p in r.atoms(sp.Pow)):
        return None
    return r if sp.expand(r**2 - x) == 0 else None


def cosh_sinhc(lam):
    """``cosh(sqrt(lam))`` and ``sinh(sqrt(lam))/sqrt(lam)``, real for real lam of any sign.

    Floats and arrays: cos/sin(x)/x for lam < 0, cosh/sinh(x)/x for lam > 0,
    the Taylor series for |lam| < 1e-2.  SymPy: exact; the trigonometric form
    when -lam is a perfect square or negative, the hyperbolic one when lam
    is, and the trigonometric form when nothing is known (the common case of
    a rotation).
    """
    if is_sympy(lam):
        sp = sympy_module()
        if lam == 0:
            return sp.Integer(1), sp.Integer(1)
        if lam.is_negative or (-lam).is_positive:
            a = sp.sqrt(-lam)
            return sp.cos(a), sp.sin(a) / a
        if lam.is_positive:
            a = sp.sqrt(lam)
            return sp.cosh(a), sp.sinh(a) / a
        a = _sympy_root(-lam)
        if a is not None:
            return sp.cos(a), sp.sin(a) / a
        a = _sympy_root(lam)
        if a is not None:
            return sp.cosh(a), sp.sinh(a) / a
        a = sp.sqrt(-lam)
        return sp.cos(a), sp.sin(a) / a
    lam = np.asarray(lam, dtype=float)
    a = np.sqrt(np.abs(lam))
    pos = lam > 0
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        c = np.where(pos, np.cosh(a), np.cos(a))
        s = np.where(pos, np.sinh(a), np.sin(a)) / np.where(a == 0, 1.0, a)
    small = np.abs(lam) < 1e-2
    if np.any(small):
        c = np.where(small, _series_c(lam), c)
        s = np.where(small, _series_s(lam), s)
    if c.ndim == 0:
        return float(c), float(s)
    return c, s


def _series_c(lam):
    """cosh(sqrt(lam)) by its series, for |lam| < 1e-2 (next term below 1e-21)."""
    return 1 + lam * (1 / 2 + lam * (1 / 24 + lam * (1 / 720 + lam * (1 / 40320 + lam / 3628800))))


def _series_s(lam):
    """sinh(sqrt(lam))/sqrt(lam) by its series, for |lam| < 1e-2."""
    return 1 + lam * (1 / 6 + lam * (1 / 120 + lam * (1 / 5040 + lam * (1 / 362880 + lam / 39916800))))


def exp_simple(B: Multivector, lam):
    """exp of a bivector with a scalar square ``lam`` (2.37 summed in closed form): C + S B."""
    c, s = cosh_sinhc(lam)
    return B * s + c


# ---------------------------------------------------- the coefficients of (*)
# Two versions of the same arithmetic: one for a single bivector (Python floats and cmath, a few
# microseconds) and one for a batch (NumPy arrays, the regimes chosen with np.where).


def _raise_angle(angle):
    raise InvalidInputError(
        f"exp: B: rotation angle {angle:.3g} rad too large (a rotor exp(B) would turn by {2 * angle:.3g} rad): "
        "beyond 2**52 rad one unit in the last place of the angle is over 1 rad, so its cos and sin have no "
        "correct digit; reduce the angle modulo 2 pi before building B"
    )


def _raise_rapidity(rapidity):
    raise InvalidInputError(
        f"exp: B: hyperbolic part (boost or dilation) of rapidity {rapidity:.6g} too large: "
        f"its cosh overflows a float (limit about {_MAX_RAPIDITY})"
    )


def _ldexp_or_inf(x: float, k: int) -> float:
    try:
        return math.ldexp(x, k)
    except OverflowError:
        return math.inf


def _cs_one(lam: complex):
    """C(lam) = cosh(sqrt(lam)) and S(lam) = sinh(sqrt(lam))/sqrt(lam), one complex lam."""
    if abs(lam) < 1e-2:
        return _series_c(lam), _series_s(lam)
    x = cmath.sqrt(lam)
    return cmath.cosh(x), cmath.sinh(x) / x


def _shc_one(z: complex):
    """sinh(z)/z, one complex z."""
    z2 = z * z
    if abs(z2) < 1e-2:
        return 1 + z2 * (1 / 6 + z2 * (1 / 120 + z2 * (1 / 5040 + z2 * (1 / 362880 + z2 / 39916800))))
    return cmath.sinh(z) / z


def exp_coefficients_one(s_sc: float, p_sc: float, k: int):
    """The coefficients of (*) for one bivector from its scaled invariants.

    ``s_sc = s 4^-k`` and ``p_sc = (F^2/4) 16^-k`` (B was scaled by 2^-k
    against overflow).  Returns ``(c0, alpha, S1 S2, h)`` for
    ``exp(B) = c0 + alpha B + S1 S2 F/2 + h F B/2``.
    """
    root = cmath.sqrt(s_sc * s_sc - 4.0 * p_sc)
    l1 = (s_sc + root) / 2 if s_sc >= 0 else (s_sc - root) / 2  # the larger root: no cancellation
    l2 = p_sc / l1 if l1 != 0 else 0j
    x1s, x2s = cmath.sqrt(l1), cmath.sqrt(l2)
    angle, rapidity = max(abs(x1s.imag), abs(x2s.imag)), max(abs(x1s.real), abs(x2s.real))
    if angle > math.ldexp(_MAX_ANGLE, -k):
        _raise_angle(_ldexp_or_inf(angle, k))
    if rapidity > math.ldexp(_MAX_RAPIDITY, -k):
        _raise_rapidity(_ldexp_or_inf(rapidity, k))
    lam1 = complex(math.ldexp(l1.real, 2 * k), math.ldexp(l1.imag, 2 * k))
    lam2 = complex(math.ldexp(l2.real, 2 * k), math.ldexp(l2.imag, 2 * k))
    c1, s1 = _cs_one(lam1)
    c2, s2 = _cs_one(lam2)
    big, gap = max(abs(lam1), abs(lam2)), abs(lam1 - lam2)
    if big <= _SMALL:
        h = _h_series(math.ldexp(s_sc, 2 * k), math.ldexp(p_sc, 4 * k))
        alpha = c2 * s1 - lam2 * h
    elif gap < _NEAR * big:
        x1, x2 = cmath.sqrt(lam1), cmath.sqrt(lam2)
        su, sv = _shc_one(x1 + x2), _shc_one(x1 - x2)
        h = (su - sv) / (2 * x1 * x2)
        alpha = (su + sv) / 2
    else:
        h = (c1 * s2 - c2 * s1) / (lam1 - lam2)
        alpha = c2 * s1 - lam2 * h
    return (c1 * c2).real, alpha.real, (s1 * s2).real, h.real


def _complex_cs(lam):
    """C(lam) = cosh(sqrt(lam)) and S(lam) = sinh(sqrt(lam))/sqrt(lam) for a complex array."""
    x = np.sqrt(lam)
    c = np.cosh(x)
    s = np.sinh(x) / np.where(x == 0, 1.0, x)
    small = np.abs(lam) < 1e-2
    return np.where(small, _series_c(lam), c), np.where(small, _series_s(lam), s)


def _shc(z):
    """sinh(z)/z for a complex array (the series near 0)."""
    z2 = z * z
    series = 1 + z2 * (1 / 6 + z2 * (1 / 120 + z2 * (1 / 5040 + z2 * (1 / 362880 + z2 / 39916800))))
    return np.where(np.abs(z2) < 1e-2, series, np.sinh(z) / np.where(z == 0, 1.0, z))


@cache
def _h_series_table():
    """T[n][k] with h = sum_n h_n(lam1, lam2) sum_k T[n][k] (lam1 lam2)^k (small roots).

    From C(l) = sum l^j/(2j)!, S(l) = sum l^k/(2k+1)!:  C1 S2 - C2 S1 =
    sum_{j>k} (a_j b_k - a_k b_j)(lam1^j lam2^k - lam1^k lam2^j), and
    (lam1^j lam2^k - lam1^k lam2^j)/(lam1 - lam2) = (lam1 lam2)^k h_{j-k-1}
    with h_n the complete symmetric polynomial of degree n in lam1, lam2.
    Truncated at degree 12: for |lam| <= 0.5 the first term left out is below 1e-25.
    """
    N = _SERIES_ORDER
    a = [Fraction(1, math.factorial(2 * j)) for j in range(N + 1)]
    b = [Fraction(1, math.factorial(2 * k + 1)) for k in range(N + 1)]
    return tuple(tuple(float(a[n + k + 1] * b[k] - a[k] * b[n + k + 1]) for k in range(N - n)) for n in range(N))


def _h_series(s, p):
    """h = (C1 S2 - C2 S1)/(lam1 - lam2) from s = lam1 + lam2 and p = lam1 lam2 (floats or arrays), |lam| <= 0.5."""
    out = 0.0 * s
    hm2, hm1 = 0.0 * s, 0.0 * s + 1.0  # h_{-1} = 0, h_0 = 1
    for row in _h_series_table():
        inner = 0.0 * s
        for coef in reversed(row):
            inner = inner * p + coef
        out = out + hm1 * inner
        hm2, hm1 = hm1, s * hm1 - p * hm2  # h_{n+1} = s h_n - p h_{n-1}
    return out


def exp_coefficients(s_sc, p_sc, k):
    """:func:`exp_coefficients_one` for arrays (a batch; ``k`` an integer array)."""
    disc = s_sc * s_sc - 4.0 * p_sc
    root = np.sqrt(disc.astype(complex))
    sign = np.where(s_sc >= 0, 1.0, -1.0)
    l1 = (s_sc + sign * root) / 2  # the larger root: no cancellation
    l2 = np.where(l1 != 0, p_sc / np.where(l1 == 0, 1.0, l1), 0.0)
    x1s, x2s = np.sqrt(l1), np.sqrt(l2)
    angle = np.ldexp(np.maximum(np.abs(x1s.imag), np.abs(x2s.imag)), k)
    rapidity = np.ldexp(np.maximum(np.abs(x1s.real), np.abs(x2s.real)), k)
    if np.any(angle > _MAX_ANGLE):
        _raise_angle(float(np.max(angle)))
    if np.any(rapidity > _MAX_RAPIDITY):
        _raise_rapidity(float(np.max(rapidity)))
    two_k = 2 * k
    lam1 = np.ldexp(l1.real, two_k) + 1j * np.ldexp(l1.imag, two_k)
    lam2 = np.ldexp(l2.real, two_k) + 1j * np.ldexp(l2.imag, two_k)
    x1, x2 = np.sqrt(lam1), np.sqrt(lam2)
    c1, s1 = _complex_cs(lam1)
    c2, s2 = _complex_cs(lam2)
    big = np.maximum(np.abs(lam1), np.abs(lam2))
    gap = np.abs(lam1 - lam2)
    small = big <= _SMALL
    near = ~small & (gap < _NEAR * big)
    # far: the divided difference as it stands
    h = (c1 * s2 - c2 * s1) / np.where(gap == 0, 1.0, lam1 - lam2)
    alpha = c2 * s1 - lam2 * h
    if np.any(near):
        su, sv = _shc(x1 + x2), _shc(x1 - x2)
        h = np.where(near, (su - sv) / np.where(near, 2 * x1 * x2, 1.0), h)
        alpha = np.where(near, (su + sv) / 2, alpha)
    if np.any(small):
        hs = _h_series(np.where(small, np.ldexp(s_sc, two_k), 0.0), np.where(small, np.ldexp(p_sc, 2 * two_k), 0.0))
        h = np.where(small, hs, h)
        alpha = np.where(small, c2 * s1 - lam2 * hs, alpha)
    return (c1 * c2).real, alpha.real, (s1 * s2).real, h.real
