"""Planar trajectory evaluation: absolute and relative pose errors (chapter 3's maps, measured the field's way).

A planar trajectory is an array of poses ``(x, y, theta)``, shape ``(T, 3)``, in metres and radians as in
:mod:`cga_lessons.mapping2d.laser`.  Against a reference ("truth") this module measures the absolute trajectory error
(ATE: RMS of the position and heading differences, pose by pose) and the relative pose error (RPE: the error of
the motion over a fixed distance of travel, which measures drift wherever it began).  TUM trajectory files are
written and read by :mod:`cga_lessons.mapping2d.tum`.

Every bad input raises :class:`cga_lessons.algebra.InvalidInputError` (a ``ValueError``) naming the function,
the argument and the problem; nothing returns NaN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks

from .poses import relative_unchecked, wrap_unchecked

__all__ = [
    "AbsoluteTrajectoryError",
    "RelativePoseError",
    "absolute_trajectory_error",
    "relative_pose_error",
    "odometry_repeats_poses",
]


# --------------------------------------------------------------------------- input checks


def _poses(value, func: str, name: str) -> np.ndarray:
    return checks.array(value, func, name, (None, 3), at_least=1)


def _pair(poses, truth, func: str, names=("poses", "truth")):
    p, t = _poses(poses, func, names[0]), _poses(truth, func, names[1])
    checks.same_length(func, **{names[0]: p, names[1]: t})
    return p, t


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

    >>> from cga_lessons.mapping2d import compose
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
