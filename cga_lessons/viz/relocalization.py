"""Matplotlib figures for chapter 5: the map in Hough space, the steps of figure 5.2, votes and success rates."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection

from .laser import draw_scan, draw_walls, new_axes

__all__ = [
    "look_around_figure",
    "hough_figure",
    "steps_figure",
    "votes_figure",
    "placements_figure",
    "rates_figure",
]


def _lines(ax, segs, color, lw, label=None, zorder=5):
    segs = np.asarray(segs, float).reshape(-1, 2, 2)
    if len(segs):
        ax.add_collection(LineCollection(segs, colors=color, linewidths=lw, label=label, zorder=zorder))
    ax.autoscale_view()


def hough_figure(M_h, L_h=None, turned=None, turn=None, ax=None):
    """Figure 5.1: the map's lines as points ``(theta, rho)``, theta cyclic on [0, 360) degrees.

    Optionally the scan's lines ``L_h`` and the same lines after the robot
    turned by ``turn`` radians (they move along theta only).
    """
    if ax is None:
        _, ax = plt.subplots(figsize=(8, 3.6), dpi=80)
    M_h = np.asarray(M_h, float)
    ax.scatter(np.degrees(M_h[:, 1]), M_h[:, 0], s=14, color="k", label=f"map M_h ({len(M_h)} lines)")
    if L_h is not None and len(L_h):
        L_h = np.asarray(L_h, float)
        ax.scatter(
            np.degrees(L_h[:, 1]), L_h[:, 0], s=40, marker="o", facecolor="none", color="tab:blue", label="scan L_h"
        )
    if turned is not None and len(turned):
        turned = np.asarray(turned, float)
        lab = "scan after turning" + (f" {np.degrees(turn):.0f} deg" if turn is not None else "")
        ax.scatter(np.degrees(turned[:, 1]), turned[:, 0], s=40, marker="x", color="tab:red", label=lab)
        for a, b in zip(L_h, turned):
            ax.annotate(
                "",
                xy=(np.degrees(b[1]), b[0]),
                xytext=(np.degrees(a[1]), a[0]),
                arrowprops=dict(arrowstyle="->", color="tab:red", lw=0.6, alpha=0.6),
            )
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_xlabel("theta (degrees), cyclic")
    ax.set_ylabel("rho (m)")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("Figure 5.1: a line map in Hough space")
    return ax


def steps_figure(walls, map_segments, scan, truth, scan_segments, placed, pairs=None, figsize=(11, 8.5), dpi=70):
    """Figure 5.2 redrawn: (a) the scan taken, (b) its local map, (c) local and stored maps, (d) relocalized.

    Parameters
    ----------
    walls : ndarray (W, 2, 2)
        The world (grey) for panel (a).
    map_segments : ndarray (M, 2, 2)
        The stored map (black).
    scan : (ranges, angles)
    truth : array_like (3,)
        Where the scan was taken (panel a).
    scan_segments : ndarray (L, 2, 2)
        The local map in the laser frame.
    placed : ndarray (L, 2, 2)
        The local map after the rotor and the translator (map frame).
    pairs : ndarray (k, 2), optional
        ``(map index, scan index)`` correspondences drawn in (d).
    """
    fig, axs = plt.subplots(2, 2, figsize=figsize, dpi=dpi)
    axs = axs.ravel()
    ranges, angles = scan
    a = new_axes(ax=axs[0], title="(a) the robot measures its surroundings")
    draw_walls(walls, ax=a, lw=2)
    draw_scan(ranges, angles, truth, ax=a, s=2, rays=True)
    b = new_axes(ax=axs[1], title="(b) the local map L (laser frame)")
    draw_scan(ranges, angles, ax=b, s=2, color="0.6")
    _lines(b, scan_segments, "tab:red", 2.5)
    c = new_axes(ax=axs[2], title="(c) the stored map M (black) and L, not yet placed")
    _lines(c, map_segments, "k", 1.0)
    _lines(c, scan_segments, "tab:red", 2.0)
    c.plot([0], [0], marker=(3, 0, -90), ms=9, color="tab:red")
    d = new_axes(ax=axs[3], title="(d) L after the rotor and the translator (zoomed)")
    _lines(d, map_segments, "k", 1.0)
    if pairs is not None and len(pairs):
        ms = np.asarray(map_segments, float)
        _lines(d, ms[np.asarray(pairs, int)[:, 0]], "tab:green", 6.0, label="matched map lines", zorder=4)
    _lines(d, placed, "tab:red", 2.0, label="L placed")
    pts = np.asarray(placed, float).reshape(-1, 2)
    lo, hi = pts.min(axis=0) - 1.5, pts.max(axis=0) + 1.5
    d.set_xlim(lo[0], hi[0])
    d.set_ylim(lo[1], hi[1])
    d.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    return fig


def votes_figure(V, ax=None, title="The vote matrix V (5.6)"):
    """The vote matrix as an image, map lines down, scan lines across, the column maxima circled."""
    V = np.asarray(V)
    if ax is None:
        _, ax = plt.subplots(figsize=(4.5, 6), dpi=80)
    im = ax.imshow(V, aspect="auto", cmap="viridis", interpolation="nearest")
    if V.size:
        rows = np.argmax(V, axis=0)
        ax.scatter(np.arange(V.shape[1]), rows, s=60, facecolor="none", edgecolor="r", lw=1.5, label="column maximum")
        ax.legend(loc="lower right", fontsize=8)
    ax.set_xlabel("scan line l_j")
    ax.set_ylabel("map line m_i")
    ax.set_title(title)
    plt.colorbar(im, ax=ax, label="votes")
    return ax


def placements_figure(map_segments, scan, poses, ax=None, colors=None, title=None, figsize=(8, 5), dpi=80, walls=None):
    """The map with the scan's points placed at several poses (a dict label -> pose)."""
    ax = ax or new_axes(figsize=figsize, dpi=dpi, title=title)
    if walls is not None:
        draw_walls(walls, ax=ax, lw=2, alpha=0.3)
    _lines(ax, map_segments, "k", 0.8, zorder=2)
    colors = colors or ["tab:green", "tab:red", "tab:orange", "tab:purple"]
    ranges, angles = scan
    for (label, pose), col in zip(poses.items(), colors):
        draw_scan(ranges, angles, pose, ax=ax, s=2, color=col)
        ax.scatter([], [], color=col, label=label)
    ax.legend(loc="upper right", fontsize=8)
    return ax


