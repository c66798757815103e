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
from cga_lessons.algebra import Multivector
from cga_lessons.checks import fail, real, relabel

from .ch2_3d import set_equal_3d
from .inputs import coords, optional_text, vector

__all__ = ["tool_outline", "fig_motor_blend", "fig_scan_registration"]


def tool_outline(length: float = 0.4, width: float = 0.12) -> np.ndarray:
    """Edges of a two-fingered gripper in its own frame, as an array (k, 2, 3) of segments.

    The palm is a bar along y at the origin, the fingers point along +x: a
    shape with no symmetry in the plane, so a wrong rotation shows.  Both sizes lie in (0, 1e6] m.
    """
    func = "tool_outline"
    f = real(length, func, "length", low=0.0, strict_low=True, high=1e6)
    w = real(width, func, "width", low=0.0, strict_low=True, high=1e6)
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


def _motors(motors, func: str) -> list:
    """A non-empty list of motors: finite even multivectors of G(4,1)."""
    if not isinstance(motors, (list, tuple)) or not motors:
        raise fail(func, "motors", "expected a non-empty list of motors")
    for k, M in enumerate(motors):
        if not isinstance(M, Multivector) or M.algebra is not cga.G41:
            raise fail(func, f"motors[{k}]", f"expected a motor (a multivector of G(4,1)), got {type(M).__name__}")
        if any(g % 2 for g in M.grades_present()) or not M.grades_present():
            raise fail(func, f"motors[{k}]", f"expected a motor (even grades), got grades {M.grades_present()}")
        if not all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in M.coeffs.values()):
            raise fail(func, f"motors[{k}]", "contains NaN or inf")
    return list(motors)


def fig_motor_blend(outline, motors, matrix_blend=None, axis_point=None, axis_direction=None, title=None):
    """The tool ``outline`` (k, 2, 3) moved by each motor of ``motors`` (a list), coloured from start to end.

    ``matrix_blend`` (optional): a list of 4x4 matrices (e.g. the entrywise
    blend of the two end poses' matrices), drawn dashed in grey for
    comparison.  ``axis_point`` and ``axis_direction`` draw the screw axis.
    """
    func = "fig_motor_blend"
    outline = coords(outline, func, "outline", (None, 2, 3), at_least=1)
    motors = _motors(motors, func)
    if matrix_blend is not None:
        if not isinstance(matrix_blend, (list, tuple, np.ndarray)):
            raise fail(func, "matrix_blend", f"expected a list of 4x4 matrices, got {type(matrix_blend).__name__}")
        matrix_blend = [coords(H, func, f"matrix_blend[{j}]", (4, 4)) for j, H in enumerate(matrix_blend)]
    if axis_point is not None:  # the axis is drawn when both are given
        axis_point = vector(axis_point, func, "axis_point", (3,))
    if axis_direction is not None:
        axis_direction = vector(axis_direction, func, "axis_direction", (3,))
        if not np.linalg.norm(axis_direction) > 0:
            raise fail(func, "axis_direction", "must not be the zero vector")
    title = optional_text(title, func, "title")
    flat = outline.reshape(-1, 3)
    with relabel(func, "motors"):
        moved_all = [cga.apply_to_points(M, flat).reshape(outline.shape) for M in motors]
    if not all(np.all(np.isfinite(m)) and np.abs(m).max() <= 1e12 for m in moved_all):
        raise fail(func, "motors", "the moved outline cannot be drawn (not finite or beyond +-1e12)")
    fig = plt.figure(figsize=(7.5, 6))
    ax = fig.add_subplot(projection="3d")
    cmap = plt.get_cmap("viridis")
    allpts = []
    for i, moved in enumerate(moved_all):
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
    func = "fig_scan_registration"
    target, source = coords(target, func, "target", (None, 2)), coords(source, func, "source", (None, 2))
    moved = coords(moved, func, "moved", (None, 2))
    if moved.shape != source.shape:
        raise fail(func, "moved", f"expected the shape of source {source.shape} (its points moved), got {moved.shape}")
    title = optional_text(title, func, "title")
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
