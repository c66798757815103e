"""TUM trajectory files: the text format of ``evo`` and most SLAM evaluation tools, written and read.

A line is ``timestamp tx ty tz qx qy qz qw``; a planar trajectory (poses ``(x, y, theta)``, shape ``(T, 3)``, in
metres and radians as in :mod:`cga_lessons.mapping2d.laser`) goes in with ``tz = 0`` and the yaw quaternion
``(qx, qy, qz, qw) = (0, 0, sin(theta / 2), cos(theta / 2))``.

Every bad input raises :class:`cga_lessons.algebra.InvalidInputError` (a ``ValueError``) naming the function,
the argument and the problem.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError
from cga_lessons.files import ExistingFileError, atomic_write

from .poses import wrap_unchecked

__all__ = ["TrajectoryFileExistsError", "write_tum", "read_tum"]


class TrajectoryFileExistsError(ExistingFileError):
    """:func:`write_tum` was asked to write over an existing file without ``overwrite=True``.

    An :class:`~cga_lessons.files.ExistingFileError`, so both an :class:`~cga_lessons.algebra.InvalidInputError`
    (a ``ValueError``) and a ``FileExistsError``.
    """


def _timestamps(value, n: int, func: str, name: str = "timestamps") -> np.ndarray:
    ts = checks.array(value, func, name, (n,))
    back = np.flatnonzero(np.diff(ts) <= 0)
    if len(back):
        k = int(back[0])
        raise checks.fail(
            func,
            name,
            f"must increase strictly; {name}[{k + 1}] = {float(ts[k + 1])!r} follows {float(ts[k])!r} "
            f"({len(back)} such steps)",
        )
    return ts


def write_tum(path, poses, timestamps, *, overwrite: bool = False) -> Path:
    """Write a planar trajectory as a TUM file: ``timestamp tx ty tz qx qy qz qw`` a line.

    The poses go in with ``tz = 0`` and the yaw quaternion
    ``(0, 0, sin(theta / 2), cos(theta / 2))``; numbers are written with
    Python's shortest round-trip representation, so :func:`read_tum` gives the
    same floats back.  The file is first written to a temporary file in the
    same folder and then renamed onto ``path``, so a reader never sees a
    partial file and an interrupted write leaves nothing behind.

    Parameters
    ----------
    path : str or Path
        The file to write; its folder must exist.
    poses : array_like, shape (T, 3)
        ``(x, y, theta)`` in metres and radians.
    timestamps : array_like, shape (T,)
        Seconds, strictly increasing (TUM readers sort and match by them).
    overwrite : bool
        Replace an existing file; without it an existing file is an error.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InvalidInputError
        On bad poses or timestamps, or a missing folder.
    TrajectoryFileExistsError
        If ``path`` exists and ``overwrite`` is false (nothing is written).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> p = write_tum(folder / "t.tum", [[0, 0, 0], [1, 0, np.pi / 2]], [0.0, 0.5])
    >>> print(p.read_text().splitlines()[-1])
    0.5 1.0 0.0 0.0 0.0 0.0 0.7071067811865475 0.7071067811865476
    >>> write_tum(p, [[0, 0, 0]], [0.0])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.mapping2d.tum.TrajectoryFileExistsError: write_tum: path: ... exists (pass overwrite=True ...)
    """
    func = "write_tum"
    overwrite = checks.flag(overwrite, func, "overwrite")
    p = checks.array(poses, func, "poses", (None, 3), at_least=1)
    ts = _timestamps(timestamps, len(p), func)
    half = p[:, 2] / 2
    rows = np.column_stack([ts, p[:, 0], p[:, 1], np.zeros(len(p)), np.zeros((len(p), 2)), np.sin(half), np.cos(half)])
    text = "".join(" ".join(repr(float(v)) for v in row) + "\n" for row in rows)
    try:
        return atomic_write(path, text, func, overwrite=overwrite)
    except ExistingFileError as exc:
        raise TrajectoryFileExistsError(str(exc)) from None


def read_tum(path, *, planar_tol: float = 1e-6):
    """Read a planar trajectory from a TUM file (``timestamp tx ty tz qx qy qz qw`` a line).

    Lines starting with ``#`` and blank lines are skipped.  The heading is the
    yaw of the quaternion, which must be a unit quaternion (within 1e-3) of a
    rotation about the z axis; ``tz`` and the tilt must be zero within
    ``planar_tol``, since a 3D trajectory cannot be read as a planar one.

    Parameters
    ----------
    path : str or Path
    planar_tol : float
        Tolerance on ``tz`` (m) and on the quaternion's ``qx``, ``qy``.

    Returns
    -------
    poses : ndarray, shape (T, 3)
        ``(x, y, theta)``, theta in ``[-pi, pi)``.
    timestamps : ndarray, shape (T,)
        Strictly increasing.

    Raises
    ------
    InvalidInputError
        On a missing file, a malformed line (naming the file and line), a
        non-planar pose, timestamps that do not increase, or a file with no pose.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "t.tum"
    >>> _ = f.write_text("# t x y z qx qy qz qw\\n1.0 2.0 3.0 0 0 0 1 0\\n")
    >>> poses, ts = read_tum(f)
    >>> poses.round(6).tolist(), ts.tolist()
    ([[2.0, 3.0, -3.141593]], [1.0])
    """
    func = "read_tum"
    planar_tol = checks.real(planar_tol, func, "planar_tol", low=0.0)
    path = checks.existing_path(path, func, "path")
    try:
        rows, linenos = _tum_rows(path, planar_tol)
    except (OSError, UnicodeDecodeError) as exc:
        raise checks.fail(func, "path", f"cannot read {str(path)!r}: {exc}") from None
    if not rows:
        raise checks.fail(func, "path", f"{path.name} holds no pose")
    arr = np.array(rows)
    back = np.flatnonzero(np.diff(arr[:, 0]) <= 0)
    if len(back):
        raise checks.fail(
            func,
            "path",
            f"{path.name}, line {linenos[back[0] + 1]}: timestamp {float(arr[back[0] + 1, 0])!r} does not "
            f"increase (the one before is {float(arr[back[0], 0])!r})",
        )
    poses = arr[:, 1:].copy()
    poses[:, 2] = wrap_unchecked(poses[:, 2])
    return poses, arr[:, 0].copy()


def _tum_rows(path: Path, planar_tol: float):
    """The poses ``(t, x, y, theta)`` of a TUM file's lines and their line numbers."""
    rows, linenos = [], []
    with open(path, encoding="utf-8") as f:
        for lineno, line in enumerate(f, start=1):
            tok = line.split()
            if not tok or tok[0].startswith("#"):
                continue
            where = f"{path.name}, line {lineno}"
            if len(tok) != 8:
                raise _bad(where, f"expected 8 numbers (timestamp tx ty tz qx qy qz qw), got {len(tok)}")
            try:
                vals = [float(v) for v in tok]
            except ValueError as exc:
                raise _bad(where, f"not a number ({exc})") from None
            if not all(math.isfinite(v) for v in vals):
                raise _bad(where, "NaN or inf")
            t, x, y, z, qx, qy, qz, qw = vals
            norm = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
            if abs(norm - 1) > 1e-3:
                raise _bad(where, f"the quaternion is not a unit quaternion (norm {norm:.6g})")
            if abs(z) > planar_tol or max(abs(qx), abs(qy)) / norm > planar_tol:
                raise _bad(where, f"not a planar pose (tz = {z:.3g}, qx = {qx:.3g}, qy = {qy:.3g})")
            rows.append((t, x, y, 2 * math.atan2(qz, qw)))
            linenos.append(lineno)
    return rows, linenos


def _bad(where: str, problem: str) -> InvalidInputError:
    return checks.fail("read_tum", "path", f"{where}: {problem}")
