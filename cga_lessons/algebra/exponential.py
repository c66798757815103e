"""The exponential of a bivector (2.37), summed in closed form.

``exp(B)`` is how the thesis writes rotors (2.94-2.96), translators (2.100) and
screws (2.110).  Import :func:`exp` from :mod:`cga_lessons.algebra`; the same
code takes float, batched (array) and SymPy coefficients.

The closed form
---------------
For a bivector B, ``B^2 = s + F`` with ``s = <B^2>_0`` and ``F = <B^2>_4 =
B ^ B`` (the grade-2 part of B^2 is the commutator of B with itself, zero).
F commutes with B.  When ``F^2`` is a scalar (always in dimension <= 5,
where every 4-vector is a blade, so in G(4,1)), ``B^4 = 2 s B^2 - s^2 + F^2``,
so the series (2.37) folds onto ``1, B, B^2, B^3``, i.e. onto ``1, B, F, F B``
(``B^3 = s B + F B``, and F B is a bivector)::

    exp(B) = C1 C2 + alpha B + (S1 S2 / 2) F + (h / 2) F B,          (*)

    alpha = C2 S1 - lam2 h,   h = (C1 S2 - C2 S1) / (lam1 - lam2),

with ``lam1, lam2`` (``|lam2| <= |lam1|``) the roots of ``lam^2 - s lam + F^2/4`` (the squares of
the two commuting planes B = B1 + B2 of the invariant decomposition,
``B1 B2 = F/2``), ``Ci = cosh(sqrt(lam_i))`` and ``Si = sinh(sqrt(lam_i)) /
sqrt(lam_i)``: entire functions of lam_i (cos and sin(x)/x for a rotation
plane, lam < 0; cosh and sinh(x)/x for a boost, lam > 0; 1 and 1 for a null
plane, lam = 0).  (*) is exp(B1) exp(B2) expanded, written with B, F and F B
instead of B1 and B2, so nothing is inverted; its coefficients are symmetric
entire functions of (lam1, lam2), and only h is a divided difference, which
is summed without cancellation in three regimes (both roots small: a series
in ``lam1 + lam2`` and ``lam1 lam2``; roots close: ``h = (shc(x1+x2) -
shc(x1-x2)) / (2 x1 x2)`` with ``x_i = sqrt(lam_i)``, ``shc(z) = sinh(z)/z``;
else the quotient itself).

A screw ``-theta/2 (l + e m)`` (2.110) has a null F (``F^2 = 0``), so
``lam2 = 0``, ``lam1 = s = -theta^2/4`` and (*) reads
``exp(B) = cos(theta/2) + (sin(theta/2)/(theta/2)) (B + F/2) + h/2 F B`` with
``h = (cos(theta/2) - sin(theta/2)/(theta/2)) / s`` (-> 1/3 as theta -> 0):
the rotation times ``1 +`` the translation part, with no division by a
small angle.  A translator (B^2 = 0) gives ``1 + B`` (2.100), a rotor
``cos + sin`` (2.94-2.96).

In G(4,1) the float path computes s, F^2/4, F and F B from B written on the
null basis ``e = e- + e+``, ``eo = (e- - e+)/2`` (2.53): a bivector is
``B = B_E + u ^ e + w ^ eo + eta E`` (u, w Euclidean vectors, B_E = omega I_E
a Euclidean bivector), and then exactly

    s = -|omega|^2 + eta^2 + 2 u . w,       F^2/4 = -2 (omega . u)(omega . w) - |d|^2,
    F/2 = (omega . u) I_E e + (omega . w) I_E eo + E d I_E,   d = eta omega - u x w,

(F B is written out in :func:`_g41_invariants`).  On the orthonormal basis
the same numbers are differences of terms of the size of the translation
squared (``(e_i e+)^2 = -1``, ``(e_i e-)^2 = +1``), which is what made the
previous split, ``B1 = B^-1 (lam1 + F/2)``, lose every digit (or raise) for a
small rotation angle with a large translation.

References: the thesis, eq. (2.37) (the series), (2.94), (2.100), (2.110);
L. Dorst, D. Fontijne, S. Mann, *Geometric Algebra for Computer Science*
(Morgan Kaufmann, 2007), ch. 13 (exponential of rigid body motions);
L. Dorst, R. Valkenburg, "Square root and logarithm of rotors in 3D
conformal geometric algebra using polar decomposition", in *Guide to
Geometric Algebra in Practice* (Springer, 2011) (the commuting split of a
bivector of G(4,1)); M. Roelfs, S. De Keninck, "Graded symmetry groups:
plane and simple", arXiv:2107.03771 (2021), Adv. Appl. Clifford Algebras 33,
30 (2023) (the invariant decomposition and the closed-form exponential).

Large arguments.  A rotation angle above ``2**52`` rad (where one unit in the
last place of the angle is 1 rad, so cos and sin of it have no correct
digit) raises rather than being reduced modulo 2 pi: the angle is only known
through the squares of B's coefficients, so its rounding error is already
about ``1e-16 * angle``; reduce the angle yourself before building B.  A
hyperbolic part (boost, dilation) whose cosh overflows raises, as does any
other overflow of the result and NaN/inf input: exp never returns inf or NaN.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons.errors import InvalidInputError

from .coefficients import any_sympy, is_sympy, is_zero
from .exponential_coefficients import cosh_sinhc, exp_coefficients, exp_coefficients_one, exp_simple, sympy_module
from .multivector import Multivector

__all__ = ["exp"]

# ------------------------------------------------------------ invariants
_E12, _E13, _E23 = 0b00011, 0b00101, 0b00110
_EP, _EM = 0b01000, 0b10000


def _g41_invariants(col):
    """s, F^2/4, F/2 and F B/2 of a bivector of G(4,1) on the null basis (module docstring).

    ``col(blade)`` is the coefficient of B on a bivector blade (floats, or
    arrays for a batch).  With ``B = B_E + u ^ e + w ^ eo + eta E``,
    ``B_E = omega I_E``, ``rho_u = omega . u``, ``rho_w = omega . w`` and
    ``d = eta omega - u x w``::

        F B / 2 = (d x u - rho_u omega) ^ e - (d x w + rho_w omega) ^ eo
                  + (rho_u w + rho_w u + eta d) I_E - (d . omega) E.

    Returns ``(s, q = F^2/4, F/2 as {blade: coefficient}, F B/2 as {blade: coefficient})``.
    """

    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])

    om = (col(_E23), -col(_E13), col(_E12))
    cp = [col((1 << i) | _EP) for i in range(3)]
    cm = [col((1 << i) | _EM) for i in range(3)]
    eta = col(_EP | _EM)
    u = [(a + b) * 0.5 for a, b in zip(cp, cm)]  # coefficient of e_i ^ e
    w = [b - a for a, b in zip(cp, cm)]  # of e_i ^ eo: exact (Sterbenz) when c+ and c- are close
    s = -dot(om, om) + eta * eta + 2.0 * dot(u, w)
    ru, rw = dot(om, u), dot(om, w)
    uxw = cross(u, w)
    d = [eta * o - c for o, c in zip(om, uxw)]
    q = -2.0 * ru * rw - dot(d, d)
    four = {
        0b01111: ru - 0.5 * rw,  # e123+
        0b10111: ru + 0.5 * rw,  # e123-
        0b11110: d[0],  # e23+-
        0b11101: -d[1],  # e13+-
        0b11011: d[2],  # e12+-
    }
    dxu, dxw = cross(d, u), cross(d, w)
    g = [a - ru * o for a, o in zip(dxu, om)]
    hh = [-a - rw * o for a, o in zip(dxw, om)]
    K = [ru * b + rw * a + eta * c for a, b, c in zip(u, w, d)]
    two = {_E23: K[0], _E13: -K[1], _E12: K[2], _EP | _EM: -dot(d, om)}
    for i in range(3):
        two[(1 << i) | _EP] = g[i] - 0.5 * hh[i]
        two[(1 << i) | _EM] = g[i] + 0.5 * hh[i]
    return s, q, four, two


def _generic_invariants(alg, coeffs: dict):
    """s, F^2/4, F/2 and F B/2 by the algebra's products; None when F^2 is not a scalar (dimension >= 6)."""
    Bs = Multivector(alg, coeffs, _prune=True)
    sq = Bs * Bs
    s = sq.scalar()
    half = sq.grade(4) * 0.5
    if not half._c:
        return s, np.zeros_like(s), {}, {}
    ff = half * half
    q = ff.scalar()
    if alg.n > 5:
        scale = max(float(np.max(np.abs(v))) for v in half._c.values()) ** 2
        rest = [float(np.max(np.abs(v))) for b, v in ff._c.items() if b != 0]
        if rest and max(rest) > 1e-13 * scale:
            return None
    fb = (half * Bs).grade(2, 6)
    return s, q, dict(half._c), dict(fb._c)


