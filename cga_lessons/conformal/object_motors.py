"""The versor that takes one geometric object onto another (lines, planes, spheres, circles, point pairs).

For two blades X and Y of one grade, scaled so that ``X^2 = Y^2 = s`` with
``s = +1`` or ``-1``, the element ``1 + s Y X`` maps X onto Y up to scale:
``(1 + s Y X) X = X + s Y X^2 = X + Y`` and ``Y (1 + s Y X) = Y + X``,
so ``(1 + s Y X) X = Y (1 + s Y X)``.  Its norm
``K = (1 + s Y X)(1 + s X Y) = 2 + s (X Y + Y X)`` is a scalar plus a
4-vector, which commutes with ``Y X``; dividing by its square root,
``V = (1 + s Y X) K^{-1/2}``, gives ``V ~V = 1`` and ``V X ~V = Y``
(Lasenby, Hadfield & Lasenby 2019, "Calculating the rotor between conformal
objects", Adv. Appl. Clifford Algebras 29:102).  The square root of
``K = a + b`` (``a`` scalar, ``b`` a 4-vector with ``b^2 = beta`` a scalar) is
``p + q b`` with ``p^2 = (a + lam)/2``, ``q = 1/(2p)``, ``lam = sqrt(a^2 - beta)``,
and its inverse ``(p - q b)/lam``.

Between two flats (lines, planes) this element is a motor: the rigid motion
that turns about and slides along the screw taking one onto the other, as in
(2.110).  Between two rounds it is a conformal map but in general not a rigid
one (it is the product of the two rounds' inversions), so rounds are taken
through their carriers: a circle's plane and a point pair's line (``X ^ e``)
are brought together by the formula, then the centre (``X e X``, the round's
reflection of the point at infinity) is slid onto the other's; spheres are
simply translated centre to centre.  Rounds of different radii have no rigid
motion between them.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, GeometryError, InvalidInputError, Multivector

from .blades_classify import classify
from .model import einf
from .multivector_checks import multivector, mv_is_finite, result_finite
from .points import down
from .versors import apply
from .versors_build import translator

__all__ = ["motor_between"]

_TOL = 1e-9  # relative size of round-off taken as zero in the checks


def _scalar_square(X: Multivector, func: str, name: str) -> float:
    multivector(X, func, name, what="an object of G(4,1) (Multivector)", single=True, numeric=True)
    vals = [float(v) for v in X.coeffs.values()]
    grades = X.grades_present()
    if len(grades) != 1 or grades[0] in (0, 5):
        raise InvalidInputError(f"{func}: {name}: expected a blade of grade 1 to 4 (an object), got grades {grades}")
    sq = X * X
    size = sum(v * v for v in vals)
    if not math.isfinite(size) or not mv_is_finite(sq):
        raise InvalidInputError(f"{func}: {name}: its coefficients are too large: their squares overflow a float")
    other = max((abs(float(v)) for b, v in sq.coeffs.items() if b != 0), default=0.0)
    s = float(sq.scalar())
    if other > 1e-6 * max(size, abs(s)):
        raise InvalidInputError(f"{func}: {name}: its square is not a scalar: not a blade (an object)")
    if abs(s) <= _TOL * size:
        raise DegenerateGeometryError(
            f"{func}: {name}: a null object (a point, a tangent or a flat point) has no size to match; "
            "between points use the translator of their positions"
        )
    return s


def _flat_versor(X: Multivector, Y: Multivector, sx: float, sy: float, func: str) -> Multivector:
    """``(1 + s Y X) K^{-1/2}`` for blades of one grade scaled to squares ``sx``, ``sy`` of one sign."""
    s = 1.0 if sx > 0 else -1.0
    Xn, Yn = X * (1.0 / math.sqrt(abs(sx))), Y * (1.0 / math.sqrt(abs(sy)))
    if float((Xn * Yn).scalar()) * s < 0:  # the shorter turn: Y with the orientation nearer X's
        Yn = -Yn
    N = 1.0 + (Yn * Xn) * s
    K = (N * ~N).grade(0, 4)
    a = float(K.scalar())
    b = K.grade(4)
    beta = float((b * b).scalar())
    disc = a * a - beta
    if a <= _TOL or disc <= (_TOL * max(a, 1.0)) ** 2:
        raise DegenerateGeometryError(f"{func}: Y: X and Y are opposite (no unique versor between them)")
    lam = math.sqrt(disc)
    p = math.sqrt((a + lam) / 2.0)
    q = 1.0 / (2.0 * p)
    return (N * ((b * (-q) + p) * (1.0 / lam))).grade(0, 2, 4)


def _centre(X: Multivector) -> np.ndarray:
    """The centre of a round: the point ``X e X`` (the round reflects the point at infinity onto its centre)."""
    return down((X * einf * X).grade(1))


def motor_between(X: Multivector, Y: Multivector) -> Multivector:
    """A motor M with ``M X ~M = Y`` (up to scale): two lines, two planes, equal circles, spheres or point pairs.

    X and Y are blades of one grade in one form (as the constructors of
    :mod:`cga_lessons.conformal.entities` return them), both real or both imaginary
    (their squares of one sign).  Their scale and orientation are matched
    first: Y is taken with the sign that makes the turn shortest (``-Y`` is
    the same object, oppositely oriented).  Flats by the formula of the
    module docstring, rounds through their carriers and centres.  The
    motion is not unique where the objects are symmetric (a sphere turned
    about its centre, a line slid along itself); the one returned is the
    shortest screw between the flats, then the shortest slide.

    >>> import numpy as np
    >>> from cga_lessons import conformal as cga
    >>> L1 = cga.line_from_points([0, 0, 0], [1, 0, 0])  # the x axis
    >>> L2 = cga.line_from_points([0, 0, 1], [0, 1, 1])  # a line along y, 1 m up
    >>> V = motor_between(L1, L2)
    >>> bool(cga.apply(V, L1).isclose(L2 * float(np.sqrt((L1 * L1).scalar() / (L2 * L2).scalar()))))
    True
    >>> cga.apply_to_points(V, [0.0, 0.0, 0.0]).round(6) + 0.0  # the origin goes to the common perpendicular's foot
    array([0., 0., 1.])

    Raises
    ------
    InvalidInputError
        Not objects of G(4,1), batches, NaN/inf, different grades or kinds,
        squares of different sign (a real and an imaginary round).
    DegenerateGeometryError
        Null objects (points, tangents), rounds of different radii, or flats
        exactly opposite (no unique turn: K has no square root).
    """
    func = "motor_between"
    try:
        V = _motor_between(X, Y, func)
    except GeometryError as exc:
        if str(exc).startswith(f"{func}:"):
            raise
        with checks.relabel(func, "X, Y"):  # a product of the inputs out of float range
            raise exc
    return result_finite(V, func, X=X, Y=Y)


def _motor_between(X, Y, func: str) -> Multivector:
    sx, sy = _scalar_square(X, func, "X"), _scalar_square(Y, func, "Y")
    if X.grades_present() != Y.grades_present():
        raise InvalidInputError(f"{func}: Y: grade {Y.grades_present()} differs from X's {X.grades_present()}")
    if (sx > 0) != (sy > 0):
        raise InvalidInputError(f"{func}: Y: X squares to {sx:.3g} and Y to {sy:.3g}: a real and an imaginary object")
    kx, ky = classify(X), classify(Y)
    if (kx.kind, kx.dimension) != (ky.kind, ky.dimension):
        raise InvalidInputError(f"{func}: Y: a {ky.name}, X a {kx.name}: no motion takes one onto the other")
    if kx.kind == "flat":
        return _flat_versor(X, Y, sx, sy, func)
    if kx.kind != "round":
        raise InvalidInputError(f"{func}: X: a {kx.name}; lines, planes, point pairs, circles and spheres only")
    r1, r2 = kx.radius2, ky.radius2
    if abs(r1 - r2) > 1e-9 * max(abs(r1), abs(r2)):
        raise DegenerateGeometryError(
            f"{func}: Y: radius^2 {r2:.6g} differs from X's {r1:.6g}: no rigid motion between rounds of "
            "different sizes (cga.dilator scales)"
        )
    if kx.dimension == 2:  # spheres: centre to centre
        return translator(_centre(Y) - _centre(X))
    cx, cy = X ^ einf, Y ^ einf  # the carriers: a circle's plane, a point pair's line
    V = _flat_versor(cx, cy, float((cx * cx).scalar()), float((cy * cy).scalar()), func)
    return translator(_centre(Y) - _centre(apply(V, X))) * V
