"""Versors of table 2.2 and rigid motions (sections 2.3.4-2.3.5, 2.4.6-2.4.7).

Conventions (checked by the tests):

* ``translator(t) = 1 + e t / 2`` (2.100) moves points by +t.
* ``rotor(axis, angle) = cos(angle/2) - sin(angle/2) n I_E`` (2.94-2.96),
  with n the unit axis, turns by +angle about n (right-hand rule).
* ``motor(axis, angle, t) = T R`` (2.102): rotate, then translate.
* ``apply(V, X) = V X^ V^-1`` with X^ the grade involution when V is odd
  (2.82); for unit even versors (rotors, translators, motors) this is the
  sandwich ``V X ~V`` (2.98, 2.101, 2.103).

Applying one versor to a batch builds the matrix of its action on each grade
once (a versor acts linearly on every grade) and multiplies, instead of
looping over the batch; a conformal point cloud costs one 5x5 product.
"""

from __future__ import annotations

import numpy as np

from .algebra import (
    DegenerateGeometryError,
    InvalidInputError,
    Multivector,
    _is_real_batch,
    _is_real_single,
    _is_sympy,
)
from .algebra import exp as _exp
from .model import G41, IE, E, _any_sym, _check_points, down, einf, euclidean, exact_constants, up, vector

__all__ = [
    "apply",
    "apply_to_points",
    "versor_matrix",
    "translator",
    "rotor",
    "rotor_about_line",
    "motor",
    "screw",
    "reflect_in_plane",
    "invert_in_sphere",
    "rotor_angle_axis",
    "decompose_motor",
    "motor_to_matrix",
    "matrix_to_motor",
]


def _consts(X: Multivector):
    return exact_constants() if _any_sym(X) else {"einf": einf, "E": E, "IE": IE}


# --------------------------------------------------------------- application
def _parity(V: Multivector) -> int:
    gs = {G41.grades[b] % 2 for b in V._c}
    if len(gs) != 1:
        raise InvalidInputError("apply: a versor is either even or odd (2.82); got mixed parity")
    return gs.pop()


def versor_matrix(V: Multivector, grade: int) -> np.ndarray:
    """Matrix of ``X -> apply(V, X)`` on the grade-``grade`` blades (order of 2.9).

    A versor acts linearly on each grade (its outermorphism), so a batch of N
    entities costs one (k, k) x (k, N) product with this matrix (k = 5 for
    points and spheres, 10 for lines and circles).  For a numeric versor it is
    built in closed form from one cached bilinear table
    (:meth:`~cga_lessons.algebra.Algebra.versor_matrices`); other numeric
    multivectors (V ~V not a scalar) use one sandwich per basis blade.
    """
    if not isinstance(grade, (int, np.integer)) or not 0 <= grade <= G41.n:
        raise InvalidInputError(f"versor_matrix: grade must be an integer in 0..{G41.n}, got {grade!r}")
    mats = G41.versor_matrices(V, (int(grade),))
    if mats is not None:
        return mats[int(grade)].copy()
    blades = G41.grade_blades[int(grade)]
    Vinv = V.inv()
    cols = []
    for b in blades:
        img = _apply_sandwich(V, Multivector(G41, {b: 1.0}), Vinv)
        cols.append([float(img._c.get(r, 0.0)) for r in blades])
    return np.array(cols).T


def _apply_sandwich(V: Multivector, X: Multivector, Vinv: Multivector | None = None) -> Multivector:
    odd = _parity(V)
    Xi = X.involute() if odd else X
    Vinv = V.inv() if Vinv is None else Vinv
    # A versor preserves grades (2.82); projecting drops round-off in others.
    return (V * Xi * Vinv).grade(*X.grades_present())


def apply(V: Multivector, X: Multivector) -> Multivector:
    """Apply a versor: ``V X^ V^-1`` (2.82); the sandwich ``V X ~V`` for motors (2.103).

    A single numeric versor takes the fast path by itself: its matrix on each
    grade present in X (:func:`versor_matrix`, built once and cached by
    value) times X's coefficients, one matrix product for a whole batch
    (array coefficients: N points, spheres, lines, ...).  The result has X's
    grades only, as the sandwich has up to round-off.  SymPy coefficients,
    batches of versors and general (non-versor) multivectors use the plain
    sandwich.
    """
    if not isinstance(V, Multivector) or not isinstance(X, Multivector):
        raise InvalidInputError("apply: V and X must be Multivectors")
    if not V._c:
        raise DegenerateGeometryError("apply: the zero multivector is not a versor")
    if X._c and V.algebra is X.algebra and (_is_real_single(X) or _is_real_batch(X)):
        mats = V.algebra.versor_matrices(V, X.grades_present())
        if mats is not None:
            return V.algebra.apply_matrices(mats, X)
    return _apply_sandwich(V, X)


