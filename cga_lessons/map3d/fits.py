"""Fitting an object's conformal entity to its points and reading its Euclidean parameters back (section 4.1, used
by the fused 3D map of section 4.2.3).

The fits are the least-squares ones of :mod:`cga_lessons.conformal` (sphere, plane, circle, and the line:
:func:`~cga_lessons.conformal.fit_line`); :func:`entity_parameters` reads centre, radius, normal, distance or
direction back from an entity with the recipes of chapter 2.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector
from cga_lessons.conformal import CircleParameters, LineParameters, PlaneParameters, SphereParameters

from .chains import check_entity

__all__ = [
    "ENTITY_KINDS",
    "entity_parameters",
    "blade_parameters",
    "check_kind",
    "fit_entity",
]


#: The classification (:func:`cga_lessons.conformal.classify`) of each kind of entity: kinds and dimension.
_ENTITY = {"sphere": (("round",), 2), "plane": (("flat",), 2), "circle": (("round",), 1),
           "line": (("flat", "dual flat"), 1)}  # fmt: skip
#: The kinds of entity the map fits.
ENTITY_KINDS = tuple(_ENTITY)


def entity_parameters(kind: str, blade) -> SphereParameters | PlaneParameters | CircleParameters | LineParameters:
    """Euclidean parameters read back from a conformal entity (section 4.1's recipes).

    ``sphere``: centre and radius (2.115, 2.116, 2.73), a :class:`SphereParameters`; ``plane``: unit normal
    and distance (2.89), a :class:`PlaneParameters`; ``circle``: centre, radius, normal (2.119-2.124), a
    :class:`CircleParameters`; ``line``: direction (2.127) and closest point to the origin (2.129), a
    :class:`LineParameters`.  ``blade`` is one numeric entity of that kind (either form).
    """
    f = "entity_parameters"
    kind = checks.choice(kind, f, "kind", tuple(_ENTITY))
    return blade_parameters(kind, check_kind(blade, kind, f, "blade"))


def check_kind(blade, kind: str, func: str, name: str) -> Multivector:
    """``blade`` if it is one numeric entity of ``kind`` (a real one: :func:`cga_lessons.conformal.classify`), or
    ``"point pair"``; else an error naming ``func`` and ``name``."""
    blade = check_entity(blade, func, name)
    if blade.shape:
        raise checks.fail(func, name, f"expected one entity, got a batch of shape {blade.shape}")
    with checks.relabel(func, name):
        got = cga.classify(blade)
        kinds, dimension = _ENTITY[kind] if kind in _ENTITY else (("round",), 0)
        if got.kind not in kinds or got.dimension != dimension or got.imaginary:
            imaginary = "an imaginary " if got.imaginary else "a "
            raise checks.fail(func, name, f"expected a {kind}, got {imaginary}{got.kind} of dimension {got.dimension}")
    return blade


def blade_parameters(kind: str, blade: Multivector):
    """:func:`entity_parameters` of an entity of that kind (the entity's kind not checked: a fit of section 4.1
    made it)."""
    if kind == "sphere":
        c, r = cga.sphere_center_radius(blade)
        return SphereParameters(center=np.asarray(c, float), radius=float(r))
    if kind == "plane":
        n, d = cga.plane_normal_distance(blade)
        return PlaneParameters(normal=np.asarray(n, float), distance=float(d))
    if kind == "circle":
        c, r, n = cga.circle_center_radius(blade)
        return CircleParameters(center=np.asarray(c, float), radius=float(r), normal=np.asarray(n, float))
    return LineParameters(direction=np.asarray(cga.line_direction(blade), float),
                          point=np.asarray(cga.line_closest_point(blade), float))  # fmt: skip


def fit_entity(kind: str, X):
    """The section-4.1 least-squares fit of ``kind`` to points X (N, 3): a sphere, plane or circle fit of
    :mod:`cga_lessons.conformal.fitting`, or a :class:`~cga_lessons.conformal.LineFit`
    (:func:`~cga_lessons.conformal.fit_line`); each has the entity as ``blade`` and its ``rms``."""
    if kind == "sphere":
        return cga.fit_sphere(X)
    if kind == "plane":
        return cga.fit_plane(X)
    if kind == "circle":
        return cga.fit_circle(X)
    return cga.fit_line(X)
