"""The matplotlib drawing of a :mod:`cga_lessons.viz.scene3d` scene: a static 3D figure at 1:1:1 scale.

:func:`draw_matplotlib` draws the primitives of a scene (the view nbval can store; the live one is
:mod:`cga_lessons.viz.meshcat_scene`), :func:`set_equal_3d` frames a box at equal aspect.
:func:`box_faces` and :func:`cylinder_grid` (the surfaces of a box and a cylinder) serve the explorers too.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.checks import fail, flag, real

from .inputs import axes, coords
from .scene3d import FRAME_COLORS, Box, Cylinder, Frame, PointCloud, Polyline, Quad, Sphere, check_scene, scene_bounds

__all__ = ["draw_matplotlib", "set_equal_3d"]


def _box(lo, hi, pad, func: str):
    lo, hi = coords(lo, func, "lo", (3,)), coords(hi, func, "hi", (3,))
    if np.any(hi < lo):
        raise fail(func, "hi", f"must be >= lo on every axis, got lo {lo.tolist()} and hi {hi.tolist()}")
    return lo, hi, real(pad, func, "pad", low=0.0, high=10.0)


def _equal_3d(ax, lo, hi, pad):
    centre = (lo + hi) / 2
    half = max(float(np.max(hi - lo)) / 2 * (1 + pad), 1e-3)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
    return ax


def set_equal_3d(ax, lo, hi, pad=0.05):
    """Make a matplotlib 3D axis show the box ``lo..hi`` at 1:1:1 scale (a cube around its centre).

    ``pad`` widens the cube by that fraction (0 to 10).
    """
    ax = axes(ax, "set_equal_3d", three_d=True, optional=False)
    return _equal_3d(ax, *_box(lo, hi, pad, "set_equal_3d"))


def box_faces(corners):
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [corners[list(f)] for f in idx]


def _sphere_grid(center, radius, n=14):
    u = np.linspace(0, 2 * np.pi, n + 1)
    v = np.linspace(0, np.pi, n // 2 + 1)
    x = center[0] + radius * np.outer(np.cos(u), np.sin(v))
    y = center[1] + radius * np.outer(np.sin(u), np.sin(v))
    z = center[2] + radius * np.outer(np.ones_like(u), np.cos(v))
    return x, y, z


def cylinder_grid(cyl, n=16):
    R = cyl.axis_rotation()
    t = np.linspace(0, 2 * np.pi, n + 1)
    ring = cyl.radius * (np.outer(np.cos(t), R[:, 0]) + np.outer(np.sin(t), R[:, 1]))  # (n+1, 3)
    grid = np.stack([cyl.start + ring, cyl.end + ring])  # (2, n+1, 3)
    return grid[..., 0], grid[..., 1], grid[..., 2]


def draw_matplotlib(ax, primitives, *, limits=None, labels=True, pad=0.05):
    """Draw primitives on a matplotlib 3D axis at equal aspect (1 m is the same length on x, y and z).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D or None
        Target axis; ``None`` makes a new 6x5 inch figure with one 3D axis.
    primitives : iterable of scene3d primitives (nested lists allowed)
    limits : ((3,), (3,)) or None
        Bounds to frame; by default :func:`scene_bounds` of the primitives.
    labels : bool
        Axis labels in metres.

    Returns
    -------
    ax
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    func = "draw_matplotlib"
    ax = axes(ax, func, three_d=True)
    prims = check_scene(primitives, func)
    if limits is None:
        lo, hi = scene_bounds(prims) if prims else (np.zeros(3) - 1, np.zeros(3) + 1)
    else:
        box = coords(limits, func, "limits", (2, 3))
        if np.any(box[1] < box[0]):
            raise fail(func, "limits", f"expected (lo, hi) with lo <= hi, got {box.tolist()}")
        lo, hi = box
    lo, hi, pad = _box(lo, hi, pad, func)
    labels = flag(labels, func, "labels")
    if ax is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(6, 5), dpi=80)
        ax = fig.add_subplot(projection="3d")
    for p in prims:
        if isinstance(p, Box):
            ax.add_collection3d(
                Poly3DCollection(
                    box_faces(p.corners()), facecolors=p.color, alpha=p.opacity, edgecolors="0.25", linewidths=0.3
                )
            )
        elif isinstance(p, Quad):
            ax.add_collection3d(
                Poly3DCollection([p.corners], facecolors=p.color, alpha=p.opacity, edgecolors="0.35", linewidths=0.3)
            )
        elif isinstance(p, Sphere):
            ax.plot_surface(*_sphere_grid(p.center, p.radius), color=p.color, alpha=p.opacity, linewidth=0, shade=True)
        elif isinstance(p, Cylinder):
            ax.plot_surface(*cylinder_grid(p), color=p.color, alpha=p.opacity, linewidth=0, shade=True)
        elif isinstance(p, Polyline):
            ax.plot(*p.points.T, color=p.color, lw=p.width * 0.6)
        elif isinstance(p, PointCloud):
            ax.scatter(*p.points.T, color=p.color, s=max(1.0, (p.size * 400) ** 2 / 16), depthshade=False)
        elif isinstance(p, Frame):
            for seg, col in zip(p.axes(), FRAME_COLORS):
                ax.plot(*seg.T, color=col, lw=1.5)
    _equal_3d(ax, lo, hi, pad)
    if labels:
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
    return ax