def motor_to_matrix(M: Multivector) -> np.ndarray:
    """The 4x4 homogeneous matrix [[R, t], [0, 1]] of a motor (numeric)."""
    R, t = decompose_motor(M)
    Rm = np.column_stack([euclidean(_apply_sandwich(R, vector(col))) for col in np.eye(3)])
    H = np.eye(4)
    H[:3, :3] = Rm
    H[:3, 3] = t
    return H


def apply_to_points(V: Multivector, x) -> np.ndarray:
    """Euclidean points moved by a motor (or any versor mapping points to points).

    ``x`` has shape (3,) or (N, 3).  For a rigid motion this is the 3x4 affine
    product ``y = R x + t`` read off the versor's 5x5 matrix (a motor keeps
    X . e = -1), the cost of a plain homogeneous matrix.  Other versors
    (inversions, dilations) and SymPy input go through the conformal point and
    :func:`~cga_lessons.model.down`.
    """
    arr, sym = _check_points(x, "apply_to_points")
    if sym or _any_sym(V):
        return down(apply(V, up(arr)))
    affine = _rigid_affine(V)
    if affine is None:
        return down(apply(V, up(arr)))
    R, t = affine
    if arr.ndim == 1:
        return R @ arr + t
    # (R x^T + t)^T: the sum runs along the long axis (adding t row by row to an (N, 3) array is several
    # times slower than the product itself); the result is the transposed view of a (3, N) block.
    out = R @ arr.T
    out += t[:, None]
    return out.T


_AFFINE_CACHE: dict = {}


def _rigid_affine(V: Multivector):
    """``(R, t)`` of a numeric versor acting on points as a rigid motion, else None.

    With A the 5x5 matrix on e1 e2 e3 e+ e-, the Euclidean part of V up(x) is
    A[:3,:3] x + A[:3,3] (x^2-1)/2 + A[:3,4] (x^2+1)/2 with weight row
    A[4]-A[3].  For a rigid motion the x^2 terms cancel and the weight stays
    that of up(x), so the map is y = R x + t with R = A[:3,:3] and
    t = (A[:3,4] - A[:3,3]) / 2.  Cached by the versor's coefficients.
    """
    if not _is_real_single(V):
        return None
    key = (tuple(V._c), tuple(V._c.values()))
    hit = _AFFINE_CACHE.get(key, False)
    if hit is not False:
        return hit
    mats = G41.versor_matrices(V, (1,))
    hit = None
    if mats is not None:
        A = mats[1]
        scale = max(1.0, float(np.abs(A).max()))
        w = A[4] - A[3]
        w[3] += 1.0
        w[4] -= 1.0
        if max(float(np.abs(A[:3, 3] + A[:3, 4]).max()), float(np.abs(w).max())) <= 1e-12 * scale:
            R, t = np.ascontiguousarray(A[:3, :3]), 0.5 * (A[:3, 4] - A[:3, 3])
            R.flags.writeable = t.flags.writeable = False
            hit = (R, t)
    if len(_AFFINE_CACHE) >= 256:
        _AFFINE_CACHE.clear()
    _AFFINE_CACHE[key] = hit
    return hit


# ------------------------------------------------------------- constructors
def translator(t) -> Multivector:
    """Translator T = 1 + e t / 2 = exp(e t / 2), Eq. (2.100); moves by +t.

    ``t`` has shape (3,) or (N, 3) (a batch of translators) or is symbolic.
    """
    tv = vector(t, "translator", "t")
    c = _consts(tv)
    half = 0.5 if not _any_sym(tv) else exact_constants()["eo"]["e-"]  # 1/2, exact when symbolic
    return (c["einf"] * tv) * half + 1


def _unit_axis(axis, func: str):
    arr, sym = _check_points(axis, func, "axis")
    if sym:
        import sympy

        n = sympy.sqrt(sum(a**2 for a in arr))
        return [sympy.simplify(a / n) for a in arr], True
    norm = np.linalg.norm(arr, axis=-1)
    if np.any(norm <= 1e-300):
        raise DegenerateGeometryError(f"{func}: the rotation axis is the zero vector")
    return arr / (norm[..., None] if arr.ndim == 2 else norm), False


def rotor(axis, angle) -> Multivector:
    """Rotor R = exp(-angle/2 l) = cos(angle/2) - sin(angle/2) l, Eqs. (2.94)-(2.96).

    ``l = n I_E`` is the unit bivector of the plane orthogonal to the axis n
    (so ``l = n1 e23 + n2 e31 + n3 e12``, 2.96).  Turns by +angle about n
    (right-hand rule).  ``axis`` (3,) or (N, 3); ``angle`` scalar or (N,).
    """
    n, sym = _unit_axis(axis, "rotor")
    if sym or _is_sympy(angle):
        import sympy

        c = exact_constants()
        l = vector(n) * c["IE"]
        return l * (-sympy.sin(angle / 2)) + sympy.cos(angle / 2)
    ang = np.asarray(angle, dtype=float)
    if not np.all(np.isfinite(ang)):
        raise InvalidInputError("rotor: angle contains NaN or inf")
    l = vector(n) * IE
    ang = float(ang) if ang.ndim == 0 else ang
    return l * (-np.sin(ang / 2)) + np.cos(ang / 2)


def rotor_about_line(L: Multivector, angle) -> Multivector:
    """Rotation about an arbitrary line, R_L = exp(-angle/2 L), Eqs. (2.106)-(2.109).

    ``L`` is a line in dual form (grade 3, ``line_from_points(a, b)``) or
    standard form (grade 2); it is normalised (2.126).  The rotation is by
    +angle about the line's direction (from a to b), right-hand rule.
    Equal to ``T R ~T`` of (2.104) with T moving the origin onto the line.
    """
    from .entities import _as_dual_line, normalize_line, standard_form

    Ln = normalize_line(_as_dual_line(L, "rotor_about_line"))
    Lstd = standard_form(Ln)
    # The standard form L = L* Ic of the unit line is l + e (t . l) of (2.108).
    B = Lstd * (-angle / 2)
    return _exp(B)


def motor(rotation_axis, angle, translation) -> Multivector:
    """Motor M = T R, Eq. (2.102): rotation by +angle about the axis through
    the origin (right-hand rule), then translation.
    """
    return translator(translation) * rotor(rotation_axis, angle)


def screw(axis, point, angle, distance) -> Multivector:
    """Screw motion M = exp(-angle/2 (l + e m)), Eq. (2.110).

    Rotation by +angle about the line through ``point`` with direction
    ``axis``, combined with a translation ``distance`` along the axis; built
    from the exponential of the screw bivector with
    ``m = t . l - (distance/angle) r`` (2.110).  Equal to ``T_dr R_L``.
    ``angle`` must be non-zero (a pure translation is :func:`translator`).
    """
    n, sym = _unit_axis(axis, "screw")
    if not sym and not _is_sympy(angle) and abs(float(angle)) < 1e-300:
        raise DegenerateGeometryError("screw: angle is 0; a pure slide is a translator")
    c = exact_constants() if (sym or _is_sympy(angle)) else {"einf": einf, "IE": IE}
    r = vector(n)
    t = vector(point, "screw", "point")
    l = r * c["IE"]
    m = (t | l) - r * (distance / angle)
    return _exp((l + c["einf"] * m) * (-angle / 2))


def reflect_in_plane(P: Multivector, X: Multivector) -> Multivector:
    """Reflection of any entity X in a plane P = n + delta e, Eqs. (2.84), (2.89)-(2.91).

    ``-P X P^-1`` for a vector X (2.84); an entity of any grade via the
    grade involution (2.82).  P in standard (grade 1) or dual (grade 4) form.
    """
    from .entities import _grade_of, standard_form

    g = _grade_of(P, "reflect_in_plane", (1, 4))
    Pv = P if g == 1 else standard_form(P)
    if not _any_sym(Pv) and np.max(np.abs(np.asarray((Pv | einf).scalar(), dtype=float))) > 1e-12:
        raise InvalidInputError("reflect_in_plane: P . e != 0, P is a sphere (use invert_in_sphere)")
    return apply(Pv, X)


def invert_in_sphere(S: Multivector, X: Multivector) -> Multivector:
    """Inversion in a sphere, -s x s^-1 = sigma x', Eqs. (2.84)-(2.88).

    Returns the image entity; for a conformal point it is scaled by sigma
    (2.87), so use :func:`~cga_lessons.model.down` for its Euclidean point,
    ``g(x) = rho^2 (x - p)/|x - p|^2 + p`` (2.88).  S in standard or dual form.
    """
    from .entities import _grade_of, standard_form

    g = _grade_of(S, "invert_in_sphere", (1, 4))
    s = S if g == 1 else standard_form(S)
    return apply(s, X)


