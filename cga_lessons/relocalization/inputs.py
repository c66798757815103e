"""Checks of the relocalization's arguments that the shared layer lacks, composed from :mod:`cga_lessons.checks`.

Segments, scans, poses, scenes, random generators, the simulated laser's
settings, logs and indices into them: each check takes the name of the public
function called and of its argument, and every error names both.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import CarmenLog, Scene, Segment

__all__ = [
    "ndim",
    "MAX_GRID_CELLS",
    "grid_shape",
    "as_segment_array",
    "check_scan",
    "check_pose",
    "check_scans_at_poses",
    "check_scene",
    "spread",
    "check_laser",
    "check_log",
    "check_indices",
]


def ndim(value) -> int:
    """The number of axes of ``value`` as an array; rows of different lengths count as one axis, which
    :func:`cga_lessons.checks.array` then refuses with its message about rows of different lengths."""
    return value.ndim if isinstance(value, np.ndarray) else np.asarray(value, dtype=object).ndim


#: The most cells of a grid (the coverage grid, the likelihood field) made for the user's input: more would not
#: fit in memory (ten bytes or so a cell).
MAX_GRID_CELLS = 1e8


def grid_shape(lo, hi, resolution: float, func: str, name: str) -> tuple[int, int]:
    """``(W, H)`` of a grid of ``resolution`` cells over ``lo .. hi`` (2,), at most :data:`MAX_GRID_CELLS`
    cells; ``name``: the arguments that make it too large."""
    span = (np.asarray(hi, float) - np.asarray(lo, float)) / resolution
    cells = float(np.prod(span + 1))
    if not np.isfinite(cells) or cells > MAX_GRID_CELLS:
        problem = f"make a grid of {cells:.3g} cells of {resolution:g} m (at most {MAX_GRID_CELLS:g})"
        raise checks.fail(func, name, problem)
    W, H = (np.ceil(span).astype(int) + 1).tolist()
    return W, H


def as_segment_array(segments, func: str = "as_segment_array", name: str = "segments", allow_empty=False) -> np.ndarray:
    """Segments as a (K, 2, 2) float array of end points.

    Accepts a list of :class:`cga_lessons.mapping2d.segment.Segment` or anything array-like
    of shape (K, 2, 2).  Raises :class:`InvalidInputError` for a wrong shape,
    NaN or inf, or (unless ``allow_empty``) no segment, and
    :class:`~cga_lessons.algebra.DegenerateGeometryError` for a segment of zero
    length; the message names ``func`` and ``name`` (the caller's function and argument).

    >>> as_segment_array([Segment([0, 0], [1, 0])]).tolist()
    [[[0.0, 0.0], [1.0, 0.0]]]
    """
    allow_empty = checks.flag(allow_empty, func, "allow_empty")
    if isinstance(segments, Segment):
        segments = [segments]
    if isinstance(segments, (list, tuple)) and segments and all(isinstance(s, Segment) for s in segments):
        segments = [[s.start, s.end] for s in segments]
    if isinstance(segments, (list, tuple)) and len(segments) == 0:
        segments = np.zeros((0, 2, 2))
    elif isinstance(segments, np.ndarray) and segments.size == 0 and segments.dtype.kind in "biuf":
        segments = segments.reshape(0, 2, 2)
    arr = checks.magnitude(checks.array(segments, func, name, (None, 2, 2)), func, name)
    if len(arr) == 0 and not allow_empty:
        raise checks.fail(func, name, "is empty (no segment)")
    lengths = np.hypot(*(arr[:, 1] - arr[:, 0]).T)
    if np.any(lengths <= 1e-9):
        raise checks.degenerate(func, name, f"segment {int(np.argmin(lengths))} has zero length")
    return arr


def check_scan(scan, func="relocalize", name="scan"):
    """A scan ``(ranges, angles)`` as two float arrays (n,), n >= 2, or :class:`InvalidInputError`.

    Ranges are > 0, ``inf`` or NaN (no return); angles finite and strictly increasing.
    """
    if scan is None or isinstance(scan, (str, bytes)):
        raise checks.fail(func, name, f"expected a pair (ranges, angles), got {type(scan).__name__}")
    try:
        ranges, angles = scan
    except (TypeError, ValueError):
        raise checks.fail(func, name, "expected a pair (ranges, angles)") from None
    r = checks.array(ranges, func, f"{name} ranges", (None,), finite=False)
    a = checks.array(angles, func, f"{name} angles", (None,))
    if r.shape != a.shape or len(r) < 2:
        raise checks.fail(func, name, f"ranges {r.shape} and angles {a.shape} must be equal 1-D shapes (n >= 2)")
    if np.any(np.diff(a) <= 0):
        raise checks.fail(func, f"{name} angles", "must be strictly increasing")
    if a[-1] - a[0] > 2 * np.pi + 1e-9:
        raise checks.fail(func, f"{name} angles", f"span {a[-1] - a[0]:.4g} rad, more than a full turn")
    if np.any(r <= 0):
        raise checks.fail(func, f"{name} ranges", "must be > 0 (inf or NaN for no return)")
    return r, a


def check_pose(pose, func: str, name: str = "pose") -> np.ndarray:
    """A pose ``(x, y, theta)`` as a finite float array (3,) (``x``, ``y`` within
    :data:`cga_lessons.checks.MAX_MAGNITUDE`)."""
    p = checks.array(pose, func, name, (3,))
    checks.magnitude(p[:2], func, name)
    return p


def check_scans_at_poses(scans, poses, func: str) -> tuple[list, np.ndarray]:
    """Scans ``[(ranges, angles), ...]`` (checked by :func:`check_scan`) and their poses (n, 3), one per scan."""
    if scans is None or isinstance(scans, (str, bytes)) or not hasattr(scans, "__iter__"):
        raise checks.fail(func, "scans", f"expected a list of scans (ranges, angles), got {type(scans).__name__}")
    scans = [check_scan(s, func, f"scans[{j}]") for j, s in enumerate(scans)]
    poses = checks.array(poses, func, "poses", (None, 3), at_least=1)
    checks.magnitude(poses[:, :2], func, "poses")
    if len(poses) != len(scans):
        raise checks.fail(func, "poses", f"must be one per scan; got {len(poses)} for {len(scans)} scan(s)")
    return scans, poses


def check_scene(scene, func: str, name: str = "scene") -> Scene:
    """A :class:`~cga_lessons.mapping2d.laser.Scene` with walls, or an error."""
    checks.instance(scene, func, name, Scene, "a Scene (load_scene)")
    if not len(scene.walls):
        raise checks.fail(func, name, "has no wall")
    return scene


def spread(sd, func: str, name: str) -> np.ndarray:
    """Standard deviations (m, m, rad) around a pose: 10 cm, 10 cm and 2 degrees by default."""
    if sd is None:
        return np.array([0.1, 0.1, np.radians(2.0)])
    sd = checks.array(sd, func, name, (3,))
    checks.magnitude(sd[:2], func, name)
    if np.any(sd < 0):
        raise checks.fail(func, name, f"must be 3 numbers >= 0, got {sd.tolist()}")
    return sd


_LASER = {
    "range_noise": lambda v, func: checks.real(v, func, "range_noise", low=0.0),
    "max_range": lambda v, func: checks.real(v, func, "max_range", low=0.0, strict_low=True),
    "n_beams": lambda v, func: checks.integer(v, func, "n_beams", low=2),
    "fov": lambda v, func: checks.real(v, func, "fov", low=0.0, high=2 * np.pi, strict_low=True),
    "mount": lambda v, func: check_pose(v, func, "mount"),
}


def check_laser(func: str, **settings) -> dict:
    """Settings of the simulated laser (:func:`~cga_lessons.mapping2d.laser.simulate_scan`: ``range_noise``,
    ``max_range``, ``n_beams``, ``fov``, ``mount``), checked in the name of ``func``."""
    bad = sorted(set(settings) - set(_LASER))
    if bad:
        raise checks.fail(func, ", ".join(bad), f"not a setting of the simulated laser ({', '.join(_LASER)})")
    out = {k: _LASER[k](v, func) for k, v in settings.items()}
    if out.get("range_noise", 0.0) > out.get("max_range", np.inf):
        raise checks.fail(func, "range_noise", f"must be <= max_range ({out['max_range']} m), got {out['range_noise']}")
    return out


def check_log(log, func: str, name: str = "log") -> CarmenLog:
    """A :class:`~cga_lessons.mapping2d.carmen.CarmenLog` (read_carmen_log), or an error."""
    return checks.instance(log, func, name, CarmenLog, "a CarmenLog (read_carmen_log)")


def check_indices(value, func: str, name: str, n: int, *, at_least: int = 1) -> np.ndarray:
    """Whole-number indices (any shape) into a sequence of ``n`` items, as a flat int array."""
    idx = checks.array(value, func, name, (None,) * max(ndim(value), 1)).ravel()
    if len(idx) < at_least:
        raise checks.fail(func, name, f"expected at least {at_least} index, got none")
    if len(idx) and (np.any(idx != np.round(idx)) or idx.min() < 0 or idx.max() >= n):
        raise checks.fail(func, name, f"must be whole numbers within 0..{n - 1}")
    return idx.astype(int)
