"""Matplotlib figures for chapter 5: the map in Hough space, the steps of figure 5.2, votes and success rates."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection

from cga_lessons.checks import array, fail, real, text

from .inputs import ANGLE_WHY, axes, coords, index_pairs, optional_text, scan_pair, trajectory, vector
from .inputs import colors as some_colors
from .inputs import dpi as fig_dpi
from .inputs import figsize as fig_size
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
    turned by ``turn`` radians (they move along theta only).  Each set is ``(rho, theta)`` rows (k, 2).
    """
    func = "hough_figure"
    M_h = coords(M_h, func, "M_h", (None, 2), limit=1e6, why=ANGLE_WHY)
    L_h = None if L_h is None else coords(L_h, func, "L_h", (None, 2), limit=1e6, why=ANGLE_WHY)
    if turned is not None:
        turned = coords(turned, func, "turned", (None, 2), limit=1e6, why=ANGLE_WHY)
        if L_h is None or len(turned) != len(L_h):
            raise fail(func, "turned", "expected the rows of L_h after the turn: as many as L_h")
    turn = None if turn is None else real(turn, func, "turn", low=-1e6, high=1e6)
    if axes(ax, func) is None:
        _, ax = plt.subplots(figsize=(8, 3.6), dpi=80)
    ax.scatter(np.degrees(M_h[:, 1]), M_h[:, 0], s=14, color="k", label=f"map M_h ({len(M_h)} lines)")
    if L_h is not None and len(L_h):
        ax.scatter(
            np.degrees(L_h[:, 1]), L_h[:, 0], s=40, marker="o", facecolor="none", color="tab:blue", label="scan L_h"
        )
    if turned is not None and len(turned):
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
    func = "steps_figure"
    walls = coords(walls, func, "walls", (None, 2, 2))
    map_segments = coords(map_segments, func, "map_segments", (None, 2, 2))
    ranges, angles = scan_pair(scan, func)
    truth = vector(truth, func, "truth", (3,))
    scan_segments = coords(scan_segments, func, "scan_segments", (None, 2, 2))
    placed = coords(placed, func, "placed", (None, 2, 2), at_least=1)
    if pairs is not None:
        pairs = index_pairs(pairs, func, "pairs", ("map_segments", len(map_segments)), ("placed", len(placed)))
    fig, axs = plt.subplots(2, 2, figsize=fig_size(figsize, func), dpi=fig_dpi(dpi, func))
    axs = axs.ravel()
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
        _lines(d, map_segments[pairs[:, 0]], "tab:green", 6.0, label="matched map lines", zorder=4)
    _lines(d, placed, "tab:red", 2.0, label="L placed")
    pts = placed.reshape(-1, 2)
    lo, hi = pts.min(axis=0) - 1.5, pts.max(axis=0) + 1.5
    d.set_xlim(lo[0], hi[0])
    d.set_ylim(lo[1], hi[1])
    d.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    return fig


def votes_figure(V, ax=None, title="The vote matrix V (5.6)"):
    """The vote matrix as an image, map lines down, scan lines across, the column maxima circled (title None: none)."""
    func = "votes_figure"
    V = coords(V, func, "V", (None, None))
    title = optional_text(title, func, "title")
    if axes(ax, func) is None:
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
    """The map with the scan's points placed at several poses (a dict label -> pose); one colour per pose."""
    func = "placements_figure"
    map_segments = coords(map_segments, func, "map_segments", (None, 2, 2))
    ranges, angles = scan_pair(scan, func)
    if not isinstance(poses, dict) or not poses:
        raise fail(func, "poses", "expected a non-empty dict label -> pose (x, y, theta)")
    poses = {text(k, func, "poses", empty=True): vector(v, func, f"poses[{k!r}]", (3,)) for k, v in poses.items()}
    colors = ["tab:green", "tab:red", "tab:orange", "tab:purple"] if colors is None else some_colors(colors, func)
    if len(colors) < len(poses):
        raise fail(func, "colors", f"expected a colour for each of the {len(poses)} poses, got {len(colors)}")
    if walls is not None:
        walls = coords(walls, func, "walls", (None, 2, 2))
    title, figsize, dpi = optional_text(title, func, "title"), fig_size(figsize, func), fig_dpi(dpi, func)
    if axes(ax, func) is None:
        ax = new_axes(figsize=figsize, dpi=dpi, title=title)
    if walls is not None:
        draw_walls(walls, ax=ax, lw=2, alpha=0.3)
    _lines(ax, map_segments, "k", 0.8, zorder=2)
    for (label, pose), col in zip(poses.items(), colors):
        draw_scan(ranges, angles, pose, ax=ax, s=2, color=col)
        ax.scatter([], [], color=col, label=label)
    ax.legend(loc="upper right", fontsize=8)
    return ax


