"""The parameters of a detected (or true) entity: :mod:`cga_lessons.conformal`'s records, a true patch's sides, and
the helpers the detector uses on them.

The detector (:func:`cga_lessons.stereo.detect_entities`) reads each conformal entity back to Euclidean parameters
((2.89) for planes, (2.115, 2.116, 2.73) for spheres, (2.119-2.124) for circles, (2.127, 2.129) for lines) and
works on those: :class:`~cga_lessons.conformal.PlaneParameters`, :class:`~cga_lessons.conformal.SphereParameters`,
:class:`~cga_lessons.conformal.CircleParameters` and :class:`~cga_lessons.conformal.LineParameters`, the class of
each kind in :data:`PARAMS`.  A detection adds what a drawing needs: the plane's ``center`` (its inliers' centroid
on the plane) and the line's ``length`` (the extent of its inliers); a true entity gives the same, and a true
patch its ``sides`` besides (:class:`PatchParameters`, a plane's parameters).

The same classes carry a *batch* of entities (a leading axis on every field) inside the search
(:func:`~cga_lessons.stereo.detect_models.hypotheses`, :func:`~cga_lessons.stereo.detect_models.residuals`); a
batch, like a trial step of the polish, is the search's working form and is made unchecked (the classes'
``unchecked``; :func:`rows` takes some entities of a batch).  One entity's fields are checked when it is made.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from cga_lessons import checks
from cga_lessons.conformal import ENTITY_PARAMETERS, PlaneParameters

__all__ = ["PatchParameters", "PARAMS", "rows", "present", "of_kind", "indices"]

#: The parameters class of each kind of entity (the conformal package's table).
PARAMS = ENTITY_PARAMETERS


def _sides(value, func, name):
    a = checks.array(value, func, name, (2,))
    if np.any(a < 0):
        raise checks.fail(func, name, f"must be two lengths >= 0, got {value!r}")
    return (float(a[0]), float(a[1]))


@dataclass(frozen=True, eq=False, kw_only=True)
class PatchParameters(PlaneParameters):
    """A true rectangular patch of a plane: its plane (``normal``, ``distance``, 2.89), its ``center`` (3,), required
    here, and its two side lengths ``sides`` (m), given by keyword."""

    center: np.ndarray = field()  # required here (a plane's is optional): no inherited default
    sides: tuple

    def __post_init__(self):
        super().__post_init__()
        checks.record(self, center=checks.vector3, sides=_sides)


def rows(params, index):
    """The entities ``index`` (an int or a slice) of a batch: every field indexed along its leading axis
    (unchecked, as the batch)."""
    return type(params).unchecked(**{f.name: getattr(params, f.name)[index] for f in fields(params)
                                if getattr(params, f.name) is not None})  # fmt: skip


def present(params) -> dict:
    """The fields that are set (not None), by name, in the class's order: for printing and JSON."""
    return {f.name: getattr(params, f.name) for f in fields(params) if getattr(params, f.name) is not None}


def of_kind(kind, params, func: str):
    """A record's ``kind`` (one of :data:`PARAMS`) and its ``params``, that kind's parameters class; a dict of
    that class's fields is accepted and made into one (a plane's with ``sides``: a :class:`PatchParameters`).
    Returns ``(kind, params)``."""
    kind = checks.choice(kind, func, "kind", tuple(PARAMS))
    cls = PARAMS[kind]
    if isinstance(params, dict):
        cls = PatchParameters if kind == "plane" and "sides" in params else cls
        unknown = set(params) - set(cls.__dataclass_fields__)
        if unknown:
            raise checks.fail(func, "params", f"{cls.__name__} has no field {sorted(unknown)[0]!r}")
        try:
            params = cls(**params)
        except TypeError as exc:
            raise checks.fail(func, "params", f"not the fields of a {cls.__name__}: {exc}") from None
    checks.instance(params, func, "params", cls, f"a {cls.__name__} (the parameters of a {kind})")
    return kind, params


def indices(value, func: str, name: str) -> np.ndarray:
    """Indices of points (a one-dimensional array of whole numbers >= 0), returned as given when they are."""
    a = np.asarray(value) if isinstance(value, (np.ndarray, list, tuple, range)) else None
    if a is None or a.ndim != 1 or (a.dtype.kind not in "iu" and not (a.size == 0 and a.dtype.kind == "f")):
        raise checks.fail(func, name, f"expected a one-dimensional array of point indices, got {value!r:.60}")
    if a.size and a.min() < 0:
        raise checks.fail(func, name, f"expected point indices >= 0, got {int(a.min())}")
    return a.astype(int) if a.dtype.kind == "f" else a
