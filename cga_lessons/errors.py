"""The errors raised for bad input, everywhere in the package.

Import them from :mod:`cga_lessons.algebra`, their public home (this module
only holds them so that the algebra's own modules can raise them without
importing each other in a circle).  Every one is a ``ValueError``, so code
that catches ``ValueError`` keeps working.
"""

from __future__ import annotations

__all__ = ["GeometryError", "DegenerateGeometryError", "InvalidInputError"]


class GeometryError(ValueError):
    """Base class of the errors raised for bad input."""


class DegenerateGeometryError(GeometryError):
    """The input describes a degenerate configuration (coincident points, ...)."""


class InvalidInputError(GeometryError):
    """The input has the wrong shape, type, or contains NaN/inf."""


# Tracebacks and reprs name the errors' public home.
for _cls in (GeometryError, DegenerateGeometryError, InvalidInputError):
    _cls.__module__ = "cga_lessons.algebra"
del _cls
