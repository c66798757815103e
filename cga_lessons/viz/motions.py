"""Figures for motions beyond the thesis's tables: blending two poses, registering two scans.

Each ``fig_*`` function draws one figure and returns the matplotlib ``Figure``
(end the notebook cell with ``;``).  The motions themselves come from
:mod:`cga_lessons.conformal` (``motor_interpolate``, ``motor_from_points``);
these functions only draw what they are given.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga

from .ch2 import set_equal_3d

__all__ = ["tool_outline", "fig_motor_blend", "fig_scan_registration"]


def tool_outline(length: float = 0.4, width: float = 0.12) -> np.ndarray:
    """Edges of a two-fingered gripper in its own frame, as an array (k, 2, 3) of segments.

    The palm is a bar along y at the origin, the fingers point along +x: a
    shape with no symmetry in the plane, so a wrong rotation shows.
    """
    w, f = width, length
    segs = [
        ([0, -w, 0], [0, w, 0]),  # palm
        ([0, -w, 0], [f, -w, 0]),  # finger 1
        ([0, w, 0], [0.6 * f, w, 0]),  # finger 2 (shorter)
        ([-0.5 * f, 0, 0], [0, 0, 0]),  # wrist
        ([0, 0, 0], [0, 0, 0.5 * w]),  # up marker (+z of the tool)
    ]
    return np.array(segs, dtype=float)


def _draw_segments(ax, segs, color, lw=1.5, ls="-", alpha=1.0, label=None):
    for i, (a, b) in enumerate(segs):
        ax.plot(*np.stack([a, b]).T, color=color, lw=lw, ls=ls, alpha=alpha, label=label if i == 0 else None)


def fig_motor_blend(outline, motors, matrix_blend=None, axis_point=None, axis_direction=None, title=None):
    """The tool ``outline`` (k, 2, 3) moved by each motor of ``motors`` (a list), coloured from start to end.

    ``matrix_blend`` (optional): a list of 4x4 matrices (e.g. the entrywise
    blend of the two end poses' matrices), drawn dashed in grey for
    comparison.  ``axis_point`` and ``axis_direction`` draw the screw axis.
    """
    fig = plt.figure(figsize=(7.5, 6))
    ax = fig.add_subplot(projection="3d")
    cmap = plt.get_cmap("viridis")
    allpts = []
    flat = outline.reshape(-1, 3)
    for i, M in enumerate(motors):
        moved = cga.apply_to_points(M, flat).reshape(outline.shape)
        allpts.append(moved.reshape(-1, 3))
        ends = i in (0, len(motors) - 1)
        label = "screw interpolation" if i == 1 else ("start and end poses" if i == 0 else None)
        _draw_segments(ax, moved, cmap(i / max(len(motors) - 1, 1)), lw=2.5 if ends else 1.3, label=label)
    if matrix_blend is not None:
        for j, H in enumerate(matrix_blend):
            moved = flat @ H[:3, :3].T + H[:3, 3]
            allpts.append(moved)
            _draw_segments(ax, moved.reshape(outline.shape), "0.5", lw=1.0, ls="--",
                           label="blend of the 4x4 matrices" if j == 0 else None)  # fmt: skip
    pts = np.concatenate(allpts)
    if axis_point is not None and axis_direction is not None:
        d = np.asarray(axis_direction, float) / np.linalg.norm(axis_direction)
        c = np.asarray(axis_point, float)
        s = (pts - c) @ d
        seg = np.stack([c + (s.min() - 0.2) * d, c + (s.max() + 0.2) * d])
        ax.plot(*seg.T, color="crimson", lw=1.2, ls=":", label="screw axis")
    set_equal_3d(ax, pts, pad=0.1, labels=("x (m)", "y (m)", "z (m)"))
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title(title or "Blending two poses along their screw")
    fig.tight_layout()
    return fig


def fig_scan_registration(target, source, moved, title=None):
    """Two laser scans in the plane: ``target`` (k, 2), ``source`` (m, 2) as given and as ``moved`` (m, 2)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 5), sharex=True, sharey=True)
    for ax, pts, name in ((axes[0], source, "before"), (axes[1], moved, "after")):
        ax.plot(*np.asarray(target).T, ".", ms=2.5, color="tab:blue", label="first scan")
        ax.plot(*np.asarray(pts).T, ".", ms=2.5, color="tab:orange", label="second scan")
        ax.set_aspect("equal")
        ax.set_title(f"{name} registration")
        ax.set_xlabel("x (m)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("y (m)")
    axes[0].legend(loc="upper right", fontsize=8, markerscale=3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig
