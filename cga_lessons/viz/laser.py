"""Matplotlib figures for chapter 3: scenes, scans, segments, Hough space, maps and trajectories."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Polygon

from cga_lessons.checks import fail, flag, instance, real, same_length
from cga_lessons.mapping2d import Scene

from .inputs import ANGLE_WHY, axes, coords, index_pairs, optional_text, scan_arrays, texts, trajectory, vector
from .inputs import color as a_color
from .inputs import colors as some_colors
from .inputs import dpi as fig_dpi
from .inputs import figsize as fig_size

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
    func = "new_axes"
    ax, title = axes(ax, func), optional_text(title, func, "title")
    figsize, dpi = fig_size(figsize, func), fig_dpi(dpi, func)  # used for a new axes only
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, dpi=dpi)
    return _labelled(ax, title)


def _labelled(ax, title):
    ax.set_aspect("equal")
    if title:
        ax.set_title(title)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    return ax


def _target(ax, func: str, kw: dict):
    """``ax``, or a new equal-aspect axes made with ``kw`` (``figsize``, ``dpi``, ``title`` of :func:`new_axes`)."""
    unknown = sorted(set(kw) - {"figsize", "dpi", "title"})
    if unknown:
        raise fail(func, unknown[0], "unknown keyword (a new axes takes figsize, dpi and title)")
    figsize, dpi = fig_size(kw.get("figsize", (6, 4)), func), fig_dpi(kw.get("dpi", 80), func)
    title = optional_text(kw.get("title"), func, "title")
    if axes(ax, func) is not None:
        return ax
    return _labelled(plt.subplots(figsize=figsize, dpi=dpi)[1], title)


def _segment_lines(segments, func: str, name: str = "segments") -> np.ndarray:
    """The ends (k, 2, 2) of segments (objects with ``start`` and ``end``, such as mapping2d's Segment)."""
    if not isinstance(segments, (list, tuple)):
        raise fail(func, name, f"expected a list of segments (with start and end), got {type(segments).__name__}")
    for k, sg in enumerate(segments):
        if not (hasattr(sg, "start") and hasattr(sg, "end")):
            raise fail(func, f"{name}[{k}]", f"expected a segment (with start and end), got {type(sg).__name__}")
    if not segments:
        return np.zeros((0, 2, 2))
    return coords([[sg.start, sg.end] for sg in segments], func, name, (None, 2, 2))


def _linestyle(value, func: str, name: str = "ls"):
    if value is None:
        raise fail(func, name, "expected a matplotlib line style ('-', '--', ':', ...), got None")
    try:
        Line2D([], [], linestyle=value)
    except (ValueError, TypeError):
        raise fail(func, name, f"not a matplotlib line style: {value!r}") from None
    return value


def _width(value, func: str, name: str = "lw") -> float:
    return real(value, func, name, low=0.0, high=100.0)


def draw_scene(scene, ax=None, color="0.85", edge="0.55", trajectory=False, **kw):
    """Fill the scene's polygons; optionally its ground-truth trajectory."""
    func = "draw_scene"
    scene = instance(scene, func, "scene", Scene, "a mapping2d Scene (load_scene)")
    color, edge, trajectory = a_color(color, func), a_color(edge, func, "edge"), flag(trajectory, func, "trajectory")
    ax = _target(ax, func, kw)
    for poly in scene.polygons:
        ax.add_patch(Polygon(poly, closed=True, facecolor=color, edgecolor=edge, lw=0.6))
    if trajectory:
        draw_trajectory(scene.trajectory, ax=ax, color="k", label="truth")
    ax.autoscale_view()
    return ax


def draw_walls(walls, ax=None, color="0.6", lw=3.0, alpha=0.6, **kw):
    """Wall segments ``(W, 2, 2)`` as thick grey lines."""
    func = "draw_walls"
    walls = coords(walls, func, "walls", (None, 2, 2))
    color, lw, alpha = a_color(color, func), _width(lw, func), real(alpha, func, "alpha", low=0.0, high=1.0)
    ax = _target(ax, func, kw)
    ax.add_collection(LineCollection(walls, colors=color, linewidths=lw, alpha=alpha))
    ax.autoscale_view()
    return ax


def draw_scan(ranges, angles, pose=(0.0, 0.0, 0.0), ax=None, color="tab:blue", s=3, rays=False, **kw):
    """Laser points (and optionally rays) of one scan, placed with ``pose``; ranges NaN or inf: no return."""
    func = "draw_scan"
    r, a = scan_arrays(ranges, angles, func)
    x, y, th = vector(pose, func, "pose", (3,))
    color, s, rays = a_color(color, func), real(s, func, "s", low=0.0, high=1e4), flag(rays, func, "rays")
    ax = _target(ax, func, kw)
    ok = np.isfinite(r)
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
    func = "draw_segments"
    lines = _segment_lines(segments, func)
    color, lw, label = a_color(color, func), _width(lw, func), optional_text(label, func)
    ends, edges = flag(ends, func, "ends"), flag(edges, func, "edges")
    if edges and not all(hasattr(sg, "start_is_edge") and hasattr(sg, "end_is_edge") for sg in segments):
        raise fail(func, "segments", "edges=True needs segments that know their edges (start_is_edge, end_is_edge)")
    ax = _target(ax, func, kw)
    if not len(lines):
        return ax
    ax.add_collection(LineCollection(lines, colors=color, linewidths=lw, label=label, zorder=5))
    if ends:
        pts = lines.reshape(-1, 2)
        ax.scatter(pts[:, 0], pts[:, 1], s=8, color=color, zorder=6)
    if edges:
        e = [p for sg, ln in zip(segments, lines) for p, f in zip(ln, (sg.start_is_edge, sg.end_is_edge)) if f]
        if e:
            e = np.array(e)
            ax.scatter(e[:, 0], e[:, 1], s=40, marker="s", facecolor="none", edgecolor="k", zorder=7, label="edge")
    ax.autoscale_view()
    return ax


def draw_trajectory(poses, ax=None, color="tab:green", label=None, lw=1.2, ls="-", **kw):
    """A trajectory ``(T, 3)`` as a line from its positions."""
    func = "draw_trajectory"
    p = trajectory(poses, func)
    color, label, lw, ls = a_color(color, func), optional_text(label, func), _width(lw, func), _linestyle(ls, func)
    ax = _target(ax, func, kw)
    ax.plot(p[:, 0], p[:, 1], color=color, lw=lw, ls=ls, label=label)
    return ax


def _hough_sets(hough_sets, func: str) -> list:
    if not isinstance(hough_sets, (list, tuple)) or not hough_sets:
        raise fail(func, "hough_sets", "expected a non-empty list of (rho, theta) pairs of arrays")
    out = []
    for k, pair in enumerate(hough_sets):
        if not isinstance(pair, (list, tuple, np.ndarray)) or len(pair) != 2:
            raise fail(func, f"hough_sets[{k}]", "expected a pair (rho, theta) of arrays")
        rho, theta = (coords(v, func, f"hough_sets[{k}]", (None,), limit=1e6, why=ANGLE_WHY) for v in pair)
        same_length(func, **{f"hough_sets[{k}] rho": rho, f"hough_sets[{k}] theta": theta})
        out.append((rho, theta))
    return out


def _markers(value, func: str, n: int) -> list:
    from matplotlib.markers import MarkerStyle

    if not isinstance(value, (list, tuple)) or len(value) < n:
        raise fail(func, "markers", f"expected a marker for each of the {n} sets, got {value!r}")
    for k, m in enumerate(value):
        try:
            MarkerStyle(m)
        except (ValueError, TypeError):
            raise fail(func, f"markers[{k}]", f"not a matplotlib marker: {m!r}") from None
    return list(value)


def draw_hough(hough_sets, labels, ax=None, markers=("o", "x", "s"), colors=("tab:blue", "tab:red", "tab:green")):
    """Lines as points ``(theta, rho)`` in Hough space (3.3), one marker per set.

    ``hough_sets``: pairs ``(rho, theta)`` of arrays (radians), one label, marker and colour each.
    """
    func = "draw_hough"
    sets = _hough_sets(hough_sets, func)
    labels = texts(labels, func, "labels", len(sets))
    markers, colors = _markers(markers, func, len(sets)), some_colors(colors, func)
    if len(colors) < len(sets):
        raise fail(func, "colors", f"expected a colour for each of the {len(sets)} sets, got {len(colors)}")
    if axes(ax, func) is None:
        _, ax = plt.subplots(figsize=(6, 3.5), dpi=80)
    for (rho, theta), lab, m, c in zip(sets, labels, markers, colors):
        ax.scatter(np.degrees(theta), rho, marker=m, color=c, label=lab, s=40 if m != "x" else 50)
    ax.set_xlabel("theta (degrees)")
    ax.set_ylabel("rho (m)")
    ax.set_xlim(0, 360)
    ax.legend(loc="best", fontsize=8)
    return ax


def draw_correspondences(global_segs, local_segs, pairs, ax=None, **kw):
    """Dashed links between the centres of corresponding global and local segments, drawn above the segments
    (zorder 8: the segments sit at 5-7) with a marker at each end, so that a short link stays visible.

    ``pairs`` (k, 2): indices ``(global, local)`` into the two lists of segments.
    """
    func = "draw_correspondences"
    g_lines, l_lines = _segment_lines(global_segs, func, "global_segs"), _segment_lines(local_segs, func, "local_segs")
    p = index_pairs(pairs, func, "pairs", ("global_segs", len(g_lines)), ("local_segs", len(l_lines)))
    ax = _target(ax, func, kw)
    for g, k in p:
        a, b = g_lines[g].mean(axis=0), l_lines[k].mean(axis=0)
        ax.plot([a[0], b[0]], [a[1], b[1]], "k--", lw=1.2, marker="o", ms=3, zorder=8)
    return ax


def draw_point_pair_spheres(pairs, ax=None, colors=("tab:blue", "tab:red"), **kw):
    """Segments with the circle on each as diameter: the spheres (2.134) of section 3.2.3.

    ``pairs`` (k, 2, 2): the two ends of each segment; the colours repeat.
    """
    func = "draw_point_pair_spheres"
    pairs, colors = coords(pairs, func, "pairs", (None, 2, 2)), some_colors(colors, func)
    ax = _target(ax, func, kw)
    for (a, b), c in zip(pairs, colors * len(pairs)):
        ctr, r = 0.5 * (a + b), 0.5 * np.hypot(*(b - a))
        ax.add_patch(Circle(ctr, r, fill=False, color=c, lw=1, ls="--"))
        ax.plot([a[0], b[0]], [a[1], b[1]], color=c, lw=2.5)
        ax.scatter([a[0], b[0]], [a[1], b[1]], color=c, s=15, zorder=5)
    ax.autoscale_view()
    return ax


def map_figure(segments, walls=None, truth=None, odometry=None, corrected=None, title=None, figsize=(9, 5.5), dpi=80):
    """The usual map figure: true walls (grey), map segments (red), and trajectories (T, 3), each optional."""
    func = "map_figure"
    _segment_lines(segments, func)
    if walls is not None:
        coords(walls, func, "walls", (None, 2, 2))
    for name, poses in (("truth", truth), ("odometry", odometry), ("corrected", corrected)):
        if poses is not None:
            trajectory(poses, func, name)
    ax = _target(None, func, {"figsize": figsize, "dpi": dpi, "title": title})
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
    func = "log_map_figure"
    _segment_lines(segments, func)
    cloud = coords(cloud, func, "cloud", (None, 2))
    truth, corrected = (trajectory(v, func, k, at_least=1, widths=(3,)) for k, v in
                        (("truth", truth), ("corrected", corrected)))  # fmt: skip
    if odometry is not None:
        trajectory(odometry, func, "odometry", widths=(3,))
    loops = index_pairs(loops, func, "loops", ("corrected", len(corrected)), ("corrected", len(corrected)))
    fig, axs = plt.subplots(1, 2, figsize=fig_size(figsize, func), dpi=fig_dpi(dpi, func))
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