# ------------------------------------------------------------------ exp
def exp(B: Multivector) -> Multivector:
    """Exponential of a bivector, the series (2.37) summed in closed form.

    ``exp(B) = C1 C2 + alpha B + (S1 S2/2) F + (h/2) F B`` with
    ``F = <B^2>_4``, exact for every bivector whose F^2 is a scalar (all of
    G(4,1) and of any algebra of dimension <= 5); see the module docstring for
    the coefficients and the references (Dorst, Fontijne & Mann 2007, ch. 13;
    Dorst & Valkenburg 2011; Roelfs & De Keninck 2021).  Special cases: a
    rotation plane (``B^2 < 0``) gives ``cos|B| + sin|B| B/|B|`` (rotors,
    2.94-2.96), a boost ``cosh + sinh``, a null bivector ``1 + B``
    (translators, 2.100), a screw ``-theta/2 (l + e m)`` the motor of (2.110).
    A scalar part, if present, multiplies by its ordinary exponential.
    Anything else (three or more planes, dimension >= 6) is summed by
    scaling and squaring of the series.

    Coefficients may be floats, arrays (a batch) or SymPy expressions (exact:
    ``exp(-theta/2 e12) = cos(theta/2) - sin(theta/2) e12``).

    Raises
    ------
    InvalidInputError
        ``exp: B: ...``: not a bivector (plus scalar), NaN or inf coefficients,
        a rotation angle beyond 2**52 rad (reduce it modulo 2 pi first), a
        hyperbolic part or a result that overflows a float.

    Examples
    --------
    >>> import math
    >>> from cga_lessons import conformal as cga
    >>> exp(cga.e1 * cga.e2 * (-math.pi / 4))  # a rotor (2.94): a quarter turn about e3
    0.707107 - 0.707107 e12
    >>> exp(cga.einf * cga.vector([2.0, 0.0, 0.0]) * 0.5)  # a translator (2.100): 1 + e t/2
    1 - 1 e1+ - 1 e1-
    >>> exp(cga.E * 0.5)  # E = e+ e- squares to +1: cosh + sinh (a dilator)
    1.12763 + 0.521095 e+-
    >>> M = cga.motor([0, 0, 1.0], 1e-6, [1e6, 0.0, 0.0])  # a tiny turn and a long slide
    >>> bool(exp(cga.motor_log(M)).isclose(M, rtol=1e-12, atol=1e-12))
    True
    """
    if not isinstance(B, Multivector):
        raise InvalidInputError(f"exp: B: expected a Multivector, got {type(B).__name__}")
    grades = set(B.grades_present())
    if not grades <= {0, 2}:
        raise InvalidInputError(
            f"exp: B: the closed form (2.37) needs a bivector (plus a scalar), got grades {sorted(grades)}"
        )
    if any_sympy(B):
        return _exp_sympy(B)
    return _exp_numeric(B)


