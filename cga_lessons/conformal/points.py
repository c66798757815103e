"""Conformal points of section 2.3: up (2.62) and down (2.111, 2.114), their weight and normalisation.

The basis and constants are in :mod:`cga_lessons.conformal.model`, the checks of the arguments in
:mod:`cga_lessons.conformal.multivector_checks`; import all of them from :mod:`cga_lessons.conformal`.

    >>> from cga_lessons import conformal as cga
    >>> cga.down(cga.up([1.0, 2.0, 3.0]))
    array([1., 2., 3.])
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import REAL_TYPES, Multivector, absmax, all_finite, any_sympy, is_real_single, is_sympy
from cga_lessons.scratch import scratch

from .model import G41, einf, exact_constants
from .multivector_checks import check_points, check_vector, multivector

__all__ = ["up", "down", "vector", "euclidean", "normalize_point"]


def vector(x, func: str = "vector", name: str = "x") -> Multivector:
    """Euclidean vector(s) x1 e1 + x2 e2 + x3 e3 of G(4,1); x of shape (3,) or (N, 3)."""
    arr, sym = check_points(x, func, name)
    if sym:
        return Multivector(G41, {1: arr[0], 2: arr[1], 4: arr[2]}, _prune=True)
    if arr.ndim == 1:
        return Multivector(G41, {1 << i: float(arr[i]) for i in range(3) if arr[i] != 0})
    return Multivector(G41, {1: arr[:, 0].copy(), 2: arr[:, 1].copy(), 4: arr[:, 2].copy()})


def up(x) -> Multivector:
    """Conformal point x + x^2 e/2 + e0 of a Euclidean point, Eq. (2.62).

    Parameters
    ----------
    x : array-like, shape (3,) or (N, 3), or three SymPy expressions
        Euclidean coordinates (metres).  A (N, 3) array gives a batch of N
        points (array coefficients).

    Returns
    -------
    Multivector
        Grade-1 null vector with ``X^2 = 0`` and ``X . e = -1`` (2.61).

    Examples
    --------
    >>> X = up([3.0, 0.0, 4.0])
    >>> X["e+"], X["e-"]  # (x^2 - 1)/2 and (x^2 + 1)/2, Eq. (2.63)
    (12.0, 13.0)
    """
    arr, sym = check_points(x, "up", limit=True)  # beyond COORD_LIMIT the e+/e- coefficients x^2/2 (2.62) overflow
    if sym:
        c = exact_constants()
        v = vector(arr, "up")
        x2 = sum(ci**2 for ci in arr)
        return v + c.einf * (x2 / 2) + c.eo
    if arr.ndim == 1:
        a0, a1, a2 = arr.tolist()
        x2 = a0 * a0 + a1 * a1 + a2 * a2  # the order of np.sum: the same bits
        coeffs = {1: a0, 2: a1, 4: a2, 8: 0.5 * (x2 - 1.0), 16: 0.5 * (x2 + 1.0)}
        return Multivector(G41, {k: v for k, v in coeffs.items() if v != 0})
    # The five coefficient arrays are the rows of one (5, N) block, so that a versor applied to the batch
    # (versors.apply) multiplies the block without copying it.  x^2 is summed over the block's contiguous
    # rows (x1 x1 + x2 x2) + x3 x3, the order of the single point's sum: the same bits.
    block = np.empty((5, arr.shape[0]))
    block[:3] = arr.T
    x2, tmp = block[4], block[3]
    np.multiply(block[0], block[0], out=x2)
    np.multiply(block[1], block[1], out=tmp)
    x2 += tmp
    np.multiply(block[2], block[2], out=tmp)
    x2 += tmp
    np.subtract(x2, 1.0, out=block[3])
    block[3] *= 0.5
    x2 += 1.0
    x2 *= 0.5
    return Multivector(G41, {1: block[0], 2: block[1], 4: block[2], 8: block[3], 16: block[4]})


def point_weight(X: Multivector):
    """-e . X, the homogeneous weight of a conformal point or sphere (2.111, 2.115); 0 for a plane."""
    check_vector(X, "point_weight", "X")
    return _weight(X)


def _weight(X: Multivector):
    return -(X | einf).scalar() if not any_sympy(X) else -(X | exact_constants().einf).scalar()


def normalize_point(X: Multivector, func: str = "normalize_point") -> Multivector:
    """Scale a conformal point (or sphere) so that X . e = -1, Eq. (2.111)/(2.115).

    ``func`` is the name errors give (for callers that normalise on a user's behalf).  Raises
    :class:`DegenerateGeometryError` when the weight is zero (the point at infinity, a plane), and
    :class:`InvalidInputError` for anything but a finite vector of G(4,1).
    """
    check_vector(X, func, "X")
    w = _weight(X)
    if is_sympy(w):
        return (X / w).simplify()
    if type(w) in REAL_TYPES and is_real_single(X):  # one point: plain floats, no NumPy calls
        scale = math.sqrt(sum(float(v) ** 2 for v in X._c.values()))
        if abs(w) <= 1e-14 * max(scale, 1e-300):
            raise checks.degenerate(func, "X", _AT_INFINITY)
        return X / float(w)
    w = np.asarray(w, dtype=float)
    scale = np.sqrt(sum(np.asarray(v, dtype=float) ** 2 for v in X._c.values())) if X._c else 0.0
    if np.any(np.abs(w) <= 1e-14 * np.maximum(scale, 1e-300)):
        raise checks.degenerate(func, "X", _AT_INFINITY)
    return X / (float(w) if w.ndim == 0 else w)


_AT_INFINITY = "X . e = 0, the input is at infinity (or a plane), not a finite point"


def euclidean(X: Multivector):
    """The e1, e2, e3 coefficients of a multivector as an array (3,) or (N, 3)."""
    multivector(X, "euclidean", "X", nonzero=False)
    if any_sympy(X):
        import sympy

        return sympy.Matrix([X._c.get(b, sympy.Integer(0)) for b in (1, 2, 4)])  # exact zeros, not 0.0
    shape = X.shape
    out = np.zeros(shape + (3,))
    for i, b in enumerate((1, 2, 4)):
        if b in X._c:
            out[..., i] = X._c[b]
    return out


def down(X: Multivector):
    """Euclidean point(s) of a conformal point, Eqs. (2.111) and (2.114).

    Normalises with ``X / (-e . X)`` (2.111), then takes the Euclidean part
    ``P_E^perp(X) = (X ^ E) E`` (2.59, 2.114).  Far from the origin the
    weight ``-e . X`` is read as ``|X_E|^2 / (X_+ + X_-)`` (equal for a null
    vector, 2.61), which keeps a few eps of accuracy where the difference
    ``X_- - X_+`` of two |x|^2-sized terms would not (:data:`SUM_OVER_WEIGHT`).

    Returns an array of shape (3,) (or (N, 3) for a batch); for SymPy
    coefficients a 3x1 ``sympy.Matrix``.

    Raises
    ------
    DegenerateGeometryError
        When ``X . e = 0`` (a point at infinity: no Euclidean point).
    InvalidInputError
        For anything but a conformal point: not a Multivector of G(4,1), NaN or inf, other grades than 1, or a
        vector that is not null (``|X . X|`` above :data:`NULL_RTOL` of its squared coefficients: a sphere).
    """
    return read_point(X, "down", "X")


#: A vector X is a point when ``|X . X| <= NULL_RTOL (|X_E|^2 + X_+^2 + X_-^2)`` (2.61, X^2 = 0).  Points built by
#: ``up`` or moved by versors keep X . X to ~1e-14 of that; a sphere of radius rho about p has
#: X . X = w^2 rho^2, so spheres pass as points only when rho^2 is below ~1e-6 (|p|^2 + |p|^4 / 2) (rho < 1e-3 at
#: the origin, a unit sphere beyond ~40 from it): there a float blade barely tells them apart.
NULL_RTOL = 1e-6


def read_point(X, func: str, name: str):
    """:func:`down` with errors in the words of ``func`` and its argument ``name`` (for readers of points)."""
    if not isinstance(X, Multivector) or X.algebra is not G41:
        multivector(X, func, name, nonzero=False)  # raises the usual error
    if is_real_single(X):
        return _down_one(X, func, name)
    if X.shape and not any_sympy(X):
        return _down_batch(X, func, name)
    if not any_sympy(X):  # numbers of other types (NumPy scalars, 0-d arrays): as floats
        multivector(X, func, name, nonzero=False)
        return _down_one(Multivector(G41, {b: float(v) for b, v in X._c.items()}), func, name)
    bad = [G41.blade_names[b] for b in X._c if G41.grades[b] != 1]
    if bad:
        raise checks.fail(func, name, f"a conformal point is a vector (grade 1), got blades {bad}")
    Xn = normalize_point(X, func)
    c = exact_constants()
    return euclidean(((Xn ^ c.E) * c.E).simplify())


#: A weight ``X_- - X_+`` within this many float epsilons of ``|X_-| + |X_+|`` is round-off, not a point: each of
#: the two terms carries half an ulp (eps/2 of its size), so a difference below a few eps of their sum is zero as far
#: as the coefficients can tell.  (Points up to about 3e7 from the origin pass; 1e-14 refused them beyond 1e7.)
_WEIGHT_ULPS = 4 * np.finfo(float).eps

#: Where ``|X_-| + |X_+|`` exceeds this many times the weight ``w = X_- - X_+`` (a point with |x|^2 above it), the
#: weight is read as ``|X_E|^2 / (X_+ + X_-)`` (= ``w^2 x^2 / (w x^2)`` for a null vector, 2.61, 2.62) instead of as
#: the difference: the difference carries the rounding of its two terms, up to eps (|X_-| + |X_+|) / 2, eps x^2 / 2
#: relative (``down(up(x) / 3)`` 1e6 out was 3e-5 off: 30 m), the quotient a few eps whatever |x|.  Below 2^12 the
#: difference is within 2^11 eps (4.5e-13) and is kept: a batch whose points all lie within ~64 of the origin pays
#: two reductions for the test, not the quotient.
SUM_OVER_WEIGHT = 4096.0


def _down_one(X: Multivector, func: str, name: str) -> np.ndarray:
    """:func:`down` of one point with real coefficients, in plain floats (the checks of :func:`_down_batch`)."""
    c = X._c
    if not all(map(math.isfinite, c.values())):
        raise checks.fail(func, name, "the coefficients contain NaN or inf")
    other = [b for b in c if G41.grades[b] != 1]
    if other:
        scale = max(abs(float(v)) for v in c.values())
        bad = [G41.blade_names[b] for b in other if abs(float(c[b])) > 1e-9 * max(scale, 1e-300)]
        if bad:
            raise checks.fail(func, name, f"a conformal point is a vector (grade 1), got blades {bad}")
    x1, x2, x3 = float(c.get(1, 0.0)), float(c.get(2, 0.0)), float(c.get(4, 0.0))
    xp, xm = float(c.get(8, 0.0)), float(c.get(16, 0.0))
    w = xm - xp  # -e . X, (2.111)
    if not abs(w) > _WEIGHT_ULPS * (abs(xm) + abs(xp)):
        raise checks.degenerate(func, name, _AT_INFINITY)
    big = 1.0
    if not _null(x1, x2, x3, xp, xm):  # X . X = 0 (2.61); scaled down when the squares overflow
        big = math.ldexp(1.0, math.frexp(max(abs(x1), abs(x2), abs(x3), abs(xp), abs(xm)))[1])  # a power of two
        if not _null(x1 / big, x2 / big, x3 / big, xp / big, xm / big):
            raise checks.fail(func, name, _NOT_NULL)
    if abs(xm) + abs(xp) > SUM_OVER_WEIGHT * abs(w):  # far out: the weight from the sum (SUM_OVER_WEIGHT)
        y1, y2, y3 = x1 / big, x2 / big, x3 / big
        w = (y1 * y1 + y2 * y2 + y3 * y3) / ((xp + xm) / big) * big
    out = [x1 / w, x2 / w, x3 / w]
    if not all(map(math.isfinite, out)):
        raise checks.fail(func, name, "the coefficients are too large: reading them overflows")
    return np.array(out)


def _null(x1, x2, x3, xp, xm, work=None):
    """Whether ``|X . X| <= NULL_RTOL (|X_E|^2 + X_+^2 + X_-^2)`` (floats, or arrays: ``work`` three spare ones).

    False where the squares overflow or underflow (callers then retry with the coefficients scaled).
    """
    if not any(isinstance(v, np.ndarray) for v in (x1, x2, x3, xp, xm)):
        e2, pp, mm = x1 * x1 + x2 * x2 + x3 * x3, xp * xp, xm * xm
        return abs(e2 + pp - mm) <= NULL_RTOL * (e2 + pp + mm) and e2 + pp + mm > 1e-290
    e2, sq, dot = (None, None, None) if work is None else work
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        e2 = np.multiply(x1, x1, out=e2)
        e2 += np.multiply(x2, x2, out=sq)
        e2 += np.multiply(x3, x3, out=sq)
        e2 += np.multiply(xp, xp, out=sq)  # |X_E|^2 + X_+^2
        sq = np.multiply(xm, xm, out=sq)
        dot = np.subtract(e2, sq, out=dot)  # X . X (2.61)
        e2 += sq
        np.abs(dot, out=dot)
        e2 *= NULL_RTOL
        return (dot <= e2) & (e2 > 1e-296)


_NOT_NULL = "X . X != 0: a sphere (or another vector that is not null), not a conformal point (2.61)"


def _down_batch(X: Multivector, func: str, name: str) -> np.ndarray:
    """:func:`down` of a batch of points, read off its five coefficient arrays (working rows: the thread's scratch).

    The weight ``-e . X = X_- - X_+`` (2.111) and the Euclidean part
    ``x_i / w`` (2.114) are read off the coefficients directly; the checks
    are those of the general path: only grade 1 (other grades within 1e-9 of
    the largest coefficient), a weight clear of zero (beyond a few float
    epsilons of ``|X_-| + |X_+|``, the terms it is the difference of), a
    null vector (:data:`NULL_RTOL`), a finite result.
    """
    c, n = X._c, X.shape
    other = [b for b in c if G41.grades[b] != 1]
    if other:
        scale = max(absmax(v) for v in c.values())
        bad = [G41.blade_names[b] for b in other if absmax(c[b]) > 1e-9 * max(scale, 1e-300)]
        if bad:
            raise checks.fail(func, name, f"a conformal point is a vector (grade 1), got blades {bad}")
    x1, x2, x3, xp, xm = (c.get(b, 0.0) for b in (1, 2, 4, 8, 16))  # arrays broadcast to n, or 0.0
    # Working rows kept by the thread (cga_lessons.scratch): fresh megabytes here cost page faults on every call.
    w, ref, t1, t2 = scratch(4 * math.prod(n), "down").reshape((4,) + n)
    np.subtract(xm, xp, out=w)  # -e . X, (2.111)
    np.abs(xm, out=ref)
    ref += np.abs(xp, out=t1)
    if not np.all(np.abs(w, out=t2) > np.multiply(ref, _WEIGHT_ULPS, out=t1)):  # relative to the terms it cancels
        if not (all_finite(w) and all_finite(ref)):  # (also false for a NaN weight)
            raise checks.fail(func, name, "the coefficients contain NaN or inf")
        raise checks.degenerate(func, name, _AT_INFINITY)
    far_out = w.size > 0 and ref.max() > SUM_OVER_WEIGHT * t2.min()  # perhaps a point far out (t2 holds |w|)
    if not np.all(_null(x1, x2, x3, xp, xm, (ref, t1, t2))):  # X . X = 0 (2.61)
        x1, x2, x3, xp, xm = (np.broadcast_to(v, n) for v in (x1, x2, x3, xp, xm))
        if not (all_finite(x1) and all_finite(x2) and all_finite(x3)):
            raise checks.fail(func, name, "the coefficients contain NaN or inf")
        big = np.maximum.reduce([np.abs(x1), np.abs(x2), np.abs(x3), np.abs(xp), np.abs(xm)])  # squares overflow?
        if not np.all(_null(x1 / big, x2 / big, x3 / big, xp / big, xm / big)):
            raise checks.fail(func, name, _NOT_NULL)
    if far_out:  # which ones (the null test used the rows)
        np.abs(xm, out=ref)
        ref += np.abs(xp, out=t1)
        far = ref > np.multiply(np.abs(w, out=t2), SUM_OVER_WEIGHT, out=t1)
    if far_out and far.any():  # the weight from the sum (SUM_OVER_WEIGHT); the coefficients scaled against overflow
        k = np.flatnonzero(far.reshape(-1))
        y1, y2, y3, yp, ym = (np.broadcast_to(v, n).reshape(-1)[k] for v in (x1, x2, x3, xp, xm))
        big = np.maximum.reduce([np.abs(y1), np.abs(y2), np.abs(y3), np.abs(yp), np.abs(ym)])
        big = np.ldexp(1.0, np.frexp(big)[1])  # a power of two: the same roundings as unscaled
        y1, y2, y3 = y1 / big, y2 / big, y3 / big
        w.reshape(-1)[k] = (y1 * y1 + y2 * y2 + y3 * y3) / ((yp + ym) / big) * big
    out = np.empty(n + (3,))
    np.divide(x1, w, out=out[..., 0])
    np.divide(x2, w, out=out[..., 1])
    np.divide(x3, w, out=out[..., 2])
    if not all_finite(out):
        raise checks.fail(func, name, "the coefficients contain NaN or inf, or are too large to read")
    return out
