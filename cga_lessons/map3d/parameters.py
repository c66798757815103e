"""The truth of the synthetic world's objects where it says more than an entity's parameters (section 4.2.3), and
the checks of the package's typed results.

An entity's Euclidean parameters are :mod:`cga_lessons.conformal`'s records (:class:`~cga_lessons.conformal.
SphereParameters`, :class:`~cga_lessons.conformal.PlaneParameters`, :class:`~cga_lessons.conformal.CircleParameters`,
:class:`~cga_lessons.conformal.LineParameters`): what :func:`~cga_lessons.map3d.entity_parameters` reads from an
entity, and the truth of the ball and the rings (:meth:`~cga_lessons.map3d.world.Ball.truth`, ...).  The board and
the posts give theirs with what a drawing of them needs besides (:class:`BoardTruth`, :class:`PostTruth`), the
pedestal as a box (:class:`BoxTruth`).  Every class checks its fields when it is made, with
:func:`cga_lessons.checks.record` and the checks here that the package's other results (fits, motors, poses, the
fused map's records) use too.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from cga_lessons import checks
from cga_lessons.conformal import LineParameters, PlaneParameters

__all__ = [
    "BoardTruth",
    "PostTruth",
    "BoxTruth",
    "count",
    "corner_points",
    "end_points",
    "pose_matrix",
]


# ----------------------------------------------------------------- checking a result's fields
def count(value, func: str, name: str) -> int:
    """A whole number, at least 0."""
    return checks.integer(value, func, name, low=0)


def corner_points(value, func: str, name: str) -> np.ndarray:
    """A rectangle's four corners, a finite float array (4, 3)."""
    return checks.array(value, func, name, (4, 3))


def end_points(value, func: str, name: str) -> np.ndarray:
    """A segment's two ends, a finite float array (2, 3)."""
    return checks.array(value, func, name, (2, 3))


def pose_matrix(value, func: str, name: str) -> np.ndarray:
    """A 4x4 pose, or a batch of them (N, 4, 4), as a finite float array."""
    a, single = checks.batch(value, func, name, (4, 4))
    return a[0] if single else a


# ----------------------------------------------------------------- the world's truth, where it says more
@dataclass(frozen=True, eq=False, kw_only=True)
class BoardTruth(PlaneParameters):
    """A board's true face: its plane (``normal``, ``distance``), the face's ``center`` (3,), required here, and
    ``corners`` (4, 3), given by keyword."""

    center: np.ndarray = field()  # required here (a plane's is optional): no inherited default
    corners: np.ndarray

    def __post_init__(self):
        super().__post_init__()
        checks.record(self, center=checks.vector3, corners=corner_points)


@dataclass(frozen=True, eq=False, kw_only=True)
class PostTruth(LineParameters):
    """A post's true axis (``direction`` up, ``point`` on the floor), its ``radius`` (m), the axis' ``ends`` (2, 3)
    (``radius`` and ``ends`` given by keyword)."""

    radius: float
    ends: np.ndarray

    def __post_init__(self):
        super().__post_init__()
        checks.record(self, radius=checks.length, ends=end_points)


@dataclass(frozen=True, eq=False)
class BoxTruth:
    """A box's true ``center`` (3,) and ``size`` (3,) (x, y, height; axis-aligned): furniture, not an entity."""

    kind: ClassVar[str] = "box"
    center: np.ndarray
    size: np.ndarray

    def __post_init__(self):
        checks.record(self, center=checks.vector3, size=checks.vector3)
