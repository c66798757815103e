"""Matplotlib figures for chapter 3: scenes, scans, segments, Hough space, maps and trajectories."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.patches import Circle, Polygon

__all__ = [
    "new_axes",
    "draw_scene",
    "draw_walls",
    "draw_scan",
    "draw_segments",
    "draw_trajectory",
    "draw_hough",
    "draw_correspondences",
    "draw_point_pair_spheres",
    "map_figure",
    "log_map_figure",
]


def new_axes(figsize=(6, 4), dpi=80, ax=None, title=None):
    """A fresh equal-aspect axes (or ``ax`` itself)."""
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, dpi=dpi)
    ax.set_aspect("equal")
    if title:
        ax.set_title(title)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    return ax


def draw_scene(scene, ax=None, color="0.85", edge="0.55", trajectory=False, **kw):
    """Fill the scene's polygons; optionally its ground-truth trajectory."""
    ax = ax or new_axes(**kw)
    for poly in scene.polygons:
        ax.add_patch(Polygon(poly, closed=True, facecolor=color, edgecolor=edge, lw=0.6))
    if trajectory:
        draw_trajectory(scene.trajectory, ax=ax, color="k", label="truth")
    ax.autoscale_view()
    return ax


def draw_walls(walls, ax=None, color="0.6", lw=3.0, alpha=0.6, **kw):
    """Wall segments ``(W, 2, 2)`` as thick grey lines."""
    ax = ax or new_axes(**kw)
    ax.add_collection(LineCollection(np.asarray(walls), colors=color, linewidths=lw, alpha=alpha))
    ax.autoscale_view()
    return ax


def draw_scan(ranges, angles, pose=(0.0, 0.0, 0.0), ax=None, color="tab:blue", s=3, rays=False, **kw):
    """Laser points (and optionally rays) of one scan, placed with ``pose``."""
    ax = ax or new_axes(**kw)
    r, a = np.asarray(ranges, float), np.asarray(angles, float)
    ok = np.isfinite(r)
    x, y, th = pose
    px = x + r[ok] * np.cos(a[ok] + th)
    py = y + r[ok] * np.sin(a[ok] + th)
    if rays:
        segs = np.stack([np.broadcast_to([x, y], (ok.sum(), 2)), np.column_stack([px, py])], axis=1)
        ax.add_collection(LineCollection(segs, colors=color, linewidths=0.3, alpha=0.25))
    ax.scatter(px, py, s=s, color=color, zorder=3)
    ax.plot([x], [y], marker=(3, 0, np.degrees(th) - 90), ms=10, color="k", zorder=4)
    ax.autoscale_view()
    return ax


def draw_segments(segments, ax=None, color="tab:red", lw=2.0, ends=True, edges=False, label=None, **kw):
    """Segments (objects with ``start``/``end``) as lines; real edges marked with squares."""
    ax = ax or new_axes(**kw)
    if not segments:
        return ax
    lines = np.array([[s.start, s.end] for s in segments])
    ax.add_collection(LineCollection(lines, colors=color, linewidths=lw, label=label, zorder=5))
    if ends:
        pts = lines.reshape(-1, 2)
        ax.scatter(pts[:, 0], pts[:, 1], s=8, color=color, zorder=6)
    if edges:
        e = [p for s in segments for p, f in ((s.start, s.start_is_edge), (s.end, s.end_is_edge)) if f]
        if e:
            e = np.array(e)
            ax.scatter(e[:, 0], e[:, 1], s=40, marker="s", facecolor="none", edgecolor="k", zorder=7, label="edge")
    ax.autoscale_view()
    return ax


def draw_trajectory(poses, ax=None, color="tab:green", label=None, lw=1.2, ls="-", **kw):
    """A trajectory ``(T, 3)`` as a line from its positions."""
    ax = ax or new_axes(**kw)
    p = np.asarray(poses, float)
    ax.plot(p[:, 0], p[:, 1], color=color, lw=lw, ls=ls, label=label)
    return ax


def draw_hough(hough_sets, labels, ax=None, markers=("o", "x", "s"), colors=("tab:blue", "tab:red", "tab:green")):
    """Lines as points ``(theta, rho)`` in Hough space (3.3), one marker per set."""
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3.5), dpi=80)
    for (rho, theta), lab, m, c in zip(hough_sets, labels, markers, colors):
        ax.scatter(np.degrees(theta), rho, marker=m, color=c, label=lab, s=40 if m != "x" else 50)
    ax.set_xlabel("theta (degrees)")
    ax.set_ylabel("rho (m)")
    ax.set_xlim(0, 360)
    ax.legend(loc="best", fontsize=8)
    return ax


