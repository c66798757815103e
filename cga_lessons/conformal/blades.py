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
* blade and versor tests, blade factorisation (DFM ch. 21).

Every function takes single multivectors of G(4,1) with real coefficients (no batches, no SymPy) and raises
:class:`InvalidInputError` or :class:`DegenerateGeometryError` (both ``ValueError``) with a message
``"function: argument: problem"``.  Blades are read in OPNS ("dual form" in the thesis's words: the outer product of
points, 2.75-2.81); :mod:`cga_lessons.conformal.blades_classify` handles the standard (IPNS) forms and names what a
blade is.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Algebra, DegenerateGeometryError, InvalidInputError, Multivector

from .model import G41, Ic
from .multivector_checks import multivector, result_finite

__all__ = [
    "require_blade",
    "left_contraction",
    "right_contraction",
    "scalar_product",
    "dual",
    "undual",
    "regressive_product",
    "is_blade",
    "blade_factors",
    "join",
    "meet",
    "project",
    "reject",
    "is_versor",
]

_IC_INV = Ic.inv()  # -Ic exactly: Ic^2 = -1
_E5 = Algebra(5)  # the Euclidean metric on the same coefficients: join and meet are metric-free (DFM ch. 5)


def _norm(X: Multivector) -> float:
    """Euclidean norm of the coefficient vector (a size, not a metric quantity)."""
    return math.hypot(*X.coeffs.values())  # no overflow for coefficients beyond 1e154


def _check(X, func: str, name: str) -> Multivector:
    """A float copy of a single numeric multivector of G(4,1) (a real number is a scalar); raises on anything else
    (:func:`~cga_lessons.conformal.versors_rigid.multivector`, the package's check of a multivector)."""
    if isinstance(X, numbers.Real) and not isinstance(X, (bool, np.bool_)):
        X = Multivector(G41, {0: checks.real(X, func, name)})
    X = multivector(X, func, name, what="a Multivector of G(4,1)", single=True, numeric=True, nonzero=False)
    return Multivector(G41, {b: float(v) for b, v in X.coeffs.items() if v != 0})


def _tol(tol, func: str, name: str = "tol") -> float:
    """A relative tolerance: a real number in [0, 1)."""
    return checks.real(tol, func, name, low=0.0, high=1.0, strict_high=True)


def _homogeneous_grade(X: Multivector, func: str, name: str, tol: float) -> tuple[Multivector, int]:
    """(X reduced to its grade, grade); grades below ``tol |X|`` are round-off and are dropped."""
    scale = _norm(X)
    if scale == 0.0:
        raise DegenerateGeometryError(f"{func}: {name}: is zero (it spans no subspace)")
    big = [g for g in X.grades_present() if _norm(X.grade(g)) > tol * scale]
    if len(big) != 1:
        raise InvalidInputError(f"{func}: {name}: not a blade (mixed grades {big})")
    return X.grade(big[0]), big[0]


def _span(A: Multivector, k: int) -> tuple[np.ndarray, float, float]:
    """(U, lam, residual): U (5, k) orthonormal, A ~ lam u1 ^ ... ^ uk, residual |A - lam U| / |A|.

    The span of a k-blade is the null space of x -> x ^ A; for a non-blade that map has fewer than k null
    directions and the residual shows it.
    """
    if k == 5:
        return np.eye(5), A["e123+-"], 0.0
    rows = G41.grade_blades[k + 1]
    M = np.zeros((len(rows), 5))
    for i in range(5):
        W = Multivector(G41, {1 << i: 1.0}) ^ A
        M[:, i] = [W.coeffs.get(b, 0.0) for b in rows]
    U = np.linalg.svd(M)[2][5 - k :].T
    F = _wedge(U)
    lam = sum(v * F.coeffs.get(b, 0.0) for b, v in A.coeffs.items())  # |F| = 1 (Cauchy-Binet)
    return U, lam, _norm(A - lam * F) / _norm(A)


def _wedge(U: np.ndarray) -> Multivector:
    out = Multivector(G41, {0: 1.0})
    for j in range(U.shape[1]):
        out = out ^ G41.vector(U[:, j])
    return out


def require_blade(A, func: str = "require_blade", name: str = "A", tol: float = 1e-6) -> tuple[Multivector, int]:
    """Check that A is a non-zero blade of G(4,1); return ``(A as floats, grade)``.

    The checking layer of this module, public so that other modules can use it.  A homogeneous multivector is a
    blade when ``x ^ A = 0`` has as many independent solutions as its grade (DFM ch. 21); grades 0, 1, 4, 5 always are.
    ``tol`` is relative to the coefficient norm: smaller grades are round-off and dropped, and a grade-2 or 3 A
    may be that far from its factorisation.  The default 1e-6 is loose on purpose: a circle of unit size built from
    floats at distance D from the origin is a blade only to about 2e-12 at D = 100 m, 1e-9 at 1 km, 1e-6 at 10 km.

    >>> from cga_lessons import conformal as cga
    >>> require_blade(cga.line_from_points([0, 0, 0], [1, 0, 0]))[1]
    3
    >>> require_blade(cga.e1 * cga.e2 + cga.e3 * cga.ep, "meet", "A")
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: meet: A: not a blade (x ^ A = 0 has fewer than 2 independent solutions)
    """
    checks.text(func, "require_blade", "func")
    checks.text(name, "require_blade", "name")
    tol = _tol(tol, func)
    A, k = _homogeneous_grade(_check(A, func, name), func, name, tol)
    if k in (2, 3):
        res = _span(A, k)[2]
        if res > tol:
            raise InvalidInputError(f"{func}: {name}: not a blade (x ^ A = 0 has fewer than {k} independent solutions)")
    return A, k


