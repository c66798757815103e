"""Powers of motors: constant-velocity interpolation, n-th roots and the square root (beyond table 2.2).

A unit motor M is a screw (Chasles); its powers ``exp(s log M)`` turn by s theta about the same axis and slide by
s times the pitch translation, built in closed form by :func:`~cga_lessons.conformal.versor_log.screw_power` (see
:mod:`cga_lessons.conformal.versor_log` for the screw, the logarithm and the formulas).  ``M`` and ``-M`` move
every entity the same way; :func:`versor_root` needs the exact versor, angle in [0, 2 pi).

References: Dorst, Fontijne & Mann (2007), *Geometric Algebra for Computer Science*, ch. 13; Dorst & Valkenburg
(2011), "Square root and logarithm of rotors in 3D conformal geometric algebra using polar decomposition", in
*Guide to Geometric Algebra in Practice*, Springer.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector

from .versor_log import screw_of_motor, screw_power, unit_motor

__all__ = ["motor_interpolate", "versor_sqrt", "versor_root"]


def _check_fraction(s, func: str):
    """s as a float or a non-empty 1-D float array (finite), by :mod:`cga_lessons.checks`."""
    if isinstance(s, (list, tuple, np.ndarray)) and np.ndim(s):
        return checks.array(s, func, "s", (None,), at_least=1)
    return np.asarray(checks.real(s, func, "s"))


def motor_interpolate(M0: Multivector, M1: Multivector, s, *, shortest: bool = True) -> Multivector:
    """Constant-velocity screw interpolation ``exp(s log(M1 ~M0)) M0``.

    ``D = M1 ~M0`` is the motion from M0 to M1; ``exp(s log D)`` turns by
    s theta about D's screw axis and slides by s times its pitch translation,
    so a point moved by the result runs along the exact helix of the screw at
    constant speed (Dorst, Fontijne & Mann 2007, ch. 13).  The powers are
    built in closed form (module docstring), not by a series.

    ``shortest=True`` (the default) takes the principal log of the motion D
    (angle in [0, pi], the shorter way round); then s = 1 gives M1 as a motion
    but possibly as the versor -M1 (when the rotor part of D has a negative
    scalar part).  ``shortest=False`` uses the versor's own log (angle in
    [0, 2 pi)), so s = 1 gives the versor M1 exactly, possibly the long way round.

    Parameters
    ----------
    M0, M1 : Multivector
        Unit motors (see :func:`motor_log` for the checks).
    s : float or array (N,)
        Fraction(s) of the way, finite; 0 gives M0, 1 gives M1, others extrapolate.

    Returns
    -------
    Multivector: one motor, or for an array s a batch (coefficients of shape
    (N,); ``.batch_item(i)`` is the i-th motor).

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> M1 = cga.motor([0, 0, 1], np.pi / 2, [0.0, 0.0, 2.0])
    >>> half_way = motor_interpolate(cga.G41.scalar(1.0), M1, 0.5)
    >>> cga.apply_to_points(half_way, [1.0, 0.0, 0.0]).round(6)  # 45 degrees up a helix
    array([0.707107, 0.707107, 1.      ])
    """
    M0 = unit_motor(M0, "motor_interpolate", "M0")
    M1 = unit_motor(M1, "motor_interpolate", "M1")
    frac = _check_fraction(s, "motor_interpolate")
    shortest = checks.flag(shortest, "motor_interpolate", "shortest")
    half, n, t, sn, _ = screw_of_motor(M1 * ~M0, exact=not shortest)
    return screw_power(half, n, t, sn, frac if frac.ndim else float(frac), "motor_interpolate: M1 ~M0:") * M0


def _check_order(n, func: str) -> int:
    if not isinstance(n, numbers.Integral):  # an int, not a float that happens to be whole
        raise checks.fail(func, "n", f"expected an integer >= 1, got {n!r}")
    return checks.integer(n, func, "n", low=1)


def versor_root(M: Multivector, n: int) -> Multivector:
    """Principal n-th root of a unit motor: X = exp(log(M)/n) with X^n == M.

    The log here is the versor's own (rotor half-angle in [0, pi], the
    analogue of the principal complex log), so that X^n is M itself, not -M;
    for M whose rotor part has a non-negative scalar it is :func:`motor_log`.
    X is the screw with the same axis, angle theta/n and slide t_par/n, built
    in closed form (module docstring; Dorst & Valkenburg 2011).  When the
    rotor part of M has a negative scalar, theta > pi and the root turns by
    more than pi/n: no root of the versor M divides the shorter motion (that
    is a root of -M; for odd n, ``-versor_root(-M, n)`` is one of M).  Near
    M = -T (theta -> 2 pi, t_perp != 0) the root's axis runs off to infinity;
    beyond a gain of 1e4 this raises :class:`DegenerateGeometryError`.  Within
    1e-12 of a full turn the rotor part is taken as -1 with the axis along t.

    Raises :class:`InvalidInputError` for bad M (see :func:`motor_log`) or an
    n that is not an integer >= 1.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> X = versor_root(cga.rotor([0, 0, 1], np.pi / 2), 3)
    >>> X
    0.965926 - 0.258819 e12
    >>> bool((X * X * X).isclose(cga.rotor([0, 0, 1], np.pi / 2)))
    True
    """
    M = unit_motor(M, "versor_root")
    n = _check_order(n, "versor_root")
    return M if n == 1 else _root(M, n, "versor_root")


def _root(M: Multivector, n: int, func: str) -> Multivector:
    half, axis, t, s, _ = screw_of_motor(M, exact=True)
    return screw_power(half, axis, t, s, 1.0 / n, f"{func}: M:")


def versor_sqrt(M: Multivector) -> Multivector:
    """Principal square root of a unit motor, ``(1 + M)/|1 + M|`` (X^2 == M).

    For a rotor ``(1 + R)/sqrt(2 (1 + <R>_0))`` is the rotor of half the
    angle.  For a motor ``(1 + M)~(1 + M) = 2 (1 + <M>_0) + 2 <M>_4`` has a
    null grade-4 part Q = <M>_4 (it contains e), which commutes with motors
    and squares to 0; so ``|1 + M|^-1 = (1 - Q / (2 a)) / sqrt(2 a)`` with
    ``a = 1 + <M>_0`` and ``sqrt(M) = (1 + M)(1 - Q/(2a)) / sqrt(2a)``
    (the polar decomposition of Dorst & Valkenburg 2011).  It is the root of
    :func:`versor_root` with n = 2.  When a < 1/2 (theta > 4 pi/3) the closed
    form loses digits and that route is taken instead; at M = -T it has no
    answer at all.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> versor_sqrt(cga.translator([2.0, 0.0, 0.0]))  # the translator by t/2
    1 - 0.5 e1+ - 0.5 e1-
    >>> X = versor_sqrt(cga.motor([1, 1, 0], 2.0, [0.5, -1.0, 3.0]))
    >>> bool((X * X).isclose(cga.motor([1, 1, 0], 2.0, [0.5, -1.0, 3.0])))
    True
    """
    M = unit_motor(M, "versor_sqrt")
    a = 1.0 + float(M.scalar())
    if a < 0.5:
        return _root(M, 2, "versor_sqrt")
    Q = M.grade(4)
    return ((1.0 + M) * (1.0 - Q * (0.5 / a))) * (1.0 / math.sqrt(2.0 * a))
