"""Motors as rigid motions: their parts and their 4x4 matrices (sections 2.4.6-2.4.7).

(Re-exported by :mod:`cga_lessons.conformal.versors` and :mod:`cga_lessons.conformal`, the modules to import.)

* :func:`decompose_motor`: ``M = T R`` into the rotor R and the translation t, Eqs. (2.140)-(2.144).
* :func:`rotor_angle_axis`: angle and axis of the rotation of a rotor or motor, Eqs. (2.135)-(2.138).
* :func:`motor_to_matrix` and :func:`matrix_to_motor`: a motor and its homogeneous matrix
  ``[[R, t], [0, 0, 0, 1]]``.

Conventions (pinned by the tests):

* A motor is an even versor commuting with the point at infinity e, ``M = R + e n`` (2.140, 2.143); a
  multiple ``s M`` (s != 0) is a versor of the same motion, ``X -> (s M) X (s M)^-1 = M X M^-1``, so every
  function here gives it the same rotation and translation as M (the translation of (2.144) is divided
  by ``R ~R``; the rotor part R keeps the factor s, so that ``M = T R`` holds as written).
* The numeric parts are those of :meth:`~cga_lessons.algebra.Algebra.rigid_motion`: read linearly off the
  coefficients, exact to round-off at any distance, with its tolerance for "is a motor".
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector, motor_tolerance

from .model import CONSTANTS, G41, IE, E, exact_constants
from .multivector_checks import multivector
from .points import euclidean

__all__ = [
    "decompose_motor",
    "rotor_angle_axis",
    "motor_to_matrix",
    "matrix_to_motor",
    "why_not_motor",
    "RIGID_MATRIX_TOLERANCE",
]

#: ``matrix_to_motor`` accepts ``[[R, t], [0, 0, 0, 1]]`` when ``max |R^T R - I|`` and the deviation of the
#: last row from (0, 0, 0, 1) are within this, and det R > 0.
RIGID_MATRIX_TOLERANCE = 1e-9

_ROTOR = (0, 3, 5, 6)  # 1 e12 e13 e23
_PLUS, _MINUS, _EE = (9, 10, 12, 15), (17, 18, 20, 23), (24, 27, 29, 30)  # e_i+, e_i-, E-blades (bitmaps)


def _is_symbolic(M: Multivector) -> bool:
    return any(hasattr(v, "free_symbols") and not isinstance(v, np.ndarray) for v in M.coeffs.values())


def _check_mv(M, func: str, name: str) -> Multivector:
    return multivector(M, func, name, what="a motor (Multivector of G(4,1))")


def why_not_motor(M: Multivector) -> str:
    """Why a numeric M (single or batch) is not a motor, or '' when it is one (the test of ``rigid_motion``).

    Raises :class:`~cga_lessons.algebra.InvalidInputError` when M is no multivector of G(4,1), or has SymPy
    coefficients (the test is numeric).
    """
    M = multivector(M, "why_not_motor", "M", numeric=True, nonzero=False, finite=False)
    if not M.coeffs:
        return "is the zero multivector (R ~R = 0)"
    odd = [G41.blade_names[b] for b in M.coeffs if G41.grades[b] % 2]
    if odd:
        return f"not an even versor (a rotor or motor is even, 2.94, 2.102); it has odd blades {odd}"
    c = {b: np.asarray(v, dtype=float) for b, v in M.coeffs.items()}
    zero = np.zeros(M.shape)

    def get(b):
        return c.get(b, zero)

    if not all(np.all(np.isfinite(v)) for v in c.values()):
        return "contains NaN or inf"
    vmax = np.maximum.reduce([np.abs(v) for v in c.values()])
    rn = np.sqrt(sum(get(b) ** 2 for b in _ROTOR))
    if np.any(rn == 0):
        return "has no rotor part (the scalar and e12, e13, e23 are zero, R ~R = 0)"
    n = [-get(b) for b in _MINUS]
    nn = np.sqrt(sum(v**2 for v in n))
    q0, q12, q13, q23 = (get(b) / rn for b in _ROTOR)
    tri = n[3] * q0 - n[0] * q23 + n[1] * q13 - n[2] * q12
    tol = motor_tolerance(vmax, nn, rn)
    # As rigid_motion weighs them: the parts that move e (e+ != e-) or scale it (an E part: a dilation) against the
    # rotor's norm, which does not grow with the translation (a similarity T_t D_s far out has an E part of rho |R|,
    # a small fraction of its largest coefficient); the trivector against the largest coefficient.
    rotor_tol = tol * rn / vmax
    checks = [
        (np.maximum.reduce([np.abs(get(p) - get(m)) for p, m in zip(_PLUS, _MINUS)]), "its e+ and e- parts differ",
         rotor_tol, rn, "its rotor's norm"),
        (np.maximum.reduce([np.abs(get(b)) for b in _EE]), "it has an E = e+e- part", rotor_tol, rn,
         "its rotor's norm"),
        (np.abs(tri), "<n ~R>_3 != 0, M ~M is not a scalar (2.145)", tol, vmax, "its largest coefficient"),
    ]  # fmt: skip
    for dev, what, bound, size, of in checks:
        if np.any(dev > bound):
            worst = float(np.max(dev / np.maximum(size, 1e-300)))
            hint = ""
            if float(np.max(nn / rn)) > 300:
                hint = (
                    "; a product of motors far from the origin loses ~eps |t|^2 to its e+/e- terms, and a "
                    "dilation (a similarity) has an E part at any distance"
                )
            return f"not a motor: it does not commute with e ({what}, {worst:.1e} of {of}{hint})"
    return ""


def _require_motor(M: Multivector, func: str, name: str) -> None:
    why = why_not_motor(M)
    if why:
        err = DegenerateGeometryError if "no rotor part" in why else InvalidInputError
        raise err(f"{func}: {name}: {why}")


# ------------------------------------------------------------- decomposition
def decompose_motor(M: Multivector):
    """Rotor and translation of a motor M = T R, Eqs. (2.140)-(2.145).

    ``R = (M ^ E) E`` (2.141), ``R' = (e- . M) I_E`` (2.142) and
    ``t = 2 R' I_E ~R`` (2.144), divided by ``R ~R`` for numeric M so that a
    scaled motor ``s M`` (the same motion) gives the same t; R keeps the
    factor s, so ``M = translator(t) * R``.  t is linear in the e-
    coefficients: exact to round-off at any distance.  Works for numeric,
    batched and SymPy motors; a SymPy motor is taken as unit (M ~M = 1, 2.145),
    as in the thesis.

    Raises :class:`InvalidInputError` when M is not a motor (odd blades, or
    not commuting with e beyond round-off; see
    :meth:`~cga_lessons.algebra.Algebra.rigid_motion`).

    Returns
    -------
    R : Multivector, the rotor part (axis through the origin)
    t : array (3,) or (N, 3) (a 3x1 SymPy matrix when symbolic)
    """
    func = "decompose_motor"
    M = _check_mv(M, func, "M")
    sym = _is_symbolic(M)
    c = exact_constants() if sym else CONSTANTS
    if sym:
        odd = [G41.blade_names[b] for b in M.coeffs if G41.grades[b] % 2]
        if odd:
            raise InvalidInputError(f"{func}: M: not an even versor (a motor is even, 2.102); it has odd blades {odd}")
    else:
        _require_motor(M, func, "M")
    R = ((M ^ c.E) * c.E).grade(0, 2)  # (2.141)
    Rp = (c.em | M) * c.IE  # (2.142)
    tv = (Rp * c.IE * ~R) * 2  # (2.144)
    if sym:
        return R, euclidean(tv.simplify())
    rigid = None if M.shape else G41.rigid_motion(M)
    if rigid is not None:
        return R, np.array(rigid[1])  # the same formula, written out (cached)
    return R, euclidean(tv) / np.asarray((R * ~R).scalar(), dtype=float)[..., None]


def rotor_angle_axis(R: Multivector):
    """Angle and axis of the rotation of a rotor (or of a motor's rotor part), Eqs. (2.135)-(2.138).

    ``c = (R + ~R)/2 = cos(angle/2)`` (2.135), ``angle = 2 acos(c)`` (2.136),
    the bivector ``(R - ~R)/2 = -sin(angle/2) n I_E`` (2.137) gives the axis.
    A rotation about a line off the origin (R_L), or a motor, is first
    brought to the origin with ``(R ^ E) E`` (2.138).

    Conventions: the angle is in [0, pi], computed with atan2 for accuracy
    near 0 and pi.  R and -R are the same rotation (2.136 alone would give
    angles in [0, 2 pi]); a rotor with c < 0 is read as -R, i.e. the angle
    ``2 pi - angle`` about the reversed axis, so ``rotor(n, 2 pi) = -1`` gives
    angle 0.  When the angle is 0 (below ~2e-15) the axis is e3 by convention;
    at pi both n and -n are right, the one of R's bivector is returned.

    Raises :class:`InvalidInputError` for SymPy or batched input and for what
    is not a rotor or motor (odd blades, e.g. a vector; parts that do not
    commute with e); :class:`DegenerateGeometryError` without rotor part.

    Returns
    -------
    angle : float
    axis : array (3,), unit
    """
    func = "rotor_angle_axis"
    R = _check_mv(R, func, "R")
    if _is_symbolic(R):
        raise InvalidInputError(f"{func}: R: numeric rotors only (the angle is defined up to sign)")
    if R.shape:
        raise InvalidInputError(f"{func}: R: one rotor at a time")
    _require_motor(R, func, "R")
    R0 = ((R ^ E) * E).grade(0, 2)  # (2.138): drop the e-parts of a general rotation
    c = float(R0.scalar())  # (2.135)
    B = ((R0 - ~R0) * 0.5).grade(2)  # (2.137): -sin(angle/2) n I_E
    v = euclidean(B * IE)  # n I_E = B / (-sin) and I_E^-1 = -I_E, so B I_E = sin(angle/2) n
    s = float(np.linalg.norm(v))
    if s <= 1e-15 * math.hypot(c, s):
        return 0.0, np.array([0.0, 0.0, 1.0])
    angle = 2.0 * math.atan2(s, abs(c))  # (2.136), folded to [0, pi]: R and -R are the same rotation
    axis = v / s if c >= 0 else -v / s
    return float(angle), axis


# ------------------------------------------------------------------ matrices
def motor_to_matrix(M: Multivector) -> np.ndarray:
    """The 4x4 homogeneous matrix [[R, t], [0, 0, 0, 1]] of a motor (numeric, one at a time).

    R is the rotation matrix of the rotor part normalised by its own norm
    (2.141) and t the translation of (2.144), both read linearly off the
    coefficients (:meth:`~cga_lessons.algebra.Algebra.rigid_motion`): exact to
    round-off at any distance.  A scaled motor ``s M`` gives the same matrix
    (the same motion ``X -> M X M^-1``).
    """
    func = "motor_to_matrix"
    M = _check_mv(M, func, "M")
    if _is_symbolic(M) or M.shape:
        raise InvalidInputError(f"{func}: M: one numeric motor at a time")
    rigid = G41.rigid_motion(M)
    if rigid is None:
        _require_motor(M, func, "M")
        raise InvalidInputError(f"{func}: M: its translation 2 <n ~R>_1 / (R ~R) (2.144) is not finite")
    H = np.eye(4)
    H[:3, :3], H[:3, 3] = rigid
    return H


def _quaternion(Rm: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z), w >= 0, of a rotation matrix: Shepperd's method, as in Markley (2008).

    Of the four expressions of the quaternion scaled by one of its components, the one of the largest
    component (from the largest of trace, R00, R11, R22) is taken: no square root of a small difference,
    so it is accurate at every angle, near pi too.
    """
    (a, b, c), (d, e, f), (g, h, i) = Rm.tolist()
    tr = a + e + i
    k = int(np.argmax([tr, a, e, i]))
    if k == 0:
        q = [1.0 + tr, h - f, c - g, d - b]
    elif k == 1:
        q = [h - f, 1.0 + a - e - i, b + d, c + g]
    elif k == 2:
        q = [c - g, b + d, 1.0 - a + e - i, f + h]
    else:
        q = [d - b, c + g, f + h, 1.0 - a - e + i]
    q = np.array(q) / math.hypot(*q)
    return -q if q[0] < 0 else q


def matrix_to_motor(H) -> Multivector:
    """Motor ``M = T R`` (2.102) of a 4x4 homogeneous rigid transform [[R, t], [0, 0, 0, 1]] (numeric).

    The rotor is that of the quaternion of R (Shepperd's method,
    accurate at all angles including near pi): ``R = w - x e23 - y e31 - z e12``
    for ``q = (w, x, y, z)`` (2.96), with w >= 0; t enters through
    ``T = 1 + e t / 2`` (2.100), the product written out.

    Raises :class:`InvalidInputError` unless H is a finite 4x4 real matrix (shape (4, 4))
    whose last row is (0, 0, 0, 1) and whose block R is a rotation
    (``max |R^T R - I|`` and the last row within ``RIGID_MATRIX_TOLERANCE``,
    det R > 0): a reflection, a scaling or a shear has no motor.
    """
    func = "matrix_to_motor"
    tol = RIGID_MATRIX_TOLERANCE
    arr = checks.array(H, func, "H", (4, 4))
    bottom = float(np.max(np.abs(arr[3] - [0.0, 0.0, 0.0, 1.0])))
    if bottom > tol:
        raise InvalidInputError(f"{func}: H: the last row must be (0, 0, 0, 1), got {arr[3].tolist()}")
    Rm = arr[:3, :3]
    ortho = float(np.max(np.abs(Rm.T @ Rm - np.eye(3))))
    if ortho > tol:
        raise InvalidInputError(
            f"{func}: H: the 3x3 block is not a rotation: max |R^T R - I| = {ortho:.1e} > {tol:g} "
            "(a scaling or shear; re-orthonormalise it, e.g. by SVD, if it is a rotation with noise)"
        )
    if np.linalg.det(Rm) <= 0:
        raise InvalidInputError(f"{func}: H: the 3x3 block is a reflection (det R < 0), not a rotation")
    w, x, y, z = _quaternion(Rm)
    r0, r12, r13, r23 = w, -z, y, -x  # R = w - x e23 - y e31 - z e12, e31 = -e13
    tx, ty, tz = arr[:3, 3].tolist()
    e = {  # T R = R + e t R / 2 (2.140): the e_i+ and e_i- coefficients, equal
        1: -(r0 * tx - r12 * ty - r13 * tz) / 2,
        2: -(r0 * ty + r12 * tx - r23 * tz) / 2,
        4: -(r0 * tz + r13 * tx + r23 * ty) / 2,
        7: -(r12 * tz - r13 * ty + r23 * tx) / 2,
    }
    coeffs = {0: r0, 3: r12, 5: r13, 6: r23}
    for b, v in e.items():
        coeffs[b | 8] = coeffs[b | 16] = v
    return Multivector(G41, {b: float(v) for b, v in coeffs.items() if v != 0})
