"""Figures of the conformal transformations of chapter 2 (section 2.3.4): an inversion in a sphere (2.84-2.88)
and two reflections in planes (2.89), both seen in the plane z = 0.

:func:`grid_lines` makes the square grid whose image under the inversion :func:`fig_inversion_grid` draws.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import FancyArrowPatch, Polygon

from cga_lessons.checks import fail, integer

from .inputs import DPI, coord, coords, optional_text, reflection_planes, vector
from .inputs import legend_loc as legend_location

__all__ = ["grid_lines", "fig_inversion_grid", "fig_two_reflections"]


def grid_lines(lo, hi, n_lines, n_pts=200):
    """A square grid in the plane z = 0: an array (2 n_lines, n_pts, 3) of polylines from ``lo`` to ``hi``."""
    func = "grid_lines"
    lo, hi = coord(lo, func, "lo"), coord(hi, func, "hi")
    n_lines = integer(n_lines, func, "n_lines", low=1, high=1000)
    n_pts = integer(n_pts, func, "n_pts", low=2, high=10**5)
    ticks = np.linspace(lo, hi, n_lines)
    s = np.linspace(lo, hi, n_pts)
    horiz = [np.column_stack([s, np.full_like(s, y), np.zeros_like(s)]) for y in ticks]
    vert = [np.column_stack([np.full_like(s, x), s, np.zeros_like(s)]) for x in ticks]
    return np.array(horiz + vert)


def fig_inversion_grid(grid, image, center, radius, window=None, highlight=None):
    """Inversion in a sphere (2.84-2.88), seen in the plane z = 0 through its centre.

    ``grid`` and ``image`` are arrays (lines, points, 3): the polylines and
    their images.  Lines of the grid become circles through the centre.
    ``highlight`` is the index of one line drawn (with its image) in black; ``window`` is ``(x0, x1, y0, y1)``.
    """
    func = "fig_inversion_grid"
    grid = coords(grid, func, "grid", (None, None, 3), at_least=1)
    image = coords(image, func, "image", (None, None, 3))
    if image.shape != grid.shape:
        raise fail(func, "image", f"expected the shape of grid {grid.shape}, got {image.shape}")
    center, radius = vector(center, func, "center"), coord(radius, func, "radius", low=0.0, strict_low=True)
    if window is not None:
        window = coords(window, func, "window", (4,))
        if not (window[0] < window[1] and window[2] < window[3]):
            raise fail(func, "window", f"expected (x0, x1, y0, y1) with x0 < x1 and y0 < y1, got {window.tolist()}")
    if highlight is not None:
        highlight = integer(highlight, func, "highlight", low=0, high=len(grid) - 1)
    fig, axes = plt.subplots(1, 2, figsize=(12, 6), dpi=DPI)
    t = np.linspace(0, 2 * np.pi, 200)
    for ax, data, color, title in (
        (axes[0], grid, "tab:blue", "a grid of lines"),
        (axes[1], image, "tab:red", "its image under the inversion $g(x)$ (2.88)"),
    ):
        for k, poly in enumerate(data):
            ax.plot(poly[:, 0], poly[:, 1], color=color, lw=0.8, alpha=0.9 if k % 2 else 0.6)
        if highlight is not None:
            ax.plot(data[highlight][:, 0], data[highlight][:, 1], color="black", lw=2, ls="--", label="one line")
        ax.plot(center[0] + radius * np.cos(t), center[1] + radius * np.sin(t), "k", lw=2, label="sphere $s$")
        ax.plot(*center[:2], "k+", ms=12, label="centre $p$")
        ax.set_aspect("equal")
        ax.set_xlabel("$e_1$")
        ax.set_ylabel("$e_2$")
        ax.set_title(title)
        ax.legend(loc="upper right")
    if window is not None:
        for ax in axes:
            ax.set_xlim(window[0], window[1])
            ax.set_ylim(window[2], window[3])
    fig.tight_layout()
    return fig


def _plane_trace(ax, normal, distance, span, color, label):
    """The trace of the plane n . x = delta in the (e1, e2) view: a line."""
    n = np.asarray(normal, dtype=float)[:2]
    n = n / np.linalg.norm(n)
    p0 = distance * n
    d = np.array([-n[1], n[0]])
    seg = p0 + np.linspace(-span, span, 2)[:, None] * d
    ax.plot(seg[:, 0], seg[:, 1], color=color, lw=2, label=label)
    ax.add_patch(FancyArrowPatch(p0, p0 + 0.5 * n, arrowstyle="-|>", mutation_scale=14, color=color, lw=1.5))


def fig_two_reflections(shape, after_first, after_second, planes, title, span=3.0, center=None, legend_loc="best"):
    """Figures 2.7 and 2.8: an object reflected in one plane and then in another.

    ``shape``, ``after_first`` and ``after_second`` are (k, 3) arrays of the
    vertices of a polygon in the plane z = 0; ``planes`` is a sequence of two
    ``(normal, distance, label)`` triples, the plane used first, then the one
    used second (2.89).  ``center``, if given, is marked (the centre of a rotation).
    """
    func = "fig_two_reflections"
    shape = coords(shape, func, "shape", (None, 3), at_least=1)
    after_first, after_second = (coords(v, func, k, shape.shape) for k, v in
                                 (("after_first", after_first), ("after_second", after_second)))  # fmt: skip
    planes, title = reflection_planes(planes, func), optional_text(title, func, "title")
    span = coord(span, func, "span", low=0.0, strict_low=True)
    center = None if center is None else vector(center, func, "center")
    legend_loc = legend_location(legend_loc, func)
    fig, ax = plt.subplots(figsize=(7, 6), dpi=DPI)
    for (n, d, label), color in zip(planes, ("tab:gray", "tab:brown")):
        _plane_trace(ax, n, d, span, color, label)
    for pts, color, label, alpha in (
        (shape, "tab:blue", "object", 0.5),
        (after_first, "tab:orange", "after the first reflection", 0.25),
        (after_second, "tab:green", "after the second reflection", 0.5),
    ):
        pts = np.asarray(pts)
        ax.add_patch(Polygon(pts[:, :2], closed=True, color=color, alpha=alpha, label=label))
        ax.plot(pts[0, 0], pts[0, 1], "o", color=color)
    for p, q in zip(np.asarray(shape), np.asarray(after_second)):
        ax.plot([p[0], q[0]], [p[1], q[1]], color="k", lw=0.5, ls=":")
    if center is not None:
        ax.plot(center[0], center[1], "k*", ms=12)
        ax.annotate("$c$", center[:2], textcoords="offset points", xytext=(6, -14), fontsize=13)
    allpts = np.vstack([shape, after_first, after_second])[:, :2]
    lo, hi = allpts.min(axis=0) - 0.7, allpts.max(axis=0) + 0.7
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("$e_1$")
    ax.set_ylabel("$e_2$")
    ax.legend(loc=legend_loc, fontsize=9)
    ax.set_title(title)
    fig.tight_layout()
    return fig
