"""What keeps loop closure's cost bounded as a run revisits its map again and again: how far the robot may have
drifted from the map, and how much of the pose graph a revisit moves.

Two questions of :mod:`cga_lessons.mapping2d.loops` were answered along the whole chain of poses since the old
lines were seen, and both grew with the log when the robot drives the same building again and again (measured on
the Intel log six laps over, 5,460 scans, seed 0, with ``benchmarks/bench_growth.py``):

* **the search window** (three standard deviations of the drift between the pose and the old lines): the
  variances summed along the chain (:func:`~cga_lessons.mapping2d.graph.chain_uncertainty`) ignore the revisits
  made on the way; in the later laps the chain gave a median of 2 m (up to 9 m) nine scans after the last
  revisit, whose corrections were 3-5 cm, and the search drew its hypotheses from 300-700 old lines, the whole
  map.  :class:`MapDrift` also keeps each pose's covariance relative to the map's frame, propagated step by
  step like the chain's and brought back to the anchor's (plus the revisit's) at each revisit; the drift between
  two poses is at most the sum of their two covariances.  Beyond the loop parameters' ``graph_horizon`` the
  window is the smaller of the two bounds.
* **the relaxation**: a revisit tied to an early anchor freed every pose since that anchor, 1,800-4,900 poses
  a solve in the later laps.  :class:`Relaxation` frees every pose since the anchor within ``graph_horizon``
  scans; beyond, a window (:func:`relax_window`) that doubles until its first pose no longer moves by more than
  the map's refit tolerance (the revisits inside the window hold the correction), and an exact solve from the
  earliest anchor deferred at twice the scan of the last exact one, so that nothing is lost for long.

Within the horizon (every bundled log is shorter) the loop closure is the chain's, to the last bit.
"""

from __future__ import annotations

import numpy as np

from .graph import relative_pose_unchecked

__all__ = ["MapDrift", "Relaxation", "relax_window"]


class MapDrift:
    """Each pose's covariance (3, 3, world frame) relative to the map's frame: propagated along the chain of poses,
    brought back by each revisit.

    Parameters
    ----------
    n_scans : int
    """

    def __init__(self, n_scans: int):
        self.cov = np.zeros((max(int(n_scans), 1), 3, 3))

    def step(self, k: int, poses, var_xy: float, var_theta: float):
        """Pose ``k`` follows pose ``k - 1`` with the step's variances (m^2 on each axis, rad^2): the heading's
        error at ``k - 1`` moves pose ``k`` by the lever of the step, as in the prediction of the pose."""
        d = poses[k, :2] - poses[k - 1, :2]
        J = np.array([[1.0, 0.0, -d[1]], [0.0, 1.0, d[0]], [0.0, 0.0, 1.0]])
        self.cov[k] = J @ self.cov[k - 1] @ J.T + np.diag([var_xy, var_xy, var_theta])

    def revisit(self, k: int, anchor: int, cov):
        """Pose ``k`` was tied to the earlier pose ``anchor`` with covariance ``cov`` (3, 3): it is known relative to
        the map as well as the anchor is, plus the tie, when that is better than the chain."""
        tied = self.cov[anchor] + cov
        if np.trace(tied) < np.trace(self.cov[k]):
            self.cov[k] = tied

    def between(self, j: int, k: int):
        """Standard deviations (position m, heading rad) of pose ``k`` relative to pose ``j``, both held by the map
        (their covariances summed: the correlation through the map is ignored, which can only widen it)."""
        c = self.cov[j] + self.cov[k]
        return float(np.sqrt(np.linalg.eigvalsh(c[:2, :2])[-1])), float(np.sqrt(c[2, 2]))


def relax_window(graph, poses, anchor: int, since: int, tolerance, robust: float):
    """Relax ``poses`` (T, 3) in ``graph`` over a window of the latest poses; returns the poses and the window's
    first pose.

    The window starts with the poses since ``since`` (the last relaxation, or the earliest revisit's scan) and
    doubles until the solve moves its first pose by no more than ``tolerance`` = (m, rad), or reaches the earliest
    revisit's ``anchor`` (the whole loop, every pose it can move).  ``robust`` is the loop edges' robust scale
    (:meth:`~cga_lessons.mapping2d.graph.PoseGraph.optimize`).
    """
    T = len(poses)
    anchor = max(int(anchor), 1)
    n = max(T - int(since), 2)
    while True:
        first = max(anchor, T - n)
        new = graph.optimize(poses, robust=robust, first_free=first)
        if first == anchor:
            return new, first
        d = relative_pose_unchecked(poses[first], new[first])
        if np.hypot(d[0], d[1]) <= tolerance[0] and abs(d[2]) <= tolerance[1]:
            return new, first
        n *= 2


class Relaxation:
    """Which poses each relaxation of the pose graph frees, over a run.

    A revisit whose anchor lies within ``horizon`` scans frees every pose since its anchor, exactly as
    :meth:`~cga_lessons.mapping2d.graph.PoseGraph.optimize` from it; an older one is relaxed over a window
    (:func:`relax_window`).  What a window leaves fixed is deferred, not lost: the first relaxation at or after
    twice the scan of the last exact one frees every pose since the earliest anchor deferred, so the exact
    solves come at scans ``n, 2n, 4n, ...`` and their cost, proportional to the poses, is bounded per scan when
    spread over the scans since the last (the build's final adjustment then adjusts every pose).

    Parameters
    ----------
    horizon : int
        Scans (:attr:`~cga_lessons.mapping2d.params.LoopParams.graph_horizon`).
    tolerance : (float, float)
        ``(m, rad)``: how far a window may leave its first pose moved (the map's refit tolerance).
    robust : float
        Scale of the loop edges' robust weight.
    """

    def __init__(self, horizon: int, tolerance, robust: float):
        self.horizon, self.tolerance, self.robust = int(horizon), tuple(tolerance), robust
        self.since = 0  # the scan of the last relaxation
        self.exact = 0  # the scan of the last exact relaxation
        self.deferred = None  # the earliest anchor relaxed over a window since then

    def relax(self, graph, poses, anchor: int, scans):
        """Relax ``poses`` (poses[:k + 1]) after revisits of scans ``scans`` whose earliest anchor is ``anchor``;
        returns the poses and the first pose freed."""
        k = len(poses) - 1
        scheduled = k >= 2 * self.exact
        if scheduled and self.deferred is not None:
            anchor = min(anchor, self.deferred)
        if scheduled or k - anchor <= self.horizon:
            new, first = graph.optimize(poses, robust=self.robust, first_free=anchor), anchor
            if self.deferred is None or anchor <= self.deferred:  # nothing is left deferred
                self.exact, self.deferred = k, None
        else:
            since = min(self.since, min(scans))
            new, first = relax_window(graph, poses, anchor, since, self.tolerance, self.robust)
            self.deferred = anchor if self.deferred is None else min(self.deferred, anchor)
        self.since = k
        return new, first
