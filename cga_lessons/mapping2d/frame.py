"""The map's frame: how far the whole map is turned, read from every odometry heading (beyond section 3.1).

The builder puts the first pose where the odometry says (the robot starts at its own origin, the footnote of 3.4)
and builds the map from the first scan's lines seen from there; every later pose is registered on that map.  So
the whole map is turned by the first scans' registration error: a scan's lines are not a rigid snapshot, and the
six bundled logs' scans disagree with their own corrected poses by 0.13-0.21 degrees (median; RMS 0.30-0.57), the
first scan by up to 0.33 degrees (``benchmarks/bench_log_consistency.py``, with none of this package's line code).
At 20 m that is 7-12 cm.

Every later odometry heading says something about that turn, as much as the odometry's drift lets it: the builder's
heading of pose ``k`` minus the odometry's is

.. math:: r_k = \\varepsilon + \\delta_k - \\sum_{i \\le k} \\eta_i

with ``epsilon`` the map's turn (before any heading is read: a registration error, variance ``s_r``), ``delta_k``
the pose's own registration error (variance ``s_r``) and ``eta_i`` the odometry's heading error on step ``i``
(variance ``q s_i`` by its drift model, scaled by what the builder learnt of the odometry,
:class:`~cga_lessons.mapping2d.noise.InnovationModel`).  The ``r_k`` are a random walk seen through white noise
that starts at ``epsilon``: its estimate is the smoothed state at the first pose (a Kalman filter forward, the
Rauch-Tung-Striebel smoother back; O(T)).  With an odometry that drifts as its model says the walk swamps every
heading after the first few and ``epsilon`` stays near zero (the prior); with an odometry that has proved exact
(the corrected logs fed their own poses: ``q`` falls to 1e-4) every heading counts and the turn of the first scan
is taken out.
"""

from __future__ import annotations

import numpy as np

from .poses import wrap_unchecked

__all__ = ["map_turn", "turn_about"]


def map_turn(headings, odometry_headings, step_variances, registration_variance: float) -> tuple[float, float]:
    """How far the map is turned from the odometry's frame, and its variance: ``(epsilon, var)`` (rad, rad^2).

    Parameters
    ----------
    headings, odometry_headings : array_like, shape (T,)
        The builder's headings and the odometry's (rad); the first pose is the odometry's by construction.
    step_variances : array_like, shape (T - 1,)
        The variance of the odometry's heading error on each step (rad^2).
    registration_variance : float
        The variance of a pose's registration error on the map, and of the map's turn before any heading is read.

    >>> rng = np.random.default_rng(0)
    >>> truth = np.cumsum(rng.normal(0, 0.3, 500))  # the robot's headings
    >>> built = truth + 0.004 + rng.normal(0, 0.005, 500)  # the map turned by 0.004 rad, 0.005 rad registrations
    >>> built[0] = truth[0]
    >>> eps, var = map_turn(built, truth, np.full(499, 1e-10), 0.005**2)  # an exact odometry
    >>> bool(abs(eps - 0.004) < 3 * np.sqrt(var)), bool(np.sqrt(var) < 0.0005)
    (True, True)
    >>> eps, var = map_turn(built, truth, np.full(499, 0.02**2), 0.005**2)  # one that drifts: the prior holds
    >>> bool(abs(eps) < 0.002), bool(np.sqrt(var) > 0.004)
    (True, True)
    """
    r = wrap_unchecked(np.asarray(headings, float) - np.asarray(odometry_headings, float))
    q = np.asarray(step_variances, float)
    s_r = float(registration_variance)
    T = len(r)
    m, P = 0.0, s_r  # the state (the walk) at pose 0: epsilon, with the prior of one registration
    means, covs, pred_means, pred_covs = np.empty(T), np.empty(T), np.empty(T), np.empty(T)
    means[0], covs[0] = m, P
    for k in range(1, T):
        mp, Pp = m, P + q[k - 1]
        K = Pp / (Pp + s_r)
        m, P = mp + K * (r[k] - mp), (1.0 - K) * Pp
        means[k], covs[k], pred_means[k], pred_covs[k] = m, P, mp, Pp
    ms, Ps = m, P
    for k in range(T - 2, -1, -1):
        G = covs[k] / pred_covs[k + 1]
        ms = means[k] + G * (ms - pred_means[k + 1])
        Ps = covs[k] + G * G * (Ps - pred_covs[k + 1])
    return float(ms), float(Ps)


def turn_about(poses, centre, angle: float) -> np.ndarray:
    """``poses`` (T, 3) turned by ``angle`` (rad) about the point ``centre`` (2,): positions and headings."""
    poses = np.array(poses, float)
    c, s = np.cos(angle), np.sin(angle)
    poses[:, :2] = (poses[:, :2] - centre) @ np.array([[c, s], [-s, c]]) + centre
    poses[:, 2] = wrap_unchecked(poses[:, 2] + angle)
    return poses
