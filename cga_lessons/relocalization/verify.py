"""Checking and refining a relocalization hypothesis against the whole scan.

* :func:`score_poses`: returning beams whose points lie on the map count for a
  pose, beams that would have to pass through a map wall count against it,
  beams without return included (they must not cross a wall within the
  laser's range);
* :func:`match_lines`: the scan lines that lie on map lines at a pose (the
  correspondences of the answer);
* :func:`refine_pose_points`: a few Gauss-Newton steps on the distances of
  the scan's points to the walls their beams meet first (projective
  association: a point is pulled to the near face of a thin wall).

The steps of :func:`cga_lessons.relocalization.relocalize` built on these are in
:mod:`cga_lessons.relocalization.candidates`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import wrap_angle

from .coverage import FREE, UNKNOWN, WALL
from .geometry import MapLines, Observation, ScanLines, first_hits, rotation_matrix
from .search import overlap_fraction

__all__ = [
    "point_normal_equations",
    "score_poses",
    "score_pose",
    "match_lines",
    "refine_pose_points",
    "pose_information",
    "pose_covariance",
]


#: With a coverage model, a pose's score is normalised by the beams that end where the map knows something, but
#: by no fewer than this fraction of the returned beams.  1: by all of them, so that a beam ending in unknown space
#: (outside the map, in a hole) is a beam the pose leaves unexplained, neither for nor against it.  Measured on the
#: six CARMEN logs (every 7th scan held out, map from the rest, the 361 runs of three scans of seed 0): at the true
#: poses 2.0 % of the returned beams end in unknown space (0.3 % Intel to 8.7 % Orebro), at the wrong candidates
#: found for those runs (up to four per run, more than 30 cm or 4 degrees off) 12.9 % (4.4 % Seattle to 23 %
#: CSAIL).  With 0.5 (the beams in unknown space left out of the count, down to half the scan) in 13 of the 361 runs
#: a wrong pose that put 20-70 % of its beams into unknown space scored 0.8 to 1.0, as high as the true one; with 1,
#: 9 more single scans and 14 more runs of the 361 were located (and 1 and 0 more confidently wrong).  Lower values
#: trade that for maps with large holes.
MIN_KNOWN = 1.0

#: A beam without return that crosses a map wall within the laser's reach counts as this many violations (a
#: returned beam that passes through a wall counts as one).  Lasers return nothing from glass, black or glancing
#: surfaces, so a missing return is weaker evidence than a return from behind a wall.  Measured on the same runs:
#: at the true poses 17 % of the beams without return cross a map wall (4.5 % ACES to 40 % CSAIL), against 35 % at
#: the wrong candidates; for returned beams 3.9 % against 15 %.  The log-likelihood ratio of a crossing beam
#: without return is 0.52 times that of a crossing returned beam (pooled; 0.38 to 0.98 per log).  Against a
#: weight of 1, 3 more single scans and 5 more runs of the 361 were located (1 and 0 more confidently wrong).
NO_RETURN_WEIGHT = 0.5


def score_poses(M: MapLines, obs: Observation, poses, inlier_distance: float, ray_margin: float, step: int = 1):
    """Check poses against the whole scan, beam by beam (one ray cast per beam and pose).

    A returned beam is an *inlier* when the first map wall along it lies within
    ``inlier_distance`` of its point (measured perpendicular to that wall).  A
    beam is a *violation* when the map says it could not have been seen: it
    meets a map wall more than ``ray_margin`` before its point or, for a beam
    without return, before ``max_range - ray_margin`` (it must not cross a wall
    within range; it counts :data:`NO_RETURN_WEIGHT` of a violation).  Beams
    that end in front of the map's walls (an object the map does not hold)
    count neither way.

    With a coverage model on the map (``M.coverage``, see
    :mod:`cga_lessons.relocalization.coverage`) the other returned beams are
    read off the grid at their points: a point in a ``WALL`` cell (something
    the mapping scans hit, a line or not) is an inlier; a point in a ``FREE``
    cell (where the mapping scans looked through) is a violation; a point in
    ``UNKNOWN`` space is neither: a beam the pose leaves unexplained.  The
    score is normalised by the beams that ended in known space, but by no
    fewer than :data:`MIN_KNOWN` of the returned beams (all of them by
    default: no renormalisation); the counts are rescaled by the same factor
    so that ``score = (inliers - violations) / returned beams`` still holds
    (and sums over several scans weigh each scan by its beams).

    Parameters
    ----------
    poses : array_like, shape (C, 3)
    step : int
        Use every ``step``-th returned beam and every ``step``-th beam without
        return (a quick screening).

    Returns
    -------
    score : ndarray, shape (C,)
        ``(inliers - violations) / returned beams`` (at most 1; ``-inf`` with no returned beam).
    inliers, violations : ndarray, shape (C,)
        Counts of beams (floats: beams without return weigh :data:`NO_RETURN_WEIGHT`; rescaled with a coverage
        model and :data:`MIN_KNOWN` below 1).
    """
    poses = np.asarray(poses, float).reshape(-1, 3)
    pts, rng, nr = obs.points, obs.ranges, obs.no_return
    if step > 1:
        pts, rng, nr = pts[::step], rng[::step], nr[::step]
    n = len(pts)
    if n == 0:
        z = np.zeros(len(poses), int)
        return np.full(len(poses), -np.inf), z, z
    dirs = np.concatenate([pts / rng[:, None], nr])
    limit = np.concatenate([rng - ray_margin, np.full(len(nr), obs.max_range - ray_margin)])
    reach = (obs.max_range if np.isfinite(obs.max_range) else float(rng.max())) + 1.0
    s_hit, seg = first_hits(M, poses, dirs, reach)
    crossed = s_hit < limit[None]
    vio = np.sum(crossed[:, :n], axis=1) + NO_RETURN_WEIGHT * np.sum(crossed[:, n:], axis=1)
    th = poses[:, 2][:, None]
    c, s = np.cos(th), np.sin(th)
    ux = c * dirs[None, :n, 0] - s * dirs[None, :n, 1]
    uy = s * dirs[None, :n, 0] + c * dirs[None, :n, 1]
    nrm = M.normal[seg[:, :n]]
    cos_inc = np.abs(nrm[..., 0] * ux + nrm[..., 1] * uy)
    with np.errstate(invalid="ignore"):
        perp = np.abs(s_hit[:, :n] - rng[None]) * cos_inc
    on_line = np.isfinite(s_hit[:, :n]) & (perp < inlier_distance)
    cov = getattr(M, "coverage", None)
    if cov is None:
        inl = np.sum(on_line, axis=1)
        return (inl - vio) / n, inl, vio
    world = np.stack([ux * rng[None] + poses[:, 0:1], uy * rng[None] + poses[:, 1:2]], axis=-1)
    state = cov.classify(world)
    rest = ~on_line & ~crossed[:, :n]
    inl = np.sum(on_line | (rest & (state == WALL)), axis=1)
    vio = vio + np.sum(rest & (state == FREE), axis=1)
    known = n - np.sum(rest & (state == UNKNOWN), axis=1)
    scale = n / np.maximum(known, MIN_KNOWN * n)
    return (inl - vio) * scale / n, inl * scale, vio * scale


def score_pose(M: MapLines, obs: Observation, pose, inlier_distance: float, ray_margin: float):
    """:func:`score_poses` for one pose: ``(score, inliers, violations)``."""
    sc, inl, vio = score_poses(M, obs, np.asarray(pose, float)[None], inlier_distance, ray_margin)
    return float(sc[0]), inl[0].item(), vio[0].item()


def match_lines(M: MapLines, S: ScanLines, pose, distance: float, parallel_tol: float, overlap_margin, min_overlap):
    """Scan lines matched to map lines at ``pose``: parallel, midpoint close, lying on the map segment.

    Returns
    -------
    ndarray of int, shape (k, 2)
        Rows ``(map index, scan index)``; each scan line gets its nearest match.
    """
    if len(S) == 0:
        return np.zeros((0, 2), int)
    R = rotation_matrix(pose[2])
    ends = S.segments @ R.T + np.asarray(pose[:2])
    mid = S.midpoint @ R.T + np.asarray(pose[:2])
    ang = np.mod(S.angle + pose[2], np.pi)
    par = np.abs(wrap_angle(2 * (M.angle[None, :] - ang[:, None])) / 2) < parallel_tol  # (L, M)
    dist = np.abs(mid @ M.normal.T - M.offset[None, :])  # (L, M)
    mi = np.broadcast_to(np.arange(len(M))[None, :], par.shape)
    frac = overlap_fraction(
        M, mi, np.broadcast_to(ends[:, None], (len(S), len(M), 2, 2)), S.length[:, None], overlap_margin
    )
    cost = np.where(par & (dist < distance) & (frac >= min_overlap), dist, np.inf)
    best = np.argmin(cost, axis=1)
    ok = np.isfinite(cost[np.arange(len(S)), best])
    return np.column_stack([best[ok], np.flatnonzero(ok)]).astype(int)


def point_normal_equations(M: MapLines, obs: Observation, poses, gate: float):
    """The scan's points against the walls their beams meet first: Gauss-Newton terms for many poses.

    Each returned point ``q = R(theta) p + t`` is paired with the map wall its
    beam meets first at the pose (projective association: a point behind the
    near face of a thin wall is pulled to the near face, not the far one); the
    residual is ``e = n_w . q - c_w`` and only points within ``gate`` of their
    wall count.

    Parameters
    ----------
    poses : ndarray, shape (C, 3)
    gate : float
        Association distance (m).

    Returns
    -------
    H : ndarray, shape (C, 3, 3)
        ``J^T J`` of the residuals in ``(x, y, theta)``.
    g : ndarray, shape (C, 3)
        ``J^T e``.
    used : ndarray, shape (C,)
        How many points counted.
    sse : ndarray, shape (C,)
        The sum of their squared distances ``e^2``.
    """
    poses = np.asarray(poses, float).reshape(-1, 3)
    p = obs.points
    C = len(poses)
    if len(p) == 0 or len(M) == 0:
        return np.zeros((C, 3, 3)), np.zeros((C, 3)), np.zeros(C), np.zeros(C)
    dirs = p / obs.ranges[:, None]
    reach = (obs.max_range if np.isfinite(obs.max_range) else float(obs.ranges.max())) + 1.0
    s_hit, seg = first_hits(M, poses, dirs, reach)
    c, s = np.cos(poses[:, 2])[:, None], np.sin(poses[:, 2])[:, None]
    rx = c * p[None, :, 0] - s * p[None, :, 1]  # R p, (C, n)
    ry = s * p[None, :, 0] + c * p[None, :, 1]
    nx, ny = M.normal[seg, 0], M.normal[seg, 1]
    e = nx * (rx + poses[:, 0:1]) + ny * (ry + poses[:, 1:2]) - M.offset[seg]
    w = (np.isfinite(s_hit) & (np.abs(e) < gate)).astype(float)
    J = np.stack([nx, ny, ny * rx - nx * ry], axis=-1) * w[..., None]  # d e / d (x, y, theta)
    H, g = np.einsum("cni,cnj->cij", J, J), np.einsum("cni,cn->ci", J, e)
    return H, g, w.sum(axis=1), np.einsum("cn,cn->c", w, e * e)


def refine_pose_points(M: MapLines, obs: Observation, poses, gates=(0.3, 0.15, 0.08, 0.05), damping: float = 1e-3):
    """Gauss-Newton steps on the scan's points against the walls their beams meet first, for many poses.

    Each returned point ``q = R(theta) p + t`` is paired with the map wall its
    beam meets first at the current pose (projective association: a point
    behind the near face of a thin wall is pulled to the near face, not the
    far one), and ``(x, y, theta)`` moves to reduce the squared distances
    ``(n_w . q - c_w)^2`` of the points within ``gate`` of their wall; one
    step per gate.  The normal equations are damped by ``damping`` times their
    diagonal, so a direction no point constrains (a corridor without ends in
    view) stays where it is.

    Parameters
    ----------
    poses : array_like, shape (C, 3)
    gates : sequence of float
        Association distances (m), one Gauss-Newton step each.

    Returns
    -------
    ndarray, shape (C, 3)
    """
    poses = np.array(poses, float).reshape(-1, 3)
    if len(obs.points) < 3 or len(M) == 0:
        return poses
    for gate in gates:
        H, g, used, _ = point_normal_equations(M, obs, poses, gate)
        H = H + damping * np.einsum("cii->ci", H)[:, :, None] * np.eye(3) + 1e-9 * np.eye(3)
        enough = used >= 3
        if not enough.any():
            break
        step = np.zeros_like(poses)
        step[enough] = -np.linalg.solve(H[enough], g[enough][..., None])[..., 0]
        poses = poses + step
        poses[:, 2] = wrap_angle(poses[:, 2])
    return poses


def pose_information(M: MapLines, obs: Observation, pose, gate: float = 0.05):
    """What the scan's points say about a pose: the information matrix ``J^T J`` (3, 3) and the residual variance.

    ``J`` holds the rows of :func:`point_normal_equations` (derivatives of each
    point's distance to the wall its beam meets first, by ``x, y, theta``) for
    the points within ``gate`` of their wall; ``sigma^2`` is their squared
    distances summed over ``n - 3`` (``inf`` with fewer than four such points).
    """
    pose = np.asarray(pose, float).reshape(3)
    if len(obs.points) < 4 or len(M) == 0:
        return np.zeros((3, 3)), np.inf
    H, _, used, sse = point_normal_equations(M, obs, pose[None], gate)
    if used[0] < 4:
        return np.zeros((3, 3)), np.inf
    return H[0], float(sse[0] / (used[0] - 3))


def pose_covariance(M: MapLines, obs: Observation, pose, gate: float = 0.05) -> np.ndarray:
    """Covariance of a pose from the scan's points, ``sigma^2 (J^T J)^-1`` (see :func:`pose_information`), (3, 3).

    A direction that no point constrains (along a corridor whose ends are out
    of sight) gets an infinite variance.
    """
    H, sigma2 = pose_information(M, obs, pose, gate)
    vals, vecs = np.linalg.eigh(H)
    tiny = vals <= 1e-9 * max(vals[-1], 1e-300)
    if not np.isfinite(sigma2) or tiny.all():
        return np.full((3, 3), np.inf)
    cov = sigma2 * (vecs[:, ~tiny] / vals[~tiny]) @ vecs[:, ~tiny].T
    for k in np.flatnonzero(tiny):
        cov = np.where(np.abs(np.outer(vecs[:, k], vecs[:, k])) > 1e-12, np.inf, cov)
    return cov
