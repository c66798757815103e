"""Planar trajectory evaluation and TUM trajectory files (chapter 3's maps, measured the field's way).

A planar trajectory is an array of poses ``(x, y, theta)``, shape ``(T, 3)``, in metres and radians as in
:mod:`cga_lessons.mapping2d.laser`.  Against a reference ("truth") this module measures the absolute trajectory error
(ATE: RMS of the position and heading differences, pose by pose) and the relative pose error (RPE: the error of
the motion over a fixed distance of travel, which measures drift wherever it began).  It writes and reads TUM
files, the text format of ``evo`` and most SLAM evaluation tools: ``timestamp tx ty tz qx qy qz qw`` a line,
here with ``tz = 0`` and the yaw quaternion ``(qx, qy, qz, qw) = (0, 0, sin(theta / 2), cos(theta / 2))``.

Every bad input raises :class:`cga_lessons.algebra.InvalidInputError` (a ``ValueError``) naming the function,
the argument and the problem; nothing returns NaN.
"""

from __future__ import annotations

import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError

from .inputs import array
from .poses import relative_unchecked, wrap_unchecked

__all__ = [
    "TrajectoryFileExistsError",
    "AbsoluteTrajectoryError",
    "RelativePoseError",
    "write_tum",
    "read_tum",
    "absolute_trajectory_error",
    "relative_pose_error",
    "odometry_repeats_poses",
]


class TrajectoryFileExistsError(InvalidInputError, FileExistsError):
    """:func:`write_tum` was asked to write over an existing file without ``overwrite=True``.

    Both an :class:`~cga_lessons.algebra.InvalidInputError` (a ``ValueError``) and a ``FileExistsError``.
    """


# --------------------------------------------------------------------------- input checks


def _poses(value, func: str, name: str) -> np.ndarray:
    return array(value, func, name, (None, 3), at_least=1)


def _pair(poses, truth, func: str, names=("poses", "truth")):
    p, t = _poses(poses, func, names[0]), _poses(truth, func, names[1])
    checks.same_length(func, **{names[0]: p, names[1]: t})
    return p, t


def _timestamps(value, n: int, func: str, name: str = "timestamps") -> np.ndarray:
    ts = array(value, func, name, (n,))
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


# --------------------------------------------------------------------------- TUM files


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
    cga_lessons.mapping2d.trajectories.TrajectoryFileExistsError: write_tum: path: ... exists (pass overwrite=True ...)
    """
    func = "write_tum"
    overwrite = checks.flag(overwrite, func, "overwrite")
    p = _poses(poses, func, "poses")
    ts = _timestamps(timestamps, len(p), func)
    path = Path(path) if isinstance(path, (str, Path)) and str(path) else path
    if isinstance(path, Path) and path.exists() and not path.is_dir() and not overwrite:
        raise TrajectoryFileExistsError(f"{func}: path: {str(path)!r} exists (pass overwrite=True to replace it)")
    path = checks.new_path(path, func, "path", overwrite=overwrite)
    half = p[:, 2] / 2
    rows = np.column_stack([ts, p[:, 0], p[:, 1], np.zeros(len(p)), np.zeros((len(p), 2)), np.sin(half), np.cos(half)])
    text = "".join(" ".join(repr(float(v)) for v in row) + "\n" for row in rows)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            umask = os.umask(0o022)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes it private; a trajectory file is an ordinary file
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        exists = TrajectoryFileExistsError(f"{func}: path: {str(path)!r} exists (pass overwrite=True to replace it)")
        if overwrite:
            os.replace(tmp, path)
        else:
            try:  # a hard link fails if the file appeared meanwhile, so nothing is ever overwritten
                os.link(tmp, path)
            except FileExistsError:
                raise exists from None
            except OSError:  # no hard links on this file system: check, then rename
                if path.exists():
                    raise exists from None
                os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


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


# --------------------------------------------------------------------------- absolute trajectory error


@dataclass(frozen=True)
class AbsoluteTrajectoryError:
    """The absolute trajectory error of :func:`absolute_trajectory_error`.

    Attributes
    ----------
    position_rmse : float
        Root-mean-square distance of the positions (m).
    heading_rmse : float
        Root-mean-square heading difference, wrapped to ``[-pi, pi)`` (rad).
    align : str
        ``"none"`` or ``"se2"``.
    alignment : tuple of float
        The pose ``(x, y, theta)`` applied to ``poses`` before comparing
        (``(0, 0, 0)`` without alignment).
    n_poses : int
    """

    position_rmse: float
    heading_rmse: float
    align: str
    alignment: tuple
    n_poses: int


def _align_se2(p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The rigid motion ``(x, y, theta)`` that best maps the positions of ``p`` onto ``t`` (least squares)."""
    cp, ct = p[:, :2].mean(0), t[:, :2].mean(0)
    a, b = p[:, :2] - cp, t[:, :2] - ct
    # Horn / Umeyama in the plane: the angle maximising sum b_k . R a_k is atan2(sum a x b, sum a . b)
    angle = math.atan2(float(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])), float(np.sum(a * b)))
    c, s = math.cos(angle), math.sin(angle)
    shift = ct - np.array([[c, -s], [s, c]]) @ cp
    return np.array([shift[0], shift[1], angle])


