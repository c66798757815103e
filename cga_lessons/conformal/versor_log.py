"""Logarithm of motors and the screw behind it; the dilator (beyond table 2.2).

The thesis writes every rigid motion as the exponential of a bivector: a
rotor ``R = exp(-theta/2 l)`` (2.94), a translator ``T = exp(e t/2)`` (2.100)
and a screw ``exp(-theta/2 (l + e m))`` (2.110).  This module goes the other
way: the bivector of a given motor, and with it the motor's powers
``exp(s log M)`` (:func:`screw_power`), which :mod:`cga_lessons.conformal.versor_powers` uses for
constant-velocity interpolation and n-th roots.

Conventions are those of :mod:`cga_lessons.conformal.versors` (``l = n I_E`` for a unit
axis n, ``M = T R`` rotates by +theta about n, then translates by t).  By
Chasles' theorem ``M`` is a screw: a rotation by theta about the line with
direction n through a point c, and a slide ``t_par = (t . n) n`` along it.
Split ``t = t_par + t_perp``; the axis point ``c`` (with ``c . n = 0``) solves
``c - Rot(theta) c = t_perp``, ``c = (t_perp + cot(theta/2) n x t_perp)/2``.
Then, with ``e ^ w`` the translation part of the logarithm::

    log M = -theta/2 l + e ^ w,
    w = (t_par + (theta/2) cot(theta/2) t_perp - (theta/2) n x t_perp) / 2,

which is (2.110) with ``w = -theta/2 m`` and tends to ``e t/2`` (the
translator's log) as theta -> 0, with no division by a small angle.  The powers
have the closed form ``exp(s log M) = T(t_s) R(n, s theta)`` with
``t_s = s t_par + sin(s theta/2)/sin(theta/2) Rot(n, -(1-s) theta/2) t_perp``.

``M`` and ``-M`` move every entity the same way (the sandwich is quadratic).
:func:`motor_log` returns the principal logarithm of the *motion*, angle in
[0, pi]; :func:`versor_root` needs the exact versor, angle in [0, 2 pi).

References: Dorst, Fontijne & Mann (2007), *Geometric Algebra for Computer
Science*, ch. 13 (exponential and logarithm of rigid body motions) and ch. 16
(conformal operators, uniform scaling); Dorst & Valkenburg (2011), "Square root
and logarithm of rotors in 3D conformal geometric algebra using polar
decomposition", in *Guide to Geometric Algebra in Practice*, Springer.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, GeometryError, InvalidInputError, Multivector

from .model import G41, IE, E, einf
from .multivector_checks import input_error, multivector, result_finite
from .points import vector
from .versors_build import rotor, translator
from .versors_rigid import decompose_motor

__all__ = ["motor_log", "rotor_log", "screw_parameters", "dilator"]

_TOL = 1e-9  # relative tolerance of the checks that a multivector is a unit motor
# Below this |sin(theta/2)| a rotor with negative scalar part is taken as -1 exactly (axis then along t).
_SNAP = 1e-12
# A power of a motor with theta > pi whose translation grows by more than this is refused (ill-conditioned).
_MAX_GAIN = 1e4
_E_BLADES = {b for b in G41.blade_order if b & 0b11000}  # blades with an e+ or e- factor


# ----------------------------------------------------------------- checks
def unit_motor(M, func: str, name: str = "M") -> Multivector:
    """The unit motor M, checked (one numeric motor of G(4,1)) and renormalised; raises otherwise."""
    where = f"{func}: {name}:"
    multivector(M, func, name, what="a motor (Multivector of G(4,1))", single=True, numeric=True, nonzero=False)
    vals = {b: float(v) for b, v in M.coeffs.items()}
    scale = max([1.0] + [abs(v) for v in vals.values()])
    odd = [G41.blade_names[b] for b, v in vals.items() if G41.grades[b] % 2 and abs(v) > _TOL * scale]
    if odd:
        raise InvalidInputError(f"{where} odd grades present (blades {odd}); a motor is even")
    M = Multivector(G41, {b: v for b, v in vals.items() if G41.grades[b] % 2 == 0 and v != 0})
    if not M.coeffs:
        raise DegenerateGeometryError(f"{where} the zero multivector is not a motor")
    comm = max([0.0] + [abs(v) for v in (M * einf - einf * M).coeffs.values()])
    if comm > _TOL * scale:
        raise InvalidInputError(
            f"{where} not a motor: it does not commute with e (|M e - e M| = {comm:.3g}), so it moves the point "
            "at infinity (a dilation, transversion or other conformal versor)"
        )
    if G41.rigid_motion(M) is None:  # its E (dilation) and e0 parts against the rotor: a similarity far out
        raise InvalidInputError(
            f"{where} not a motor: it has an E = e+e- or e0 part beyond round-off of its rotor part (a dilation "
            "or another conformal versor), or is a product of motors so far out that it is no motor to working "
            "precision (see Algebra.rigid_motion)"
        )
    # M ~M = R ~R for M = T R: its scalar is the rotor part's squared norm, read from the blades free of e+ and e-
    # (the full product would sum the translation's coefficients squared, which cancel to eps |t|^2, not to 0).
    n2 = sum(v * v for b, v in M.coeffs.items() if not b & 0b11000)
    MM = M * ~M
    rest = max([0.0] + [abs(v) for b, v in MM.coeffs.items() if b != 0])
    if abs(n2 - 1.0) > _TOL or rest > _TOL * scale * scale:
        raise InvalidInputError(
            f"{where} not a unit motor: M ~M = {n2:.6g} (other grades up to {rest:.3g}), expected 1; "
            "a scaled motor must be normalised explicitly, M / M.norm()"
        )
    return M * (1.0 / math.sqrt(n2))


def screw_of_motor(M: Multivector, exact: bool):
    """Screw parameters of a unit motor: (half angle, unit axis n, translation t, sin(half), sign).

    ``exp(-half l) = sign R`` with ``M = T_t R``; half in [0, pi/2] (sign -1 when
    the rotor's scalar part is negative) or, ``exact``, half in [0, pi], sign 1.
    """
    R, t = decompose_motor(M)
    t = np.asarray(t, dtype=float)
    c = float(R.scalar())
    v = -np.array([R["e23"], R["e31"], R["e12"]], dtype=float)  # sin(half) n, from R = c - sin(half) n I_E
    sign = 1.0
    if not exact and c < 0:
        c, v, sign = -c, -v, -1.0
    s = float(np.linalg.norm(v))
    if c < 0 and s <= _SNAP:
        s = 0.0  # R = -1: a full turn about any axis; pick it along t so that the slide commutes
    half = math.atan2(s, c)
    norm_t = float(np.linalg.norm(t))
    n = v / s if s > 0 else (t / norm_t if norm_t > 0 else np.array([0.0, 0.0, 1.0]))
    return half, n, t, s, sign


def _log_from_screw(half, n, t, s) -> Multivector:
    """B = -half l + e ^ w with w as in the module docstring."""
    t_par = float(t @ n) * n
    t_perp = t - t_par
    c = math.cos(half)
    f = half * c / s if s > 0 else (1.0 if c > 0 else 0.0)  # (theta/2) cot(theta/2); t_perp = 0 when c = -1
    w = 0.5 * (t_par + f * t_perp - half * np.cross(n, t))
    return ((vector(n) * IE) * (-half) + einf * vector(w)).grade(2)


def screw_power(half, n, t, s, frac, where: str) -> Multivector:
    """exp(frac log M) in closed form: T(t_s) R(n, 2 frac half); frac scalar or (N,) array."""
    frac = np.asarray(frac, dtype=float)
    t_par = float(t @ n) * n
    t_perp = t - t_par
    sigma = np.sin(frac * half) / s if s > 0 else frac  # sin(s theta/2)/sin(theta/2) -> s as theta -> 0
    gain = float(np.max(np.abs(sigma))) * float(np.linalg.norm(t_perp)) / max(1.0, float(np.linalg.norm(t)))
    if half > np.pi / 2 and gain > _MAX_GAIN:
        raise DegenerateGeometryError(
            f"{where} near -T (rotation angle {2 * half:.6g}, close to 2 pi, with a translation off the axis): "
            f"the power translates {gain:.1e} times farther than M, ill-conditioned; "
            "the same motion -M has a well-behaved one"
        )
    alpha = -(1.0 - frac) * half
    rot = np.multiply.outer(np.cos(alpha), t_perp) + np.multiply.outer(np.sin(alpha), np.cross(n, t_perp))
    t_s = np.multiply.outer(frac, t_par) + sigma[..., None] * rot
    angle = 2.0 * half * frac
    return translator(t_s) * rotor(n, float(angle) if angle.ndim == 0 else angle)


# ------------------------------------------------------------------ public
def motor_log(M: Multivector) -> Multivector:
    """Principal logarithm of a unit motor: the bivector B with exp(B) = +-M, angle in [0, pi].

    Inverts (2.94), (2.100) and (2.110) by the screw (Chasles) decomposition:
    the rotor part of ``M = T R`` (2.141) gives the angle theta and the unit
    axis n (2.135-2.137); the translation t (2.144) splits into the slide
    ``t_par`` along the axis and ``t_perp``, which moves the axis off the
    origin.  Then ``B = -theta/2 l + e ^ w`` with ``l = n I_E`` and
    ``w = (t_par + (theta/2) cot(theta/2) t_perp - (theta/2) n x t_perp)/2``
    (see the module docstring; Dorst, Fontijne & Mann 2007, ch. 13).

    Conventions.  A rotor about z by theta has log ``-theta/2 e12``; a
    translator ``1 + e t/2`` has log ``e t/2 = e ^ t/2``.  M and -M are the same
    motion; the log is that of the motion with theta in [0, pi] (the shortest
    screw), so ``exp(B) == M`` when the scalar part of the rotor part of M is
    >= 0 and ``exp(B) == -M`` otherwise.  At theta = pi exactly both axis
    orientations are logs; the one of M's rotor is returned.

    Parameters
    ----------
    M : Multivector
        One numeric unit motor (rotor, translator, screw); M ~M must be 1
        within a relative 1e-9, a scaled motor raises (normalise it with
        ``M / M.norm()``).

    Returns
    -------
    Multivector, grade 2.

    Raises
    ------
    InvalidInputError
        Not a Multivector, a batch, SymPy coefficients, NaN/inf, odd grades,
        not a motor (a dilation moves e), not unit.

    Examples
    --------
    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> motor_log(cga.rotor([0, 0, 1], np.pi / 2))  # -theta/2 e12
    -0.785398 e12
    >>> motor_log(cga.translator([2.0, 0.0, 0.0]))  # e t/2
    -1 e1+ - 1 e1-
    >>> M = cga.motor([0, 0, 1], 1.0, [1.0, 2.0, 3.0])
    >>> bool(cga.exp(motor_log(M)).isclose(M))
    True
    """
    M = unit_motor(M, "motor_log")
    half, n, t, s, _ = screw_of_motor(M, exact=False)
    return _log_from_screw(half, n, t, s)


def screw_parameters(M: Multivector):
    """The screw of a unit motor: ``(angle, axis, point, distance)`` with ``cga.screw(axis, point, angle, distance)``
    the same motion, Chasles' theorem read off (2.110).

    ``angle`` in [0, pi] about the unit ``axis`` (the rotor part, 2.135-2.137),
    ``point`` the point of the screw axis nearest the origin, and ``distance``
    the slide along the axis (``t . axis`` of the translation 2.144).  The axis
    point solves ``c - Rot(angle) c = t_perp``: ``c = (t_perp + cot(angle/2) axis x t_perp)/2``.
    A pure translation has no axis: raises :class:`DegenerateGeometryError`
    (its screw is at infinity; use the translation of ``decompose_motor``).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> M = cga.screw([0, 0, 1], [1.0, 2.0, 0.0], np.pi / 2, 0.5)
    >>> angle, axis, point, distance = screw_parameters(M)
    >>> round(angle, 6), axis.round(6), point.round(6), round(distance, 6)
    (1.570796, array([0., 0., 1.]), array([1., 2., 0.]), 0.5)
    """
    M = unit_motor(M, "screw_parameters")
    half, n, t, s, _ = screw_of_motor(M, exact=False)
    if s <= _SNAP:
        raise DegenerateGeometryError(
            "screw_parameters: M: no rotation, a pure translation has its screw axis at infinity"
        )
    t_par = float(t @ n)
    t_perp = t - t_par * n
    c = 0.5 * (t_perp + (math.cos(half) / s) * np.cross(n, t_perp))
    return 2.0 * half, n + 0.0, c + 0.0, t_par  # + 0.0: no negative zeros


def rotor_log(R: Multivector) -> Multivector:
    """Logarithm of a rotor about the origin, ``-theta/2 l`` of (2.94), angle in [0, pi].

    The Euclidean part of :func:`motor_log`: with ``R = cos(theta/2) -
    sin(theta/2) n I_E`` (2.95), theta and n come from the scalar and bivector
    parts (2.135-2.137), with atan2 for accuracy near 0 and pi.  ``exp`` of the
    result is R, or -R when R's scalar part is negative (the same rotation).

    Raises :class:`InvalidInputError` for what :func:`motor_log` refuses and
    for a motor that moves the origin (use :func:`motor_log` for those).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> rotor_log(cga.rotor([1, 0, 0], 0.5))  # -theta/2 e23
    -0.25 e23
    """
    R = unit_motor(R, "rotor_log", "R")
    scale = max(1.0, max(abs(v) for v in R.coeffs.values()))
    moved = max([0.0] + [abs(v) for b, v in R.coeffs.items() if b in _E_BLADES])
    if moved > _TOL * scale:
        raise InvalidInputError(f"rotor_log: R: not a rotor about the origin (e-parts {moved:.3g}); use motor_log")
    half, n, t, s, _ = screw_of_motor(R.grade(0, 2), exact=False)
    return _log_from_screw(half, n, np.zeros(3), s)


def dilator(scale, center=None) -> Multivector:
    """Dilation versor ``D = exp(-ln(scale)/2 E) = a - b E``, ``a = cosh(g)``, ``b = sinh(g)``, g = ln(scale)/2.

    Not numbered in the thesis (its table 2.2 holds the rigid motions,
    inversions and reflections); see Dorst, Fontijne & Mann (2007), ch. 16
    (uniform scaling).  ``E = e+ e- = e ^ e0`` (2.55) squares to +1, so the
    series (2.37) sums to cosh/sinh, here written ``a = (s + 1) / (2 sqrt(s))``,
    ``b = (s - 1) / (2 sqrt(s))`` (no logarithm: b is exact to a few ulp for s
    near 1, and ``a^2 - b^2 = 1``).  The sandwich ``apply(D, up(x))`` is
    ``up(scale x) / scale`` and ``down`` (2.111) removes the factor.

    With a centre c it is ``T_c D ~T_c`` (T_c the translator of 2.100), written
    out: ``E e = -e``, ``e E = e`` and c commutes with E, so ``T_c E ~T_c =
    E + e c`` and::

        D_c = a - b E - b e ^ c,        x -> c + scale (x - c),

    each coefficient one product (``b c_i`` on the e+ and e- blades): no
    ``|c|^2``-sized terms that cancel, so ``dilator(1.0, c)`` is exactly 1 and
    the map holds to round-off at any distance (the product ``T_c D ~T_c``
    rounded terms of size ``|c|^2 b`` and left a scale off by ~1e-4 1e6 out).
    D is an even unit versor (D ~D = 1) but not a motor: it moves e, so
    :func:`motor_log` refuses it; its log is ``-ln(scale)/2 E`` (about the
    origin).  :func:`~cga_lessons.conformal.apply_to_points` maps points by
    ``x -> scale x + (1 - scale) c`` read off D
    (:func:`~cga_lessons.conformal.similarities.similarity_factors`); the plain
    conformal image of a point has weight ``-e . X = 1/scale``, the difference
    of its e+ and e- parts of size ``scale |x|^2``, so ``down`` of a plain
    blade keeps about ``eps |scale x|^2`` relative accuracy (7e-8 at
    ``|scale x|`` = 3e4; an anchored entity keeps its frame).

    Parameters
    ----------
    scale : float, finite and > 0
    center : array-like (3,), optional (the origin by default)

    >>> from cga_lessons import conformal as cga
    >>> D = dilator(2.0)
    >>> D
    1.06066 - 0.353553 e+-
    >>> cga.down(cga.apply(D, cga.up([1.0, 2.0, 3.0])))
    array([2., 4., 6.])
    >>> cga.down(cga.apply(dilator(3.0, [1.0, 1.0, 1.0]), cga.up([2.0, 1.0, 1.0])))
    array([4., 1., 1.])
    >>> dilator(1.0, [123456.7, -234567.8, 345678.9])
    1
    """
    scale = checks.real(scale, "dilator", "scale", low=0.0, strict_low=True)
    root = math.sqrt(scale)
    a, b = (scale + 1.0) / (2.0 * root), (scale - 1.0) / (2.0 * root)
    D = E * (-b) + a if b != 0.0 else G41.scalar(a)
    if center is None:
        return D
    c = checks.array(center, "dilator", "center", (3,))
    if b == 0.0:
        return D
    try:
        return result_finite(D - (einf ^ vector(c * b)), "dilator", scale=scale, center=c)
    except GeometryError as exc:  # a product refused to overflow
        if str(exc).startswith("dilator:"):
            raise
        raise input_error("dilator", {"scale": scale, "center": c}, exc) from None