# ------------------------------------------------------------- decomposition
def rotor_angle_axis(R: Multivector):
    """Angle and axis of a rotor, Eqs. (2.135)-(2.138).

    ``c = (R + ~R)/2 = cos(angle/2)`` (2.135), ``angle = 2 acos(c)`` (2.136),
    the bivector ``(R - ~R)/2`` (2.137) gives the axis.  A rotation about a
    line off the origin (R_L) is first brought to the origin with
    ``(R ^ E) E`` (2.138).  The angle is returned in [0, pi] with the axis
    oriented to match (computed with atan2 for accuracy near 0 and pi).

    Returns
    -------
    angle : float
    axis : array (3,), unit (e3 by convention when the angle is 0)
    """
    if _any_sym(R):
        raise InvalidInputError("rotor_angle_axis: numeric rotors only (the angle is defined up to sign)")
    if R.shape:
        raise InvalidInputError("rotor_angle_axis: one rotor at a time")
    R0 = ((R ^ E) * E).grade(0, 2)  # (2.138): drop the e-parts of a general rotation
    c = float(R0.scalar())  # (2.135)
    B = ((R0 - ~R0) * 0.5).grade(2)  # (2.137): -sin(angle/2) n I_E
    # n I_E = B / (-sin); n = -(B I_E^-1)/sin = (B I_E)/sin since I_E^-1 = -I_E
    v = euclidean(B * IE)
    s = float(np.linalg.norm(v))
    angle = 2.0 * np.arctan2(s, c)  # (2.136) via atan2
    if s < 1e-15:
        return (0.0 if c > 0 else 2 * np.pi), np.array([0.0, 0.0, 1.0])
    axis = v / s
    if angle > np.pi:
        angle, axis = 2 * np.pi - angle, -axis
    return float(angle), axis


def decompose_motor(M: Multivector):
    """Rotor and translation of a motor M = T R, Eqs. (2.140)-(2.145).

    ``R = (M ^ E) E`` (2.141), ``R' = (e- . M) I_E`` (2.142) and
    ``t = 2 R' I_E ~R`` (2.144).  Works for numeric, batched and SymPy motors.

    Returns
    -------
    R : Multivector, the rotor part (axis through the origin)
    t : array (3,) or (N, 3) (a 3x1 SymPy matrix when symbolic)
    """
    c = exact_constants() if _any_sym(M) else {"E": E, "IE": IE, "em": G41.blade("e-")}
    bad = [G41.blade_names[b] for b in M._c if G41.grades[b] % 2]
    if bad:
        raise InvalidInputError(f"decompose_motor: a motor is even; got odd blades {bad}")
    R = ((M ^ c["E"]) * c["E"]).grade(0, 2)  # (2.141)
    Rp = (c["em"] | M) * c["IE"]  # (2.142)
    tv = (Rp * c["IE"] * ~R) * 2  # (2.144)
    if _any_sym(M):
        tv = tv.simplify()
    t = euclidean(tv)
    return R, t


def matrix_to_motor(H) -> Multivector:
    """Motor of a 4x4 homogeneous rigid transform [[R, t], [0, 1]] (numeric)."""
    H = np.asarray(H, dtype=float)
    if H.shape != (4, 4) or not np.all(np.isfinite(H)):
        raise InvalidInputError(f"matrix_to_motor: H must be a finite 4x4 matrix, got shape {H.shape}")
    Rm = H[:3, :3]
    if not np.allclose(Rm @ Rm.T, np.eye(3), atol=1e-9) or np.linalg.det(Rm) < 0:
        raise InvalidInputError("matrix_to_motor: the 3x3 block is not a rotation")
    # axis-angle from the rotation matrix (robust via the skew part and trace)
    angle = float(np.arccos(np.clip((np.trace(Rm) - 1) / 2, -1.0, 1.0)))
    if angle < 1e-12:
        axis = np.array([0.0, 0.0, 1.0])
    elif np.pi - angle < 1e-6:
        # near pi: axis from the largest column of (R + I)/2
        S = (Rm + np.eye(3)) / 2
        k = int(np.argmax(np.diag(S)))
        axis = S[:, k] / np.sqrt(S[k, k])
    else:
        axis = np.array([Rm[2, 1] - Rm[1, 2], Rm[0, 2] - Rm[2, 0], Rm[1, 0] - Rm[0, 1]]) / (2 * np.sin(angle))
    return motor(axis, angle, H[:3, 3])
