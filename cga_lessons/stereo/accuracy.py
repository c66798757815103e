"""The accuracy of reconstructed entities: their errors against the truth (section 4.1, the stereo notebook).

Both sides are dicts ``entity name -> record``: the records of :mod:`cga_lessons.stereo.entities` that
:func:`cga_lessons.stereo.reconstruct_entities` (the estimate) and :meth:`cga_lessons.stereo.StereoScene.truth` (the
truth) give; an estimate may also be a least-squares fit of :mod:`cga_lessons.conformal` (a circle, plane or sphere).
The errors come back as one typed record per entity.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import fail

from . import validate as vd

__all__ = ["entity_errors", "PositionError", "LineError", "PlaneError", "CircleError", "SphereError"]


def _angle(u, v, signed=True) -> float:
    """The angle between two checked non-zero vectors (between lines if not ``signed``)."""
    u, v = u / np.linalg.norm(u), v / np.linalg.norm(v)
    c = float(np.dot(u, v))
    c = c if signed else abs(c)
    return float(np.arctan2(np.linalg.norm(np.cross(u, v)), c))


def _errors(record) -> None:
    """Every field of an error record: a finite number >= 0 (metres or radians)."""
    checks.record(record, **dict.fromkeys(record.__dataclass_fields__, checks.length))


@dataclass(frozen=True)
class PositionError:
    """Points and point pairs: the largest ``position`` error of a point (metres)."""

    position: float

    def __post_init__(self):
        _errors(self)


@dataclass(frozen=True)
class LineError:
    """A line: the angle of its ``direction`` (radians), the ``position`` error of its closest point to the origin and
    its ``offset``, the distance of the true segment's midpoint from the estimated line (metres)."""

    direction: float
    position: float
    offset: float

    def __post_init__(self):
        _errors(self)


@dataclass(frozen=True)
class PlaneError:
    """A plane: the angle between the ``normal`` lines (radians) and the ``offset`` of the true object's centre from
    the estimated plane (metres)."""

    normal: float
    offset: float

    def __post_init__(self):
        _errors(self)


@dataclass(frozen=True)
class CircleError:
    """A circle: ``center`` and ``radius`` errors (metres) and the angle between the ``normal`` lines (radians)."""

    center: float
    radius: float
    normal: float

    def __post_init__(self):
        _errors(self)


@dataclass(frozen=True)
class SphereError:
    """A sphere: ``center`` and ``radius`` errors (metres)."""

    center: float
    radius: float

    def __post_init__(self):
        _errors(self)


_POINTS, _VEC, _NUM = (None, 3), (3,), ()
#: The parameters :func:`entity_errors` reads, by entity.
_TRUTH = {
    "point": {"points": _POINTS},
    "pair": {"endpoints": (2, 3)},
    "line": {"direction": _VEC, "closest_point": _VEC, "midpoint": _VEC},
    "circle": {"center": _VEC, "radius": _NUM, "normal": _VEC},
    "plane": {"normal": _VEC, "center": _VEC},
    "sphere": {"center": _VEC, "radius": _NUM},
}
_ESTIMATE = {**_TRUTH, "line": {"direction": _VEC, "closest_point": _VEC}, "plane": {"normal": _VEC, "distance": _NUM}}


def _parameters(d, func: str, name: str, spec: dict) -> dict:
    """The checked parameters ``entity -> {quantity: value}`` of the records in ``d`` that ``spec`` names."""
    d = checks.instance(d, func, name, dict, "a dict entity name -> record (as reconstruct_entities returns)")
    out = {}
    for k in (k for k in spec if k in d):
        where = f"{name}[{k!r}]"
        out[k] = {}
        for q, shape in spec[k].items():
            if not hasattr(d[k], q) or isinstance(d[k], (dict, str)):
                raise fail(func, where, f"expected a {k} record with {q!r} (reconstruct_entities, a fit), got "
                                        f"{type(d[k]).__name__}")  # fmt: skip
            a = vd.array(getattr(d[k], q), func, f"{where}.{q}", shape, at_least=1 if shape else 0)
            if q in ("direction", "normal"):
                vd.direction(a, func, f"{where}.{q}")
            out[k][q] = float(a) if shape == () else a
    return out


def entity_errors(truth: dict, est: dict) -> dict:
    """Errors of estimated entity parameters against the truth (metres, radians).

    Points and point pairs: largest position error.  Lines: direction angle,
    closest-point error and ``offset``, the distance of the true segment's
    midpoint from the estimated line.  Circles and spheres: centre and radius errors
    (and the circle's normal).  Planes: normal angle and ``offset``, the
    distance of the true object's centre from the estimated plane (the plane's
    distance to the world origin would mix in the normal error times a lever
    arm of metres).  Normals of circles and planes are compared as unoriented
    lines (their sign depends on the order of the points).

    Returns
    -------
    dict
        ``entity name -> error record`` (:class:`PositionError`, :class:`LineError`, :class:`PlaneError`,
        :class:`CircleError`, :class:`SphereError`) for the entities present in both.
    """
    f = "entity_errors"
    truth, est = _parameters(truth, f, "truth", _TRUTH), _parameters(est, f, "est", _ESTIMATE)
    out = {}
    both = [k for k in _TRUTH if k in est and k in truth]
    for k in ("point", "pair"):
        if k in both:
            key = "points" if k == "point" else "endpoints"
            checks.same_length(f, **{f"est[{k!r}]": est[k][key], f"truth[{k!r}]": truth[k][key]})
    for k in both:
        e, t = est[k], truth[k]
        if k in ("point", "pair"):
            key = "points" if k == "point" else "endpoints"
            out[k] = PositionError(float(np.max(np.linalg.norm(e[key] - t[key], axis=1))))
        elif k == "line":
            pos = float(np.linalg.norm(e["closest_point"] - t["closest_point"]))
            m = t["midpoint"] - e["closest_point"]
            offset = float(np.linalg.norm(m - np.dot(m, e["direction"]) * e["direction"]))
            out[k] = LineError(direction=_angle(e["direction"], t["direction"]), position=pos, offset=offset)
        elif k == "plane":
            offset = abs(float(np.dot(e["normal"], t["center"])) - e["distance"])
            out[k] = PlaneError(normal=_angle(e["normal"], t["normal"], signed=False), offset=offset)
        elif k == "circle":
            out[k] = CircleError(center=float(np.linalg.norm(e["center"] - t["center"])),
                                 radius=abs(e["radius"] - t["radius"]),
                                 normal=_angle(e["normal"], t["normal"], signed=False))  # fmt: skip
        else:
            out[k] = SphereError(center=float(np.linalg.norm(e["center"] - t["center"])),
                                 radius=abs(e["radius"] - t["radius"]))  # fmt: skip
    return out
