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
  what the builder learnt of the odometry (:class:`~cga_lessons.mapping2d.noise.InnovationModel`'s
  ``q``, per step: a log whose odometry is right is held by it).

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
from scipy.sparse.linalg import splu

from cga_lessons.errors import InvalidInputError

from .corrections import line_variances_unchecked
from .geometry import SegmentSet
from .noise import RANGE_NOISE_FLOOR, segment_residual_sigma
from .poses import wrap_unchecked

__all__ = ["AdjustParams", "Adjustment", "adjust_map", "adjust_built_map", "solve_spd"]


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


def solve_spd(H, b):
    """Solve ``H x = b`` for a sparse symmetric positive definite ``H``; None if the factorisation fails.

    SuperLU in its symmetric mode: a minimum-degree ordering of ``H`` (``MMD_AT_PLUS_A``) and no pivoting off the
    diagonal, which keeps the fill of a Cholesky factor.  On the adjustment of the Intel log (4,297 unknowns) it
    took 23 ms against 101 ms for ``spsolve``'s default column ordering with partial pivoting; three laps of it
    (10,259 unknowns): 109 ms against 1,084 ms.
    """
    try:
        lu = splu(sparse.csc_matrix(H), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                  options=dict(SymmetricMode=True))  # fmt: skip
    except RuntimeError:  # exactly singular
        return None
    return lu.solve(np.asarray(b, float))


def _huber(u, k):
    return np.where(u <= k, 1.0, k / np.maximum(u, 1e-300))


def _cauchy(u, k):
    return 1.0 / (1.0 + (u / k) ** 2)


KERNELS = {"huber": _huber, "cauchy": _cauchy}


def _rot(theta):
    c, s = np.cos(theta), np.sin(theta)
    return c, s


def _scan_noise(sigma, scan, T):
    """Per-scan range noise: the median of its segments' residual sigmas (as the builder's corrector does)."""
    out = np.full(T, np.nan)
    order = np.argsort(scan, kind="stable")
    s, sig = scan[order], sigma[order]
    cuts = np.flatnonzero(np.diff(s)) + 1
    for part, k in zip(np.split(sig, cuts), s[np.concatenate([[0], cuts])] if len(s) else []):
        out[k] = np.median(part)
    good = np.isfinite(out)
    fill = np.median(out[good]) if good.any() else RANGE_NOISE_FLOOR
    return np.maximum(np.where(good, out, fill), RANGE_NOISE_FLOOR)


def _edge_sightings(obs, scan, line, X, G, theta, mount, edge_match):
    """The real-edge ends of the observations: (observation, point in the robot frame, key ``2 line + end``,
    position along the line at the poses ``X``).

    Each sighting is tied to the end of its map line (``G``'s start or end) that lies nearer along the line,
    and dropped when farther than ``edge_match`` from it (an edge of another part of the wall).
    """
    mc, ms = _rot(mount[2])
    idx, pts = [], []
    for side, ends in ((0, obs.start), (1, obs.end)):
        f = np.flatnonzero(obs.edge[:, side] > 0)
        idx.append(f)
        pts.append(ends[f])
    e_obs = np.concatenate(idx)
    p = np.concatenate(pts) if len(e_obs) else np.zeros((0, 2))
    rob = np.column_stack([mc * p[:, 0] - ms * p[:, 1] + mount[0], ms * p[:, 0] + mc * p[:, 1] + mount[1]])
    k, j = scan[e_obs], line[e_obs]
    c, s = _rot(X[k, 2])
    w = np.column_stack([c * rob[:, 0] - s * rob[:, 1] + X[k, 0], s * rob[:, 0] + c * rob[:, 1] + X[k, 1]])
    d = np.column_stack([-np.sin(theta[j]), np.cos(theta[j])])
    along = np.einsum("ij,ij->i", d, w)
    a0, a1 = np.einsum("ij,ij->i", d, G.start[j]), np.einsum("ij,ij->i", d, G.end[j])
    end = (np.abs(along - a1) < np.abs(along - a0)).astype(int)
    near = np.abs(along - np.where(end == 1, a1, a0)) <= edge_match
    return e_obs[near], rob[near], 2 * j[near] + end[near], along[near]


