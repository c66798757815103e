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
Where the tables cannot resolve a versor's ``V ~V`` (its round-off ``eps |V|^2``
beyond 1e-12 of it: a sphere, a plane or a dilation far from the origin),
:func:`apply` takes it by its factors: the inversions in
:mod:`cga_lessons.conformal.anchored_versors`, the similarities and reflections in
:mod:`cga_lessons.conformal.similarities`; a versor no factors cover whose
``V ~V`` is lost to round-off (a product of motors far out) raises.

The constructors (:func:`translator`, :func:`rotor`, :func:`rotor_about_line`,
:func:`motor`, :func:`screw`) live in :mod:`cga_lessons.conformal.versors_build`, the
rigid-motion conversions (:func:`decompose_motor`, :func:`rotor_angle_axis`,
:func:`motor_to_matrix`, :func:`matrix_to_motor`) in
:mod:`cga_lessons.conformal.versors_rigid` (the facade :mod:`cga_lessons.conformal` exports all three).
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import (
    GeometryError,
    Multivector,
    any_sympy,
    is_real_batch,
    is_real_single,
)

from .anchored import Anchored, frame, inverted, moved, times_invariant
from .anchored_ops import view
from .anchored_versors import (
    far_parts,
    far_product,
    in_versor_frame,
    inverted_and_moved,
    lost_versor_apply,
    moves_infinity,
    unresolved,
)
from .inversions import inversion_of, inverted_points
from .model import G41, einf
from .model import Ic as IC
from .multivector_checks import COORD_LIMIT, COORD_WHY, check_points, input_error, multivector, mv_is_finite
from .points import down, up
from .similarities import similar, similarity_factors, similarity_product

__all__ = [
    "apply",
    "apply_to_points",
    "versor_matrix",
    "reflect_in_plane",
    "invert_in_sphere",
]


# --------------------------------------------------------------- application
def _parity(V: Multivector, func: str = "apply", name: str = "V") -> int:
    gs = {V.algebra.grades[b] % 2 for b in V._c}
    if len(gs) != 1:
        raise checks.fail(func, name, "a versor is either even or odd (2.82); got mixed parity")
    return gs.pop()


def versor_matrix(V: Multivector, grade: int) -> np.ndarray:
    """Matrix of ``X -> apply(V, X)`` on the grade-``grade`` blades (order of 2.9).

    A versor acts linearly on each grade (its outermorphism), so a batch of N
    entities costs one (k, k) x (k, N) product with this matrix (k = 5 for
    points and spheres, 10 for lines and circles).  For a numeric versor it is
    built in closed form from one cached bilinear table
    (:meth:`~cga_lessons.algebra.Algebra.versor_matrices`); where those cannot
    resolve ``V ~V`` (a sphere, a dilation or a plane far from the origin) its
    columns are :func:`apply` of the basis blades, which takes such a versor
    by its factors (or raises where none cover it); other numeric multivectors
    (V ~V not a scalar) use one sandwich per basis blade.
    """
    func = "versor_matrix"
    multivector(V, func, "V", what="a versor (Multivector of G(4,1))", single=True, numeric=True)
    grade = checks.integer(grade, func, "grade", low=0, high=G41.n)
    mats = G41.versor_matrices(V, (grade,))
    if mats is not None:
        out = mats[grade].copy()
    else:  # the route of apply, a basis blade at a time: the sandwich, or the factors of a versor far out
        blades = G41.grade_blades[grade]
        _parity(V, func)
        cols = []
        for b in blades:
            img = _apply(V, Multivector(G41, {b: 1.0}), func, "V", "grade")
            cols.append([float(img._c.get(r, 0.0)) for r in blades])
        out = np.array(cols).T
    if not np.all(np.isfinite(out)):
        raise checks.fail(func, "V", "its matrix overflows a float (the coefficients' magnitudes are too large)")
    return out


def _inverse(V: Multivector, func: str, name: str) -> Multivector:
    try:
        return V.inv()
    except GeometryError as exc:
        raise checks.degenerate(func, name, f"has no inverse, so it is no versor ({exc})") from None


