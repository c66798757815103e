"""Pose hypotheses for the relocalization: rotations from angle votes, exact translations from line pairs.

The search of :func:`cga_lessons.relocalization.relocalize` (chapter 5 made
to work; the literal method is :mod:`cga_lessons.relocalization.hough`):

* :func:`rotation_votes` / :func:`propose_rotations`: the angle part of the
  votes (5.1, 5.6), which is sound: a rotation about the laser moves every line
  by the same angle, so the differences of line directions between map and
  scan pile up at the rotation.  Directions are compared modulo ``pi`` (a map
  wall may be stored either way round), so each proposal gives two rotations.
* :func:`pose_hypotheses`: for a rotation, a pair of non-parallel scan lines
  matched to a pair of map lines parallel to them fixes the translation
  exactly (two equations of (3.11): the least squares (3.12) with two lines);
  the matched scan segments must lie on their map segments.  When the scan
  holds nothing across its longest line (a corridor), positions along that
  line's map partners are tried too.  Each hypothesis gets a quick score:
  the scan length that lands on map segments.

Checking the hypotheses against the scan is :mod:`cga_lessons.relocalization.verify`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import wrap_angle

from .geometry import MapLines, ScanLines, rotation_matrix

__all__ = ["rotation_votes", "propose_rotations", "parallel_pairs", "overlap_fraction", "pose_hypotheses"]


# --------------------------------------------------------------------------- rotations from angle votes


def rotation_votes(map_angle, scan_angle, scan_weight, xi_theta):
    """Angle votes: for every pair (map line, scan line), the weight of all pairs that agree on its rotation.

    The rotation that carries scan line ``l`` onto map line ``m`` is ``delta =
    angle_m - angle_l`` modulo pi (5.1 with directions, so the two faces of a
    wall agree).  The vote of ``delta`` is the total weight of pairs whose own
    ``delta`` lies within ``xi_theta`` of it: (5.6) with the ``rho`` test left
    out.  Sorting the ``|M| |L|`` differences makes it ``O(|M| |L| log)``.

    Returns
    -------
    delta : ndarray, shape (M, L)
    votes : ndarray, shape (M, L)
    """
    delta = np.mod(np.asarray(map_angle)[:, None] - np.asarray(scan_angle)[None, :], np.pi)
    w = np.broadcast_to(np.asarray(scan_weight, float)[None, :], delta.shape).ravel()
    d = delta.ravel()
    order = np.argsort(d, kind="stable")
    ds = np.concatenate([d[order] - np.pi, d[order], d[order] + np.pi])
    cw = np.concatenate([[0.0], np.cumsum(np.tile(w[order], 3))])
    lo = np.searchsorted(ds, d - xi_theta, side="left")
    hi = np.searchsorted(ds, d + xi_theta, side="right")
    return delta, (cw[hi] - cw[lo]).reshape(delta.shape)


def propose_rotations(map_angle, scan_angle, scan_weight, xi_theta, n_max: int = 8):
    """The rotations the angle votes propose: the best-voted ``delta``, at least ``2 xi_theta`` apart.

    Each proposal is refined to the weighted mean of the differences within
    ``xi_theta`` of it, and gives two rotations, ``delta`` and ``delta + pi``.

    Returns
    -------
    rotations : ndarray, shape (2 p,)
        In ``[-pi, pi)``.
    votes : ndarray, shape (2 p,)
    """
    if len(map_angle) == 0 or len(scan_angle) == 0:
        return np.zeros(0), np.zeros(0)
    delta, votes = rotation_votes(map_angle, scan_angle, scan_weight, xi_theta)
    d, v = delta.ravel(), votes.ravel()
    w = np.broadcast_to(np.asarray(scan_weight, float)[None, :], delta.shape).ravel()
    free = np.ones(len(d), bool)
    picked, pv = [], []
    while len(picked) < n_max and free.any():
        k = np.flatnonzero(free)[np.argmax(v[free])]
        gap = np.abs(wrap_angle(2 * (d - d[k])) / 2)
        near = gap <= xi_theta
        picked.append(d[k] + np.sum(w[near] * wrap_angle(2 * (d[near] - d[k])) / 2) / np.sum(w[near]))
        pv.append(v[k])
        free &= gap >= 2 * xi_theta
    rot = np.concatenate([np.array(picked), np.array(picked) + np.pi])
    return wrap_angle(rot), np.concatenate([pv, pv])


# --------------------------------------------------------------------------- hypotheses


def parallel_pairs(M: MapLines, S: ScanLines, rotation, tol):
    """(scan index, map index) pairs parallel under ``rotation``, with the sign of the map normal."""
    ang = np.mod(S.angle + rotation, np.pi)
    diff = np.abs(wrap_angle(2 * (M.angle[None, :] - ang[:, None])) / 2)
    li, mi = np.nonzero(diff < tol)
    return li, mi


def overlap_fraction(M: MapLines, mi, ends, scan_len, margin):
    """Fraction of each scan segment (ends (..., 2, 2) in the map frame) within its map segment's extent."""
    s = np.einsum("...ki,...i->...k", ends - M.start[mi][..., None, :], M.direction[mi])
    lo = np.maximum(np.minimum(s[..., 0], s[..., 1]), -margin)
    hi = np.minimum(np.maximum(s[..., 0], s[..., 1]), M.length[mi] + margin)
    return np.clip(hi - lo, 0.0, None) / scan_len


def pose_hypotheses(
    M: MapLines,
    S: ScanLines,
    rotation: float,
    *,
    parallel_tol: float,
    n_anchor_pairs: int,
    min_anchor_angle: float,
    overlap_margin: float,
    min_overlap: float,
    line_tolerance: float,
    slide_step: float = 0.2,
    slide_below: float = 1.0,
):
    """Poses for one rotation from pairs of non-parallel scan lines matched to pairs of map lines.

    For scan lines ``a``, ``b`` (the longest non-parallel pairs) and map lines
    ``m1 || a``, ``m2 || b`` the translation ``t`` solves the two equations of
    (3.11), ``n_m . (R mid_l + t) = c_m``: the least squares (3.12) with two
    lines, which is exact.  A hypothesis is kept when both scan segments lie on
    their map segments (at least ``min_overlap`` of their length within the map
    segment's extent widened by ``overlap_margin``).  Its quick score is the
    total length of scan segments that then lie on some map segment (midpoint
    within ``line_tolerance`` of a parallel map line, ``min_overlap`` of it
    within that segment's extent); with ``R`` fixed all of it is linear in ``t``.

    When the scan lines across the longest one (at ``min_anchor_angle`` or
    more) add up to less than ``slide_below`` metres, the lines cannot fix the
    position along it (a corridor): the longest line is also put on each of
    its map partners at positions ``slide_step`` apart (0 disables this; the
    step grows when that would give more than about 300 positions).

    Returns
    -------
    poses : ndarray, shape (H, 3)
    quick : ndarray, shape (H,)
    """
    empty = np.zeros((0, 3)), np.zeros(0)
    li, mi = parallel_pairs(M, S, rotation, parallel_tol)
    if len(li) == 0:
        return empty
    R = rotation_matrix(rotation)
    ends = S.segments @ R.T  # (L, 2, 2) rotated, not yet translated
    mid = S.midpoint @ R.T
    poses = [
        _anchored_translations(M, S, li, mi, a, b, mid, ends, overlap_margin, min_overlap)
        for a, b in _anchor_pairs(S, li, min_anchor_angle)[:n_anchor_pairs]
    ]
    poses.append(
        _slide(M, S, li, mi, mid, ends, min_anchor_angle, overlap_margin, min_overlap, slide_step, slide_below)
    )
    t = np.concatenate(poses)
    if len(t) == 0:
        return empty
    # de-duplicate translations (2 cm grid)
    _, first = np.unique(np.round(t / 0.02).astype(np.int64), axis=0, return_index=True)
    t = t[np.sort(first)]
    quick = _quick_scores(M, S, li, mi, t, mid, ends, line_tolerance, overlap_margin, min_overlap)
    return np.column_stack([t, np.full(len(t), rotation)]), quick


def _anchor_pairs(S: ScanLines, li, min_anchor_angle) -> list:
    """The anchor pairs ``(a, b)`` of :func:`pose_hypotheses`: the non-parallel pairs of scan lines with map partners
    (``li``), longest (and most orthogonal) first."""
    has = np.unique(li)
    pairs = []
    for x in range(len(has)):
        for y in range(x + 1, len(has)):
            a, b = has[x], has[y]
            ang = abs(wrap_angle(2 * (S.angle[a] - S.angle[b])) / 2)
            if ang >= min_anchor_angle:
                pairs.append((S.length[a] * S.length[b] * np.sin(ang), a, b))
    pairs.sort(key=lambda p: -p[0])
    return [(a, b) for _, a, b in pairs]


