"""The segments CSV of the command line: the map files ``map2d`` writes and ``relocalize`` reads.

Written whole or not at all by the package's file writer, :func:`cga_lessons.files.atomic_open` (every segment
checked before the file is opened; an existing file is kept unless ``overwrite``), read through
:func:`cga_lessons.cli.inputs.read_csv_rows`
(binary, UTF-16, over-long lines and absurd point counts refused with the file and line named).
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path

from cga_lessons.errors import GeometryError, InvalidInputError
from cga_lessons.files import atomic_open

from .errors import InputFileError, OutputPathError
from .inputs import read_csv_rows
from .outputs import check_output_files

__all__ = ["SEGMENT_COLUMNS", "MAX_SEGMENT_POINTS", "read_segments_csv", "write_segments_csv"]

SEGMENT_COLUMNS = ("x_start", "y_start", "x_end", "y_end", "rho", "theta", "n_points", "start_is_edge", "end_is_edge")
# The most laser points a segment of a map may count: far more than any log gives one wall (about 6000 per
# 1000 scans of the Intel log), far less than the 1e12 a corrupt file may claim.
MAX_SEGMENT_POINTS = 10**9


def write_segments_csv(path, segments, *, overwrite: bool = False) -> Path:
    """Write segments (objects with ``start``, ``end``, ``rho``, ``theta``, ...) with the columns of
    :data:`SEGMENT_COLUMNS`; metres and radians, ``rho``/``theta`` the Hough form (3.3) about the origin.

    Every segment is checked before the file is opened, and the file is written to a temporary file in the
    same folder and renamed onto ``path`` (:func:`cga_lessons.files.atomic_open`): a bad segment or an
    interrupted write leaves no partial file and no existing file is touched.

    Raises
    ------
    InvalidInputError
        A segment without finite end points, ``rho`` and ``theta`` or with a point count that is not an
        integer from 0 to :data:`MAX_SEGMENT_POINTS`.
    cga_lessons.cli.errors.OutputExistsError
        ``path`` exists and ``overwrite`` is false (also a ``FileExistsError``; a file that appears while the
        map is written raises :class:`cga_lessons.files.ExistingFileError`, a ``FileExistsError`` too).
    cga_lessons.cli.errors.OutputPathError
        ``path`` is a folder, or a symbolic link and ``overwrite`` is false (with it, the link itself is
        replaced, never its target), or its folder does not exist.
    """
    f = "write_segments_csv"
    path = _path(path, f)
    if not isinstance(overwrite, bool):
        raise InvalidInputError(f"{f}: overwrite: must be True or False, got {overwrite!r}")
    if isinstance(segments, (str, bytes)):
        raise InvalidInputError(f"{f}: segments: must be an iterable of segments, got {type(segments).__name__}")
    try:
        segments = list(segments)
    except TypeError:
        kind = type(segments).__name__
        raise InvalidInputError(f"{f}: segments: must be an iterable of segments, got {kind}") from None
    rows = []
    for i, s in enumerate(segments):
        try:
            values = [float(v) for v in (*s.start, *s.end, s.rho, s.theta)]
            if len(values) != 6 or not all(math.isfinite(v) for v in values):
                raise ValueError("start, end, rho and theta must be finite, the end points of length 2")
            try:
                n = int(s.n_points)
            except (TypeError, ValueError, OverflowError):
                n = -1
            if n != s.n_points or not 0 <= n <= MAX_SEGMENT_POINTS:
                raise ValueError(f"n_points {s.n_points!r} is not an integer from 0 to {MAX_SEGMENT_POINTS}")
            rows.append([f"{v:.6f}" for v in values] + [n, int(bool(s.start_is_edge)), int(bool(s.end_is_edge))])
        except (AttributeError, TypeError, ValueError, OverflowError) as exc:
            raise InvalidInputError(f"{f}: segments: segment {i} ({type(s).__name__}): {exc}") from None
    try:
        check_output_files([path], overwrite=overwrite)  # the command line's rules: links and folders named
        if not path.parent.is_dir():
            raise OutputPathError(f"cannot write {str(path)!r}: no such folder {str(path.parent)!r}")
    except OutputPathError as exc:  # the same error, naming the function and its argument
        raise type(exc)(f"{f}: path: {exc}") from None
    with atomic_open(path, f, overwrite=overwrite, newline="") as out:
        w = csv.writer(out)
        w.writerow(SEGMENT_COLUMNS)
        w.writerows(rows)
    return path


def _path(path, func: str) -> Path:
    """``path`` (a str or an os.PathLike, not empty) as a :class:`Path`."""
    if isinstance(path, (str, os.PathLike)) and str(path):
        return Path(path)
    raise InvalidInputError(f"{func}: path: expected a path (a str or a Path), got {path!r:.60}")


def _point_count(text: str) -> int:
    value = float(text)  # "1e3" is a count too
    if not (value.is_integer() and 0 <= value <= MAX_SEGMENT_POINTS):
        raise ValueError(f"n_points {text!r} is not a count from 0 to {MAX_SEGMENT_POINTS}")
    return int(value)


def _even_sums(x0, y0, x1, y1, n):
    """The point sums of :class:`cga_lessons.mapping2d.segment.Segment` for n points spread evenly from start to end
    (what it computes from the n points themselves), in closed form: no array of n points, whatever n is."""
    vx, vy = x1 - x0, y1 - y0
    st, stt = n / 2, n * (2 * n - 1) / (6 * (n - 1))  # sums of t and t^2 over t = k / (n - 1), k = 0 .. n - 1
    return [
        n,
        n * x0 + vx * st,
        n * y0 + vy * st,
        n * x0 * x0 + 2 * x0 * vx * st + vx * vx * stt,
        n * x0 * y0 + (x0 * vy + y0 * vx) * st + vx * vy * stt,
        n * y0 * y0 + 2 * y0 * vy * st + vy * vy * stt,
    ]


def read_segments_csv(path) -> list:
    """Read a segments CSV written by ``map2d``: a list of :class:`cga_lessons.mapping2d.segment.Segment`.

    Raises :class:`InputFileError` (a :class:`~cga_lessons.cli.CLIError`) naming the file and line when it is
    missing, not UTF-8 text (binary, UTF-16) or malformed (a field beyond the csv module's limit, a point count
    that is not an integer from 0 to :data:`MAX_SEGMENT_POINTS`, a segment of length zero).
    """
    f = "read_segments_csv"
    path = _path(path, f)
    try:
        return _read_segments(path)
    except InputFileError as exc:  # the same error, naming the function and its argument
        raise InputFileError(f"{f}: path: {exc}") from None


def _read_segments(path: Path) -> list:
    from cga_lessons.mapping2d import Segment

    out = []
    rows = read_csv_rows(path, what="map file")
    _, header = next(rows, (1, None))
    if header is None or [h.strip() for h in header[:4]] != list(SEGMENT_COLUMNS[:4]):
        columns = ", ".join(SEGMENT_COLUMNS[:4])
        raise InputFileError(f"{path}: not a segments CSV (the header must start with {columns})")
    for lineno, row in rows:
        if not row:
            continue
        try:
            x0, y0, x1, y1 = (float(v) for v in row[:4])
            n = max(_point_count(row[6]) if len(row) > 6 else 2, 2)
            e0, e1 = (bool(int(row[i])) if len(row) > i else False for i in (7, 8))
            if not all(math.isfinite(v) for v in (x0, y0, x1, y1)):
                raise ValueError("non-finite coordinate")
            # the sums of n evenly spread points, as Segment would compute them, without making the n points
            out.append(Segment([x0, y0], [x1, y1], n, _even_sums(x0, y0, x1, y1, n), e0, e1))
        except (ValueError, IndexError) as exc:
            problem = str(exc).split(": ", 2)[-1] if isinstance(exc, GeometryError) else str(exc)
            raise InputFileError(f"{path}, line {lineno}: malformed segment row ({problem})") from None
    if not out:
        raise InputFileError(f"{path}: the map holds no segment")
    return out
