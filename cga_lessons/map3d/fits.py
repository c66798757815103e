"""Fitting an object's conformal entity to its points and reading its Euclidean parameters back (section 4.1, used
by the fused 3D map of section 4.2.3).

The fits are the least-squares ones of :mod:`cga_lessons.conformal.fitting` (sphere, plane, circle) and a
total-least-squares line (:func:`fit_line_3d`); :func:`entity_parameters` reads centre, radius, normal, distance or
direction back from an entity with the recipes of chapter 2.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .chains import check_entity

__all__ = ["ENTITY_KINDS", "fit_line_3d", "entity_parameters", "blade_parameters", "fit_entity"]


def fit_line_3d(X) -> dict:
    """Total-least-squares line through points (N, 3) as a conformal line ``e ^ a ^ b`` (2.81).

    The line passes through the centroid along the principal direction; ``a``
    and ``b`` are the projections of the extreme points, kept as the point
    pair ``a ^ b`` (2.68) that says where to draw it (section 4.1).

    Returns
    -------
    dict
        ``blade`` (dual line, 2.81), ``pair`` (2.68), ``direction`` (3,),
        ``point`` (the centroid), ``ends`` (2, 3), ``rms`` (m).
    """
    f = "fit_line_3d"
    X = checks.rows(X, f, "X", 3)
    if len(X) < 2:
        raise checks.degenerate(f, "X", f"need at least 2 points, got {len(X)}")
    checks.magnitude(X, f, "X")
    c = X.mean(axis=0)
    _, s, Vt = np.linalg.svd(X - c, full_matrices=False)
    if s[0] <= 1e-12 * max(1.0, np.abs(X).max()):
        raise checks.degenerate(f, "X", "all points coincide")
    d = Vt[0] if Vt[0][np.argmax(np.abs(Vt[0]))] > 0 else -Vt[0]
    t = (X - c) @ d
    ends = c + np.outer([t.min(), t.max()], d)
    resid = (X - c) - np.outer(t, d)
    return {
        "blade": cga.line_from_points(ends[0], ends[1]),
        "pair": cga.point_pair(ends[0], ends[1]),
        "direction": d,
        "point": c,
        "ends": ends,
        "rms": float(np.sqrt(np.mean(np.sum(resid**2, axis=1)))),
    }


#: The classification (:func:`cga_lessons.conformal.classify`) of each kind of entity: kinds and dimension.
_ENTITY = {"sphere": (("round",), 2), "plane": (("flat",), 2), "circle": (("round",), 1),
           "line": (("flat", "dual flat"), 1)}  # fmt: skip
#: The kinds of entity the map fits.
ENTITY_KINDS = tuple(_ENTITY)


def entity_parameters(kind: str, blade) -> dict:
    """Euclidean parameters read back from a conformal entity (section 4.1's recipes).

    ``sphere``: centre and radius (2.115, 2.116, 2.73); ``plane``: unit normal
    and distance (2.89); ``circle``: centre, radius, normal (2.119-2.124);
    ``line``: direction (2.127) and closest point to the origin (2.129).
    ``blade`` is one numeric entity of that kind (either form).
    """
    f = "entity_parameters"
    kind = checks.choice(kind, f, "kind", tuple(_ENTITY))
    blade = check_entity(blade, f, "blade")
    if blade.shape:
        raise checks.fail(f, "blade", f"expected one entity, got a batch of shape {blade.shape}")
    with checks.relabel(f, "blade"):
        got = cga.classify(blade)
        kinds, dimension = _ENTITY[kind]
        if got.kind not in kinds or got.dimension != dimension or got.imaginary:
            imaginary = "an imaginary " if got.imaginary else "a "
            raise checks.fail(f, "blade", f"expected a {kind}, got {imaginary}{got.kind} of dimension {got.dimension}")
        return blade_parameters(kind, blade)


def blade_parameters(kind: str, blade: Multivector) -> dict:
    """:func:`entity_parameters` of an entity of that kind (no checks: the fits of section 4.1 made it)."""
    if kind == "sphere":
        c, r = cga.sphere_center_radius(blade)
        return {"center": np.asarray(c, float), "radius": float(r)}
    if kind == "plane":
        n, d = cga.plane_normal_distance(blade)
        return {"normal": np.asarray(n, float), "distance": float(d)}
    if kind == "circle":
        c, r, n = cga.circle_center_radius(blade)
        return {"center": np.asarray(c, float), "radius": float(r), "normal": np.asarray(n, float)}
    return {"direction": np.asarray(cga.line_direction(blade), float),
            "point": np.asarray(cga.line_closest_point(blade), float)}  # fmt: skip


def fit_entity(kind: str, X) -> dict:
    """The section-4.1 least-squares fit of ``kind`` to points X (N, 3) (:mod:`cga_lessons.conformal.fitting`)."""
    if kind == "sphere":
        return cga.fit_sphere(X)
    if kind == "plane":
        return cga.fit_plane(X)
    if kind == "circle":
        return cga.fit_circle(X)
    return fit_line_3d(X)