def _anchored_translations(M: MapLines, S: ScanLines, li, mi, a, b, mid, ends, overlap_margin, min_overlap):
    """The translations (n, 2) that put scan lines ``a`` and ``b`` (rotated: ``mid``, ``ends``) on a pair of their
    map partners, (3.11) solved exactly for two lines, kept when both scan segments lie on their map segments."""
    d_scan = S.pair_distance
    m1 = mi[li == a]
    m2 = mi[li == b]
    # a map segment shorter than what must lie on it cannot be the partner
    m1 = m1[M.length[m1] + 2 * overlap_margin >= min_overlap * S.length[a]]
    m2 = m2[M.length[m2] + 2 * overlap_margin >= min_overlap * S.length[b]]
    # the two map segments hold the two scan segments, so they are at most as far apart (plus the margins)
    near = M.pair_distance[np.ix_(m1, m2)] <= d_scan[a, b] + 2 * overlap_margin
    A1, A2 = np.nonzero(near)
    A1, A2 = m1[A1], m2[A2]
    n1, n2 = M.normal[A1], M.normal[A2]
    r1 = M.offset[A1] - n1 @ mid[a]
    r2 = M.offset[A2] - n2 @ mid[b]
    det = n1[:, 0] * n2[:, 1] - n1[:, 1] * n2[:, 0]
    ok = np.abs(det) > 1e-9
    t = np.column_stack([(r1 * n2[:, 1] - r2 * n1[:, 1]), (n1[:, 0] * r2 - n2[:, 0] * r1)])[ok] / det[ok, None]
    A1, A2 = A1[ok], A2[ok]
    fa = overlap_fraction(M, A1, ends[a][None] + t[:, None, :], S.length[a], overlap_margin)
    fb = overlap_fraction(M, A2, ends[b][None] + t[:, None, :], S.length[b], overlap_margin)
    keep = (fa >= min_overlap) & (fb >= min_overlap)
    return t[keep]


def _quick_scores(M: MapLines, S: ScanLines, li, mi, t, mid, ends, line_tolerance, overlap_margin, min_overlap):
    """The quick score of each translation ``t`` (H, 2) of :func:`pose_hypotheses`: the scan length that lands on
    parallel map segments, linear in t; the offsets first (dense), the extents only where the offset fits."""
    resid0 = np.einsum("pi,pi->p", M.normal[mi], mid[li]) - M.offset[mi]  # (P,)
    resid = t @ M.normal[mi].T
    resid += resid0
    h, q = np.nonzero(np.abs(resid) < line_tolerance)
    s0 = np.einsum("pki,pi->pk", ends[li[q]] - M.start[mi[q]][:, None, :], M.direction[mi[q]])  # (n, 2)
    shift = np.einsum("ni,ni->n", t[h], M.direction[mi[q]])
    lo = np.maximum(s0.min(axis=1) + shift, -overlap_margin)
    hi = np.minimum(s0.max(axis=1) + shift, M.length[mi[q]] + overlap_margin)
    inside = hi - lo >= min_overlap * S.length[li[q]]
    explained = np.zeros((len(t), len(S)), bool)
    explained[h[inside], li[q[inside]]] = True
    quick = explained.astype(float) @ S.length
    return quick


def _slide(M: MapLines, S: ScanLines, li, mi, mid, ends, min_angle, margin, min_overlap, step, below, budget=300):
    """Translations putting the longest scan line on each map partner, ``step`` apart along it and with an
    end on an end of the partner (see above)."""
    has = np.unique(li)
    if step <= 0 or len(has) == 0:
        return np.zeros((0, 2))
    a = has[np.argmax(S.length[has])]
    across = np.abs(wrap_angle(2 * (S.angle - S.angle[a])) / 2) >= min_angle
    if np.sum(S.length[across]) >= below:
        return np.zeros((0, 2))
    m = mi[li == a]
    m = m[M.length[m] + 2 * margin >= min_overlap * S.length[a]]
    # where the line may sit on each partner: a range of shifts along it
    p = np.sort(
        np.einsum("ki,mi->mk", ends[a], M.direction[m]) - np.einsum("mi,mi->m", M.start[m], M.direction[m])[:, None]
    )
    need = min_overlap * S.length[a]
    lo, hi = -margin - p[:, 1] + need, M.length[m] + margin - p[:, 0] - need
    ok = hi >= lo
    m, lo, hi = m[ok], lo[ok], hi[ok]
    step = max(step, float(np.sum(hi - lo)) / budget)  # at most about ``budget`` positions
    out = []
    p = p[ok]
    for k, a0, a1, (p0, p1) in zip(m, lo, hi, p):
        t_perp = (M.offset[k] - M.normal[k] @ mid[a]) * M.normal[k]
        along = np.arange(a0, a1 + 1e-9, step) if a1 - a0 > step else np.array([0.5 * (a0 + a1)])
        # and the exact shifts that put an end of the scan segment on an end of the map segment (a door
        # jamb, a wall end): the grid is ``step`` coarse, an end fixes the position along the wall
        ends_on_ends = np.array([-p0, M.length[k] - p1])
        along = np.concatenate([along, ends_on_ends[(ends_on_ends >= a0) & (ends_on_ends <= a1)]])
        out.append(t_perp + along[:, None] * M.direction[k])
    return np.concatenate(out) if out else np.zeros((0, 2))
