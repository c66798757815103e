"""Similarities by their factors: a dilation (the dilator, not numbered in the thesis: Dorst, Fontijne & Mann 2007,
ch. 16), its products with a motor (2.102) or a reflection in a plane (2.89-2.91), and the odd isometries (a plane,
or its product with a motor): read off the coefficients, applied factor by factor, and anchored entities moved with
their frames.  Used by :func:`~cga_lessons.conformal.apply` and :func:`~cga_lessons.conformal.apply_to_points`.

**Reading them** (:func:`similarity_factors`, :func:`similarity`, :func:`similar`).  A versor that fixes the point
at infinity (Y = 0) and is no motor is ``V = T_t U D_s`` with U a Euclidean versor (a rotor, or odd: a reflection
in a plane through the origin, 2.90) and ``D_s = a - b E_pm`` the dilator (:func:`~cga_lessons.conformal.dilator`;
not numbered in the thesis, see Dorst, Fontijne & Mann 2007, ch. 16), ``s = (a + b) / (a - b)``: with the split
``V = E + Xe e + Y e0 + D E_pm`` of :mod:`~cga_lessons.conformal.anchored_versors` its parts are ``E = a U``,
``D = -b U`` and ``Xe = (a - b) t U / 2``, its point map ``x -> s R x + t`` (R that of U).  So ``rho = b / a``
is ``-<D ~E>_0 / <E ~E>_0``, ``V (1 + rho E_pm)`` is ``T_t U`` times a number, read linearly by
:meth:`~cga_lessons.algebra.Algebra.rigid_motion` (2.141-2.144), and since ``D_s T_f = T_{s f} D_s``,
``T_{-f'} V T_f = U D_s`` with ``f' = s R f + t``: the anchor goes to f' and the local blade is ``W L^ W^-1``,
``W = U (1 - rho E_pm)``, coefficients of the size of U (never products of the global ones).  An odd isometry is
the case rho = 0: ``V e1`` is a motor (2.90, 2.102).

**Applying them** (:func:`similarity_product`).  The product tables of
:meth:`~cga_lessons.algebra.Algebra.versor_matrices` sum ``V ~V`` from the squared coefficients, round-off
``eps |V|^2``: for a dilation times a reflection in a plane 1e6 out (e+ and e- coefficients near 3e6) that is
~4e-3 of ``V ~V = 1``, and the affine part of its matrix, tested for an isometry with a tolerance of the size of
its ``|t|^2`` entries, passed for a rigid map (``x -> (x1, x2, 2.0008e6)`` where the truth is
``10 (x1, x2, 2e6 - x3)``).  Here nothing is a difference of such terms: the point map ``x -> s R x + t`` is read
linearly, and ``apply`` takes the dilation about the origin coefficient by coefficient (:func:`dilated`), the
reflection in e1 by signs (:func:`reflected_in_e1`), then the motor by its own closed form.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons.algebra import Multivector

from .anchored import Anchored, frame
from .anchored_ops import NoFrame, Pending, chain_depth
from .anchored_versors import moves_infinity
from .model import G41, E, e1

__all__ = [
    "Similarity",
    "similarity_factors",
    "similarity",
    "similar",
    "dilated",
    "reflected_in_e1",
    "similarity_product",
]

#: The reflection in the plane e1 (through the origin, 2.90) as a matrix: the point map of the vector e1.
_H1 = np.diag([-1.0, 1.0, 1.0])


@dataclass(frozen=True)
class Similarity:
    """A versor that fixes the point at infinity, read by its factors (module docstring): ``V = M H^odd D``
    up to a number, with ``D = 1 - rho E_pm`` the dilator about the origin by ``scale = (1 + rho) / (1 - rho)``
    (rho = 0: none), ``H = e1`` the reflection in the plane e1 through the origin (2.90) when V is odd, and M
    the motor ``motor`` (2.102).  Its point map is ``x -> scale R x + t`` (``rigid``: R, t, det R = -1 when odd);
    ``euclid`` is U, the Euclidean part of ``V (1 + rho E_pm)``."""

    rho: float
    scale: float
    rigid: tuple
    motor: Multivector
    odd: bool
    euclid: Multivector


_SIMILAR_CACHE: dict = {}


def similarity_factors(V: Multivector) -> Similarity | None:
    """V (single, real) read as a similarity or an odd isometry, :class:`Similarity`; None for anything else
    (a motor, a versor that moves the point at infinity, mixed parity, no Euclidean part, |rho| >= 1, or
    ``V (1 + rho E_pm)`` (times e1 when odd) no motor to :meth:`~cga_lessons.algebra.Algebra.rigid_motion`'s
    tolerance).  rho is read off the small coefficients, ``-<D ~E>_0 / <E ~E>_0``, and the motion off the
    motor linearly (2.141-2.144): exact to round-off at any distance, no ``|t|^2``-sized term.  Cached by value."""
    c = V.coeffs
    key = (tuple(c), tuple(c.values()))
    hit = _SIMILAR_CACHE.get(key, False)
    if hit is not False:
        return hit
    hit = _similarity_factors(V)
    if len(_SIMILAR_CACHE) >= 256:
        _SIMILAR_CACHE.clear()
    _SIMILAR_CACHE[key] = hit
    return hit


def _similarity_factors(V: Multivector) -> Similarity | None:
    c = V.coeffs
    parity = {G41.grades[b] & 1 for b in c}
    if len(parity) != 1 or moves_infinity(V):
        return None
    odd = parity.pop() == 1
    A = [float(c.get(x, 0.0)) for x in range(8)]
    AA = sum(a * a for a in A)
    if not AA > 0.0:
        return None
    rho = -sum(float(c.get(x | 24, 0.0)) * a for x, a in enumerate(A)) / AA
    if not (-1.0 < rho < 1.0) or (rho == 0.0 and not odd):
        return None  # even with no E part: a motor, or no versor
    M = V * (1.0 + rho * E) if rho != 0.0 else V  # T_t U times a number: the dilation divided out
    motor = M * e1 if odd else M  # an odd isometry times e1 is a motor (2.90, 2.102)
    rigid = G41.rigid_motion(motor)
    if rigid is None:
        return None
    R, t = rigid
    if odd:  # apply(M, X) = apply(M e1, apply(e1, X)): first the reflection in the plane e1
        R = R @ _H1
        R.flags.writeable = False
    U = Multivector(G41, {b: v for b, v in M.coeffs.items() if b < 8})
    return Similarity(rho, (1.0 + rho) / (1.0 - rho), (R, t), motor, odd, U)


def similarity(V: Multivector):
    """``(s, R, t, W, odd)`` of a single real versor V of G(4,1) that maps points by ``x -> s R x + t`` with
    ``s != 1`` (a dilation, 2.55, or its product with a motor or a reflection; module docstring), else None:
    R (3, 3) has determinant -1 when V is odd, and ``W = U (1 - rho E_pm)`` is ``T_{-f'} V T_f`` up to a number
    (``f' = s R f + t``), the versor that moves a local blade (:func:`similarity_factors`)."""
    if not any(b & 24 == 24 for b in V.coeffs):
        return None  # no E_pm part (no dilation)
    sim = similarity_factors(V)
    if sim is None or sim.rho == 0.0:
        return None
    R, t = sim.rigid
    return sim.scale, R, t, sim.euclid * (1.0 - sim.rho * E), sim.odd


def similar(X: Anchored, Y: Multivector, V: Multivector):
    """``Y = apply(V, X)`` anchored, for V a similarity (:func:`similarity`); None for any other V.  The anchor f
    goes to ``s R f + t``, the local blade L to ``W L^ W^-1`` (2.82); built when first read."""
    sim = similarity(V)
    if sim is None:
        return None
    s, R, t, W, odd = sim
    norm = 1.0 / (W * ~W).scalar()
    depth = chain_depth(X)

    def build():
        f, L = frame(X)
        if f is None:
            raise NoFrame("the dilated entity lost its frame")
        g = s * (f @ R.T) + t
        if not np.all(np.isfinite(g)):
            raise NoFrame("the anchor's image overflows")
        loc = (W * (L.involute() if odd else L) * ~W).grade(*L.grades_present()) * norm
        g.flags.writeable = False
        return g, loc

    return Anchored.derive(Y, Pending(build, depth))


def dilated(X: Multivector, scale: float) -> Multivector:
    """``apply(D, X)`` for D the dilator about the origin by ``scale`` (``D up(x) D^-1 = up(scale x) / scale``),
    coefficient by coefficient: D commutes with the Euclidean blades B and with E_pm, and on each pair
    ``B e+``, ``B e-`` (coefficients a, b) scales ``B e`` by s and ``B e0`` by 1/s (e and e0 of 2.53).  Written on
    ``(a, w) = (a, b - a)`` (w the e0 coefficient, ``a + w/2`` the e one): ``a' = s a + (s - 1/s) w / 2``,
    ``w' = w / s``, ``b' = a' + w'``, so that the weight of a point far away is one rounding of ``w / s`` (the
    null-basis route of the motors, :mod:`cga_lessons.algebra.motor_matrices`)."""
    c = X.coeffs
    s = float(scale)
    half = 0.5 * (s - 1.0 / s)
    out = {b: v for b, v in c.items() if b & 24 in (0, 24)}
    for x in range(8):
        a, b = c.get(x | 8), c.get(x | 16)
        if a is None and b is None:
            continue
        a = 0.0 if a is None else a
        w = -a if b is None else b - a
        a2 = s * a + half * w
        out[x | 8], out[x | 16] = a2, a2 + w / s
    return Multivector(G41, out)


def reflected_in_e1(X: Multivector) -> Multivector:
    """``apply(e1, X) = e1 X^ e1^-1`` (2.82, 2.90): the reflection in the plane e1 through the origin, on each
    blade the sign -1 when it holds e1 (the outermorphism of ``x1 -> -x1``)."""
    return Multivector(G41, {b: (-v if b & 1 else v) for b, v in X.coeffs.items()})


def similarity_product(sim: Similarity, X: Multivector, step) -> Multivector:
    """``apply(V, X)`` for the :class:`Similarity` of V, by its factors: the dilation about the origin
    (:func:`dilated`), the reflection in e1 when V is odd (:func:`reflected_in_e1`), then the motor
    (``step(M, Z)``, the caller's apply: the null-basis route of a motor, 2.102).  Each is exact to a rounding per
    coefficient, where the tables of a versor far out sum terms ``eps |V|^2`` off (module docstring)."""
    Z = dilated(X, sim.scale) if sim.rho != 0.0 else X
    if sim.odd:
        Z = reflected_in_e1(Z)
    if set(sim.motor.coeffs) != {0}:
        Z = step(sim.motor, Z)
    return Z