def _real_coefficients(B: Multivector) -> dict:
    out = {}
    for b, v in B._c.items():
        a = np.asarray(v)
        if a.dtype.kind not in "fiu":
            raise InvalidInputError(f"exp: B: coefficients must be real numbers or arrays, got {a.dtype} ({v!r})")
        out[b] = a.astype(float)
        if not np.all(np.isfinite(out[b])):
            raise InvalidInputError(f"exp: B: coefficient of {B.algebra.blade_names[b]} contains NaN or inf")
    return out


def _exp_numeric(B: Multivector) -> Multivector:
    alg = B.algebra
    vals = _real_coefficients(B)
    shape = B.shape
    factor = None
    if 0 in vals and np.any(vals[0] != 0):
        with np.errstate(over="ignore"):
            factor = np.exp(vals[0])
        if not np.all(np.isfinite(factor)):
            raise InvalidInputError(
                f"exp: B: scalar part {float(np.max(vals[0])):.6g} too large: its exponential overflows a float"
            )
    blades = alg.grade_blades[2]
    pos = {b: i for i, b in enumerate(blades)}
    X = np.zeros(shape + (len(blades),))
    for b, v in vals.items():
        if b:
            X[..., pos[b]] = v
    if not np.any(X):
        out = Multivector(alg, {0: np.ones(shape) if shape else 1.0})
    else:
        out = _exp_bivector(alg, X, blades, pos, shape)
    if factor is not None:
        with np.errstate(over="ignore", invalid="ignore"):
            out = out._scale(factor if shape else float(factor))  # unchecked: the test below says why
        if not all(np.all(np.isfinite(v)) for v in out._c.values()):
            raise InvalidInputError(
                f"exp: B: the result overflows a float: exp of the scalar part (up to {float(np.max(vals[0])):.6g}) "
                "times the exponential of the bivector part"
            )
    return out


