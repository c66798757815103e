"""Anchored entities under the versors that are no isometry, no similarity and no single inversion: an inversion times
a motor (the versor action 2.82; inversions 2.84-2.88,
reflections 2.89-2.91, translators 2.100, motors 2.102); and the global result of an inversion whose ``V ~V`` the
product tables cannot resolve (a small sphere far out).  Used by :func:`~cga_lessons.conformal.apply`.

**Null parts.**  A multivector of G(4,1) is ``V = E + Xe e + Y e0 + D E_pm`` with E, Xe, Y, D Euclidean (the split
of :mod:`~cga_lessons.conformal.entities_frame`; e and e0 of 2.53, ``E_pm = e+ e- = e ^ e0``, 2.55).  Its square
is ``<V ~V>_0 = <(E - D) ~(E + D)>_0 - 2 <Xe ~Y>_0`` (:func:`square`): terms of the size of the geometry, where the
squares of the e+/e- coefficients, |c|^4-sized for a round |c| out, cancel.

**Similarities** (a dilation and its products with a motor or a reflection, and the odd isometries): by their
factors in :mod:`~cga_lessons.conformal.similarities`.

**An inversion times a motor** (:func:`inversion_motor`, :func:`inverted_and_moved`).  An odd versor that moves
the point at infinity is ``V = S M = M S'`` (M = R + e Q a motor, Q = t R / 2; S, S' spheres ``p + beta e + e0``,
2.72, S' = M^-1 S M).  Multiplying out (``e0 e = -1 - E_pm``, ``e e0 = -1 + E_pm``)::

    S M  = (p R - Q) - Q E_pm + (beta R - p Q) e + R e0
    M S' = (R p' + Q) - Q E_pm + (beta' R + Q p') e + R e0

so ``R = Y``, ``Q = -D``, ``p = <(E - D) ~R>_1 / <R ~R>_0``, ``p' = <~R (E + D)>_1 / <R ~R>_0`` and, for both, the
squared radius ``r2 = <V ~V>_0 / <R ~R>_0`` (``V ~V = S^2 M ~M``, 2.83), summed exactly from the stored
coefficients.  The frame follows the factors: the motor's motion (:func:`~cga_lessons.conformal.anchored.moved`),
then the inversion's (:func:`~cga_lessons.conformal.anchored.inverted`), or the other way round.  As exact as V
holds its factors: the float product of a sphere and a motor that both reach |c| from the origin rounds terms of
size |c|^3 that cancel (``e e = 0`` summed as ``e+ e+ + e- e-``) and holds its rotor R (its e0 part, a difference
of |c|^2-sized e+/e- coefficients) to eps |c|^2 only; one of them near the origin, it holds them to eps |c|.

**Far inversions** (:func:`far_parts`, :func:`far_product`; :func:`unresolved` for what no factors cover).  The
tables of :meth:`~cga_lessons.algebra.Algebra.versor_matrices` compute ``V ~V`` as the signed sum of the squared
coefficients, round-off ``eps |V|^2``: for a unit sphere 1e6 out (e+ and e- coefficients near 5e11) about 1e8,
where ``V ~V = 1``, so the scale of the result was garbage or V was refused as having no inverse.  Where that
round-off passes ``TABLE_TOLERANCE`` of ``V ~V`` (summed by its null parts), the global result is the product of
the factors instead: the motor, the translation by -p, the inversion in the sphere of squared radius r2 about the
origin, the translation back (2.100, 2.84-2.88), each well conditioned; centre and radius are read off the
sphere's local blade when it is anchored (exact at any distance), else off its coefficients (their own limit,
``eps |p|^2``).  ``V ~V`` zero to within its round-off (a sphere of radius 0: a point) has no inverse and raises.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError, Multivector, is_real_batch, is_real_single

from .anchored import Anchored, frame, inverted, moved, times_invariant
from .anchored_ops import NoFrame, Pending, about, chain_depth, read_only, translated, view
from .entities_frame import EPS, split
from .entities_read import read_sphere
from .model import G41, einf, eo
from .model import Ic as IC
from .points import euclidean
from .versors_build import translator

__all__ = [
    "TABLE_TOLERANCE",
    "LOST_TOLERANCE",
    "Inversion",
    "square",
    "moves_infinity",
    "unresolved",
    "inversion_motor",
    "inverted_and_moved",
    "far_parts",
    "far_product",
    "in_versor_frame",
    "image_in_frame",
    "lost_versor_apply",
]

#: The round-off of ``V ~V`` in the product tables (``eps |V|^2``, |V|^2 the sum of the squared coefficients) is
#: trusted up to this much of ``V ~V`` (the relative tolerance of the algebra's versor test); beyond it an inversion
#: is applied by its factors (:func:`far_product`).  For a unit sphere: beyond about 10 from the origin.
TABLE_TOLERANCE = 1e-12
#: Beyond this much of ``V ~V`` its round-off ``eps |V|^2`` leaves no motion to apply (:func:`unresolved`): the
#: sandwich of the versor as stored would be off by more than the package's 1e-9.
LOST_TOLERANCE = 1e-9
_VECTOR = (1, 2, 4, 8, 16)  # e1 e2 e3 e+ e-


def _euclid(a) -> Multivector:
    """The Euclidean multivector of an 8-array of parts (index: the blade's bitmap, 0 ... 7)."""
    return Multivector(G41, {x: float(a[x]) for x in range(8) if a[x] != 0.0})


def square(V: Multivector):
    """``(<V ~V>_0, bound)`` of a single real multivector of G(4,1): the scalar of ``V ~V`` (2.83) summed exactly
    from the stored coefficients (fractions; one rounding), and eight eps of the absolute sum of its terms
    ``<(E - D) ~(E + D)>_0 - 2 <Xe ~Y>_0`` (module docstring), the round-off of coefficients rounded by eps each,
    the e0 part Y taken as stored (the constructors store it exactly).  ``|<V ~V>_0| <= bound``: V is null to
    within its round-off."""
    d = Fraction(0)
    for b, v in V.coeffs.items():
        q = Fraction(float(v)) ** 2
        d += -q if b & 16 else q  # <b ~b> = -1 for the blades with e- (e-^2 = -1), else +1
    Eu, Xe, Y, D, _, _ = split(V, "apply", "V")
    terms = np.abs((Eu - D) * (Eu + D)).sum() + 2.0 * np.abs(Xe * Y).sum()
    return float(d), 8.0 * EPS * float(terms)


def moves_infinity(V: Multivector) -> bool:
    """Whether V (single, real) has an e0 part Y beyond round-off (16 eps of its largest coefficient): the versors
    that fix the point at infinity e (motors, reflections, similarities) have none, and their float products none
    at all (the e+ and e- coefficients are summed alike); an inversion times a motor has ``Y = R``, about
    2 / |p|^2 of its largest coefficient (9000 eps for a sphere 1e6 out)."""
    c = V.coeffs
    vmax = max((abs(float(v)) for v in c.values()), default=0.0)
    return any(abs(float(c.get(x | 16, 0.0)) - float(c.get(x | 8, 0.0))) > 16.0 * EPS * vmax for x in range(8))


# ------------------------------------------------------------------------------- inversion times a motor
@dataclass(frozen=True)
class Inversion:
    """An inversion times a motor, ``V = S M`` (``motor_first``: the motor acts first) or ``M S``: the sphere's
    centre and signed squared radius (2.84-2.88), the motor M (2.102) and its ``(R, t)``; ``null``: ``V ~V`` is
    zero to within its round-off (a sphere of radius 0, no inverse)."""

    centre: np.ndarray
    radius2: float
    motor: Multivector
    rigid: tuple
    motor_first: bool
    null: bool


def inversion_motor(V: Multivector) -> Inversion | None:
    """V (single, real, odd) read as an inversion times a motor (module docstring), the form of the smaller centre
    chosen (its coordinates round least); None when V fixes the point at infinity or is no such product to a
    relative 1e-9 of its coefficients."""
    if any(G41.grades[b] % 2 == 0 for b in V.coeffs) or not moves_infinity(V):
        return None
    Eu, Xe, Y, D, _, _ = split(V, "apply", "V")
    R = _euclid(Y)
    RR = float(np.dot(Y, Y))
    if not RR > 0.0 or any(Y[x] != 0.0 for x in (1, 2, 4, 7)):
        return None
    p1 = euclidean(_euclid(Eu - D) * ~R) / RR  # V = S M: the motor first
    p2 = euclidean(~R * _euclid(Eu + D)) / RR  # V = M S'
    d, bound = square(V)
    r2 = d / RR
    first = bool(p1 @ p1 <= p2 @ p2)
    p = p1 if first else p2
    M = R - einf * _euclid(D)
    S = Multivector(G41, {1: p[0], 2: p[1], 4: p[2]}) + (0.5 * (p @ p - r2)) * einf + eo
    back = S * M if first else M * S
    scale = max(abs(float(v)) for v in V.coeffs.values())
    keys = set(V.coeffs) | set(back.coeffs)
    if max(abs(float(back.coeffs.get(b, 0.0)) - float(V.coeffs.get(b, 0.0))) for b in keys) > 1e-9 * scale:
        return None
    rigid = G41.rigid_motion(M)
    if rigid is None:
        return None
    return Inversion(p, r2, M, rigid, first, abs(d) <= bound)


def inverted_and_moved(X: Anchored, Y: Multivector, inv: Inversion) -> Anchored:
    """``Y = apply(V, X)`` anchored for ``V = S M`` or ``M S`` (:class:`Inversion`): the motor's motion and the
    inversion's, one after the other as V applies them (:func:`~cga_lessons.conformal.anchored.moved`, 2.102;
    :func:`~cga_lessons.conformal.anchored.inverted`, 2.84-2.88).  The intermediate entity carries Y's
    coefficients, never read."""
    R, t = inv.rigid
    if inv.motor_first:
        return inverted(moved(X, Y, inv.motor, R, t), Y, inv.centre, inv.radius2)
    return moved(inverted(X, Y, inv.centre, inv.radius2), Y, inv.motor, R, t)


# ------------------------------------------------------------------------------------------ far inversions
def far_parts(V: Multivector, func: str, name: str):
    """``(centre, r2, motor, motor_first, dual)`` of a single real V of G(4,1) that is an inversion (a sphere,
    standard or dual form, or its product with a motor) whose ``V ~V`` the tables cannot resolve (module
    docstring; motor None for a sphere alone), else None.  The centre and radius of a sphere are read as
    :func:`~cga_lessons.conformal.entities_read.read_sphere` reads them (off its local blade when anchored).
    Raises :class:`~cga_lessons.algebra.DegenerateGeometryError` for a V whose ``V ~V`` is zero to within its
    round-off."""
    c = V.coeffs
    vector = all(b in _VECTOR for b in c)
    if vector:  # a sphere or a plane: the test below in a few flops
        x1, x2, x3, p, m = (float(c.get(b, 0.0)) for b in _VECTOR)
        if p == m:
            return None  # a plane (2.89): an isometry
        d = x1 * x1 + x2 * x2 + x3 * x3 + (p - m) * (p + m)
        size = x1 * x1 + x2 * x2 + x3 * x3 + p * p + m * m
        if EPS * size <= TABLE_TOLERANCE * abs(d):
            return None  # the tables resolve V ~V
    grades = {G41.grades[b] for b in c}
    dual = grades == {4}
    if dual:  # S Ic (2.31): V X V^-1 = S X^ S^-1 for the sphere S = V Ic (Ic is central), up to a number
        V, grades = times_invariant(V, IC), {1}
    if any(g % 2 == 0 for g in grades):
        return None
    if not vector:
        vals = np.array([float(v) for v in V.coeffs.values()])
        Eu, Xe, Y, D, _, _ = split(V, func, name)
        if not np.any(Y):
            return None  # it fixes the point at infinity: an isometry or a similarity, no inversion
        d = float(np.dot(Eu - D, Eu + D) - 2.0 * np.dot(Xe, Y))
        if EPS * float(vals @ vals) <= TABLE_TOLERANCE * abs(d):
            return None  # the tables resolve V ~V
    if grades == {1}:
        try:
            p, r2, _, tol = read_sphere(V, func, name)
        except GeometryError:
            return None
        p, r2 = np.asarray(p, dtype=float), float(r2)
        if abs(r2) <= float(tol):
            raise _null(func, name)
        return None if not np.any(p) else (p, r2, None, True, dual)  # about the origin: the tables' own route
    inv = inversion_motor(V)
    if inv is None:
        return None
    if inv.null:
        raise _null(func, name)
    return inv.centre, inv.radius2, inv.motor, inv.motor_first, dual


def _null(func: str, name: str):
    return checks.degenerate(
        func, name, "has no inverse, so it is no versor (V ~V = 0 to within its round-off: a sphere of radius 0)"
    )


def far_product(parts, X: Multivector, step) -> Multivector:
    """``apply(V, X)`` for the :func:`far_parts` of V, by its factors: ``step(W, Z)`` applies one factor W to Z
    (the caller's apply, its errors in the caller's words).  The inversion in the sphere (p, r2) is
    ``T_p S0 ~T_p`` with ``S0 = e0 - r2 e / 2`` about the origin (2.72, 2.100); a dual form's action is that of its
    sphere on ``X^`` (2.82)."""
    p, r2, M, motor_first, dual = parts
    Z = X.involute() if dual else X
    if M is not None and motor_first:
        Z = step(M, Z)
    S0 = eo.plain_operation("-", (0.5 * r2) * einf)  # plain: its own frame (at the origin) adds nothing
    Z = step(translator(p), step(S0, step(translator(-p), Z))) if np.any(p) else step(S0, Z)
    if M is not None and not motor_first:
        Z = step(M, Z)
    return Z


def unresolved(V: Multivector) -> str:
    """Why apply cannot take V (single, real, one parity, not a vector) to working precision, or '': ``V ~V``
    summed exactly from its coefficients is below ``eps |V|^2 / LOST_TOLERANCE`` (|V|^2 the sum of the squared
    coefficients, the round-off of V's own products and of its sandwich): a versor that far from the origin which
    is no motor, similarity, sphere or inversion times a motor (the float product of motors or spheres far out)
    no longer holds its motion to 1e-9, and its inverse would be the round-off's."""
    c = V.coeffs
    if len({G41.grades[b] & 1 for b in c}) != 1 or all(G41.grades[b] == 1 for b in c):
        return ""
    d, _ = square(V)
    size = sum(float(v) ** 2 for v in c.values())
    if EPS * size <= LOST_TOLERANCE * abs(d):
        return ""
    return (
        f"V ~V = {d:.3g} is lost to the round-off of its coefficients (eps |V|^2 = {EPS * size:.3g}): a versor "
        "this far from the origin that is no motor, similarity, sphere or inversion times a motor (a product of "
        "motors or spheres far out) holds no motion to working precision; compose rigid motions as matrices "
        "(motor_to_matrix, matrix_to_motor) or build the versor with its constructor"
    )


# ------------------------------------------------------------------------------------ anchored versors
def in_versor_frame(X: Anchored, Y: Multivector, V: Anchored, step) -> Anchored:
    """``Y = apply(V, X)`` for an anchored versor V (anchor f; a product of anchored spheres, planes or entities:
    two inversions, say), anchored at f, its local blade :func:`image_in_frame` (built when first read)."""
    depth = chain_depth(X, V)

    def build():
        if frame(X)[0] is None:
            raise NoFrame("the entity lost its frame")
        f, local = image_in_frame(V, X, step)
        if f is None:
            raise NoFrame("the versor lost its frame")
        return read_only(f, Y.shape), local

    return Anchored.derive(Y, Pending(build, depth))


def image_in_frame(V: Multivector, X: Multivector, step):
    """``(f, L)``: the action of an anchored versor V (anchor f) on X in V's frame: since
    ``T_{-f} (V X V^-1) T_f = V_f X_f V_f^-1`` (2.82, 2.100) with ``V_f`` V's local versor and ``X_f`` X's local
    blade moved into f's frame (a plain X: its coefficients moved), ``L = step(V_f, X_f)`` (the caller's apply),
    every term of the size of the geometry about f; ``(None, None)`` when V has no frame."""
    fv, lv = frame(V)
    if fv is None:
        return None, None
    fx, lx = frame(X)
    return fv, step(lv, about(lx, fx, fv) if fx is not None else translated(view(X), -fv))


def lost_versor_apply(V: Multivector, X: Multivector, step, lost: bool = False):
    """apply(V, X) for an anchored versor V (anchor f; a product of anchored spheres: two inversions, 2.84-2.88)
    whose global coefficients no longer hold it: they differ from its local versor translated back,
    ``T_f V_f ~T_f`` (2.100), by more than ``LOST_TOLERANCE`` of their size (1e5 out the scalar ``S1 . S2`` of two
    spheres is a difference of |c|^4-sized terms, and can vanish).  Then the action is taken in V's frame
    (:func:`image_in_frame`) and the global coefficients are the result translated back, anchored at f when X is.
    None where V's global coefficients hold it (the plain route, its bits), or V has no frame.  ``lost``: they are
    known not to hold it (its ``V ~V`` is round-off: :func:`unresolved`)."""
    if not lost and len({G41.grades[b] for b in V.coeffs}) == 1 and G41.grades[next(iter(V.coeffs))] in (1, 4):
        return None  # a sphere or plane: read exactly off its frame by the closed forms (inversions.sphere_of)
    if not is_real_single(V) or not (is_real_single(X) or is_real_batch(X)):
        return None
    fv, lv = frame(V)
    if fv is None:
        return None
    back = translated(lv, fv)
    size = max(abs(float(v)) for v in back.coeffs.values())
    keys = set(back.coeffs) | set(V.coeffs)
    if not lost and max(abs(float(back.coeffs.get(b, 0.0)) - float(V.coeffs.get(b, 0.0))) for b in keys) <= (
        LOST_TOLERANCE * size
    ):
        return None
    f, local = image_in_frame(V, X, step)
    Y = translated(local, f)
    if frame(X)[0] is None:
        return Y
    return Anchored(Y.algebra, Y.coeffs, anchor=np.broadcast_to(f, Y.shape + (3,)), local=local)