def left_contraction(A, B) -> Multivector:
    """Left contraction ``A _| B = sum_{r,s} <A_r B_s>_{s-r}``, zero where ``s < r`` (DFM 3.2-3.4, 6.3).

    Unlike the thesis's inner product (2.29), ``<A_r B_s>_|r-s|`` with ``scalar . M = 0`` (2.28), it keeps scalars
    (``a _| B = a B``) and vanishes when A has the higher grade.  Same as ``A << B`` of :mod:`cga_lessons.algebra`.

    >>> from cga_lessons import conformal as cga
    >>> left_contraction(cga.e1, cga.e1 ^ cga.e2), left_contraction(cga.e1 ^ cga.e2, cga.e1)
    (1 e2, 0)
    """
    A, B = _check(A, "left_contraction", "A"), _check(B, "left_contraction", "B")
    return result_finite(_left_contraction(A, B), "left_contraction", A=A, B=B)


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
    A, B = _check(A, "right_contraction", "A"), _check(B, "right_contraction", "B")
    return result_finite(~_left_contraction(~B, ~A), "right_contraction", A=A, B=B)


def scalar_product(A, B) -> float:
    """Scalar product ``A * B = <A B>_0`` as a float (DFM 3.1); for points ``-|a - b|^2 / 2`` (2.66).

    >>> from cga_lessons import conformal as cga
    >>> scalar_product(cga.up([0, 0, 0]), cga.up([3, 4, 0]))
    -12.5
    """
    A, B = _check(A, "scalar_product", "A"), _check(B, "scalar_product", "B")
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
    return _check(A, "dual", "A") * _IC_INV  # a signed permutation of the coefficients: finite


def undual(A) -> Multivector:
    """Undual ``A Ic``, the inverse of :func:`dual`; the thesis's standard form of a dual-form entity (2.31).

    >>> from cga_lessons import conformal as cga
    >>> undual(dual(cga.e1 ^ cga.e2))
    1 e12
    """
    return _check(A, "undual", "A") * Ic


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
    A, B = _check(A, "regressive_product", "A"), _check(B, "regressive_product", "B")
    return result_finite(((A * _IC_INV) ^ (B * _IC_INV)) * Ic, "regressive_product", A=A, B=B)


def is_blade(A, tol: float = 1e-6) -> bool:
    """True when A is a non-zero blade: one grade k and ``x ^ A = 0`` solved by k independent vectors (DFM ch. 21).

    ``tol`` is relative to the coefficient norm of A: grades below it are round-off, and a grade-2 or grade-3 A is
    a blade when it is that close to its best factorisation.  Points, point pairs and circles are blades even when
    they are null (tangents): the test does not use the metric.

    >>> from cga_lessons import conformal as cga
    >>> is_blade(cga.up([1, 2, 3]) ^ cga.up([0, 1, 0])), is_blade(cga.e1 * cga.e2 + cga.e3 * cga.ep)
    (True, False)
    """
    tol = _tol(tol, "is_blade")
    try:
        require_blade(A, "is_blade", "A", tol)
    except DegenerateGeometryError:
        return False
    except InvalidInputError as exc:
        if "not a blade" in str(exc):
            return False
        raise
    return True


def blade_factors(A, tol: float = 1e-6) -> list[Multivector]:
    """k vectors whose outer product is the k-blade A (DFM ch. 21, outer factorisation).

    The span of A is the null space of the linear map ``x -> x ^ A`` (an SVD of its 5 x C(5, k+1) matrix); its
    Euclidean-orthonormal basis ``u1 ... uk`` gives ``A = lam u1 ^ ... ^ uk`` and the factors are
    ``lam u1, u2, ..., uk``.  Raises for a scalar (no vector factors) and for a non-blade.

    >>> from cga_lessons import conformal as cga
    >>> A = cga.line_from_points([0, 0, 0], [1, 1, 0])
    >>> f = blade_factors(A)
    >>> len(f), ((f[0] ^ f[1] ^ f[2]) - A).iszero(1e-12)
    (3, True)
    """
    A, k = require_blade(A, "blade_factors", "A", tol)
    if k == 0:
        raise InvalidInputError("blade_factors: A: a scalar has no vector factors")
    U, lam, _ = _span(A, k)
    vecs = [G41.vector(U[:, j]) for j in range(k)]
    return [lam * vecs[0], *vecs[1:]]