def _exp_bivector(alg, X, blades, pos, shape) -> Multivector:
    """exp of the bivector with coefficients ``X`` (shape + (number of bivector blades,)), by (*)."""
    g41 = alg.metric == (1, 1, 1, 1, -1)
    # B is scaled by 2^-k (exact) so that its squares cannot overflow; the roots come back as lam 4^k.
    if not shape:
        x = X.tolist()
        biggest = max(abs(v) for v in x)
        k = math.frexp(biggest)[1] if biggest > 1.0 else 0
        xs = [math.ldexp(v, -k) for v in x] if k else x
        if g41:
            got = _g41_invariants(lambda blade: xs[pos[blade]])
        else:
            got = _generic_invariants(alg, {b: v for b, v in zip(blades, xs)})
        if got is None:
            return _exp_series(Multivector(alg, dict(zip(blades, x)), _prune=True))
        s, q, four, two = got
        try:
            c0, alpha, ss, h = exp_coefficients_one(float(s), float(q), k)
            out = {0: c0}
            for b, v in zip(blades, x):
                if v:
                    out[b] = alpha * v
            for b, v in two.items():
                out[b] = out.get(b, 0.0) + h * math.ldexp(float(v), 3 * k)
            for b, v in four.items():
                out[b] = ss * math.ldexp(float(v), 2 * k)
            ok = all(math.isfinite(v) for v in out.values())
        except OverflowError:
            ok = False
        if not ok:
            _raise_overflow(alg, float(np.max(np.abs(X))))
        return Multivector(alg, out, _prune=True)
    biggest = np.max(np.abs(X), axis=-1)
    k = np.where(biggest > 1.0, np.frexp(biggest)[1], 0)
    Xs = np.ldexp(X, -k[..., None])
    if g41:
        got = _g41_invariants(lambda blade: Xs[..., pos[blade]])
    else:
        got = _generic_invariants(alg, {b: Xs[..., i] for i, b in enumerate(blades)})
    if got is None:
        return _exp_series(Multivector(alg, {b: X[..., i] for i, b in enumerate(blades)}, _prune=True))
    s, q, four, two = got
    s = np.broadcast_to(np.asarray(s, dtype=float), shape)
    q = np.broadcast_to(np.asarray(q, dtype=float), shape)
    with np.errstate(all="ignore"):
        c0, alpha, ss, h = exp_coefficients(s, q, k)
        out = {0: c0}
        for i, b in enumerate(blades):
            out[b] = alpha * X[..., i]
        for b, v in two.items():
            out[b] = out.get(b, 0.0) + h * np.ldexp(v, 3 * k)
        for b, v in four.items():
            out[b] = ss * np.ldexp(v, 2 * k)
    if not all(np.all(np.isfinite(v)) for v in out.values()):
        _raise_overflow(alg, float(np.max(np.abs(X))))
    return Multivector(alg, out, _prune=True)


