"""Grade projection, the involutions and the dual of a multivector (2.16-2.18, 2.31-2.35).

``<M>_k`` (:func:`grade`), the even and odd parts, the reverse ``~M`` (2.32-2.33), the grade involution (2.35), the
Clifford conjugate, and the dual ``M* = M I^-1`` (2.31) with its inverse.  Plain functions of a multivector X, each
one of the methods of :class:`~cga_lessons.algebra.multivector.Multivector` (``~X`` is :func:`reverse`,
``X.grade(2)`` :func:`grade`, ...).
"""

from __future__ import annotations

from cga_lessons.checks import integer

from .operands import finite_out


def _same_kind(X, coeffs: dict):
    """A multivector of X's type and algebra holding ``coeffs`` as they are (already pruned: no checks, no copy)."""
    m = object.__new__(type(X))
    m.algebra = X.algebra
    m._c = coeffs
    return m


def reverse(X):
    """Reverse (2.32-2.33): grade k gets the sign (-1)^(k(k-1)/2)."""
    flip = X.algebra._rev_flip
    return _same_kind(X, {b: (-v if flip[b] else v) for b, v in X._c.items()})


def involute(X):
    """Grade involution (2.35): grade k gets the sign (-1)^k."""
    g = X.algebra.grades
    return type(X)(X.algebra, {b: (-v if g[b] & 1 else v) for b, v in X._c.items()})


def conjugate(X):
    """Clifford conjugate: reverse of the grade involution."""
    return involute(reverse(X))


def grade(X, *ks):
    """Grade projection <M>_k (2.18); several grades give their sum (zero above the dimension)."""
    alg = X.algebra
    for k in ks:
        if type(k) is not int or k < 0:  # a grade above the dimension is allowed: its part is zero
            integer(k, "Multivector.grade", "k", low=0)
    g = alg.grades
    return type(X)(alg, {b: v for b, v in X._c.items() if g[b] in ks})


def even(X):
    """Even part (2.16)."""
    g = X.algebra.grades
    return type(X)(X.algebra, {b: v for b, v in X._c.items() if g[b] % 2 == 0})


def odd(X):
    """Odd part (2.17)."""
    g = X.algebra.grades
    return type(X)(X.algebra, {b: v for b, v in X._c.items() if g[b] % 2 == 1})


def dual(X):
    """Dual M* = M I^-1 (2.31)."""
    alg = X.algebra
    return finite_out(alg._products.product(X, alg.pseudoscalar().inv(), "gp"), "Multivector.dual", "self")


def undual(X):
    """Inverse of :func:`dual`: M I."""
    alg = X.algebra
    return finite_out(alg._products.product(X, alg.pseudoscalar(), "gp"), "Multivector.undual", "self")