def absolute_trajectory_error(poses, truth, align: str = "none") -> AbsoluteTrajectoryError:
    """Absolute trajectory error (ATE) of a planar trajectory against the truth, pose by pose.

    Without alignment (the default) the poses are compared as they are.  That
    is right here: the map builder and the simulated odometry both start at
    the truth's first pose (:func:`cga_lessons.mapping2d.laser.simulate_odometry`), so
    both trajectories share one frame, and an alignment would hide part of the
    error (a rotation of the whole trajectory by an early heading error, say).
    With ``align="se2"`` the rigid motion of the plane that best maps the
    positions onto the truth's (Horn's / Umeyama's closed form, no scale) is
    applied first, as evo's ``--align`` does; use it for trajectories given
    in another frame.

    Parameters
    ----------
    poses, truth : array_like, shape (T, 3)
        ``(x, y, theta)`` in metres and radians, pose ``k`` of one against pose ``k`` of the other.
    align : {"none", "se2"}

    Returns
    -------
    AbsoluteTrajectoryError

    Examples
    --------
    >>> truth = [[0, 0, 0], [1, 0, 0], [2, 0, 0]]
    >>> ate = absolute_trajectory_error([[0, 0.3, 0], [1, 0.3, 0], [2, 0.3, 0]], truth)
    >>> round(ate.position_rmse, 12), ate.heading_rmse
    (0.3, 0.0)
    >>> round(absolute_trajectory_error([[0, 0.3, 0], [1, 0.3, 0], [2, 0.3, 0]], truth, align="se2").position_rmse, 12)
    0.0
    """
    func = "absolute_trajectory_error"
    p, t = _pair(poses, truth, func)
    align = checks.choice(align, func, "align", ("none", "se2"))
    motion = np.zeros(3)
    if align == "se2":
        motion = _align_se2(p, t)
        c, s = math.cos(motion[2]), math.sin(motion[2])
        p = np.column_stack([p[:, :2] @ np.array([[c, s], [-s, c]]) + motion[:2], p[:, 2] + motion[2]])
    with np.errstate(over="ignore", invalid="ignore"):
        pos = math.sqrt(float(np.mean(np.sum((p[:, :2] - t[:, :2]) ** 2, axis=1))))
        head = math.sqrt(float(np.mean(wrap_unchecked(p[:, 2] - t[:, 2]) ** 2)))
    checks.finite_result((pos, *motion), func, "poses, truth")
    return AbsoluteTrajectoryError(pos, head, align, tuple(float(v) for v in motion), len(p))


# --------------------------------------------------------------------------- relative pose error


@dataclass(frozen=True)
class RelativePoseError:
    """The relative pose error of :func:`relative_pose_error`.

    Attributes
    ----------
    translation_per_metre : float
        Root mean square over the segments of (translation error / segment length): metres per metre.
    heading_per_metre : float
        Root mean square over the segments of (heading error / segment length): radians per metre.
    translation_rmse : float
        Root mean square of the segments' translation errors (m), what evo reports for this ``delta``.
    heading_rmse : float
        Root mean square of the segments' heading errors (rad).
    delta : float
        The segment length asked for (m of the truth's travelled path).
    pairs : tuple of (int, int)
        The segments: indices ``(i, j)`` of their first and last pose.
    lengths : tuple of float
        Each segment's length along the truth (m), at least ``delta``.
    """

    translation_per_metre: float
    heading_per_metre: float
    translation_rmse: float
    heading_rmse: float
    delta: float
    pairs: tuple
    lengths: tuple


