"""Errors of a trajectory and of a line map against the truth (for chapter 3's result tables)."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from cga_lessons.algebra import InvalidInputError

from .laser import wrap_angle

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
    p, t = np.asarray(poses, float), np.asarray(truth, float)
    if p.shape != t.shape or p.ndim != 2 or p.shape[1] != 3:
        raise InvalidInputError(f"pose_errors: shapes {p.shape} and {t.shape} must be equal (T, 3)")
    pos = np.sqrt(np.mean(np.sum((p[:, :2] - t[:, :2]) ** 2, axis=1)))
    head = np.sqrt(np.mean(wrap_angle(p[:, 2] - t[:, 2]) ** 2))
    return float(pos), float(head)


def map_errors(segments, walls):
    """Distance (m) of every segment end point to the nearest true wall.

    Parameters
    ----------
    segments : list of Segment
    walls : array_like, shape (W, 2, 2)

    Returns
    -------
    ndarray, shape (2 * len(segments),)
    """
    walls = np.asarray(walls, float).reshape(-1, 2, 2)
    if not segments:
        return np.zeros(0)
    pts = np.array([p for s in segments for p in (s.start, s.end)])
    a, v = walls[:, 0], walls[:, 1] - walls[:, 0]
    rel = pts[:, None, :] - a[None]
    t = np.clip(np.einsum("pwi,wi->pw", rel, v) / np.maximum(np.einsum("wi,wi->w", v, v), 1e-300), 0, 1)
    d = np.hypot(*(rel - t[..., None] * v[None]).transpose(2, 0, 1))
    return d.min(axis=1)


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
    ref = np.asarray(points, float).reshape(-1, 2)
    if not segments or len(ref) == 0:
        return np.zeros(0)
    ends = np.array([p for s in segments for p in (s.start, s.end)])
    d, _ = cKDTree(ref).query(ends)
    return d


def read_log_benchmark(path) -> tuple[dict, list]:
    """The table ``benchmarks/bench_logs.py --json PATH`` wrote: ``(meta, rows)``.

    Raises
    ------
    InvalidInputError
        If the file is missing or is not such a table.
    """
    import json
    from pathlib import Path

    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        meta, rows = data["meta"], data["rows"]
        for r in rows:
            r["name"], r["rmse"], r["odo"]  # noqa: B018 - the fields every row has
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InvalidInputError(f"read_log_benchmark: {path} is not a bench_logs.py table ({exc})") from None
    return meta, rows


def format_log_benchmark(rows) -> str:
    """The rows of :func:`read_log_benchmark` as a fixed-width text table, one line a run.

    The ``odometry`` column says ``truth`` for the run fed the log's own poses (its "corrected" column is then how
    far the builder moved them) and ``seed N`` for simulated drift; ``ratio`` is odometry RMSE / corrected RMSE.
    """
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
