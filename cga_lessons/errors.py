"""The errors raised for bad input, everywhere in the package.

Import them from :mod:`cga_lessons.algebra`, their public home (this module
only holds them so that the algebra's own modules can raise them without
importing each other in a circle).  Every one is a ``ValueError``, so code
that catches ``ValueError`` keeps working.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["GeometryError", "DegenerateGeometryError", "InvalidInputError", "finite_real", "finite_rows"]


class GeometryError(ValueError):
    """Base class of the errors raised for bad input."""


class DegenerateGeometryError(GeometryError):
    """The input describes a degenerate configuration (coincident points, ...)."""


class InvalidInputError(GeometryError):
    """The input has the wrong shape, type, or contains NaN/inf."""


def finite_real(value, func: str, name: str) -> float:
    """``value`` as a finite float, or :class:`InvalidInputError` "func: name: problem".

    For a plain numeric setting (a slider, a threshold): refuses bools, strings,
    None, complex numbers, NaN and inf.

    >>> finite_real(2, "f", "x")
    2.0
    >>> finite_real(float("nan"), "f", "x")
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: x: is NaN or inf (nan)
    """
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        raise InvalidInputError(f"{func}: {name}: must be a real number, got the bool {value!r}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    except (TypeError, ValueError):
        raise InvalidInputError(f"{func}: {name}: must be a real number, got {value!r:.40}") from None
    if isinstance(value, complex) or not math.isfinite(x):
        raise InvalidInputError(f"{func}: {name}: is NaN or inf ({value!r:.40})")
    return x


# Tracebacks and reprs name the errors' public home.
for _cls in (GeometryError, DegenerateGeometryError, InvalidInputError):
    _cls.__module__ = "cga_lessons.algebra"
del _cls


def finite_rows(x, func: str, name: str, width: int, *, at_least: int = 0):
    """``x`` as a finite float array of shape (N, width), or :class:`InvalidInputError` "func: name: problem".

    >>> finite_rows([[0, 1, 2]], "f", "poses", 3).shape
    (1, 3)
    >>> finite_rows([[0, 1]], "f", "poses", 3)
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: poses: expected shape (N, 3), got (1, 2)
    """
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise InvalidInputError(f"{func}: {name}: expected numbers of shape (N, {width})") from None
    if a.ndim != 2 or a.shape[1] != width:
        raise InvalidInputError(f"{func}: {name}: expected shape (N, {width}), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{func}: {name}: contains NaN or inf")
    if len(a) < at_least:
        raise InvalidInputError(f"{func}: {name}: expected at least {at_least} rows, got {len(a)}")
    return a