def relative_pose_error(poses, truth, delta: float = 1.0) -> RelativePoseError:
    """Relative pose error (RPE) per metre of travel, over segments of ``delta`` metres of the truth's path.

    The truth's path is cut into consecutive segments: from pose ``i``, the
    segment ends at the first pose ``j`` where the path travelled since ``i``
    reaches ``delta`` (so each is at least ``delta`` long), and the next one
    starts there.  For each segment, the motion from ``i`` to ``j`` as the
    trajectory gives it, ``P_i^-1 P_j``, is compared with the truth's,
    ``Q_i^-1 Q_j``: the error motion is ``E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j)``,
    its translation length is the segment's translation error and its angle the
    heading error.  Dividing by the segment length gives errors per metre
    travelled, the KITTI benchmark's normalisation; the root mean square is
    taken over the segments.  The segments are those of
    ``evo.core.metrics.RPE(delta=delta, delta_unit=Unit.meters,
    pairs_from_reference=True)``, and ``translation_rmse`` is evo's RMSE.

    Parameters
    ----------
    poses, truth : array_like, shape (T, 3)
        ``(x, y, theta)`` in metres and radians.
    delta : float
        Segment length (m), positive; the truth must travel at least this far.

    Returns
    -------
    RelativePoseError

    Examples
    --------
    A robot driving straight ahead 1 m a step whose odometry reports each step
    as 1 m ahead and a turn of 0.01 rad: each 1 m segment is off by 0.01 rad
    in heading and by nothing in translation (in the frame of its start).

    >>> from cga_lessons.mapping2d.laser import compose
    >>> truth = np.column_stack([np.arange(5.0), np.zeros(5), np.zeros(5)])
    >>> est = [np.zeros(3)]
    >>> for _ in range(4):
    ...     est.append(compose(est[-1], [1.0, 0.0, 0.01]))
    >>> rpe = relative_pose_error(est, truth)
    >>> len(rpe.pairs), round(rpe.heading_per_metre, 12), round(rpe.translation_per_metre, 12)
    (4, 0.01, 0.0)
    """
    func = "relative_pose_error"
    p, t = _pair(poses, truth, func)
    delta = checks.real(delta, func, "delta", low=0.0, strict_low=True)
    steps = np.hypot(*np.diff(t[:, :2], axis=0).T) if len(t) > 1 else np.zeros(0)
    ids, travelled = [0], 0.0
    for k, d in enumerate(steps, start=1):
        travelled += float(d)
        if travelled >= delta:
            ids.append(k)
            travelled = 0.0
    if len(ids) < 2:
        raise checks.fail(
            func,
            "truth, delta",
            f"truth travels {float(steps.sum()):.3f} m, less than delta = {delta} m: no segment to compare",
        )
    i, j = np.array(ids[:-1]), np.array(ids[1:])
    cum = np.concatenate([[0.0], np.cumsum(steps)])
    lengths = cum[j] - cum[i]
    with np.errstate(over="ignore", invalid="ignore"):
        move_p, move_t = relative_unchecked(p[i], p[j]), relative_unchecked(t[i], t[j])
        err_xy = np.hypot(move_p[:, 0] - move_t[:, 0], move_p[:, 1] - move_t[:, 1])  # |t(E)|: R(Q)^T is a rotation
        err_th = np.abs(wrap_unchecked(move_p[:, 2] - move_t[:, 2]))
        square = np.concatenate([err_xy, err_xy / lengths]) ** 2
    checks.finite_result(square, func, "poses, truth")

    def rms(x):
        return math.sqrt(float(np.mean(x**2)))

    return RelativePoseError(
        rms(err_xy / lengths),
        rms(err_th / lengths),
        rms(err_xy),
        rms(err_th),
        float(delta),
        tuple(zip(i.tolist(), j.tolist())),
        tuple(lengths.tolist()),
    )


# --------------------------------------------------------------------------- logs


def odometry_repeats_poses(log, tol: float = 1e-6) -> bool:
    """True when a log's odometry fields equal its poses, up to the precision they were printed with.

    A CARMEN FLASER line carries two poses: the laser pose ``x y theta`` and
    the odometry ``odom_x odom_y odom_theta``.  In the "corrected" logs of the
    Radish collection the odometry fields repeat the corrected (SLAM) pose, so
    the log holds no raw odometry: a map built from it has nothing to correct,
    and drift must be simulated (:func:`cga_lessons.mapping2d.laser.simulate_odometry`).
    The logs print poses with about six decimals, hence the tolerance.

    Parameters
    ----------
    log : CarmenLog
        Anything with ``poses`` and ``odometry`` arrays of shape ``(T, 3)``.
    tol : float
        Largest difference taken as equal, in metres for positions and radians
        for headings (compared modulo 2 pi).

    Returns
    -------
    bool

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> poses = np.array([[0.0, 0.0, 3.1415926], [1.0, 0.0, 0.0]])
    >>> odometry_repeats_poses(SimpleNamespace(poses=poses, odometry=poses * [1, 1, -1]))
    True
    >>> odometry_repeats_poses(SimpleNamespace(poses=poses, odometry=poses + [0.01, 0, 0]))
    False
    """
    func = "odometry_repeats_poses"
    if not (hasattr(log, "poses") and hasattr(log, "odometry")):
        raise checks.fail(func, "log", f"must have poses and odometry (a CarmenLog), got {type(log).__name__}")
    tol = checks.real(tol, func, "tol", low=0.0)
    p, o = _pair(log.poses, log.odometry, func, ("log.poses", "log.odometry"))
    return bool(np.all(np.abs(p[:, :2] - o[:, :2]) <= tol) and np.all(np.abs(wrap_unchecked(p[:, 2] - o[:, 2])) <= tol))