def rates_figure(x, series, xlabel, ax=None, title=None, counts=None):
    """Success rates (a dict label -> rates in [0, 1], NaN where there is no sample) against ``x``; optional sample
    counts written under the points."""
    func = "rates_figure"
    x = coords(x, func, "x", (None,), at_least=1)
    if not isinstance(series, dict) or not 1 <= len(series) <= 5:
        raise fail(func, "series", "expected a dict of 1 to 5 labels -> rates (one per x)")
    for label, y in series.items():
        text(label, func, "series", empty=True)
        y = array(y, func, f"series[{label!r}]", x.shape, finite=False)  # NaN: no sample, not drawn
        if np.any(np.isinf(y)) or np.any(y[~np.isnan(y)] < 0) or np.any(y[~np.isnan(y)] > 1):
            raise fail(func, f"series[{label!r}]", "rates must lie in [0, 1] (NaN: no sample)")
    xlabel, title = text(xlabel, func, "xlabel", empty=True), optional_text(title, func, "title")
    if counts is not None:
        counts = array(counts, func, "counts", x.shape)
        if np.any(counts < 0) or np.any(counts != np.round(counts)) or np.any(counts > 1e15):
            raise fail(func, "counts", "expected whole numbers from 0 to 1e15, one per x")
        counts = counts.astype(int)
    if axes(ax, func) is None:
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


def _history(history, n_scans: int, func: str) -> None:
    """Answers after each scan (``Relocalizer.add``): a trajectory of a pose per scan, candidates with scores."""
    if not isinstance(history, (list, tuple)) or not history:
        raise fail(func, "history", "expected a non-empty list of answers (Relocalizer.add's return values)")
    for k, h in enumerate(history):
        if not all(hasattr(h, a) for a in ("trajectory", "candidates", "status")):
            raise fail(func, f"history[{k}]", f"expected a SequenceRelocalization, got {type(h).__name__}")
        for c in h.candidates[:6]:
            vector(getattr(c, "pose", None), func, f"history[{k}]", (3,))
            real(getattr(c, "score", None), func, f"history[{k}]")
    if len(history[-1].trajectory) < n_scans:
        raise fail(func, "history", f"the last answer places {len(history[-1].trajectory)} scans, not {n_scans}")
    trajectory(history[-1].trajectory, func, "history")


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
    func = "look_around_figure"
    map_segments = coords(map_segments, func, "map_segments", (None, 2, 2))
    if not isinstance(scans, (list, tuple)) or not scans:
        raise fail(func, "scans", "expected a non-empty list of scans (ranges, angles)")
    scans = [scan_pair(sc, func, f"scans[{j}]") for j, sc in enumerate(scans)]
    _history(history, len(scans), func)
    truth = None if truth is None else trajectory(truth, func, "truth", at_least=1)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=fig_size(figsize, func), dpi=fig_dpi(dpi, func),
                                 gridspec_kw={"width_ratios": [1.7, 1]})  # fmt: skip
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
