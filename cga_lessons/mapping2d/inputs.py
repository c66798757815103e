"""The argument checks of the 2D line map that the shared layer (:mod:`cga_lessons.checks`) lacks, built on it.

Poses, batches of poses, arrays of any shape, laser scans, a random generator, a distance that may be infinite:
each check takes the value, the public function's name and the argument's name, and returns the value to
compute with or raises :class:`~cga_lessons.algebra.InvalidInputError` with ``"func: name: problem"`` (through
:func:`cga_lessons.checks.fail`).  Checks of the package's own types (segments, segment sets, parameters) are
beside those types.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.errors import GeometryError

__all__ = [
    "array",
    "batch",
    "numbers",
    "pose",
    "poses",
    "pose_array",
    "broadcast",
    "reach",
    "generator",
    "scan",
    "scan_list",
    "squares_finite",
    "covariance",
    "vector",
    "relabel",
]


def _ragged(value) -> bool:
    """Whether ``value`` is a nest of sequences of unequal lengths (which NumPy cannot make an array of)."""
    try:
        np.ndim(value)
    except ValueError:
        return True
    return False


def array(value, func: str, name: str, shape: tuple, **options) -> np.ndarray:
    """:func:`cga_lessons.checks.array`, with rows of unequal length refused by name too."""
    if _ragged(value):
        raise checks.fail(func, name, "must be an array of numbers (its rows differ in length)")
    return checks.array(value, func, name, shape, **options)


def batch(value, func: str, name: str, tail: tuple, **options):
    """:func:`cga_lessons.checks.batch`, with rows of unequal length refused by name too."""
    if _ragged(value):
        raise checks.fail(func, name, "must be an array of numbers (its rows differ in length)")
    return checks.batch(value, func, name, tail, **options)


def numbers(value, func: str, name: str, *, finite: bool = True) -> np.ndarray:
    """``value`` as a float array of any shape (a number: shape ()), finite unless ``finite=False``."""
    if _ragged(value):
        raise checks.fail(func, name, "must be an array of numbers (its rows differ in length)")
    return checks.array(value, func, name, (None,) * np.ndim(value), finite=finite)


def pose(value, func: str, name: str) -> np.ndarray:
    """One pose ``(x, y, theta)``: a finite float array of shape (3,)."""
    return array(value, func, name, (3,))


def poses(value, func: str, name: str, *, at_least: int = 0) -> np.ndarray:
    """Poses ``(x, y, theta)`` a row: a finite float array of shape (N, 3)."""
    return array(value, func, name, (None, 3), at_least=at_least)


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


def generator(value, func: str, name: str, *, optional: bool = False):
    """A :class:`numpy.random.Generator` (or None when ``optional``)."""
    if value is None and optional:
        return None
    what = "a numpy.random.Generator (numpy.random.default_rng(seed))" + (" or None" if optional else "")
    return checks.instance(value, func, name, np.random.Generator, what)


def scan(ranges, angles, func: str, names=("ranges", "angles"), *, increasing=False) -> tuple[np.ndarray, np.ndarray]:
    """One laser scan: ranges (n,) (``inf`` or NaN: no return) and finite angles (n,), as float arrays.

    With ``increasing``, at least two angles, strictly increasing (counter-clockwise), as the extractor needs.
    """
    r = array(ranges, func, names[0], (None,), finite=False)
    a = array(angles, func, names[1], (None,))
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


def squares_finite(value, func: str, name: str):
    """``value`` if the squares of its numbers are finite (distances of its points can be computed), else an error:
    magnitudes beyond 1e154 overflow every squared distance."""
    a = np.asarray(value, float)
    if a.size and float(np.max(np.abs(a))) > 1e150:
        raise checks.fail(func, name, "magnitudes beyond 1e150 overflow the squared distances")
    return value


def vector(value, func: str, name: str, *, at_least: int = 0, finite: bool = True) -> np.ndarray:
    """A number or a 1-D array of numbers, as a float array of shape (N,)."""
    return batch(value, func, name, (), finite=finite, at_least=at_least)[0]


def covariance(value, func: str, name: str) -> np.ndarray:
    """The inverse (information matrix) of a covariance (3, 3) that must be symmetric and positive definite."""
    cov = array(value, func, name, (3, 3))
    if np.max(np.abs(cov - cov.T)) > 1e-9 * np.max(np.abs(cov)):
        raise checks.fail(func, name, "a covariance must be symmetric")
    try:
        np.linalg.cholesky(cov)
    except np.linalg.LinAlgError:
        raise checks.fail(func, name, "a covariance must be positive definite (no zero or negative variance)") from None
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        info = np.linalg.inv(cov)
    return checks.finite_result(info, func, name)


def relabel(func: str, name: str, call, *args, **kwargs):
    """``call(*args, **kwargs)``; an error it raises about its own argument becomes one of ``func``'s ``name``.

    For a public function that hands an argument to another public function which checks it (a conformal point
    to :func:`cga_lessons.conformal.down`): the user is told which of their calls and arguments was at fault.
    """
    try:
        return call(*args, **kwargs)
    except GeometryError as exc:
        parts = str(exc).split(": ", 2)
        problem = parts[-1] if len(parts) == 3 else str(exc)
        raise type(exc)(f"{func}: {name}: {problem}") from None
