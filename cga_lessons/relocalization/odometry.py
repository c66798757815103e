"""Does a chain of relocalized poses move as the odometry says?  (Beyond chapter 5.)

A run of scans relocalized one after another (:mod:`cga_lessons.relocalization.sequence`)
ties its poses by the odometry only loosely: each pose is snapped to its own
scan, and in a corridor the best chain can slide from candidate to candidate,
metres apart, where the odometry says centimetres.  Such a chain is no answer.
:func:`odometry_misfit` weighs each step of a chain against the odometry
increment by the drift model's covariance for that increment plus the
registration error of the two scans, and names the first step beyond the
99.9 % bound.  (Measured with ``benchmarks/bench_reloc_logs.py``, runs of three
scans on the six CARMEN logs, seeds 0-3: the runs confidently wrong went from 36
to 28 of 1,444 and the runs located from 1,005 to 996.)
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import OdometryModel, compose, relative, wrap_angle

__all__ = ["REGISTRATION_XY", "REGISTRATION_THETA", "ODOMETRY_GATE", "odometry_misfit"]

#: Registration error (m, rad) of one scan on a map built from a log: the robust spread of the bundled CARMEN
#: logs' scans about their own corrected poses (2-3 cm and 0.4-0.6 degrees on Intel, ACES and CSAIL).
REGISTRATION_XY, REGISTRATION_THETA = 0.03, np.radians(0.6)
#: The 99.9 % point of the chi-square law of 3 degrees of freedom: a right chain is refused for its odometry about
#: once in a thousand steps.
ODOMETRY_GATE = 16.27


def odometry_misfit(poses, odometry, model: OdometryModel | None = None) -> int | None:
    """The first index ``j`` at which the step ``poses[j-1] -> poses[j]`` departs from the odometry's, or None.

    Parameters
    ----------
    poses : array_like, shape (n, 3)
        The chain's poses ``(x, y, theta)``, one per scan.
    odometry : array_like, shape (n, 3)
        The odometry poses at the same scans (only their increments are used).
    model : OdometryModel, optional
        The drift model (default :class:`~cga_lessons.mapping2d.laser.OdometryModel`).

    A step's departure ``e`` (the chain's step against the odometry increment
    ``u``, in the frame of the moved pose) has the drift model's covariance of
    that increment (:meth:`~cga_lessons.mapping2d.laser.OdometryModel.step_covariance`)
    plus twice the registration error; the step fails when its chi-square
    exceeds :data:`ODOMETRY_GATE`.

    >>> odo = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    >>> odometry_misfit(odo + [0.0, 0.02, 0.0], odo) is None  # the same steps, shifted: no misfit
    True
    >>> odometry_misfit(np.array([[0.0, 0, 0], [1.0, 0, 0], [3.0, 0, 0]]), odo)  # a 1 m jump at the second step
    2
    """
    func = "odometry_misfit"
    P = checks.array(poses, func, "poses", (None, 3))
    O = checks.array(odometry, func, "odometry", (None, 3))
    checks.same_length(func, poses=P, odometry=O)
    m = OdometryModel() if model is None else model
    for j in range(1, len(P)):
        u = relative(O[j - 1], O[j])
        e = relative(compose(P[j - 1], u), P[j])
        v = np.diag(m.step_covariance(u))
        v_xy, v_th = v[0] + 2 * REGISTRATION_XY**2, v[2] + 2 * REGISTRATION_THETA**2
        if (e[0] ** 2 + e[1] ** 2) / v_xy + wrap_angle(e[2]) ** 2 / v_th > ODOMETRY_GATE:
            return j
    return None
