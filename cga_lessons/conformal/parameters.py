"""The Euclidean parameters of a conformal entity as typed records: a sphere, a plane, a circle and a line.

An entity of table 2.1 read back to Euclidean terms: a sphere's centre and radius (2.115, 2.116, 2.73), a plane's
unit normal and distance (2.89), a circle's centre, radius and normal (2.119-2.124), a line's direction (2.127) and
a point of it (2.129).  :class:`SphereParameters`, :class:`PlaneParameters`, :class:`CircleParameters` and
:class:`LineParameters` hold them, each saying its ``kind``; :data:`ENTITY_PARAMETERS` gives the class of each kind.
The stereo detector (:mod:`cga_lessons.stereo`) and the fused 3D map (:mod:`cga_lessons.map3d`) both read their
entities back to these records, and add what a drawing needs: a plane's ``center`` (a point of the plane to draw it
around) and a segment's ``length``; what only one of them knows is a subclass there (a true patch's sides, a board's
corners, a post's radius).

One entity's fields are checked when it is made: finite 3-vectors (3,), finite numbers, radii and lengths >= 0.

A *batch* of entities, every field with a leading axis (the detector's hypotheses through minimal point sets, a
trial step of a maximum-likelihood polish whose radius may turn negative before the step is refused), is made
unchecked with the class method ``unchecked``::

    >>> import numpy as np
    >>> planes = PlaneParameters.unchecked(normal=np.eye(3), distance=np.zeros(3))
    >>> planes.normal.shape, planes.center is None
    ((3, 3), True)
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import ClassVar

import numpy as np

from cga_lessons import checks

__all__ = ["SphereParameters", "PlaneParameters", "CircleParameters", "LineParameters", "ENTITY_PARAMETERS"]


class _Parameters:
    """What the four parameter classes share: checking their fields, and unchecked batches."""

    kind: ClassVar[str]

    @classmethod
    def unchecked(cls, **values):
        """A record made without checking its fields (the fields not given take their defaults): for a batch of
        entities, every field with a leading axis, or a trial step of a search, which checking would refuse."""
        record = object.__new__(cls)
        for f in fields(cls):
            object.__setattr__(record, f.name, values.get(f.name, f.default))
        return record


@dataclass(frozen=True, eq=False)
class SphereParameters(_Parameters):
    """A sphere's ``center`` (3,) and ``radius`` (m), read back with (2.115, 2.116, 2.73)."""

    kind: ClassVar[str] = "sphere"
    center: np.ndarray
    radius: float

    def __post_init__(self):
        checks.record(self, center=checks.vector3, radius=checks.length)


@dataclass(frozen=True, eq=False)
class PlaneParameters(_Parameters):
    """A plane's unit ``normal`` (3,) and ``distance`` (m): ``normal . x = distance`` on the plane (2.89).

    ``center`` (3,): a point of the plane to draw it around (a detection's inliers' centroid on the plane, a true
    patch's or board's centre), None when nothing says where.
    """

    kind: ClassVar[str] = "plane"
    normal: np.ndarray
    distance: float
    center: np.ndarray | None = None

    def __post_init__(self):
        checks.record(self, normal=checks.vector3, distance=checks.real, center=checks.vector3)


@dataclass(frozen=True, eq=False)
class CircleParameters(_Parameters):
    """A circle's ``center`` (3,), ``radius`` (m) and the unit ``normal`` (3,) of its plane (2.119-2.124)."""

    kind: ClassVar[str] = "circle"
    center: np.ndarray
    radius: float
    normal: np.ndarray

    def __post_init__(self):
        checks.record(self, center=checks.vector3, radius=checks.length, normal=checks.vector3)


@dataclass(frozen=True, eq=False)
class LineParameters(_Parameters):
    """A line's unit ``direction`` (3,) (2.127) and a ``point`` (3,) of it (2.129: the closest to the origin, or
    where the points fitted are).

    ``length`` (m): the extent of a segment of it (a detection's inliers along it, a true segment), None for a line.
    """

    kind: ClassVar[str] = "line"
    direction: np.ndarray
    point: np.ndarray
    length: float | None = None

    def __post_init__(self):
        checks.record(self, direction=checks.vector3, point=checks.vector3, length=checks.length)


#: The parameters class of each kind of entity.
ENTITY_PARAMETERS = {c.kind: c for c in (SphereParameters, PlaneParameters, CircleParameters, LineParameters)}
