"""All the poses and all the map lines estimated together from every observation (beyond section 3.1).

The builder of :mod:`cga_lessons.mapping2d` corrects one scan at a time
against the map built so far (3.5-3.12) and relaxes a pose graph when it
recognises a revisit.  Each of those steps summarises what a scan saw in one
pose and one covariance, and the summaries are not exact: a step's stated
uncertainty is a model, and a revisit then bends a chain whose steps were
right (measured on the CARMEN logs fed their own corrected poses).  Once the
map is built, nothing has to be summarised: every scan's segments and the map
line each was fused into are kept (:class:`~cga_lessons.mapping2d.observations.Observations`),
so the poses and the lines can be estimated at once, as one least-squares
problem whose unknowns are

* every pose after the first (the first fixes the map's frame, 3.4's
  footnote: the robot starts at its own origin), and
* every map line seen from two scans or more, in the Hough form of (3.3):
  ``x cos(theta) + y sin(theta) = rho``;
* the position along its line of every end that scans saw as a real edge;

and whose measurements are

* each observation of a line by a scan: its centroid's distance to the line
  and its angle to the line, with the variances of a line fitted to ``n``
  points with the scan's range noise (the same
  :func:`~cga_lessons.mapping2d.corrections.line_variances` the corrections
  use, with the model floors the builder learnt, and the registration error
  common to a scan's lines as that observation sees it), under a robust
  kernel so that a wrong association cannot pull the map;
* each sighting of a real edge: its position along the line (corridor walls
  alone say nothing along the corridor; their doors and ends do);
* each odometry increment, with the covariance of its drift model scaled by
  what the builder learnt of the odometry over the whole run (:class:`~cga_lessons.mapping2d.noise.InnovationModel`'s
  ``q``, :meth:`~cga_lessons.mapping2d.run.MapRun.odometry_scale`: a log whose odometry is right is held by it).

The point-to-line cost of a segment's points about a line is, exactly, ``n``
times its centroid's squared distance plus the scatter about the centroid
across the line, so the two rows per observation carry what the points carry.
Gauss-Newton with the sparse normal equations (each row touches one pose and
one line, or two poses) converges in about a dozen rounds from the builder's
poses (the robust weights change every round).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse

from cga_lessons.errors import InvalidInputError

from .adjust_rows import edge_rows, edge_sightings, line_observations, line_params, observation_rows, odometry_rows
from .geometry import SegmentSet
from .least_squares import KERNELS, solve_spd
from .poses import wrap_unchecked

__all__ = ["AdjustParams", "Adjustment", "adjust_map", "adjust_built_map"]


@dataclass(frozen=True)
class AdjustParams:
    """Settings of :func:`adjust_map`.

    Attributes
    ----------
    iterations : int
        Most Gauss-Newton rounds (20).  The robust weights change every round, so the steps shrink by about a
        third a round (Intel, from the builder's poses: 18 cm, 5 cm, 4 cm, ... 1 mm at the eleventh).
    tolerance : (float, float)
        Stop when no pose moves by more than this in a round (m, rad): 1 mm and 0.3 mrad (0.02 degrees), a
        tenth of the range noise of the bundled logs' lasers (0.7-1.4 cm) and of the disagreement of two
        registrations of one pair of their scans (0.2-0.3 degrees).
    kernel : float
        The kernel's scale, in standard deviations of an observation's two rows together (2: the builder's
        ``robust_kernel``).
    edge_match : float
        A real-edge sighting is tied to its line's nearer end when within this (m; the builder's ``edge_match``).
    loss : {"cauchy", "huber"}
        The robust kernel.  Cauchy (a wrong association's pull fades to nothing): measured on the six logs,
        seeds 0-3, against Huber (whose pull stays constant): ratio target met in 21 against 20 of 24 runs, map
        median in 20 against 14 of 30, the logs' own poses held in 2 against 1 of 6.
    min_scans : int
        A line enters when at least this many scans saw it (2: a line seen once constrains no pose).
    """

    iterations: int = 20
    tolerance: tuple = (1e-3, 3e-4)
    kernel: float = 2.0
    min_scans: int = 2
    edge_match: float = 0.3
    loss: str = "cauchy"


@dataclass(frozen=True)
class Adjustment:
    """The result of :func:`adjust_map`.

    Attributes
    ----------
    poses : ndarray, shape (T, 3)
    iterations : int
    cost : (float, float)
        Robust cost (sum of squared standardised rows, weighted by the kernel) at the first and the last round.
    lines, observations : int
        Lines and line observations that took part.
    outliers : int
        Observations down-weighted by the kernel at the end.
    """

    poses: np.ndarray
    iterations: int
    cost: tuple
    lines: int
    observations: int
    outliers: int


def adjust_map(poses, increments, step_covs, obs: SegmentSet, scan, line, G: SegmentSet, *, mount=(0, 0, 0),
               floors=(0.0, 0.0, 9e-4), scan_cov=None, params: AdjustParams | None = None) -> Adjustment:  # fmt: skip
    """Estimate all poses and lines together from the observations and the odometry (see the module's text).

    Parameters
    ----------
    poses : array_like, shape (T, 3)
        The builder's poses (the start); ``poses[0]`` is kept.
    increments : array_like, shape (T - 1, 3)
        Odometry increments ``relative(odometry[k - 1], odometry[k])``.
    step_covs : array_like, shape (T - 1, 3, 3)
        Their covariances (the drift model scaled by the learnt ``q``).
    obs : SegmentSet
        Every observation's segment in its laser frame (with its point sums).
    scan, line : array_like of int, shape (m,)
        The scan of each observation and the row of ``G`` of the map line it was fused into.
    G : SegmentSet
        The map lines (the start of their estimates).
    mount : array_like, shape (3,)
        The laser's pose on the robot.
    floors : (float, float, float)
        Model-error variances of every observation's angle (rad^2), offset (m^2) and real edge's position along
        its line (m^2): the builder's learnt floors.
    scan_cov : array_like, shape (3, 3), optional
        The registration error common to all lines of a scan that the builder learnt
        (:attr:`~cga_lessons.mapping2d.correction.ScanCorrector.registration_cov`), added to every
        observation as it sees it.  A segment's fit claims millimetres; a scan's lines disagree with the map
        by centimetres and tenths of a degree together (the scan is not a rigid snapshot: the robot moves
        while the beams sweep).
    params : AdjustParams, optional

    Returns
    -------
    Adjustment
    """
    func = "adjust_map"
    p = params or AdjustParams()
    X, inc, Q, scan, line = _checked(func, poses, increments, step_covs, obs, scan, line, G, p)
    T = len(X)
    # the lines seen from at least min_scans distinct scans
    pairs = np.unique(np.column_stack([line, scan]), axis=0) if len(line) else np.zeros((0, 2), int)
    seen = np.bincount(pairs[:, 0], minlength=len(G)) if len(pairs) else np.zeros(len(G), int)
    keep = seen[line] >= p.min_scans
    obs, scan, line = obs.take(np.flatnonzero(keep)), scan[keep], line[keep]
    used, line = np.unique(line, return_inverse=True)
    theta, rho = line_params(G.take(used))
    nl, m = len(used), len(scan)
    R = np.zeros((3, 3)) if scan_cov is None else np.asarray(scan_cov, float)
    ob = line_observations(obs, scan, line, mount, floors, R, T)
    # odometry rows, whitened by the Cholesky factor of each step's information
    Linf = np.linalg.cholesky(np.linalg.inv(Q + np.eye(3) * 1e-12))  # information = L L^T
    Wod = np.transpose(Linf, (0, 2, 1))  # rows r' = L^T r
    # real edges: each sighting tied to the nearer end of its map line (within edge_match), one unknown per end
    ed, sval = edge_sightings(obs, scan, line, X, G.take(used), theta, mount, p.edge_match, floors, R)
    n_pose = 3 * (T - 1)
    n_lines = n_pose + 2 * nl
    n = n_lines + ed.n_ends
    kernel = KERNELS[p.loss]
    cost0, cost, it, u = None, 0.0, 0, np.zeros(m)
    for it in range(1, p.iterations + 1):  # noqa: B007 (the count is reported)
        r_obs, rows, cols, vals, weights, u = observation_rows(X, theta, rho, ob, kernel, p.kernel, n_pose)
        r_e, we, e_rows, e_cols, e_vals = edge_rows(X, theta, sval, ed, kernel, p.kernel, 2 * m, n_pose, n_lines)
        r_od, o_rows, o_cols, o_vals = odometry_rows(X, inc, Wod, 2 * m + len(ed.scan))
        cost = float(np.sum(weights * u**2) + np.sum(we * r_e**2) + np.sum(r_od**2))
        cost0 = cost if cost0 is None else cost0
        A = sparse.csr_matrix((np.concatenate(vals + e_vals + o_vals),
                               (np.concatenate(rows + e_rows + o_rows), np.concatenate(cols + e_cols + o_cols))),
                              shape=(2 * m + len(ed.scan) + 3 * (T - 1), n))  # fmt: skip
        r = np.concatenate([r_obs, r_e * np.sqrt(we), r_od.ravel()])
        H = (A.T @ A).tocsc() + sparse.identity(n, format="csc") * 1e-9
        step = solve_spd(H, -(A.T @ r))
        if step is None or not np.all(np.isfinite(step)):
            raise InvalidInputError(f"{func}: the normal equations are singular (a line or pose is not determined)")
        X[1:] += step[:n_pose].reshape(-1, 3)
        X[1:, 2] = wrap_unchecked(X[1:, 2])
        theta = theta + step[n_pose:n_lines:2]
        rho = rho + step[n_pose + 1 : n_lines : 2]
        sval = sval + step[n_lines:]
        moved = step[:n_pose].reshape(-1, 3)
        if np.abs(moved[:, :2]).max(initial=0) < p.tolerance[0] and np.abs(moved[:, 2]).max(initial=0) < p.tolerance[1]:
            break
    return Adjustment(X, it, (cost0 if cost0 is not None else 0.0, cost), nl, m, int(np.sum(u > p.kernel)))


def _checked(func, poses, increments, step_covs, obs, scan, line, G, p):
    """The checked arguments of :func:`adjust_map`: poses, increments, step covariances, scan and line indices."""
    X = np.array(poses, float)
    T = len(X)
    inc = np.asarray(increments, float).reshape(-1, 3)
    Q = np.asarray(step_covs, float).reshape(-1, 3, 3)
    scan, line = np.asarray(scan, int).reshape(-1), np.asarray(line, int).reshape(-1)
    if X.ndim != 2 or X.shape[1] != 3 or not np.all(np.isfinite(X)):
        raise InvalidInputError(f"{func}: poses must be a finite (T, 3) array, got shape {X.shape}")
    if len(inc) != T - 1 or len(Q) != T - 1 or not (np.all(np.isfinite(inc)) and np.all(np.isfinite(Q))):
        raise InvalidInputError(f"{func}: increments and step_covs must be finite, one per step ({T - 1})")
    if not (len(scan) == len(line) == len(obs)) or (len(scan) and (scan.min() < 0 or scan.max() >= T)):
        raise InvalidInputError(f"{func}: scan and line must give one scan in 0..{T - 1} and one line per observation")
    if p.loss not in KERNELS:
        raise InvalidInputError(f"{func}: params.loss must be one of {sorted(KERNELS)}, got {p.loss!r}")
    if len(line) and (line.min() < 0 or line.max() >= len(G)):
        raise InvalidInputError(f"{func}: line indices must lie in 0..{len(G) - 1}")
    return X, inc, Q, scan, line


def adjust_built_map(builder, poses, increments, step_covs, params: AdjustParams | None = None) -> Adjustment:
    """:func:`adjust_map` on what a :class:`~cga_lessons.mapping2d.builder.MapBuilder` gathered; its map refitted.

    The observations, the lines they went into and the builder's learnt model floors are read from
    ``builder``; after the adjustment the map lines are refitted from their observations at the new poses
    (:meth:`~cga_lessons.mapping2d.builder.MapBuilder.refit`) and duplicates that now coincide are merged.
    """
    local, scan, ids = builder.observations()
    gid = builder.line_ids
    if len(local) == 0 or len(gid) == 0:
        return Adjustment(np.array(poses, float), 0, (0.0, 0.0), 0, 0, 0)
    rows = np.minimum(np.searchsorted(gid, ids), len(gid) - 1)
    inmap = gid[rows] == ids
    floors = builder.corrector.floors.variances
    params = params or AdjustParams(edge_match=builder.params.correspondence.edge_match)
    adj = adjust_map(poses, increments, step_covs, local.take(np.flatnonzero(inmap)), scan[inmap], rows[inmap],
                     builder.lines, mount=builder.mount, floors=floors, scan_cov=builder.corrector.registration_cov,
                     params=params)  # fmt: skip
    builder.refit(adj.poses)
    builder.remove_duplicates()
    return adj
