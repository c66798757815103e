"""The rows of the final adjustment (:func:`cga_lessons.mapping2d.adjust.adjust_map`): what each measurement says
and how it moves with the unknowns.

Three kinds of rows, each whitened by its standard deviation: every observation of a map line by a scan (its
centroid's offset from the line and its angle to the line, :func:`line_observations`, :func:`observation_rows`),
every sighting of a real edge (its position along the line against the line's end, :func:`edge_sightings`,
:func:`edge_rows`) and every odometry step (:func:`odometry_rows`).  The unknowns are laid out as
``[poses 1..T-1 (x, y, phi), lines (theta, rho), edge ends (s)]``; each ``*_rows`` function returns the weighted
residuals and the Jacobian's entries ``(rows, cols, vals)`` of its block.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .corrections import line_variances_unchecked
from .geometry import SegmentSet
from .noise import RANGE_NOISE_FLOOR, segment_residual_sigma
from .poses import wrap_unchecked

__all__ = [
    "LineObservations",
    "EdgeSightings",
    "line_params",
    "line_observations",
    "edge_sightings",
    "observation_rows",
    "edge_rows",
    "odometry_rows",
]


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


def line_params(G: SegmentSet):
    """Hough ``(theta, rho)`` of the map lines about the origin (3.3), normals as in the builder's geometry."""
    d = G.end - G.start
    d = d / np.hypot(d[:, 0], d[:, 1])[:, None]
    n = np.column_stack([d[:, 1], -d[:, 0]])
    theta = np.arctan2(n[:, 1], n[:, 0])
    rho = np.einsum("ij,ij->i", n, G.centroid)
    return theta, rho


@dataclass(frozen=True)
class LineObservations:
    """The observations of map lines, as the adjustment uses them (fixed through its rounds).

    Attributes
    ----------
    scan, line : ndarray of int, shape (m,)
        The scan of each observation and the adjusted line (index into the unknowns' lines).
    c_rob : ndarray, shape (m, 2)
        The observation's centroid in its robot frame.
    a_rob : ndarray, shape (m,)
        The angle of its normal in its robot frame.
    w_t, w_r : ndarray, shape (m,)
        The weights (one over the standard deviation) of its angle row and its offset row.
    """

    scan: np.ndarray
    line: np.ndarray
    c_rob: np.ndarray
    a_rob: np.ndarray
    w_t: np.ndarray
    w_r: np.ndarray


def line_observations(obs: SegmentSet, scan, line, mount, floors, scan_cov, T: int) -> LineObservations:
    """Each observation (laser frame) in its robot frame, with the variances of its angle and offset: the fit's
    (the scan's range noise), the model ``floors`` and the registration error ``scan_cov`` common to a scan's
    lines as this observation sees it.

    The first scan's angles carry no angle floor.  Its pose is fixed (the map's frame), so its observations are
    all that says how the whole map is turned about it (rotating every later pose and every line about the
    first position changes no other row but the first odometry step's).  The angle floor was learnt against map
    lines that carry the errors of the poses that built them, as an error independent from line to line; on
    the first scan's few lines it left that turn loose: on the Intel log (floor 0.92 degrees, the first scan's
    two lines at 0.97 degrees each) the map came out turned by 1.2 degrees about the first pose with seed 3's
    odometry, whose first step is 2.7 degrees off (0.33 degrees without the floor on scan 0).  Its registration
    error, common to its lines (``scan_cov``), stays."""
    mc, ms = _rot(mount[2])
    cen = obs.centroid
    c_rob = np.column_stack([mc * cen[:, 0] - ms * cen[:, 1] + mount[0], ms * cen[:, 0] + mc * cen[:, 1] + mount[1]])
    d = obs.end - obs.start
    a_rob = np.arctan2(-d[:, 0], d[:, 1]) + mount[2]  # the normal: direction turned by -90 degrees
    noise = _scan_noise(segment_residual_sigma(obs), scan, T)[scan]
    var_t, var_r = line_variances_unchecked(obs, obs.centroid, 1.0, 0.0, 0.0)  # per unit noise, at the centroid
    # the registration error common to a scan's lines (learnt by the builder), seen by each observation: its
    # angle, and its offset at the centroid (a turn about the robot moves the centroid along the lever)
    R = scan_cov
    ua = np.column_stack([np.cos(a_rob), np.sin(a_rob)])  # the normal in the robot frame
    lever = ua[:, 0] * c_rob[:, 1] - ua[:, 1] * c_rob[:, 0]  # the centroid's position along the line
    scan_t = np.full(len(scan), R[2, 2])
    scan_r = np.einsum("ni,ij,nj->n", ua, R[:2, :2], ua) + R[2, 2] * lever**2
    angle_floor = np.where(scan == 0, 0.0, floors[0])  # the fixed first scan: see above
    w_t = 1 / np.sqrt(var_t * noise**2 + angle_floor + scan_t)
    w_r = 1 / np.sqrt(var_r * noise**2 + floors[1] + scan_r)
    return LineObservations(scan, line, c_rob, a_rob, w_t, w_r)


@dataclass(frozen=True)
class EdgeSightings:
    """The sightings of real edges, each tied to one end of its line (one unknown position ``s`` per end).

    Attributes
    ----------
    scan, line : ndarray of int, shape (me,)
    rob : ndarray, shape (me, 2)
        The sighting in its robot frame.
    end : ndarray of int, shape (me,)
        The unknown end each sighting is of (index into the ends).
    n_ends : int
    weight : float
        One over the standard deviation of a sighting's position along its line.
    """

    scan: np.ndarray
    line: np.ndarray
    rob: np.ndarray
    end: np.ndarray
    n_ends: int
    weight: float