def _join(A, ka, B, kb, tol):
    if ka == 0 or kb == 0:
        return B if ka == 0 else A
    UA, UB = _span(A, ka)[0], _span(B, kb)[0]
    R = UB - UA @ (UA.T @ UB)  # the part of span(B) outside span(A)
    u, s, _ = np.linalg.svd(R)
    m = int(np.sum(s > tol))
    if m == kb:
        return A ^ B
    return A ^ _wedge(u[:, :m]) if m else A


def join(A, B, tol: float = 1e-10) -> Multivector:
    """Join ``A ∪ B``: a blade of the smallest subspace that contains both blades (DFM 5.1-5.3, ch. 21).

    When the spans are disjoint this is ``A ^ B``.  Otherwise it is ``A ^ c1 ^ ... ^ cm`` with ``c`` a
    Euclidean-orthonormal basis of the part of span(B) outside span(A); its weight is then that of A (the join
    has no canonical weight).  ``tol`` bounds the sines of the principal angles counted as zero.  The join does
    not use the metric; a scalar joins to the other argument.

    >>> from cga_lessons import conformal as cga
    >>> L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])
    >>> L2 = cga.line_from_points([0, 1, 0], [1, 1, 0])  # parallel: both lie in the plane z = 0
    >>> J = join(L1, L2)
    >>> J.grades_present(), (cga.up([5, -3, 0]) ^ J).iszero(1e-9)
    ([4], True)
    """
    tol = _tol(tol, "join")
    A, ka = require_blade(A, "join", "A")
    B, kb = require_blade(B, "join", "B")
    return result_finite(_join(A, ka, B, kb, tol), "join", A=A, B=B)


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

    >>> from cga_lessons import conformal as cga
    >>> L = cga.line_from_points([0, 0, 0], [0, 0, 1])            # the z axis
    >>> P = cga.plane_from_points([0, 0, 2], [1, 0, 2], [0, 1, 2])  # z = 2
    >>> F = meet(L, P)                                            # the flat point einf ^ up([0, 0, 2]), weighted
    >>> (cga.up([0, 0, 2]) ^ F).iszero(1e-12), F.grades_present()
    (True, [2])
    """
    tol = _tol(tol, "meet")
    A, ka = require_blade(A, "meet", "A")
    B, kb = require_blade(B, "meet", "B")
    J = _join(A, ka, B, kb, tol)
    if J.grades_present() == [5]:
        return result_finite(((B * _IC_INV) ^ (A * _IC_INV)) * Ic, "meet", A=A, B=B)
    JJ = float((J * ~J).scalar())
    if abs(JJ) > tol * _norm(J) ** 2:
        M = _left_contraction(_left_contraction(B, ~J * (1.0 / JJ)), A)
    else:  # a null join: the subspace is metric-free, take it in the Euclidean metric
        AE, BE, JE = (Multivector(_E5, dict(X.coeffs)) for X in (A, B, J))
        M = Multivector(G41, dict(((BE << JE.inv()) << AE).coeffs))
    return _check(result_finite(M, "meet", A=A, B=B), "meet", "A, B")


def _invertible(B, func: str):
    B, _ = require_blade(B, func, "B")
    BB = float((B * ~B).scalar())
    if abs(BB) <= 1e-12 * _norm(B) ** 2:
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
    A, _ = require_blade(A, "project", "A")
    B, Binv = _invertible(B, "project")
    return result_finite(_left_contraction(A, B) * Binv, "project", A=A, B=B)


def reject(A, B) -> Multivector:
    """Rejection ``(A ^ B) B^-1`` of a blade by an invertible blade (DFM 3.6; the thesis's 2.59 for B = E).

    For a vector A this is ``A - project(A, B)``, the part orthogonal to B.  For a k-blade it is the blade of
    A's components orthogonal to B, zero when A and B share a direction.

    >>> from cga_lessons import conformal as cga
    >>> reject(cga.e1 + 2 * cga.e2 + 3 * cga.ep, cga.E)  # P_E^perp(a) = (a ^ E) E, (2.59)
    1 e1 + 2 e2
    """
    A, _ = require_blade(A, "reject", "A")
    B, Binv = _invertible(B, "reject")
    return result_finite((A ^ B) * Binv, "reject", A=A, B=B)


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
    tol = _tol(tol, "is_versor")
    V = _check(V, "is_versor", "V")
    scale2 = _norm(V) ** 2
    if scale2 == 0.0 or min(_norm(V.even()), _norm(V.odd())) > tol * math.sqrt(scale2):
        return False
    N = V * ~V
    if abs(N.scalar()) <= tol * scale2 or _norm(N - N.scalar()) > tol * scale2:
        return False
    for i in range(5):
        W = V * Multivector(G41, {1 << i: 1.0}) * ~V
        if _norm(W - W.grade(1)) > tol * scale2:
            return False
    return True
