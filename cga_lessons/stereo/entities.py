"""The objects of section 4.1 as typed records: points, a point pair, a line, a circle, a plane and a sphere.

One class per kind of entity holds its Euclidean parameters and its conformal ``blade`` (dual form, as built from
points: 2.62, 2.68, 2.75, 2.77, 2.80, 2.81).  :func:`cga_lessons.stereo.reconstruct_entities` returns them rebuilt
from a stereo pair and :meth:`cga_lessons.stereo.StereoScene.truth` the true ones, both as a dict ``entity name ->
record`` (``"point"``, ``"pair"``, ``"line"``, ``"circle"``, ``"plane"``, ``"sphere"``);
:func:`cga_lessons.stereo.entity_errors` compares the two.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector

from . import validate as vd

__all__ = ["ScenePoints", "ScenePair", "SceneLine", "SceneCircle", "ScenePlane", "SceneSphere"]


def _checked(record, func: str, **fields) -> None:
    """Check a record's fields: a shape (a finite array), ``"unit"`` (a direction), a lower bound or None (a finite
    number); and its blade (a multivector with finite coefficients)."""
    for name, spec in fields.items():
        value = getattr(record, name)
        if spec == "unit":
            value = vd.array(value, func, name, (3,))
            vd.direction(value, func, name)
        elif isinstance(spec, tuple):
            value = vd.array(value, func, name, spec, at_least=1)
        else:
            value = checks.real(value, func, name, low=spec)
        object.__setattr__(record, name, value)
    blade = checks.instance(record.blade, func, "blade", Multivector, "a conformal blade (a Multivector)")
    if not all(np.all(np.isfinite(np.asarray(c, float))) for c in blade.coeffs.values()):
        raise checks.fail(func, "blade", "has NaN or inf coefficients")


@dataclass(frozen=True)
class ScenePoints:
    """Points: ``points`` (N, 3) and ``blade``, the batch of their conformal points (2.62; ``points`` by 2.114)."""

    points: np.ndarray
    blade: Multivector

    def __post_init__(self):
        _checked(self, "ScenePoints", points=(None, 3))


@dataclass(frozen=True)
class ScenePair:
    """A point pair: its ``endpoints`` (2, 3) (2.131) and ``blade`` ``a ^ b`` (2.68)."""

    endpoints: np.ndarray
    blade: Multivector

    def __post_init__(self):
        _checked(self, "ScenePair", endpoints=(2, 3))


@dataclass(frozen=True)
class SceneLine:
    """A line through a segment: unit ``direction`` (2.127), ``closest_point`` to the origin (2.129), the segment's
    ``length`` (2.125) and ``midpoint``, and ``blade`` ``e ^ a ^ b`` (2.81)."""

    direction: np.ndarray
    closest_point: np.ndarray
    length: float
    midpoint: np.ndarray
    blade: Multivector

    def __post_init__(self):
        _checked(self, "SceneLine", direction="unit", closest_point=(3,), length=0.0, midpoint=(3,))


@dataclass(frozen=True)
class SceneCircle:
    """A circle: ``center`` (2.123, 2.115, 2.116), ``radius`` (2.122), unit ``normal`` of its plane (2.119), the
    centre found the first way of 4.1, ``center_via_plane`` (2.119-2.121), and ``blade`` ``a ^ b ^ c`` (2.80)."""

    center: np.ndarray
    radius: float
    normal: np.ndarray
    center_via_plane: np.ndarray
    blade: Multivector

    def __post_init__(self):
        _checked(self, "SceneCircle", center=(3,), radius=0.0, normal="unit", center_via_plane=(3,))


@dataclass(frozen=True)
class ScenePlane:
    """A plane: unit ``normal`` and ``distance`` (``normal . x = distance`` on it, 2.77), a ``center`` on it and a
    ``radius`` about it to draw it by (the circumcircle of the points it was made from; the board's centre and
    half diagonal for the truth), and ``blade`` ``e ^ a ^ b ^ c`` (2.77)."""

    normal: np.ndarray
    distance: float
    center: np.ndarray
    radius: float
    blade: Multivector

    def __post_init__(self):
        _checked(self, "ScenePlane", normal="unit", distance=None, center=(3,), radius=0.0)


@dataclass(frozen=True)
class SceneSphere:
    """A sphere: ``center`` and ``radius`` (2.115, 2.116, 2.73) and ``blade`` ``a ^ b ^ c ^ d`` (2.75)."""

    center: np.ndarray
    radius: float
    blade: Multivector

    def __post_init__(self):
        _checked(self, "SceneSphere", center=(3,), radius=0.0)