def edge_sightings(obs: SegmentSet, scan, line, X, G: SegmentSet, theta, mount, edge_match, floors, scan_cov):
    """The real-edge ends of the observations, each tied to the end of its map line (``G``'s start or end) that lies
    nearer along the line at the poses ``X``, and dropped when farther than ``edge_match`` from it (an edge of
    another part of the wall): the :class:`EdgeSightings` and the ends' first positions ``s`` (their sightings'
    mean)."""
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
    e_obs, e_rob, e_key, along = e_obs[near], rob[near], 2 * j[near] + end[near], along[near]
    keys, e_id = np.unique(e_key, return_inverse=True)
    ne = len(keys)
    sval = np.bincount(e_id, weights=along, minlength=ne) / np.maximum(np.bincount(e_id, minlength=ne), 1)
    w_e = 1 / np.sqrt(max(float(floors[2]) + scan_cov[0, 0], 1e-12))
    return EdgeSightings(scan[e_obs], line[e_obs], e_rob, e_id, ne, w_e), sval


def observation_rows(X, theta, rho, ob: LineObservations, kernel, scale, n_pose: int):
    """The observations' rows at the poses ``X`` and lines ``(theta, rho)``, robustly weighted (``kernel`` at
    ``scale``, both rows of an observation together): ``(residuals (2m,), rows, cols, vals, weights, u)`` with
    ``u`` the observations' standardised sizes."""
    scan, line, c_rob, w_t, w_r = ob.scan, ob.line, ob.c_rob, ob.w_t, ob.w_r
    m = len(scan)
    c, s = _rot(X[scan, 2])
    wx = c * c_rob[:, 0] - s * c_rob[:, 1] + X[scan, 0]
    wy = s * c_rob[:, 0] + c * c_rob[:, 1] + X[scan, 1]
    ct, st = np.cos(theta[line]), np.sin(theta[line])
    raw_off = ct * wx + st * wy - rho[line]
    psi = wrap_unchecked(ob.a_rob + X[scan, 2] - theta[line])
    psi = np.where(psi > np.pi / 2, psi - np.pi, np.where(psi <= -np.pi / 2, psi + np.pi, psi))  # unoriented
    r_off, r_ang = raw_off * w_r, np.sin(psi) * w_t
    u = np.sqrt(r_off**2 + r_ang**2)
    weights = kernel(u, scale)
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
    return np.concatenate([r_off * sw, r_ang * sw]), rows, cols, vals, weights, u


def edge_rows(X, theta, sval, ed: EdgeSightings, kernel, scale, first_row: int, n_pose: int, n_lines: int):
    """The edge sightings' rows: each sighting's position along its line against its end ``s``, robustly
    weighted: ``(raw weighted residuals r_e, kernel weights we, rows, cols, vals)``."""
    e_scan, e_line, e_rob, e_id = ed.scan, ed.line, ed.rob, ed.end
    ec, es = _rot(X[e_scan, 2])
    ex = ec * e_rob[:, 0] - es * e_rob[:, 1] + X[e_scan, 0]
    ey = es * e_rob[:, 0] + ec * e_rob[:, 1] + X[e_scan, 1]
    dxj, dyj = -np.sin(theta[e_line]), np.cos(theta[e_line])
    raw_e = dxj * ex + dyj * ey - sval[e_id]
    r_e = raw_e * ed.weight
    we = kernel(np.abs(r_e), scale)
    rows, cols, vals = [], [], []
    swe = np.sqrt(we) * ed.weight
    i_e = first_row + np.arange(len(e_scan))
    e_mov = e_scan > 0
    dphi_e = dxj * (-(ey - X[e_scan, 1])) + dyj * (ex - X[e_scan, 0])
    for k, v in enumerate((dxj, dyj, dphi_e)):
        rows.append(i_e[e_mov])
        cols.append(3 * (e_scan[e_mov] - 1) + k)
        vals.append((v * swe)[e_mov])
    rows += [i_e, i_e]
    cols += [n_pose + 2 * e_line, n_lines + e_id]
    vals += [-(np.cos(theta[e_line]) * ex + np.sin(theta[e_line]) * ey) * swe, -swe]
    return r_e, we, rows, cols, vals


def odometry_rows(X, inc, Wod, first_row: int):
    """The odometry steps' rows ``r = W e``, ``e = relative(x_a, x_b) - u`` (``W`` whitens each step's
    covariance): ``(r_od (T-1, 3), rows, cols, vals)``."""
    T = len(X)
    c0, s0 = _rot(X[:-1, 2])
    dx, dy = X[1:, 0] - X[:-1, 0], X[1:, 1] - X[:-1, 1]
    rel = np.column_stack([c0 * dx + s0 * dy, -s0 * dx + c0 * dy, wrap_unchecked(X[1:, 2] - X[:-1, 2])])
    e = rel - inc
    e[:, 2] = wrap_unchecked(e[:, 2])
    r_od = np.einsum("kij,kj->ki", Wod, e)
    rows, cols, vals = [], [], []
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
                rows.append(first_row + 3 * ka[ok] + i)
                cols.append(3 * (pose_of[ok] - 1) + j)
                vals.append(J[ok, i, j])
    return r_od, rows, cols, vals
