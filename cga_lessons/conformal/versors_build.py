"""Constructors of the versors of table 2.2: translator, rotor, motor, screw, rotation about a line (2.94-2.110).

(Re-exported by :mod:`cga_lessons.conformal.versors` and :mod:`cga_lessons.conformal`, the modules to import; the
conventions are in the former's docstring.)

Angles and distances are finite real numbers (or SymPy expressions), checked by :mod:`cga_lessons.checks`; a NaN,
inf, complex, bool, string or None raises :class:`~cga_lessons.algebra.InvalidInputError` naming the function the
caller called and the argument, ``"motor: angle: ..."``.  Axes and points are read by
:func:`~cga_lessons.conformal.multivector_checks.check_points`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError, Multivector, any_sympy, is_sympy
from cga_lessons.algebra import exp as _exp

from .model import CONSTANTS, IE, einf, exact_constants
from .multivector_checks import check_points, multivector, result_finite
from .points import vector

__all__ = ["translator", "rotor", "rotor_about_line", "motor", "screw"]


def _consts(X: Multivector):
    return exact_constants() if any_sympy(X) else CONSTANTS


# ------------------------------------------------------------- constructors
def _real(x, func: str, name: str, *, array: bool = False, limit: float | None = None):
    """A finite real angle or distance: a float (a 1-D float array when ``array``), or a SymPy expression.

    :func:`cga_lessons.checks.real` (``checks.array`` for an array): refuses bools, strings, None, complex
    numbers, NaN and inf, and a SymPy expression known to be non-real or infinite, with "func: name: problem";
    ``limit`` bounds ``|x|``.
    """
    if is_sympy(x):
        if x.is_real is False or x.is_finite is False or x.has(_sympy_nan()):
            raise checks.fail(func, name, f"must be a finite real number, got {checks.short(x)}")
        return x
    if array and (isinstance(x, (list, tuple)) or isinstance(x, np.ndarray) and x.ndim):
        a = checks.array(x, func, name, (None,), at_least=1)
    else:
        a = checks.real(x, func, name)
    if limit is not None:
        checks.magnitude(a, func, name, limit=limit, why="no float precision is left for its sine and cosine")
    return a


def _sympy_nan():
    import sympy

    return sympy.nan


def _exact(a):
    """A Python/NumPy number as an exact SymPy number: integers stay integers, other floats become the
    rational of their shortest decimal form (0.6 -> 3/5)."""
    import sympy

    if is_sympy(a):
        return a
    a = float(a)
    return sympy.Integer(int(a)) if a.is_integer() else sympy.nsimplify(a, rational=True)


def _translator(t, func: str, name: str) -> Multivector:
    tv = vector(t, func, name)
    c = _consts(tv)
    half = 0.5 if not any_sympy(tv) else exact_constants().eo["e-"]  # 1/2, exact when symbolic
    return (c.einf * tv) * half + 1


def translator(t) -> Multivector:
    """Translator T = 1 + e t / 2 = exp(e t / 2), Eq. (2.100); moves by +t.

    ``t`` has shape (3,) or (N, 3) (a batch of translators) or is symbolic.
    """
    return _translator(t, "translator", "t")


def _unit_axis(axis, func: str, name: str = "axis", exact: bool = False):
    """Unit axis (numeric, or SymPy when the axis is symbolic or ``exact``), from ``func``'s argument ``name``.

    A numeric axis is scaled by its largest component before its norm is
    taken, so that neither 1e200 nor 1e-200 over- or underflows.
    """
    arr, sym = check_points(axis, func, name)
    if sym or exact:
        import sympy

        if not sym:
            if arr.ndim != 1:
                raise checks.fail(func, name, f"one axis (shape (3,)) with a SymPy angle, got {arr.shape}")
            arr = [_exact(a) for a in arr]
        n = sympy.sqrt(sum(a**2 for a in arr))
        if n == 0:
            raise checks.degenerate(func, name, "the rotation axis is the zero vector")
        return [sympy.simplify(a / n) for a in arr], True
    big = np.max(np.abs(arr), axis=-1, keepdims=True)
    if np.any(big == 0):
        raise checks.degenerate(func, name, "the rotation axis is the zero vector")
    arr = arr / big
    return arr / np.linalg.norm(arr, axis=-1, keepdims=True), False


def _rotor(axis, angle, func: str, axis_name: str) -> Multivector:
    angle = _real(angle, func, "angle", array=True)
    exact = is_sympy(angle)
    n, sym = _unit_axis(axis, func, axis_name, exact=exact)
    if type(angle) is np.ndarray and not sym and n.ndim == 2 and angle.shape != n.shape[:1]:
        raise checks.fail(func, "angle", f"one angle, or one per axis ({len(n)}), got {len(angle)}")
    if sym:
        import sympy

        l = vector(n) * exact_constants().IE
        return l * (-sympy.sin(angle / 2)) + sympy.cos(angle / 2)
    l = vector(n) * IE
    return l * (-np.sin(angle / 2)) + np.cos(angle / 2)


def rotor(axis, angle) -> Multivector:
    """Rotor R = exp(-angle/2 l) = cos(angle/2) - sin(angle/2) l, Eqs. (2.94)-(2.96).

    ``l = n I_E`` is the unit bivector of the plane orthogonal to the axis n
    (so ``l = n1 e23 + n2 e31 + n3 e12``, 2.96).  Turns by +angle about n
    (right-hand rule).  ``axis`` (3,) or (N, 3); ``angle`` scalar or (N,).
    A SymPy angle gives an exact rotor, a numeric axis then taken as exact
    (``rotor([0, 0, 1], pi/2) = sqrt(2)/2 - sqrt(2)/2 e12``).
    """
    return _rotor(axis, angle, "rotor", "axis")


def rotor_about_line(L: Multivector, angle) -> Multivector:
    """Rotation about an arbitrary line, R_L = exp(-angle/2 L), Eqs. (2.106)-(2.109).

    ``L`` is a line in dual form (grade 3, ``line_from_points(a, b)``) or
    standard form (grade 2); it is normalised (2.126).  The rotation is by
    +angle about the line's direction (from a to b), right-hand rule.
    Equal to ``T R ~T`` of (2.104) with T moving the origin onto the line.
    """
    from .entities import standard_form
    from .entities_read import read_line
    from .lines_circles import as_dual_line, normalize_line

    func = "rotor_about_line"
    angle = _real(angle, func, "angle", array=True, limit=_MAX_ANGLE)
    Ld = as_dual_line(multivector(L, func, "L", what="a line (Multivector of G(4,1))"), func)
    if not any_sympy(Ld):
        d, _ = read_line(Ld, func, "L")  # a line, not a circle; with a direction
        big = float(np.max(np.abs(d)))
        if not 1e-150 < big < 1e150:  # |d|^2 would under- or overflow in normalize_line: scale first
            Ld = Ld * (1.0 / big)
        if type(angle) is np.ndarray and Ld.shape and Ld.shape != angle.shape:
            raise checks.fail(func, "angle", f"one angle, or one per line ({Ld.shape[0]}), got {len(angle)}")
    Lstd = standard_form(normalize_line(Ld))
    # The standard form L = L* Ic of the unit line is l + e (t . l) of (2.108).
    B = Lstd * (-angle / 2)
    return _exp_named(B, func, "L, angle")


#: Largest |angle| (rad) of :func:`rotor_about_line` and :func:`screw`: at 2**52 a float's step is one radian
#: (and the exponential refuses larger half-angles).
_MAX_ANGLE = 2.0**52


def _exp_named(B: Multivector, func: str, names: str) -> Multivector:
    """exp(B), its errors (a screw too large for floats) in the words of ``func``."""
    try:
        return result_finite(_exp(B), func, **{names: B})
    except GeometryError as exc:
        if str(exc).startswith(f"{func}:"):
            raise
        raise checks.fail(func, names, f"the motor cannot be formed in floats ({exc})") from None


def motor(rotation_axis, angle, translation) -> Multivector:
    """Motor M = T R, Eq. (2.102): rotation by +angle about the axis through
    the origin (right-hand rule), then translation.
    """
    T = _translator(translation, "motor", "translation")
    R = _rotor(rotation_axis, angle, "motor", "rotation_axis")
    if T.shape and R.shape and T.shape != R.shape:
        raise checks.fail("motor", "translation", f"a batch of {T.shape[0]} translations and of {R.shape[0]} rotations")
    return T * R


def screw(axis, point, angle, distance) -> Multivector:
    """Screw motion M = exp(-angle/2 (l + e m)), Eq. (2.110).

    Rotation by +angle about the line through ``point`` with direction
    ``axis``, combined with a translation ``distance`` along the axis; built
    from the exponential of the screw bivector with
    ``m = t . l - (distance/angle) r`` (2.110).  Equal to ``T_dr R_L``.
    ``angle`` must be non-zero (a pure translation is :func:`translator`).
    With a SymPy angle or distance the motor is built as that product,
    ``T_dr T_p R ~T_p`` (2.104, 2.110), in closed form: exact and fast (the
    exponential of a symbolic screw bivector needs SymPy to simplify square
    roots of its square, which takes minutes).
    """
    func = "screw"
    angle = _real(angle, func, "angle", limit=_MAX_ANGLE)
    distance = _real(distance, func, "distance")
    pt, psym = check_points(point, func, "point")
    exact = is_sympy(angle) or is_sympy(distance) or psym
    if angle == 0:
        raise checks.degenerate(func, "angle", "is 0; a pure slide is a translator")
    n, sym = _unit_axis(axis, func, "axis", exact=exact)
    if sym:  # T_dr T_p R ~T_p, exact
        if not psym:
            if pt.ndim != 1:
                raise checks.fail(func, "point", f"one point (shape (3,)) when symbolic, got {pt.shape}")
            pt = [_exact(a) for a in pt]
        Tp = _translator(pt, func, "point")
        Td = _translator([a * distance for a in n], func, "distance")
        return Td * Tp * _rotor(n, angle, func, "axis") * ~Tp
    r = vector(n)
    l = r * IE
    m = (vector(pt, func, "point") | l) - r * (distance / angle)  # (2.110)
    return _exp_named((l + einf * m) * (-angle / 2), func, "point, angle, distance")
