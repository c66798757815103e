"""Blades of G(4,1) and the subspaces they span: the test that a multivector is a blade, and its factorisation.

A homogeneous multivector A of grade k is a blade when ``x ^ A = 0`` has k independent solutions (DFM ch. 21,
Dorst, Fontijne & Mann 2007); those solutions span its subspace, and an orthonormal basis of them factorises A.
:func:`require_blade` is the check the operations of :mod:`cga_lessons.conformal.blades` (join, meet, projection)
run on their arguments; :func:`blade_span` and :func:`wedge_columns` are the linear algebra behind join and meet.

Every function takes single multivectors of G(4,1) with real coefficients (no batches, no SymPy) and raises
:class:`InvalidInputError` or :class:`DegenerateGeometryError` (both ``ValueError``) with a message
``"function: argument: problem"``.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError, Multivector

from .model import G41
from .multivector_checks import multivector

__all__ = ["require_blade", "is_blade", "blade_factors"]


def coefficient_norm(X: Multivector) -> float:
    """Euclidean norm of the coefficient vector (a size, not a metric quantity)."""
    return math.hypot(*X.coeffs.values())  # no overflow for coefficients beyond 1e154


def single_multivector(X, func: str, name: str) -> Multivector:
    """A float copy of a single numeric multivector of G(4,1) (a real number is a scalar); raises on anything else
    (:func:`~cga_lessons.conformal.versors_rigid.multivector`, the package's check of a multivector)."""
    if isinstance(X, numbers.Real) and not isinstance(X, (bool, np.bool_)):
        X = Multivector(G41, {0: checks.real(X, func, name)})
    X = multivector(X, func, name, what="a Multivector of G(4,1)", single=True, numeric=True, nonzero=False)
    return Multivector(G41, {b: float(v) for b, v in X.coeffs.items() if v != 0})


def relative_tolerance(tol, func: str, name: str = "tol") -> float:
    """A relative tolerance: a real number in [0, 1)."""
    return checks.real(tol, func, name, low=0.0, high=1.0, strict_high=True)


def homogeneous_grade(X: Multivector, func: str, name: str, tol: float) -> tuple[Multivector, int]:
    """(X reduced to its grade, grade); grades below ``tol |X|`` are round-off and are dropped."""
    scale = coefficient_norm(X)
    if scale == 0.0:
        raise DegenerateGeometryError(f"{func}: {name}: is zero (it spans no subspace)")
    big = [g for g in X.grades_present() if coefficient_norm(X.grade(g)) > tol * scale]
    if len(big) != 1:
        raise InvalidInputError(f"{func}: {name}: not a blade (mixed grades {big})")
    return X.grade(big[0]), big[0]


def blade_span(A: Multivector, k: int) -> tuple[np.ndarray, float, float]:
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
    F = wedge_columns(U)
    lam = sum(v * F.coeffs.get(b, 0.0) for b, v in A.coeffs.items())  # |F| = 1 (Cauchy-Binet)
    return U, lam, coefficient_norm(A - lam * F) / coefficient_norm(A)


def wedge_columns(U: np.ndarray) -> Multivector:
    """The outer product of the columns of U (vectors of G(4,1)), 1 for none."""
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
    tol = relative_tolerance(tol, func)
    A, k = homogeneous_grade(single_multivector(A, func, name), func, name, tol)
    if k in (2, 3):
        res = blade_span(A, k)[2]
        if res > tol:
            raise InvalidInputError(f"{func}: {name}: not a blade (x ^ A = 0 has fewer than {k} independent solutions)")
    return A, k


def is_blade(A, tol: float = 1e-6) -> bool:
    """True when A is a non-zero blade: one grade k and ``x ^ A = 0`` solved by k independent vectors (DFM ch. 21).

    ``tol`` is relative to the coefficient norm of A: grades below it are round-off, and a grade-2 or grade-3 A is
    a blade when it is that close to its best factorisation.  Points, point pairs and circles are blades even when
    they are null (tangents): the test does not use the metric.

    >>> from cga_lessons import conformal as cga
    >>> is_blade(cga.up([1, 2, 3]) ^ cga.up([0, 1, 0])), is_blade(cga.e1 * cga.e2 + cga.e3 * cga.ep)
    (True, False)
    """
    tol = relative_tolerance(tol, "is_blade")
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
    U, lam, _ = blade_span(A, k)
    vecs = [G41.vector(U[:, j]) for j in range(k)]
    return [lam * vecs[0], *vecs[1:]]