def draw_correspondences(global_segs, local_segs, pairs, ax=None, **kw):
    """Dashed links between the centres of corresponding global and local segments, drawn above the segments
    (zorder 8: the segments sit at 5-7) with a marker at each end, so that a short link stays visible."""
    ax = ax or new_axes(**kw)
    for g, k in pairs:
        a, b = global_segs[g].midpoint, local_segs[k].midpoint
        ax.plot([a[0], b[0]], [a[1], b[1]], "k--", lw=1.2, marker="o", ms=3, zorder=8)
    return ax


def draw_point_pair_spheres(pairs, ax=None, colors=("tab:blue", "tab:red"), **kw):
    """Segments with the circle on each as diameter: the spheres (2.134) of section 3.2.3."""
    ax = ax or new_axes(**kw)
    for (a, b), c in zip(pairs, colors * len(pairs)):
        a, b = np.asarray(a, float), np.asarray(b, float)
        ctr, r = 0.5 * (a + b), 0.5 * np.hypot(*(b - a))
        ax.add_patch(Circle(ctr, r, fill=False, color=c, lw=1, ls="--"))
        ax.plot([a[0], b[0]], [a[1], b[1]], color=c, lw=2.5)
        ax.scatter([a[0], b[0]], [a[1], b[1]], color=c, s=15, zorder=5)
    ax.autoscale_view()
    return ax


def map_figure(segments, walls=None, truth=None, odometry=None, corrected=None, title=None, figsize=(9, 5.5), dpi=80):
    """The usual map figure: true walls (grey), map segments (red), and trajectories."""
    ax = new_axes(figsize=figsize, dpi=dpi, title=title)
    if walls is not None:
        draw_walls(walls, ax=ax)
    draw_segments(segments, ax=ax, lw=1.5, ends=False, label="map")
    if odometry is not None:
        draw_trajectory(odometry, ax=ax, color="tab:orange", label="odometry", ls=":")
    if truth is not None:
        draw_trajectory(truth, ax=ax, color="k", label="truth", lw=1.0)
    if corrected is not None:
        draw_trajectory(corrected, ax=ax, color="tab:green", label="corrected", ls="--")
    ax.legend(loc="upper right", fontsize=8)
    return ax


def log_map_figure(segments, cloud, truth, corrected, odometry=None, loops=(), figsize=(13, 6.2), dpi=80):
    """A real log's map next to its truth: left the log's points at the true poses and the true trajectory,
    right the line map over the same points (faint) with the corrected trajectory and the closed loops.

    Parameters
    ----------
    segments : list of Segment
    cloud : ndarray, shape (k, 2)
        The log's points placed with the true poses.
    truth, corrected : ndarray, shape (T, 3)
    odometry : ndarray, shape (T, 3), optional
    loops : sequence of (int, int)
        Revisits (earlier scan, scan), drawn as thin links between the corrected poses.

    Returns
    -------
    (Figure, ndarray of Axes)
    """
    fig, axs = plt.subplots(1, 2, figsize=figsize, dpi=dpi)
    new_axes(ax=axs[0], title="the log's points at the true poses")
    axs[0].scatter(*np.asarray(cloud).T, s=0.3, color="0.45")
    draw_trajectory(truth, ax=axs[0], color="k", lw=0.6, label="truth")
    new_axes(ax=axs[1], title="line map and corrected trajectory (truth points faint)")
    axs[1].scatter(*np.asarray(cloud).T, s=0.3, color="0.85")
    draw_segments(segments, ax=axs[1], lw=1.0, ends=False, label="map")
    if odometry is not None:
        draw_trajectory(odometry, ax=axs[1], color="tab:orange", ls=":", lw=0.8, label="odometry")
    draw_trajectory(corrected, ax=axs[1], color="tab:green", lw=0.6, label="corrected")
    c = np.asarray(corrected)
    for j, k in loops:
        axs[1].plot(c[[j, k], 0], c[[j, k], 1], color="tab:purple", lw=0.8)
    if len(loops):
        axs[1].plot([], [], color="tab:purple", lw=0.8, label="loop closed")
    for ax in axs:
        ax.set_xlim(axs[0].get_xlim())
        ax.set_ylim(axs[0].get_ylim())
    axs[1].legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    return fig, axs
