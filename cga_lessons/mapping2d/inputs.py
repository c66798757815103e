"""The argument checks of the 2D line map that the shared layer (:mod:`cga_lessons.checks`) lacks, built on it.

Poses, batches of poses, arrays of any shape, laser scans, a distance that may be infinite:
each check takes the value, the public function's name and the argument's name, and returns the value to
compute with or raises :class:`~cga_lessons.algebra.InvalidInputError` with ``"func: name: problem"`` (through
:func:`cga_lessons.checks.fail`).  Checks of the package's own types (segments, segment sets, parameters) are
beside those types.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks

__all__ = [
    "numbers",
    "pose",
    "poses",
    "pose_array",
    "broadcast",
    "reach",
    "scan",
    "scan_list",
    "covariance",
    "vector",
]


def numbers(value, func: str, name: str, *, finite: bool = True) -> np.ndarray:
    """``value`` as a float array of any shape (a number: shape ()), finite unless ``finite=False``."""
    # ragged rows count as one axis, which checks.array refuses with its message about rows of different lengths
    nd = value.ndim if isinstance(value, np.ndarray) else np.asarray(value, dtype=object).ndim
    return checks.array(value, func, name, (None,) * nd, finite=finite)


def pose(value, func: str, name: str) -> np.ndarray:
    """One pose ``(x, y, theta)``: a finite float array of shape (3,)."""
    return checks.array(value, func, name, (3,))


def poses(value, func: str, name: str, *, at_least: int = 0) -> np.ndarray:
    """Poses ``(x, y, theta)`` a row: a finite float array of shape (N, 3)."""
    return checks.array(value, func, name, (None, 3), at_least=at_least)


def pose_array(value, func: str, name: str) -> np.ndarray:
    """One pose or a batch of any shape ``(..., 3)``: a finite float array whose last axis is (x, y, theta)."""
    p = numbers(value, func, name)
    if p.ndim == 0 or p.shape[-1] != 3:
        raise checks.fail(func, name, f"expected shape (3,) or (N, 3) as (x, y, theta), got {p.shape}")
    return p


def broadcast(func: str, **named) -> tuple:
    """The common shape of the named arrays (NumPy's broadcasting), or an error naming them."""
    try:
        return np.broadcast_shapes(*(np.shape(v) for v in named.values()))
    except ValueError:
        shapes = " and ".join(str(np.shape(v)) for v in named.values())
        raise checks.fail(func, ", ".join(named), f"shapes {shapes} do not broadcast together") from None


def reach(value, func: str, name: str) -> float:
    """A distance > 0 that may be ``inf`` (no limit): a float."""
    if isinstance(value, (float, np.floating)) and value == math.inf:
        return math.inf
    return checks.real(value, func, name, low=0.0, strict_low=True)


def scan(ranges, angles, func: str, names=("ranges", "angles"), *, increasing=False) -> tuple[np.ndarray, np.ndarray]:
    """One laser scan: ranges (n,) (``inf`` or NaN: no return) and finite angles (n,), as float arrays.

    With ``increasing``, at least two angles, strictly increasing (counter-clockwise), as the extractor needs.
    """
    r = checks.array(ranges, func, names[0], (None,), finite=False)
    a = checks.array(angles, func, names[1], (None,))
    checks.same_length(func, **{names[0]: r, names[1]: a})
    if increasing and (len(a) < 2 or np.any(np.diff(a) <= 0)):
        raise checks.fail(func, names[1], "must be strictly increasing (counter-clockwise), at least 2 of them")
    return r, a


def scan_list(value, func: str, name: str = "scans", *, increasing=False) -> list:
    """A sequence of laser scans ``(ranges, angles)``: a list of float array pairs (see :func:`scan`)."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise checks.fail(func, name, f"expected a sequence of (ranges, angles) pairs, got {type(value).__name__}")
    out = []
    for k, item in enumerate(value):
        if isinstance(item, (str, bytes)) or not hasattr(item, "__len__") or len(item) != 2:
            raise checks.fail(func, name, f"scan {k} is not a (ranges, angles) pair")
        names = (f"{name}[{k}] ranges", f"{name}[{k}] angles")
        out.append(scan(item[0], item[1], func, names, increasing=increasing))
    return out


def vector(value, func: str, name: str, *, at_least: int = 0, finite: bool = True) -> np.ndarray:
    """A number or a 1-D array of numbers, as a float array of shape (N,)."""
    return checks.batch(value, func, name, (), finite=finite, at_least=at_least)[0]


def covariance(value, func: str, name: str) -> np.ndarray:
    """The inverse (information matrix) of a covariance (3, 3) that must be symmetric and positive definite."""
    cov = checks.array(value, func, name, (3, 3))
    if np.max(np.abs(cov - cov.T)) > 1e-9 * np.max(np.abs(cov)):
        raise checks.fail(func, name, "a covariance must be symmetric")
    try:
        np.linalg.cholesky(cov)
    except np.linalg.LinAlgError:
        raise checks.fail(func, name, "a covariance must be positive definite (no zero or negative variance)") from None
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        info = np.linalg.inv(cov)
    return checks.finite_result(info, func, name)
