"""The settings of the segment extractor (:func:`cga_lessons.mapping2d.extract_segments`, thesis section 3.1.1):
:class:`ExtractionParams`, the one place their defaults are written, and their checks."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from cga_lessons import checks

from .inputs import reach

__all__ = ["ExtractionParams", "EXTRACTION", "extraction_settings"]

EXTRACTION = ("xi", "phi_xi", "min_points", "min_length", "max_gap", "jump_ratio", "max_range", "edge_tolerance")


def extraction_settings(settings: dict, func: str, prefix: str = "") -> dict:
    """The checked settings of :func:`~cga_lessons.mapping2d.extract_segments` (names from :data:`EXTRACTION`); an
    unknown name or a bad value is an error of ``func``'s argument ``prefix + name``."""
    return {name: _setting(name, value, func, prefix + str(name)) for name, value in settings.items()}


def _setting(name, value, func: str, arg: str):
    """One setting ``name`` checked (and converted: plain floats and ints) as ``func``'s argument ``arg``."""
    if name in ("xi", "phi_xi", "max_gap"):
        return checks.real(value, func, arg, low=0.0, strict_low=True)
    if name in ("min_length", "jump_ratio", "edge_tolerance"):
        return checks.real(value, func, arg, low=0.0)
    if name == "min_points":
        return checks.integer(value, func, arg, low=2)
    if name == "max_range":
        return reach(value, func, arg)
    raise checks.fail(func, arg, f"unknown setting; the settings are {', '.join(EXTRACTION)}")


def _field(value, func: str, name: str):
    """A field of :class:`ExtractionParams` checked by :func:`cga_lessons.checks.record`."""
    return _setting(name, value, func, name)


@dataclass(frozen=True)
class ExtractionParams:
    """The settings of :func:`~cga_lessons.mapping2d.extract_segments` (section 3.1.1), checked when made.

    Attributes
    ----------
    xi : float
        The thesis's ``xi``: largest distance (m) of a point from its line; a
        group whose farthest point is at least this far is split (3.2).
    phi_xi : float
        The thesis's ``phi_xi``: neighbouring lines whose inclinations differ
        by less than this (radians) are merged.
    min_points : int
        Fewest points a segment needs (fewer: a chair leg, a stray return).
    min_length : float
        Shortest segment kept (m).
    max_gap : float
        Neighbouring points further apart than this (m) always start a new run.
    jump_ratio : float
        ... or further apart than ``jump_ratio`` times the beam spacing at their
        range (``r * dphi``), which allows grazing walls but cuts at range jumps.
    max_range : float
        Readings at or beyond this (m) count as no return; also the range
        within which the sensor would have seen a wall that continued (edge test).
    edge_tolerance : float
        A neighbour beam landing this far (m) behind the line marks a real edge.
    """

    xi: float = 0.03
    phi_xi: float = np.radians(5.0)
    min_points: int = 6
    min_length: float = 0.15
    max_gap: float = 0.20
    jump_ratio: float = 5.0
    max_range: float = np.inf
    edge_tolerance: float = 0.15

    def __post_init__(self):
        checks.record(self, **{f.name: _field for f in fields(self)})  # as plain floats and ints