def rates_figure(x, series, xlabel, ax=None, title=None, counts=None):
    """Success rates (a dict label -> rates) against ``x``; optional sample counts written under the points."""
    if ax is None:
        _, ax = plt.subplots(figsize=(5.5, 3.5), dpi=80)
    for (label, y), m in zip(series.items(), "osd^v"):
        ax.plot(x, y, marker=m, label=label)
    if counts is not None:
        for xi, n in zip(x, counts):
            ax.annotate(f"n={n}", (xi, 0.02), ha="center", fontsize=7, color="0.4")
    ax.set_ylim(0, 1.05)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("fraction of poses")
    if title:
        ax.set_title(title)
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def look_around_figure(map_segments, scans, history, truth=None, figsize=(12, 4.8), dpi=70):
    """A look around: the scans placed at the best chain's poses, and the candidates' scores scan by scan.

    Parameters
    ----------
    map_segments : (M, 2, 2)
    scans : list of (ranges, angles)
    history : list of SequenceRelocalization
        The answer after each scan (``Relocalizer.add``'s return values).
    truth : ndarray (n, 3), optional
        The true poses, drawn as small triangles.
    """
    fig, (ax, bx) = plt.subplots(1, 2, figsize=figsize, dpi=dpi, gridspec_kw={"width_ratios": [1.7, 1]})
    _lines(ax, map_segments, "k", 0.8, zorder=2)
    final = history[-1]
    cols = ["tab:green", "tab:blue", "tab:orange", "tab:purple", "tab:brown", "tab:pink"]
    for j in range(len(scans)):
        ax.scatter([], [], color=cols[j % len(cols)], label=f"scan {j + 1}")
    for j in range(len(scans) - 1, -1, -1):  # the first scan on top
        ranges, angles = scans[j]
        draw_scan(ranges, angles, final.trajectory[j], ax=ax, s=3, color=cols[j % len(cols)])
    first = history[0].candidates[:6]
    if first:
        c = np.array([k.pose for k in first])
        ax.scatter(c[:, 0], c[:, 1], marker="x", color="tab:red", s=40, zorder=8, label="candidates after scan 1")
    if truth is not None:
        t = np.asarray(truth)[-1]
        ax.scatter([t[0]], [t[1]], marker="^", color="k", s=40, zorder=9, label="truth")
    ax.set_aspect("equal")
    ax.set_title(f"the scans placed at the answer ({final.status})")
    ax.legend(loc="upper right", fontsize=7)
    for k, h in enumerate(history):
        sc = [c.score for c in h.candidates[:6]]
        bx.scatter(np.full(len(sc), k + 1), sc, color=["tab:green"] + ["tab:red"] * (len(sc) - 1), s=25, zorder=3)
        if len(sc) > 1:
            bx.plot([k + 0.8, k + 1.2], [0.98 * sc[0]] * 2, color="0.4", lw=1)
    bx.set_xlabel("scans so far")
    bx.set_ylabel("score over all scans")
    bx.set_xticks(np.arange(1, len(history) + 1))
    bx.set_title("best (green), rivals (red), 98 % of the best (grey)")
    bx.grid(alpha=0.3)
    fig.tight_layout()
    return fig