def _raise_overflow(alg, biggest: float):
    raise InvalidInputError(
        f"exp: B: the result overflows a float (largest coefficient of B {biggest:.3g}; "
        "the exponential of its hyperbolic part or its products with the translation part are too large)"
    )


def _exp_sympy(B: Multivector) -> Multivector:
    """The closed form (*) with SymPy coefficients: exact, simplified."""
    sp = sympy_module()
    alg = B.algebra
    zero, one = sp.Integer(0), sp.Integer(1)
    scal = B._c.get(0, zero)
    B = B.grade(2)
    factor = None if is_zero(scal) else (sp.exp(scal) if is_sympy(scal) else np.exp(scal))
    if not B._c:
        out = Multivector(alg, {0: one})
        return out * factor if factor is not None else out
    sq = B * B
    s = sp.simplify(sq._c.get(0, zero))
    half = sq.grade(4).simplify() * sp.Rational(1, 2)
    if not half._c:
        out = exp_simple(B, s)
    else:
        ff = (half * half).simplify()
        if any(b != 0 for b in ff._c):
            raise InvalidInputError(
                "exp: B: no closed form for this symbolic bivector (three or more commuting planes, "
                f"dimension {alg.n} >= 6); substitute numbers first"
            )
        p = ff._c.get(0, zero)
        disc = sp.simplify(s**2 - 4 * p)
        if p == 0:  # a screw-like bivector: one plane null (lam2 = 0), lam1 = s
            c1, s1 = cosh_sinhc(s)
            c0, alpha, ss = c1, s1, s1
            h = sp.Rational(1, 3) if s == 0 else (c1 - s1) / s
        elif disc == 0:  # repeated root lam1 = lam2 = s/2 (an isoclinic pair of planes)
            lam = s / 2
            c, sh = cosh_sinhc(lam)
            c0, ss = c * c, sh * sh
            alpha = (c * sh + 1) / 2
            h = (c * sh - 1) / (2 * lam)
        else:
            r = sp.sqrt(disc)
            lam1, lam2 = (s + r) / 2, (s - r) / 2
            c1, s1 = cosh_sinhc(lam1)
            c2, s2 = cosh_sinhc(lam2)
            c0, ss = c1 * c2, s1 * s2
            h = (c1 * s2 - c2 * s1) / r
            alpha = c2 * s1 - lam2 * h
        fb = (half * B).grade(2, 6)
        out = (B * alpha + half * ss + fb * h + c0).simplify()
    return out * factor if factor is not None else out


def _exp_series(B: Multivector, terms: int = 30) -> Multivector:
    """exp by scaling and squaring of the series (2.37), for what has no closed form (numeric only).

    B is halved k times until the sum of the absolute values of its
    coefficients (a bound on every product norm of the algebra) is at most
    1/2, the series summed to ``terms`` terms (error below 0.5^terms/terms!),
    and the sum squared k times.
    """
    vals = _real_coefficients(B)
    size = sum(np.abs(v) for v in vals.values()) if vals else 0.0
    size = float(np.max(size)) if np.size(size) else 0.0
    k = max(0, math.frexp(size)[1] + 1) if size > 0.5 else 0
    X = Multivector(B.algebra, {b: np.ldexp(v, -k) if v.ndim else math.ldexp(float(v), -k) for b, v in vals.items()})
    out = Multivector(B.algebra, {0: 1.0})
    term = Multivector(B.algebra, {0: 1.0})
    alg = B.algebra
    with np.errstate(over="ignore", invalid="ignore"):  # unchecked products: the test below names exp
        for i in range(1, terms):
            term = alg._products.product(term, X, "gp")._scale(1.0 / i)
            out = out._plus(term)
        for _ in range(k):
            out = alg._products.product(out, out, "gp")
    bad = [b for b, v in out._c.items() if not np.all(np.isfinite(v))]
    if bad:
        raise InvalidInputError(f"exp: B: the result overflows a float (coefficients of B up to {size:.3g})")
    return out
