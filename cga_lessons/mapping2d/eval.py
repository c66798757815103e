"""Errors of a trajectory and of a line map against the truth (for chapter 3's result tables)."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from cga_lessons import checks

from .inputs import numbers
from .poses import wrap_unchecked
from .segment import Segment

__all__ = ["pose_errors", "map_errors", "map_point_errors", "read_log_benchmark", "format_log_benchmark"]


def pose_errors(poses, truth):
    """Root-mean-square position (m) and heading (radians) error of a trajectory.

    Parameters
    ----------
    poses, truth : array_like, shape (T, 3)

    Returns
    -------
    (float, float)
    """
    f = "pose_errors"
    p = checks.array(poses, f, "poses", (None, 3), at_least=1)
    t = checks.array(truth, f, "truth", (len(p), 3))
    with np.errstate(over="ignore", invalid="ignore"):
        pos = np.sqrt(np.mean(np.sum((p[:, :2] - t[:, :2]) ** 2, axis=1)))
        head = np.sqrt(np.mean(wrap_unchecked(p[:, 2] - t[:, 2]) ** 2))
    return checks.finite_result((float(pos), float(head)), f, "poses, truth")


def _segments(segments, func: str) -> list:
    """A list (or tuple) of :class:`~cga_lessons.mapping2d.Segment`."""
    if not isinstance(segments, (list, tuple)):
        raise checks.fail(func, "segments", f"expected a list of Segment, got {type(segments).__name__}")
    for s in segments:
        checks.instance(s, func, "segments", Segment, "a list of Segment")
    return list(segments)


def map_errors(segments, walls):
    """Distance (m) of every segment end point to the nearest true wall.

    Parameters
    ----------
    segments : list of Segment
    walls : array_like, shape (W, 2, 2) or (W, 4)

    Returns
    -------
    ndarray, shape (2 * len(segments),)
    """
    f = "map_errors"
    segments = _segments(segments, f)
    walls = numbers(walls, f, "walls")
    flat = walls.ndim == 2  # segments as rows (x0, y0, x1, y1)
    walls = checks.array(walls, f, "walls", (None, 4) if flat else (None, 2, 2), at_least=1).reshape(-1, 2, 2)
    checks.magnitude(walls, f, "walls")
    if not segments:
        return np.zeros(0)
    pts = np.array([p for s in segments for p in (s.start, s.end)])
    a, v = walls[:, 0], walls[:, 1] - walls[:, 0]
    rel = pts[:, None, :] - a[None]
    t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.maximum(np.einsum("wi,wi->w", v, v), 1e-300), 0, 1)
    d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1))
    return checks.finite_result(d.min(axis=1), f, "segments, walls")


def map_point_errors(segments, points):
    """Distance (m) of every segment end point to the nearest reference point (e.g. a log's scans at the true poses).

    Parameters
    ----------
    segments : list of Segment
    points : array_like, shape (k, 2)

    Returns
    -------
    ndarray, shape (2 * len(segments),)
    """
    f = "map_point_errors"
    segments = _segments(segments, f)
    ref = checks.array(points, f, "points", (None, 2))
    checks.magnitude(ref, f, "points")
    if not segments or len(ref) == 0:
        return np.zeros(0)
    ends = np.array([p for s in segments for p in (s.start, s.end)])
    d, _ = cKDTree(ref).query(ends)
    return checks.finite_result(d, f, "segments, points")


def read_log_benchmark(path) -> tuple[dict, list]:
    """The table ``benchmarks/bench_logs.py --json PATH`` wrote: ``(meta, rows)``.

    Raises
    ------
    InvalidInputError
        If the file is missing or is not such a table.
    """
    import json

    f = "read_log_benchmark"
    path = checks.existing_path(path, f, "path")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        meta, rows = data["meta"], data["rows"]
        if not isinstance(meta, dict):
            raise TypeError("its meta is not a table")
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        why = f"missing field {exc}" if isinstance(exc, KeyError) else str(exc)
        raise checks.fail(f, "path", f"{str(path)!r} is not a bench_logs.py table ({why})") from None
    _rows(rows, f, "path")
    return meta, rows


_NUMBERS = ("odo", "rmse", "heading_deg", "rpe_cm", "map_cm", "ms")  # the columns of every row


def _rows(rows, func: str, name: str) -> list:
    """The rows of a bench_logs.py table: dicts with a ``name``, finite ``_NUMBERS``, whole ``loops`` and a
    ``seed`` (None for the run on the log's own poses)."""
    if not isinstance(rows, list):
        raise checks.fail(func, name, f"the rows must be a list of dicts, got {type(rows).__name__}")
    for k, r in enumerate(rows):
        if not isinstance(r, dict):
            raise checks.fail(func, name, f"row {k} is not a dict")
        missing = [c for c in ("name", *_NUMBERS, "loops") if c not in r]
        if missing:
            raise checks.fail(func, name, f"row {k} lacks {', '.join(missing)}")
        checks.text(r["name"], func, f"{name}: row {k}: name")
        for c in _NUMBERS:
            checks.real(r[c], func, f"{name}: row {k}: {c}")
        checks.integer(r["loops"], func, f"{name}: row {k}: loops", low=0)
        if r.get("seed") is not None:
            checks.integer(r["seed"], func, f"{name}: row {k}: seed")
    return rows


def format_log_benchmark(rows) -> str:
    """The rows of :func:`read_log_benchmark` as a fixed-width text table, one line a run.

    The ``odometry`` column says ``truth`` for the run fed the log's own poses (its "corrected" column is then how
    far the builder moved them) and ``seed N`` for simulated drift; ``ratio`` is odometry RMSE / corrected RMSE.
    """
    _rows(rows, "format_log_benchmark", "rows")
    out = []
    header = ["log", "odometry", "odo RMSE m", "corrected m", "ratio", "heading deg", "RPE cm/m", "map cm", "loops",
              "ms/scan", "verdict"]  # fmt: skip
    widths = [13, 9, 10, 11, 7, 11, 8, 6, 5, 7, 0]
    out.append(" ".join(f"{h:<{w}}" if i < 2 or not w else f"{h:>{w}}" for i, (h, w) in enumerate(zip(header, widths))))
    for r in rows:
        truth = r.get("seed") is None
        cells = [
            f"{r['name']:<13}",
            f"{'truth' if truth else 'seed ' + str(r['seed']):<9}",
            f"{r['odo']:>10.2f}",
            f"{r['rmse']:>11.3f}",
            f"{'-' if truth else format(r['odo'] / max(r['rmse'], 1e-12), '.0f') + 'x':>7}",
            f"{r['heading_deg']:>11.2f}",
            f"{r['rpe_cm']:>8.2f}",
            f"{r['map_cm']:>6.1f}",
            f"{r['loops']:>5d}",
            f"{r['ms']:>7.1f}",
            r.get("verdict", ""),
        ]
        out.append(" ".join(cells))
    return "\n".join(out)