def _line_params(G: SegmentSet):
    """Hough ``(theta, rho)`` of the map lines about the origin (3.3), normals as in the builder's geometry."""
    d = G.end - G.start
    d = d / np.hypot(d[:, 0], d[:, 1])[:, None]
    n = np.column_stack([d[:, 1], -d[:, 0]])
    theta = np.arctan2(n[:, 1], n[:, 0])
    rho = np.einsum("ij,ij->i", n, G.centroid)
    return theta, rho


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
    # the lines seen from at least min_scans distinct scans
    pairs = np.unique(np.column_stack([line, scan]), axis=0) if len(line) else np.zeros((0, 2), int)
    seen = np.bincount(pairs[:, 0], minlength=len(G)) if len(pairs) else np.zeros(len(G), int)
    keep = seen[line] >= p.min_scans
    obs, scan, line = obs.take(np.flatnonzero(keep)), scan[keep], line[keep]
    used, line = np.unique(line, return_inverse=True)
    theta, rho = _line_params(G.take(used))
    nl, m = len(used), len(scan)
    # each observation in its robot frame: centroid c, normal angle a, and its variances
    mc, ms = _rot(mount[2])
    cen = obs.centroid
    c_rob = np.column_stack([mc * cen[:, 0] - ms * cen[:, 1] + mount[0], ms * cen[:, 0] + mc * cen[:, 1] + mount[1]])
    d = obs.end - obs.start
    a_rob = np.arctan2(-d[:, 0], d[:, 1]) + mount[2]  # the normal: direction turned by -90 degrees
    noise = _scan_noise(segment_residual_sigma(obs), scan, T)[scan]
    var_t, var_r = line_variances_unchecked(obs, obs.centroid, 1.0, 0.0, 0.0)  # per unit noise, at the centroid
    # the registration error common to a scan's lines (learnt by the builder), seen by each observation: its
    # angle, and its offset at the centroid (a turn about the robot moves the centroid along the lever)
    R = np.zeros((3, 3)) if scan_cov is None else np.asarray(scan_cov, float)
    ua = np.column_stack([np.cos(a_rob), np.sin(a_rob)])  # the normal in the robot frame
    lever = ua[:, 0] * c_rob[:, 1] - ua[:, 1] * c_rob[:, 0]  # the centroid's position along the line
    scan_t = np.full(m, R[2, 2])
    scan_r = np.einsum("ni,ij,nj->n", ua, R[:2, :2], ua) + R[2, 2] * lever**2
    w_t = 1 / np.sqrt(var_t * noise**2 + floors[0] + scan_t)
    w_r = 1 / np.sqrt(var_r * noise**2 + floors[1] + scan_r)
    # odometry rows, whitened by the Cholesky factor of each step's information
    Linf = np.linalg.cholesky(np.linalg.inv(Q + np.eye(3) * 1e-12))  # information = L L^T
    Wod = np.transpose(Linf, (0, 2, 1))  # rows r' = L^T r
    # real edges: each sighting tied to the nearer end of its map line (within edge_match), one unknown per end
    ends = _edge_sightings(obs, scan, line, X, G.take(used), theta, mount, p.edge_match)
    e_obs, e_rob, e_key, along = ends
    e_scan, e_line = scan[e_obs], line[e_obs]
    keys, e_id = np.unique(e_key, return_inverse=True)
    ne = len(keys)
    sval = np.bincount(e_id, weights=along, minlength=ne) / np.maximum(np.bincount(e_id, minlength=ne), 1)
    w_e = 1 / np.sqrt(max(float(floors[2]) + R[0, 0], 1e-12))
    me = len(e_obs)
    n_pose = 3 * (T - 1)
    n_lines = n_pose + 2 * nl
    n = n_lines + ne
    cost0 = None
    it = 0
    weights = np.ones(m)
    for it in range(1, p.iterations + 1):  # noqa: B007 (the count is reported)
        # --- observation rows
        c, s = _rot(X[scan, 2])
        wx = c * c_rob[:, 0] - s * c_rob[:, 1] + X[scan, 0]
        wy = s * c_rob[:, 0] + c * c_rob[:, 1] + X[scan, 1]
        ct, st = np.cos(theta[line]), np.sin(theta[line])
        raw_off = ct * wx + st * wy - rho[line]
        psi = wrap_unchecked(a_rob + X[scan, 2] - theta[line])
        psi = np.where(psi > np.pi / 2, psi - np.pi, np.where(psi <= -np.pi / 2, psi + np.pi, psi))  # unoriented
        r_off, r_ang = raw_off * w_r, np.sin(psi) * w_t
        # --- edge rows: the sighting's position along its line against the line's end
        ec, es = _rot(X[e_scan, 2])
        ex = ec * e_rob[:, 0] - es * e_rob[:, 1] + X[e_scan, 0]
        ey = es * e_rob[:, 0] + ec * e_rob[:, 1] + X[e_scan, 1]
        dxj, dyj = -np.sin(theta[e_line]), np.cos(theta[e_line])
        raw_e = dxj * ex + dyj * ey - sval[e_id]
        r_e = raw_e * w_e
        # --- odometry rows
        c0, s0 = _rot(X[:-1, 2])
        dx, dy = X[1:, 0] - X[:-1, 0], X[1:, 1] - X[:-1, 1]
        rel = np.column_stack([c0 * dx + s0 * dy, -s0 * dx + c0 * dy, wrap_unchecked(X[1:, 2] - X[:-1, 2])])
        e = rel - inc
        e[:, 2] = wrap_unchecked(e[:, 2])
        r_od = np.einsum("kij,kj->ki", Wod, e)
        # --- robust weights per observation (both rows together)
        u = np.sqrt(r_off**2 + r_ang**2)
        kernel = KERNELS[p.loss]
        weights = kernel(u, p.kernel)
        we = kernel(np.abs(r_e), p.kernel)
        cost = float(np.sum(weights * u**2) + np.sum(we * r_e**2) + np.sum(r_od**2))
        cost0 = cost if cost0 is None else cost0
        # --- Jacobian: observation rows
        rows, cols, vals = [], [], []
        sw = np.sqrt(weights)
        pc = 3 * (scan - 1)  # pose columns (scan 0 is fixed)
        movable = scan > 0
        lc = n_pose + 2 * line
        i_off, i_ang = np.arange(m), m + np.arange(m)
        # d r_off / d (x, y, phi): n . dw; dw/dphi = perp(w - t)
        dphi = ct * (-(wy - X[scan, 1])) + st * (wx - X[scan, 0])
        for k, v in enumerate((ct, st, dphi)):
            rows.append(i_off[movable])
            cols.append(pc[movable] + k)
            vals.append((v * w_r * sw)[movable])
        # d r_off / d theta = n_perp . w ; d r_off / d rho = -1
        rows += [i_off, i_off]
        cols += [lc, lc + 1]
        vals += [(-st * wx + ct * wy) * w_r * sw, -w_r * sw]
        # d r_ang / d phi = cos(psi); d r_ang / d theta = -cos(psi)
        cp = np.cos(psi) * w_t * sw
        rows += [i_ang[movable], i_ang]
        cols += [pc[movable] + 2, lc]
        vals += [cp[movable], -cp]
        # --- Jacobian: edge rows
        swe = np.sqrt(we) * w_e
        i_e = 2 * m + np.arange(me)
        e_mov = e_scan > 0
        dphi_e = dxj * (-(ey - X[e_scan, 1])) + dyj * (ex - X[e_scan, 0])
        for k, v in enumerate((dxj, dyj, dphi_e)):
            rows.append(i_e[e_mov])
            cols.append(3 * (e_scan[e_mov] - 1) + k)
            vals.append((v * swe)[e_mov])
        rows += [i_e, i_e]
        cols += [n_pose + 2 * e_line, n_lines + e_id]
        vals += [-(np.cos(theta[e_line]) * ex + np.sin(theta[e_line]) * ey) * swe, -swe]
        # --- Jacobian: odometry rows r = W e, e = rel(x_a, x_b) - u
        base = 2 * m + me
        ka = np.arange(T - 1)
        Ja = np.zeros((T - 1, 3, 3))
        Jb = np.zeros((T - 1, 3, 3))
        Ja[:, 0, 0], Ja[:, 0, 1], Ja[:, 1, 0], Ja[:, 1, 1] = -c0, -s0, s0, -c0
        Ja[:, 0, 2] = -s0 * dx + c0 * dy
        Ja[:, 1, 2] = -c0 * dx - s0 * dy
        Ja[:, 2, 2] = -1.0
        Jb[:, 0, 0], Jb[:, 0, 1], Jb[:, 1, 0], Jb[:, 1, 1] = c0, s0, -s0, c0
        Jb[:, 2, 2] = 1.0
        WJa, WJb = Wod @ Ja, Wod @ Jb
        for J, pose_of in ((WJa, ka), (WJb, ka + 1)):
            ok = pose_of > 0
            for i in range(3):
                for j in range(3):
                    rows.append(base + 3 * ka[ok] + i)
                    cols.append(3 * (pose_of[ok] - 1) + j)
                    vals.append(J[ok, i, j])
        A = sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                              shape=(2 * m + me + 3 * (T - 1), n))  # fmt: skip
        r = np.concatenate([r_off * sw, r_ang * sw, r_e * np.sqrt(we), r_od.ravel()])
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


