"""Inversions read off a versor, and their point map in closed form (2.84-2.88).

A sphere (standard or dual form) or its product with a motor inverts points by ``x -> p + r2 (x - p) / |x - p|^2``
(the motor's rigid map before or after it): :func:`inversion_of` reads p, r2 and the motor, :func:`inverted_points`
maps points with terms of the size of the geometry (``x - p``), where the conformal point of a far x holds its
weight only to eps |x|^2.  Used by :func:`~cga_lessons.conformal.apply_to_points` and
:func:`~cga_lessons.conformal.apply`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError, Multivector

from .anchored import times_invariant
from .anchored_versors import Inversion, inversion_motor
from .entities_read import read_sphere
from .model import G41
from .model import Ic as IC

__all__ = ["sphere_of", "inversion_of", "inverted_points"]


def sphere_of(V):
    """``(p, r2)``: the centre and signed squared radius of a grade-1 V that is a real or imaginary sphere (its
    e0 weight not zero), read as :func:`~cga_lessons.conformal.entities_read.read_sphere` reads a sphere (off its
    local blade when V is anchored: exact at any distance); None for anything else."""
    if any(b not in (1, 2, 4, 8, 16) for b in V._c):
        return None
    try:
        p, r2, _, _ = read_sphere(V, "apply", "V")
    except GeometryError:  # a plane (an isometry: taken before), or no sphere
        return None
    r2 = float(r2)
    return None if r2 == 0.0 else (np.asarray(p, dtype=float), r2)


def inversion_of(V: Multivector) -> Inversion | None:
    """V (single, real) read as an inversion in a sphere (standard or dual form, 2.84-2.88) or its product with a
    motor (2.102), an :class:`~cga_lessons.conformal.anchored_versors.Inversion` (``motor`` and ``rigid`` None for a
    sphere alone): the centre and squared radius read as :func:`sphere_of` reads them (off the local blade of an
    anchored sphere: exact at any distance); None for anything else, and for a null V (no inverse)."""
    grades = {G41.grades[b] for b in V._c}
    if grades == {1} or grades == {4}:
        sphere = sphere_of(V if grades == {1} else times_invariant(V, IC))
        return None if sphere is None else Inversion(*sphere, None, None, True, False)
    if not all(g % 2 for g in grades):
        return None
    parts = inversion_motor(V)
    return None if parts is None or parts.null or parts.radius2 == 0.0 else parts


def inverted_points(inversion, arr: np.ndarray, func: str) -> np.ndarray:
    """Points mapped by an inversion (:func:`inversion_of`) in closed form: ``x -> p + r2 (x - p) / |x - p|^2``
    (2.84-2.88; r2 < 0 for an imaginary sphere), the motor's ``R x + t`` before or after it.  Every term is of the
    size of the geometry (``x - p``), where the conformal point of a far x holds its weight only to eps |x|^2."""
    p, r2, rigid, motor_first = inversion.centre, inversion.radius2, inversion.rigid, inversion.motor_first
    y = np.atleast_2d(arr)
    if rigid is not None and motor_first:
        y = y @ rigid[0].T + rigid[1]
    q = y - p
    qq = np.einsum("ij,ij->i", q, q)
    if np.any(qq == 0.0):
        raise checks.degenerate(func, "x", "V sends a point to infinity (the point is the inverting sphere's centre)")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        y = p + (r2 / qq)[:, None] * q
        if rigid is not None and not motor_first:
            y = y @ rigid[0].T + rigid[1]
    if not np.all(np.isfinite(y)):
        raise checks.degenerate(func, "x", "V sends a point out of a float's range")
    return y[0] if arr.ndim == 1 else y