def _apply_sandwich(
    V: Multivector, X: Multivector, Vinv: Multivector | None = None, func: str = "apply", name: str = "V"
) -> Multivector:
    odd = _parity(V, func, name)
    Xi = X.involute() if odd else X
    Vinv = _inverse(V, func, name) if Vinv is None else Vinv
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

    Raises :class:`~cga_lessons.algebra.InvalidInputError` naming V or X
    (``"apply: X: contains NaN or inf"``) for what is not a multivector, NaN
    or inf coefficients, mixed parity, multivectors of two algebras, or a
    result that overflows, and :class:`~cga_lessons.algebra.DegenerateGeometryError`
    for a zero or non-invertible V (a point).  A batch X is taken as checked
    where it was made (``up``, the entity constructors): scanning its
    coefficients for NaN would cost about 15 % of the call.
    """
    return _apply(V, X, "apply", "V", "X")


def _apply(V, X, func: str, vname: str, xname: str) -> Multivector:
    """:func:`apply` with its checks in the words of the public function ``func`` (arguments ``vname``,
    ``xname``): V and X multivectors of one algebra, V non-zero and invertible of one parity, the result finite
    (a NaN or inf in V or X, or an overflow, is refused; the check of a finite result is one sum)."""
    if type(V) is not Multivector or (type(X) is not Multivector and type(X) is not Anchored):  # checked when made
        multivector(V, func, vname, what="a versor (Multivector)", algebra=None)
        multivector(X, func, xname, what="a Multivector", algebra=None, nonzero=False)
    if not V._c:
        raise checks.degenerate(func, vname, "the zero multivector is not a versor")
    if X.algebra is not V.algebra:
        raise checks.fail(func, xname, f"a multivector of {X.algebra!r}, V one of {V.algebra!r}")
    Y = None
    if type(V) is Anchored and X._c:
        Y = lost_versor_apply(V, X, lambda W, Z: _apply(W, Z, func, vname, xname))
        if Y is not None:
            return Y
    try:
        if X._c and (is_real_single(X) or is_real_batch(X)):
            far = None if 0 in V._c or V.algebra is not G41 or not is_real_single(V) else far_parts(V, func, vname)
            if far is not None:  # an inversion whose V ~V the tables cannot resolve: by its factors
                Y = far_product(far, view(X), lambda W, Z: _apply(W, Z, func, vname, xname))
            else:
                mats = V.algebra.versor_matrices(V, X.grades_present())
                if mats is not None:
                    Y = V.algebra.apply_matrices(mats, X)
                elif V.algebra is G41 and is_real_single(V):  # V ~V beyond the tables (a versor far out)
                    Y = _far_similarity(V, X, func, vname, xname)
        if Y is None:  # the sandwich (SymPy, batches of versors, non-versors, and what the matrices refused)
            multivector(V, func, vname, what="a versor (Multivector)", algebra=None)
            multivector(X, func, xname, what="a Multivector", algebra=None, nonzero=False)
            Y = _apply_sandwich(V, X, None, func, vname)
    except GeometryError as exc:  # an operation of the algebra refused a NaN, inf or overflow
        if str(exc).startswith(f"{func}:"):
            raise
        raise input_error(func, {vname: V, xname: X}, exc) from None
    try:  # mv_is_finite inlined for one entity (NaN and inf propagate through the sum)
        if math.isfinite(math.fsum(Y._c.values())):
            return Y if type(X) is Multivector else _keep_frame(V, X, Y)
    except (TypeError, ValueError, OverflowError):  # arrays (a batch), SymPy, inf - inf, or terms near 1e308
        pass
    if mv_is_finite(Y, batches=False):  # a batch of entities is checked where it is made (up, the constructors)
        return Y if type(X) is Multivector else _keep_frame(V, X, Y)
    raise input_error(func, {vname: V, xname: X})


def _far_similarity(V, X, func: str, vname: str, xname: str):
    """apply(V, X) for a single real V whose ``V ~V`` the tables refused: a similarity or an odd isometry by its
    factors (:func:`~cga_lessons.conformal.similarities.similarity_product`: a dilation, a reflection in a plane
    far out, 2.89-2.91, or their products with a motor, 2.102); raises for a V that no factors cover and whose
    ``V ~V`` is lost to round-off (:func:`~cga_lessons.conformal.anchored_versors.unresolved`); None for the
    others (the sandwich)."""
    dual = all(G41.grades[b] == 4 for b in V._c)
    # a dual form K Ic (2.31): Ic is central, so V X V^-1 = K X K^-1 = apply(K, X^) (2.82)
    sim = similarity_factors(times_invariant(V, IC) if dual else V)
    if sim is not None:
        Z = view(X)
        return similarity_product(sim, Z.involute() if dual else Z, lambda W, Z: _apply(W, Z, func, vname, xname))
    why = unresolved(V)
    if why:  # an anchored versor (two anchored spheres multiplied, say) is taken in its own frame, else refused
        Y = lost_versor_apply(V, X, lambda W, Z: _apply(W, Z, func, vname, xname), lost=True)
        if Y is None:
            raise checks.fail(func, vname, why)
        return Y
    return None


def _keep_frame(V, X, Y) -> Multivector:
    """Y = apply(V, X) anchored when X is anchored and V maps points to points in a way its local blade can follow
    accurately; Y as it is otherwise (a versor without a frame of its own that no closed form below reads, an
    inversion times a reflection say; a batch of versors; SymPy: the frame is dropped).

    * V a motor T_t R (2.102): the anchor moves as a point and the local blade turns by the rotor part of V
      (:func:`~cga_lessons.conformal.anchored.moved`; a scaled motor's scale cancels in ``V X V^-1``).
    * V an odd isometry ``T_t U`` (U a Euclidean versor: a reflection in a plane ``n + d e``, 2.89-2.91, or its
      product with a motor): ``T_{-f'} V T_f`` with f' = V(f) fixes the origin, so it is U (the reflection in the
      plane n through the origin): the anchor moves as a point, ``local`` is reflected by V's Euclidean part; its
      (R, t) read off the motor ``V e1`` (:func:`~cga_lessons.conformal.similarities.similarity_factors`), exact at
      any distance.
    * V a sphere (an inversion, 2.84-2.88): :func:`~cga_lessons.conformal.anchored.inverted`.
    * V a similarity (a dilation, its product with a motor or a reflection):
      :mod:`~cga_lessons.conformal.similarities`; an inversion times a motor:
      :mod:`~cga_lessons.conformal.anchored_versors`.
    * any other V that carries a frame itself (two anchored spheres multiplied): applied in V's frame
      (:func:`_in_frame`).
    """
    f, _ = frame(X, settle=False)
    if f is None or V.algebra is not G41:
        return Y
    motion = G41.rigid_motion(V)
    if motion is not None:
        return moved(X, Y, V, *motion)
    if not is_real_single(V):
        return Y
    grades = {G41.grades[b] for b in V._c}
    if grades == {4}:  # a dual form S Ic (2.31): Ic is central, V X V^-1 = S X S^-1
        K, inv = times_invariant(V, IC), False
    elif all(g % 2 for g in grades):
        K, inv = V, True
    else:  # even, no motor: a similarity?
        Z = similar(X, Y, V)
        return _in_frame(V, X, Y) if Z is None else Z
    Z = similar(X, Y, K)  # odd: a reflection times a dilation
    if Z is not None:
        return Z
    sim = None if moves_infinity(K) else similarity_factors(K)
    if sim is not None:  # an odd isometry T_t U (rho = 0): (R, t) read exactly off the motor K e1
        # U its Euclidean part; a half-turn about a line (L, grade 3) has no such U
        if any(b < 8 and v != 0.0 for b, v in K._c.items()):
            return moved(X, Y, K, *sim.rigid, involute=inv)
        return _in_frame(V, X, Y)
    parts = inversion_of(K)  # a sphere, or an inversion times a motor
    if parts is None:
        return _in_frame(V, X, Y)
    if parts.motor is None:
        return inverted(X, Y, parts.centre, parts.radius2, involute=inv)
    return inverted_and_moved(X, Y, parts)


def _in_frame(V, X, Y) -> Multivector:
    """Y = apply(V, X) for a versor no closed form above reads, anchored when V carries a frame too (a product of
    anchored spheres, 2.84-2.88, say: two inversions): applied in V's frame
    (:func:`~cga_lessons.conformal.anchored_versors.in_versor_frame`); Y as it is otherwise."""
    if frame(V, settle=False)[0] is None:
        return Y
    return in_versor_frame(X, Y, V, lambda W, Z: _apply(W, Z, "apply", "V", "X"))


def apply_to_points(V: Multivector, x) -> np.ndarray:
    """Euclidean points moved by a motor (or any versor mapping points to points).

    ``x`` has shape (3,) or (N, 3).  For a motor this is ``y = R x + t`` with
    R and t read linearly off its coefficients
    (:meth:`~cga_lessons.algebra.Algebra.rigid_motion`, 2.141-2.144): exact to
    round-off at any distance, at the cost of a plain homogeneous matrix.  A
    similarity (a dilation, its product with a motor or a reflection) and an
    odd isometry (a reflection in a plane, 2.89-2.91, or its product with a
    motor) map by ``y = s R x + t``, read as linearly off their factors
    (:func:`~cga_lessons.conformal.similarities.similarity_factors`; s = 1, det R
    = -1 for the isometry): exact at any distance too.  An inversion in a
    sphere (2.84-2.88) or its product with a motor maps by its closed form
    ``x -> p + r2 (x - p) / |x - p|^2`` (the sphere's centre and squared
    radius read off its local frame when it has one: exact at any distance).
    Other versors and SymPy input go through the conformal point and
    :func:`~cga_lessons.conformal.points.down`.
    """
    func = "apply_to_points"
    arr, sym = check_points(x, func)
    if type(V) is not Multivector:
        multivector(V, func, "V", what="a versor (Multivector of G(4,1))")
    if sym or any_sympy(V):
        return down(_apply(V, up(arr), func, "V", "x"))
    try:
        affine = G41.rigid_motion(V) if V.algebra is G41 else None
    except GeometryError:  # NaN or inf coefficients, refused by the algebra: say it in this function's words
        affine = None
    if affine is None:
        multivector(V, func, "V", what="a versor (Multivector of G(4,1))")
        sim = similarity_factors(V) if is_real_single(V) else None
        if sim is None:
            inversion = inversion_of(V) if is_real_single(V) else None
            if inversion is not None:
                return inverted_points(inversion, arr, func)
            return _points_through_conformal(V, arr, func)
        R, t = sim.rigid
        if sim.rho != 0.0:
            R = sim.scale * R
    else:
        R, t = affine
    if arr.ndim == 1:
        y = R @ arr + t
        try:
            ok = math.isfinite(math.fsum(y.tolist()))
        except (OverflowError, ValueError):  # coordinates near 1e308, or inf - inf
            ok = False
        if not ok and not np.all(np.isfinite(y)):
            raise checks.fail(func, "x", "the moved point overflows a float (its coordinates are too large)")
        return y
    # (R x^T + t)^T: the sum runs along the long axis (adding t row by row to an (N, 3) array is several
    # times slower than the product itself); the result is the transposed view of a (3, N) block.
    try:
        with np.errstate(over="raise"):
            out = R @ arr.T
            out += t[:, None]
    except FloatingPointError:
        raise checks.fail(func, "x", "the moved points overflow a float (their coordinates are too large)") from None
    return out.T


def _points_through_conformal(V: Multivector, arr: np.ndarray, func: str) -> np.ndarray:
    """``down(apply(V, up(x)))`` for a versor that is no isometry (an inversion, a dilation), errors named."""
    checks.magnitude(arr, func, "x", limit=COORD_LIMIT, why=COORD_WHY)
    Y = _apply(V, up(arr), func, "V", "x")
    try:
        return down(Y)
    except GeometryError as exc:
        raise checks.degenerate(func, "x", f"V sends a point to infinity or out of range ({exc})") from None


def reflect_in_plane(P: Multivector, X: Multivector) -> Multivector:
    """Reflection of any entity X in a plane P = n + delta e, Eqs. (2.84), (2.89)-(2.91).

    ``-P X P^-1`` for a vector X (2.84); an entity of any grade via the
    grade involution (2.82).  P in standard (grade 1) or dual (grade 4) form.
    """
    from .entities import grade_of, standard_form

    func = "reflect_in_plane"
    g = grade_of(multivector(P, func, "P", what="a plane (Multivector of G(4,1))"), func, (1, 4), "P")
    Pv = P if g == 1 else standard_form(P)
    if not any_sympy(Pv) and np.max(np.abs(np.asarray((Pv | einf).scalar(), dtype=float))) > 1e-12:
        raise checks.fail(func, "P", "P . e != 0: a sphere (or a point), not a plane (use invert_in_sphere)")
    return _apply(Pv, X, func, "P", "X")


def invert_in_sphere(S: Multivector, X: Multivector) -> Multivector:
    """Inversion in a sphere, -s x s^-1 = sigma x', Eqs. (2.84)-(2.88).

    Returns the image entity; for a conformal point it is scaled by sigma
    (2.87), so use :func:`~cga_lessons.conformal.points.down` for its Euclidean point,
    ``g(x) = rho^2 (x - p)/|x - p|^2 + p`` (2.88).  S in standard or dual form.
    """
    from .entities import grade_of, standard_form

    func = "invert_in_sphere"
    g = grade_of(multivector(S, func, "S", what="a sphere (Multivector of G(4,1))"), func, (1, 4), "S")
    s = S if g == 1 else standard_form(S)
    return _apply(s, X, func, "S", "X")