def adjust_built_map(builder, poses, increments, step_covs, params: AdjustParams | None = None) -> Adjustment:
    """:func:`adjust_map` on what a :class:`~cga_lessons.mapping2d.builder.MapBuilder` gathered; its map refitted.

    The observations, the lines they went into and the builder's learnt model floors are read from
    ``builder``; after the adjustment the map lines are refitted from their observations at the new poses
    (:meth:`~cga_lessons.mapping2d.builder.MapBuilder.refit`) and duplicates that now coincide are merged.
    """
    local, scan, ids = builder.observations()
    gid = builder.gid
    if len(local) == 0 or len(gid) == 0:
        return Adjustment(np.array(poses, float), 0, (0.0, 0.0), 0, 0, 0)
    rows = np.minimum(np.searchsorted(gid, ids), len(gid) - 1)
    inmap = gid[rows] == ids
    floors = builder.corrector.floors.variances
    params = params or AdjustParams(edge_match=builder.p.edge_match)
    adj = adjust_map(poses, increments, step_covs, local.take(np.flatnonzero(inmap)), scan[inmap], rows[inmap],
                     builder.G, mount=builder.mount, floors=floors, scan_cov=builder.corrector.registration_cov,
                     params=params)  # fmt: skip
    builder.refit(adj.poses)
    builder.remove_duplicates()
    return adj
