"""The stereo package's argument checks, composed from the shared checking layer (:mod:`cga_lessons.checks`).

Cameras, calibrations, rotations, points and pixels, random generators, depth ranges, conformal entities, the JSON
files of the bundled head and scene: each check takes the value, the name of the public function being called and
the name of its argument, and returns the value to compute with or raises the layer's error ``"func: name:
problem"``.  Nothing else in the package checks arguments its own way.

>>> rotation(2 * np.eye(3), "projection_matrix", "R")
Traceback (most recent call last):
...
cga_lessons.algebra.InvalidInputError: projection_matrix: R: is not a rotation matrix (R R^T != I or det R < 0)

Magnitudes are bounded by :data:`LIMIT` (1e50, not the layer's 1e150): the camera model multiplies coordinates with
matrix entries and squares them (norms, determinants), so larger numbers overflow a float half way through.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail
from cga_lessons.paths import data_path

__all__ = [
    "LIMIT",
    "WHY",
    "array",
    "batch",
    "numbers",
    "camera",
    "calibration",
    "rotation",
    "depth_range",
    "interval",
    "image_size",
    "json_object",
    "direction",
    "entity",
]

#: Largest magnitude of a coordinate or matrix entry (their products and squares must stay below 1e308).
LIMIT = 1e50
#: Why :data:`LIMIT` is lower than :data:`cga_lessons.checks.MAX_MAGNITUDE`.
WHY = "the camera model multiplies coordinates with matrix entries and squares them, overflowing a float"


def array(value, func: str, name: str, shape: tuple, *, at_least: int = 0, finite: bool = True) -> np.ndarray:
    """:func:`cga_lessons.checks.array` (floats of ``shape``, finite unless told), bounded by :data:`LIMIT`."""
    a = checks.array(value, func, name, shape, at_least=at_least, finite=finite)
    return checks.magnitude(a, func, name, limit=LIMIT, why=WHY) if finite else a


def batch(value, func: str, name: str, tail: tuple, *, at_least: int = 0):
    """:func:`cga_lessons.checks.batch` (one item or a batch, finite), bounded by :data:`LIMIT`."""
    a, single = checks.batch(value, func, name, tail, at_least=at_least)
    return checks.magnitude(a, func, name, limit=LIMIT, why=WHY), single


def numbers(value, func: str, name: str) -> np.ndarray:
    """An array of any shape with at least one axis (points ``(..., D)``), finite and bounded.

    The number of axes is read along the first items (ragged rows are then refused by :func:`array`).
    """
    axes, first = 0, value
    while isinstance(first, (list, tuple)) and len(first):
        axes, first = axes + 1, first[0]
    axes += first.ndim if isinstance(first, np.ndarray) else 0
    return array(value, func, name, (None,) * max(axes, 1))


def camera(P, func: str, name: str = "P") -> np.ndarray:
    """A projection matrix (3, 4) of rank 3 (a camera: its centre is a point, finite or at infinity)."""
    P = array(P, func, name, (3, 4))
    s = np.linalg.svd(P, compute_uv=False)
    if s[2] <= 1e-12 * s[0]:
        raise degenerate(func, name, "has rank < 3: it is not a camera")
    return P


def calibration(K, func: str, name: str = "K") -> np.ndarray:
    """A calibration matrix (3, 3) that is invertible (no zero focal length)."""
    K = array(K, func, name, (3, 3))
    m = float(np.max(np.abs(K)))
    if m == 0 or abs(np.linalg.det(K / m)) <= 1e-15:
        raise degenerate(func, name, "is singular: a calibration matrix needs non-zero focal lengths (A.2)")
    return K


def rotation(R, func: str, name: str = "R") -> np.ndarray:
    """A rotation matrix (3, 3): ``R R^T = I`` and ``det R = +1``."""
    R = array(R, func, name, (3, 3))
    if not np.allclose(R @ R.T, np.eye(3), atol=1e-9) or np.linalg.det(R) < 0:
        raise fail(func, name, "is not a rotation matrix (R R^T != I or det R < 0)")
    return R


def depth_range(value, func: str, name: str = "depth") -> tuple:
    """``(near, far)`` with ``0 < near <= far``: distances in front of the camera (metres)."""
    return interval(value, func, name, "(near, far) in front of the camera")


def interval(value, func: str, name: str, what: str = "(low, high)") -> tuple:
    """``(low, high)`` with ``0 < low <= high``, as two floats."""
    low, high = array(value, func, name, (2,))
    if not 0 < low <= high:
        raise fail(func, name, f"must be {what}: two numbers with 0 < the first <= the second, got {value!r:.40}")
    return float(low), float(high)


def image_size(value, func: str, name: str = "image_size") -> tuple[int, int]:
    """``(width, height)``: two whole numbers from 1 to 2^31 - 1 (OpenCV's int)."""
    if isinstance(value, (str, bytes)) or not isinstance(value, (tuple, list, np.ndarray)) or len(value) != 2:
        raise fail(func, name, f"must be (width, height) in pixels, got {value!r:.40}")
    return tuple(checks.integer(v, func, name, low=1, high=2**31 - 1) for v in value)


def json_object(path, default: str, func: str, keys: tuple) -> dict:
    """The JSON object in ``path`` (None: the bundled ``data/<default>``), which must hold ``keys``."""
    p = data_path(default) if path is None else checks.existing_path(path, func, "path")
    try:
        d = json.loads(Path(p).read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise fail(func, "path", f"{p} is not a JSON file ({exc})") from None
    missing = [k for k in keys if k not in d] if isinstance(d, dict) else list(keys)
    if missing:
        raise fail(func, "path", f"{p} is not the right JSON object: it lacks {', '.join(missing)}")
    return d


def direction(value, func: str, name: str) -> np.ndarray:
    """A non-zero vector (3,), returned as a unit vector."""
    a = array(value, func, name, (3,))
    n = np.linalg.norm(a)
    if n == 0:
        raise degenerate(func, name, "the zero vector is not a direction")
    return a / n


def entity(X, func: str, name: str, kinds: tuple):
    """A conformal blade of one of ``kinds`` (names of :func:`cga_lessons.conformal.classify`, dual form)."""
    X = checks.instance(X, func, name, cga.Multivector, f"a {' or '.join(kinds)} (a conformal blade)")
    if not all(np.all(np.isfinite(c)) for c in X.coeffs.values() if not hasattr(c, "free_symbols")):
        raise fail(func, name, "has NaN or inf coefficients")
    try:
        kind = cga.classify(X).name
    except (GeometryError, TypeError) as exc:
        raise fail(func, name, f"is not a {' or '.join(kinds)}: {exc}") from None
    if kind not in kinds:
        raise fail(func, name, f"must be a {' or '.join(kinds)} (dual form), got a {kind}")
    return X
