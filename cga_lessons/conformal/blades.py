"""Blades of G(4,1): contractions, duality, join and meet, projection, factorisation.

The thesis builds every entity with the outer product (2.14, 2.30) and reads it with its inner product (2.21-2.29,
``A | B = <A B>_|r-s|``).  Intersections appear there only as outer products of standard forms (2.79, table 2.1:
``z = s1 ^ s2``, ``L = P1 ^ P2``, ``PP = s1 ^ s2 ^ s3``) and through the sign test of Theorem 2.4.1.  This module
adds the operations of Dorst, Fontijne & Mann (2007), *Geometric Algebra for Computer Science* (DFM below) that make
those constructions work in every position (parallel, coincident, tangent, imaginary):

* left/right contraction and scalar product, grade by grade (DFM 3.1-3.4, 6.3);
* dual and undual with the pseudoscalar ``Ic`` of (2.60), ``A* = A Ic^-1`` as in (2.31) and as
  :meth:`Multivector.dual` and :func:`cga_lessons.conformal.entities.dual_form` already do;
* the regressive product, the join and the meet of blades (DFM ch. 5 and ch. 21);
* projection and rejection (DFM 3.6; the thesis's 2.58-2.59 are the case B = E);
* the versor test (DFM ch. 21); the blade test and blade factorisation are in
  :mod:`cga_lessons.conformal.blades_span`.

Every function takes single multivectors of G(4,1) with real coefficients (no batches, no SymPy) and raises
:class:`InvalidInputError` or :class:`DegenerateGeometryError` (both ``ValueError``) with a message
``"function: argument: problem"``.  Blades are read in OPNS ("dual form" in the thesis's words: the outer product of
points, 2.75-2.81); :mod:`cga_lessons.conformal.blades_classify` handles the standard (IPNS) forms and names what a
blade is.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Algebra, DegenerateGeometryError, Multivector

from .anchored import Anchored, frame
from .anchored_ops import about, follow, translated
from .blades_span import (
    blade_span,
    coefficient_norm,
    relative_tolerance,
    require_blade,
    single_multivector,
    wedge_columns,
)
from .model import G41, Ic
from .multivector_checks import result_finite

__all__ = [
    "left_contraction",
    "right_contraction",
    "scalar_product",
    "dual",
    "undual",
    "regressive_product",
    "join",
    "meet",
    "project",
    "reject",
    "is_versor",
]

_IC_INV = Ic.inv()  # -Ic exactly: Ic^2 = -1
_E5 = Algebra(5)  # the Euclidean metric on the same coefficients: join and meet are metric-free (DFM ch. 5)


def left_contraction(A, B) -> Multivector:
    """Left contraction ``A _| B = sum_{r,s} <A_r B_s>_{s-r}``, zero where ``s < r`` (DFM 3.2-3.4, 6.3).

    Unlike the thesis's inner product (2.29), ``<A_r B_s>_|r-s|`` with ``scalar . M = 0`` (2.28), it keeps scalars
    (``a _| B = a B``) and vanishes when A has the higher grade.  Same as ``A << B`` of :mod:`cga_lessons.algebra`.

    >>> from cga_lessons import conformal as cga
    >>> left_contraction(cga.e1, cga.e1 ^ cga.e2), left_contraction(cga.e1 ^ cga.e2, cga.e1)
    (1 e2, 0)
    """
    A0, B0 = A, B
    A, B = single_multivector(A, "left_contraction", "A"), single_multivector(B, "left_contraction", "B")
    return follow(result_finite(_left_contraction(A, B), "left_contraction", A=A, B=B), _lc, A0, B0)


def _lc(a, b) -> Multivector:
    """:func:`_left_contraction` of two local blades (or a local blade and a number)."""
    return _left_contraction(_as_mv(a), _as_mv(b))


def _as_mv(x) -> Multivector:
    """A number as a scalar multivector, a multivector as it is."""
    return x if isinstance(x, Multivector) else Multivector(G41, {0: float(x)} if x else {})


def _left_contraction(A: Multivector, B: Multivector) -> Multivector:
    out = Multivector(G41, {})
    for r in A.grades_present():
        for s in B.grades_present():
            if s >= r:
                out = out + (A.grade(r) * B.grade(s)).grade(s - r)
    return out


def right_contraction(A, B) -> Multivector:
    """Right contraction ``A |_ B = sum_{r,s} <A_r B_s>_{r-s}``, zero where ``r < s`` (DFM 3.4, 6.3).

    ``A |_ B = (~B _| ~A)~``.

    >>> from cga_lessons import conformal as cga
    >>> right_contraction(cga.e1 ^ cga.e2, cga.e2), right_contraction(cga.e2, cga.e1 ^ cga.e2)
    (1 e1, 0)
    """
    A0, B0 = A, B
    A, B = single_multivector(A, "right_contraction", "A"), single_multivector(B, "right_contraction", "B")
    out = result_finite(~_left_contraction(~B, ~A), "right_contraction", A=A, B=B)
    return follow(out, lambda a, b: ~_lc(~_as_mv(b), ~_as_mv(a)), A0, B0)


def scalar_product(A, B) -> float:
    """Scalar product ``A * B = <A B>_0`` as a float (DFM 3.1); for points ``-|a - b|^2 / 2`` (2.66).

    >>> from cga_lessons import conformal as cga
    >>> scalar_product(cga.up([0, 0, 0]), cga.up([3, 4, 0]))
    -12.5
    """
    A, B = single_multivector(A, "scalar_product", "A"), single_multivector(B, "scalar_product", "B")
    out = float((A * B).scalar())
    if not math.isfinite(out):
        raise checks.fail(
            "scalar_product", "A, B", "the result overflows a float (the inputs' magnitudes are too large)"
        )
    return out


def dual(A) -> Multivector:
    """Dual ``A* = A Ic^-1 = -A Ic`` (2.31), with ``Ic = e+-123`` of (2.60).

    The thesis's convention, the same as :meth:`Multivector.dual` and :func:`cga_lessons.conformal.entities.dual_form`
    (standard form -> dual form).  DFM 3.5 write ``A* = A _| I^-1``, equal for every A in G(4,1).

    >>> from cga_lessons import conformal as cga
    >>> dual(cga.e1)
    -1 e23+-
    """
    out = single_multivector(A, "dual", "A") * _IC_INV  # a signed permutation of the coefficients: finite
    return follow(out, lambda a: _as_mv(a) * _IC_INV, A)


def undual(A) -> Multivector:
    """Undual ``A Ic``, the inverse of :func:`dual`; the thesis's standard form of a dual-form entity (2.31).

    >>> from cga_lessons import conformal as cga
    >>> undual(dual(cga.e1 ^ cga.e2))
    1 e12
    """
    return follow(single_multivector(A, "undual", "A") * Ic, lambda a: _as_mv(a) * Ic, A)


def regressive_product(A, B) -> Multivector:
    """Regressive product ``A v B = (A* ^ B*) Ic = A* _| B`` with the dual of (2.31) (DFM ch. 5).

    It does not depend on the metric: kingdon builds its ``&`` from the Hodge complement and ``A & B`` equals
    ``regressive_product(B, A)``, which is the general-position meet ``A ∩ B`` of DFM 5.3 (see :func:`meet`).

    >>> from cga_lessons import conformal as cga
    >>> P = cga.plane_from_points([0, 0, 0], [1, 0, 0], [0, 1, 0])
    >>> Q = cga.plane_from_points([0, 0, 0], [0, 1, 0], [0, 0, 1])
    >>> regressive_product(P, Q)  # -(einf ^ eo ^ e2) = -(E ^ e2): the y axis
    -1 e2+-
    """
    A0, B0 = A, B
    A, B = single_multivector(A, "regressive_product", "A"), single_multivector(B, "regressive_product", "B")
    out = result_finite(((A * _IC_INV) ^ (B * _IC_INV)) * Ic, "regressive_product", A=A, B=B)
    return follow(out, lambda a, b: ((_as_mv(a) * _IC_INV) ^ (_as_mv(b) * _IC_INV)) * Ic, A0, B0)


def _join_covariant(A, ka, B, kb, tol):
    """``(J, covariant)``: the join, and whether it is a covariant expression of A and B (a translation of both
    translates it, weight included: ``A ^ B``, A or B), not one weighted by a Euclidean-orthonormal basis of the
    coefficient space (a partial overlap), whose weight depends on the frame."""
    if ka == 0 or kb == 0:
        return (B if ka == 0 else A), True
    UA, UB = blade_span(A, ka)[0], blade_span(B, kb)[0]
    R = UB - UA @ (UA.T @ UB)  # the part of span(B) outside span(A)
    u, s, _ = np.linalg.svd(R)
    m = int(np.sum(s > tol))
    if m == kb:
        return A ^ B, True
    return (A ^ wedge_columns(u[:, :m]), False) if m else (A, True)


def _local(op, covariant, out: Multivector, ka: int, kb: int):
    """The local blade of a join or meet ``out`` of anchored blades (``op(A, ka, B, kb) -> (blade, covariant)``, the
    same routine on the local blades).  When both took the same covariant branch (:func:`_join_covariant`,
    :func:`_meet`) it is the result about the anchor, exactly.  Otherwise the subspace still is (join and meet are
    metric-free) but the weight depends on the frame: the local blade is scaled by the least-squares factor that
    makes it, translated back by the anchor, the global result (whose large coefficients hold it to round-off), so
    that both are one blade, with one orientation.  A local decision of another grade is taken before this
    (:func:`_decided_locally` returns the local result); should it still differ here, the frame is dropped."""

    def build(f, a, b):
        L, branch = op(_as_mv(a).grade(ka), ka, _as_mv(b).grade(kb), kb)
        if L.grades_present() != out.grades_present():
            raise DegenerateGeometryError("the local blade has another grade: the frames decide differently")
        if branch and branch == covariant:
            return L
        W = translated(L, f)
        ww = sum(float(v) * float(v) for v in W.coeffs.values())
        lam = sum(float(v) * float(out.coeffs.get(b, 0.0)) for b, v in W.coeffs.items()) / ww if ww else 0.0
        if not (math.isfinite(lam) and lam != 0.0):
            raise DegenerateGeometryError("the local blade does not match the global one")
        return L * lam

    return build


def _decided_locally(op, out: Multivector, A0, B0, ka: int, kb: int):
    """The join or meet of two anchored blades A0 (anchor f) and B0 when their local blades decide otherwise than
    the global ones (a result of another grade); else None.

    ``op(A, ka, B, kb) -> (blade, branch)`` runs on A0's local blade and B0's moved into f's frame (2.100), as
    :func:`~cga_lessons.conformal.anchored_ops.follow` moves it.  Far from the origin the global coefficients of two
    nearby rounds span subspaces whose principal angles are below ``tol`` (8e-13 for two unit spheres 1e6 out): the
    global decision is then round-off, the local one the geometry's.  The local result L is the entity, anchored at
    f, and its global coefficients are L translated back by f (``T_f L ~T_f``), not the plain routine's.  Where both
    decide the same grade (or an operand has no frame) the caller keeps the plain result and lets the frame follow,
    bit for bit as before."""
    fa, La = frame(A0)
    fb, Lb = frame(B0)
    if fa is None or fb is None:
        return None
    Lb = about(Lb, fb, fa)
    try:
        L, _ = op(La.grade(ka), ka, Lb.grade(kb), kb)
    except (ValueError, ArithmeticError):  # GeometryError is a ValueError: no local decision to take
        return None
    if not L.coeffs or L.grades_present() == out.grades_present():
        return None
    W = translated(L, fa)
    if W.grades_present() != L.grades_present() or not all(math.isfinite(float(v)) for v in W.coeffs.values()):
        return None
    return Anchored(G41, dict(W.coeffs), anchor=fa, local=L)


def join(A, B, tol: float = 1e-10) -> Multivector:
    """Join ``A ∪ B``: a blade of the smallest subspace that contains both blades (DFM 5.1-5.3, ch. 21).

    When the spans are disjoint this is ``A ^ B``.  Otherwise it is ``A ^ c1 ^ ... ^ cm`` with ``c`` a
    Euclidean-orthonormal basis of the part of span(B) outside span(A); its weight is then that of A (the join
    has no canonical weight).  ``tol`` bounds the sines of the principal angles counted as zero.  The join does
    not use the metric; a scalar joins to the other argument.  Anchored blades give an anchored join
    (:mod:`~cga_lessons.conformal.anchored_ops`; in a partial overlap its local blade is scaled to the global one),
    decided on their local blades as :func:`meet` is.

    >>> from cga_lessons import conformal as cga
    >>> L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])
    >>> L2 = cga.line_from_points([0, 1, 0], [1, 1, 0])  # parallel: both lie in the plane z = 0
    >>> J = join(L1, L2)
    >>> J.grades_present(), (cga.up([5, -3, 0]) ^ J).iszero(1e-9)
    ([4], True)
    """
    tol = relative_tolerance(tol, "join")
    A0, B0 = A, B
    A, ka = require_blade(A, "join", "A")
    B, kb = require_blade(B, "join", "B")
    J, covariant = _join_covariant(A, ka, B, kb, tol)
    J = result_finite(J, "join", A=A, B=B)
    op = lambda a, ka, b, kb: _join_covariant(a, ka, b, kb, tol)  # noqa: E731
    local = _decided_locally(op, J, A0, B0, ka, kb)
    return local if local is not None else follow(J, _local(op, covariant, J, ka, kb), A0, B0, anchor_arg=True)


def meet(A, B, tol: float = 1e-10) -> Multivector:
    """Meet ``A ∩ B = (B _| J^-1) _| A`` of two blades in OPNS (dual) form, J = ``join(A, B)`` (DFM 5.3).

    In general position (J the whole space) this is ``(B _| Ic^-1) _| A`` = ``regressive_product(B, A)``, with the
    weight fixed by the unit pseudoscalar; its standard form is, up to sign, the outer product of the standard
    forms of (2.79) and table 2.1 (:func:`cga_lessons.conformal.blades_classify.intersect` fixes the sign).  Otherwise J
    comes from :func:`join` (two coplanar lines meet in a flat point, a line in its plane meets it in the line
    itself); when J is a null blade (tangents at one point) the same formula runs in the Euclidean metric, which
    gives the same subspace.

    Nothing is refused for geometric reasons: parallel planes meet in a line at infinity (a free bivector
    ``einf ^ B``, which :func:`cga_lessons.conformal.blades_classify.classify` reports as a "direction"), skew lines
    in a multiple of ``einf``, a sphere and a line that miss each other in an imaginary point pair, blades with no
    common subspace in a scalar.

    Anchored blades (:mod:`~cga_lessons.conformal.anchored`) give an anchored meet, exact far from the origin: its
    local blade is the same meet of the local blades, scaled to the global one where the join's weight depends on
    the frame.  Which case applies is decided on the local blades (the second moved into the first's frame): 1e5
    out or more the global coefficients of two unit spheres are one subspace to the default ``tol`` (a plain
    blade's meet is there of grade 4), their local blades are not.  Where both decide the same grade the global
    coefficients are the plain meet's, bit for bit; where they differ, the local blade translated back by the
    anchor (:func:`_decided_locally`).

    >>> from cga_lessons import conformal as cga
    >>> L = cga.line_from_points([0, 0, 0], [0, 0, 1])            # the z axis
    >>> P = cga.plane_from_points([0, 0, 2], [1, 0, 2], [0, 1, 2])  # z = 2
    >>> F = meet(L, P)                                            # the flat point einf ^ up([0, 0, 2]), weighted
    >>> (cga.up([0, 0, 2]) ^ F).iszero(1e-12), F.grades_present()
    (True, [2])
    """
    tol = relative_tolerance(tol, "meet")
    A0, B0 = A, B
    A, ka = require_blade(A, "meet", "A")
    B, kb = require_blade(B, "meet", "B")
    M, covariant = _meet(A, ka, B, kb, tol)
    if covariant == "regressive":
        M = result_finite(M, "meet", A=A, B=B)
    else:
        M = single_multivector(result_finite(M, "meet", A=A, B=B), "meet", "A, B")
    op = lambda a, ka, b, kb: _meet(a, ka, b, kb, tol)  # noqa: E731
    local = _decided_locally(op, M, A0, B0, ka, kb)
    return local if local is not None else follow(M, _local(op, covariant, M, ka, kb), A0, B0, anchor_arg=True)


def _meet(A, ka, B, kb, tol):
    """``(M, covariant)``: the meet of :func:`meet` and how it was made: ``"regressive"`` (the join is the whole
    space), True (a covariant join, non-null), False (a join weighted in the coefficient space, or a null join
    taken in the Euclidean metric: the weight depends on the frame)."""
    J, covariant = _join_covariant(A, ka, B, kb, tol)
    if J.grades_present() == [5]:
        return ((B * _IC_INV) ^ (A * _IC_INV)) * Ic, "regressive"
    JJ = float((J * ~J).scalar())
    if abs(JJ) > tol * coefficient_norm(J) ** 2:
        return _left_contraction(_left_contraction(B, ~J * (1.0 / JJ)), A), covariant
    # a null join: the subspace is metric-free, take it in the Euclidean metric
    AE, BE, JE = (Multivector(_E5, dict(X.coeffs)) for X in (A, B, J))
    return Multivector(G41, dict(((BE << JE.inv()) << AE).coeffs)), False


def _invertible(B, func: str):
    B, _ = require_blade(B, func, "B")
    BB = float((B * ~B).scalar())
    if abs(BB) <= 1e-12 * coefficient_norm(B) ** 2:
        raise DegenerateGeometryError(f"{func}: B: is a null blade (B ~B = 0), it has no inverse to project with")
    return B, ~B * (1.0 / BB)


def project(A, B) -> Multivector:
    """Orthogonal projection ``P_B[A] = (A _| B) B^-1`` of a blade onto an invertible blade (DFM 3.6).

    The thesis's ``P_E(a) = (a . E) E`` (2.58) is the case B = E (``E^-1 = E``).  Raises for a null B (a point,
    a tangent), which has no inverse (2.19).

    >>> from cga_lessons import conformal as cga
    >>> project(cga.e1 + 2 * cga.e2 + 3 * cga.ep, cga.E)  # P_E keeps the Minkowski plane, (2.58)
    3 e+
    """
    A0, B0 = A, B
    A, _ = require_blade(A, "project", "A")
    B, Binv = _invertible(B, "project")
    out = result_finite(_left_contraction(A, B) * Binv, "project", A=A, B=B)
    return follow(out, lambda a, b: _lc(a, b) * _blade_inverse(b), A0, B0)


def _blade_inverse(b) -> Multivector:
    """``~B / (B ~B)`` (2.19) of a local blade (or a number)."""
    b = _as_mv(b)
    return ~b * (1.0 / float((b * ~b).scalar()))


def reject(A, B) -> Multivector:
    """Rejection ``(A ^ B) B^-1`` of a blade by an invertible blade (DFM 3.6; the thesis's 2.59 for B = E).

    For a vector A this is ``A - project(A, B)``, the part orthogonal to B.  For a k-blade it is the blade of
    A's components orthogonal to B, zero when A and B share a direction.

    >>> from cga_lessons import conformal as cga
    >>> reject(cga.e1 + 2 * cga.e2 + 3 * cga.ep, cga.E)  # P_E^perp(a) = (a ^ E) E, (2.59)
    1 e1 + 2 e2
    """
    A0, B0 = A, B
    A, _ = require_blade(A, "reject", "A")
    B, Binv = _invertible(B, "reject")
    out = result_finite((A ^ B) * Binv, "reject", A=A, B=B)
    return follow(out, lambda a, b: (_as_mv(a) ^ _as_mv(b)) * _blade_inverse(b), A0, B0)


def is_versor(V, tol: float = 1e-9) -> bool:
    """True when V is a versor: ``V ~V`` a non-zero scalar and ``x -> V x V^-1`` keeps every vector a vector.

    A versor is a geometric product of invertible vectors (2.82; DFM ch. 7, ch. 21); it has one parity and acts on
    each basis vector ``e_i`` as ``V e_i ~V / (V ~V)``, a vector.  Every test is relative to ``|V|^2`` (the
    coefficient norm squared), so the answer does not depend on the scale of V.

    >>> from cga_lessons import conformal as cga
    >>> T = cga.translator([1.0, 0.0, 0.0])   # T = 1 + e t / 2, (2.100)
    >>> is_versor(T), is_versor(cga.up([1, 0, 0])), is_versor(1 + cga.e1)
    (True, False, False)
    """
    tol = relative_tolerance(tol, "is_versor")
    V = single_multivector(V, "is_versor", "V")
    scale2 = coefficient_norm(V) ** 2
    if scale2 == 0.0 or min(coefficient_norm(V.even()), coefficient_norm(V.odd())) > tol * math.sqrt(scale2):
        return False
    N = V * ~V
    if abs(N.scalar()) <= tol * scale2 or coefficient_norm(N - N.scalar()) > tol * scale2:
        return False
    for i in range(5):
        W = V * Multivector(G41, {1 << i: 1.0}) * ~V
        if coefficient_norm(W - W.grade(1)) > tol * scale2:
            return False
    return True
