"""Versors of table 2.2 and rigid motions (sections 2.3.4-2.3.5, 2.4.6-2.4.7).

Conventions (checked by the tests):

* ``translator(t) = 1 + e t / 2`` (2.100) moves points by +t.
* ``rotor(axis, angle) = cos(angle/2) - sin(angle/2) n I_E`` (2.94-2.96),
  with n the unit axis, turns by +angle about n (right-hand rule).
* ``motor(axis, angle, t) = T R`` (2.102): rotate, then translate.
* ``apply(V, X) = V X^ V^-1`` with X^ the grade involution when V is odd
  (2.82); for unit even versors (rotors, translators, motors) this is the
  sandwich ``V X ~V`` (2.98, 2.101, 2.103).
* A multiple ``s M`` (s != 0) of a motor is a versor of the same motion,
  ``(s M) X (s M)^-1 = M X M^-1``: :func:`apply`, :func:`apply_to_points`,
  :func:`motor_to_matrix` and :func:`decompose_motor`'s t give it M's motion
  (only ``V >> X = V X ~V`` scales, by s^2).
* Angles and distances are finite real numbers (or SymPy expressions); a
  NaN, inf, complex, bool, string or None raises
  :class:`~cga_lessons.algebra.InvalidInputError` naming the function the
  caller called and the argument, ``"motor: angle: ..."``.

Applying one versor to a batch builds the matrix of its action on each grade
once (a versor acts linearly on every grade) and multiplies, instead of
looping over the batch; a conformal point cloud costs one 5x5 product.  A
motor's matrices are built in closed form from its rotation and translation
(:meth:`~cga_lessons.algebra.Algebra.rigid_motion`), so that points far from
the origin keep their precision (see :mod:`cga_lessons.algebra.versor_matrices`).

The rigid-motion conversions (:func:`decompose_motor`, :func:`rotor_angle_axis`,
:func:`motor_to_matrix`, :func:`matrix_to_motor`) live in
:mod:`cga_lessons.conformal.versors_rigid` and are re-exported here.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons.algebra import (
    DegenerateGeometryError,
    InvalidInputError,
    Multivector,
    any_sympy,
    is_real_batch,
    is_real_single,
    is_sympy,
)
from cga_lessons.algebra import exp as _exp

from .model import G41, IE, E, check_points, down, einf, exact_constants, up, vector
from .versors_rigid import decompose_motor, matrix_to_motor, motor_to_matrix, rotor_angle_axis

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
    return exact_constants() if any_sympy(X) else {"einf": einf, "E": E, "IE": IE}


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
    if X._c and V.algebra is X.algebra and (is_real_single(X) or is_real_batch(X)):
        mats = V.algebra.versor_matrices(V, X.grades_present())
        if mats is not None:
            return V.algebra.apply_matrices(mats, X)
    return _apply_sandwich(V, X)


def apply_to_points(V: Multivector, x) -> np.ndarray:
    """Euclidean points moved by a motor (or any versor mapping points to points).

    ``x`` has shape (3,) or (N, 3).  For a motor this is ``y = R x + t`` with
    R and t read linearly off its coefficients
    (:meth:`~cga_lessons.algebra.Algebra.rigid_motion`, 2.141-2.144): exact to
    round-off at any distance, at the cost of a plain homogeneous matrix.  A
    reflection in a plane uses the 3x4 affine part of its 5x5 matrix.  Other
    versors (inversions, dilations) and SymPy input go through the conformal
    point and :func:`~cga_lessons.conformal.model.down`.
    """
    arr, sym = check_points(x, "apply_to_points")
    if not isinstance(V, Multivector):
        raise InvalidInputError(f"apply_to_points: V: expected a versor (Multivector), got {type(V).__name__}")
    if sym or any_sympy(V):
        return down(apply(V, up(arr)))
    affine = G41.rigid_motion(V) if V.algebra is G41 else None
    if affine is None:
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
    """``(R, t)`` of a numeric versor (not a motor: a reflection) acting on points as an isometry, else None.

    With A the 5x5 matrix on e1 e2 e3 e+ e-, the Euclidean part of V up(x) is
    A[:3,:3] x + A[:3,3] (x^2-1)/2 + A[:3,4] (x^2+1)/2 with weight row
    A[4]-A[3].  For a rigid motion the x^2 terms cancel and the weight stays
    that of up(x), so the map is y = R x + t with R = A[:3,:3] and
    t = (A[:3,4] - A[:3,3]) / 2.  Cached by the versor's coefficients.
    """
    if not is_real_single(V):
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
def _real(x, func: str, name: str, *, array: bool = False):
    """A finite real angle or distance: a float (a float array when ``array``), or a SymPy expression.

    Refuses bools, strings, None, complex numbers, NaN and inf (a SymPy
    expression known to be non-real or infinite too) with "func: name: problem".
    """
    if is_sympy(x):
        if x.is_real is False or x.is_finite is False or x.has(_sympy_nan()):
            raise InvalidInputError(f"{func}: {name}: must be a finite real number, got {_short(x)}")
        return x
    if isinstance(x, (bool, np.bool_)):
        raise InvalidInputError(f"{func}: {name}: must be a real number, got the bool {x!r}")
    if isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "iuf":
        x = x[()]  # a 0-d array: its number
    if isinstance(x, numbers.Real):
        try:
            v = float(x)
        except OverflowError:
            v = math.inf
        if not math.isfinite(v):
            raise InvalidInputError(f"{func}: {name}: is NaN or inf ({_short(x)})")
        return v
    if array and isinstance(x, (np.ndarray, list, tuple)):
        a = np.asarray(x) if not isinstance(x, np.ndarray) else x
        if a.dtype.kind in "iuf" and a.ndim:
            a = a.astype(float)
            if not np.all(np.isfinite(a)):
                raise InvalidInputError(f"{func}: {name}: contains NaN or inf")
            return a
    what = "a real number or an array of them" if array else "a real number"
    raise InvalidInputError(f"{func}: {name}: must be {what}, got {_short(x)} ({type(x).__name__})")


def _short(x) -> str:
    r = repr(x)
    return r if len(r) <= 40 else r[:37] + "..."


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
    half = 0.5 if not any_sympy(tv) else exact_constants()["eo"]["e-"]  # 1/2, exact when symbolic
    return (c["einf"] * tv) * half + 1


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
                raise InvalidInputError(f"{func}: {name}: one axis (shape (3,)) with a SymPy angle, got {arr.shape}")
            arr = [_exact(a) for a in arr]
        n = sympy.sqrt(sum(a**2 for a in arr))
        if n == 0:
            raise DegenerateGeometryError(f"{func}: {name}: the rotation axis is the zero vector")
        return [sympy.simplify(a / n) for a in arr], True
    big = np.max(np.abs(arr), axis=-1, keepdims=True)
    if np.any(big == 0):
        raise DegenerateGeometryError(f"{func}: {name}: the rotation axis is the zero vector")
    arr = arr / big
    return arr / np.linalg.norm(arr, axis=-1, keepdims=True), False


def _rotor(axis, angle, func: str, axis_name: str) -> Multivector:
    angle = _real(angle, func, "angle", array=True)
    exact = is_sympy(angle)
    n, sym = _unit_axis(axis, func, axis_name, exact=exact)
    if sym:
        import sympy

        l = vector(n) * exact_constants()["IE"]
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
    from .entities import as_dual_line, normalize_line, standard_form

    angle = _real(angle, "rotor_about_line", "angle", array=True)
    Ln = normalize_line(as_dual_line(L, "rotor_about_line"))
    Lstd = standard_form(Ln)
    # The standard form L = L* Ic of the unit line is l + e (t . l) of (2.108).
    B = Lstd * (-angle / 2)
    return _exp(B)


def motor(rotation_axis, angle, translation) -> Multivector:
    """Motor M = T R, Eq. (2.102): rotation by +angle about the axis through
    the origin (right-hand rule), then translation.
    """
    return _translator(translation, "motor", "translation") * _rotor(rotation_axis, angle, "motor", "rotation_axis")


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
    angle = _real(angle, func, "angle")
    distance = _real(distance, func, "distance")
    pt, psym = check_points(point, func, "point")
    exact = is_sympy(angle) or is_sympy(distance) or psym
    if angle == 0:
        raise DegenerateGeometryError("screw: angle: is 0; a pure slide is a translator")
    n, sym = _unit_axis(axis, func, "axis", exact=exact)
    if sym:  # T_dr T_p R ~T_p, exact
        if not psym:
            if pt.ndim != 1:
                raise InvalidInputError(f"{func}: point: one point (shape (3,)) when symbolic, got {pt.shape}")
            pt = [_exact(a) for a in pt]
        Tp = _translator(pt, func, "point")
        Td = _translator([a * distance for a in n], func, "distance")
        return Td * Tp * _rotor(n, angle, func, "axis") * ~Tp
    r = vector(n)
    l = r * IE
    m = (vector(pt, func, "point") | l) - r * (distance / angle)  # (2.110)
    return _exp((l + einf * m) * (-angle / 2))


def reflect_in_plane(P: Multivector, X: Multivector) -> Multivector:
    """Reflection of any entity X in a plane P = n + delta e, Eqs. (2.84), (2.89)-(2.91).

    ``-P X P^-1`` for a vector X (2.84); an entity of any grade via the
    grade involution (2.82).  P in standard (grade 1) or dual (grade 4) form.
    """
    from .entities import grade_of, standard_form

    g = grade_of(P, "reflect_in_plane", (1, 4))
    Pv = P if g == 1 else standard_form(P)
    if not any_sympy(Pv) and np.max(np.abs(np.asarray((Pv | einf).scalar(), dtype=float))) > 1e-12:
        raise InvalidInputError("reflect_in_plane: P . e != 0, P is a sphere (use invert_in_sphere)")
    return apply(Pv, X)


def invert_in_sphere(S: Multivector, X: Multivector) -> Multivector:
    """Inversion in a sphere, -s x s^-1 = sigma x', Eqs. (2.84)-(2.88).

    Returns the image entity; for a conformal point it is scaled by sigma
    (2.87), so use :func:`~cga_lessons.conformal.model.down` for its Euclidean point,
    ``g(x) = rho^2 (x - p)/|x - p|^2 + p`` (2.88).  S in standard or dual form.
    """
    from .entities import grade_of, standard_form

    g = grade_of(S, "invert_in_sphere", (1, 4))
    s = S if g == 1 else standard_form(S)
    return apply(s, X)
