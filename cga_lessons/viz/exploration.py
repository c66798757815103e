"""Figures for the exploration document (figures 3.3-3.10): labelled nodes, the view, the detour.

Colours follow the document: seen nodes red, not seen blue; occupied nodes black,
analysed nodes green, the sphere's points grey.  Lengths are drawn in the data's
unit (cm for the document's cases), angles shown in degrees.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons.checks import array, choice, fail, flag, integer
from cga_lessons.exploration import ANALYSED, LABEL_NAMES, NOT_SEEN, OCCUPIED, SEEN, Grid, Scenario

from .inputs import axes, coord, coords, optional_text

__all__ = ["plot_scenario", "plot_nodes", "plot_occupancy_steps", "plot_disagreements", "plot_detour"]

COLORS = {NOT_SEEN: "tab:blue", SEEN: "tab:red", ANALYSED: "tab:green", OCCUPIED: "black"}
_AXES = {"xy": (0, 1), "xz": (0, 2)}


def _ray_length(result):
    g = result.grid
    far = np.asarray(g.origin) + g.spacing * (np.asarray(g.shape) - 1)
    return 1.1 * np.max(np.abs(np.r_[g.origin[:2], far[:2]] - np.tile(result.view.position[:2], 2)))


def _rays(ax, result, plane):
    """Field-of-view edges (solid red) and tangents to the obstacle (dashed magenta) from the robot."""
    o = np.asarray(result.view.position)
    i, j = _AXES[plane]
    length = min(_ray_length(result), result.view.max_range)
    pr = result.projections
    lines = [(a, "-", "tab:red", "field of view") for a in pr.edges]
    if pr.tangents is not None:
        lines += [(t, "--", "m", "tangent to obstacle") for t in pr.tangents]
    for k, (rel, style, color, label) in enumerate(lines):
        a = result.view.heading + rel
        end = o + length * np.array([np.cos(a), np.sin(a), 0.0])
        ax.plot([o[i], end[i]], [o[j], end[j]], style, color=color, lw=1.2, label=label if k in (0, 2) else None)


def _result(result, func: str, *, obstacle: bool = False):
    """A scenario's result (:func:`cga_lessons.exploration.run_scenario`); with ``obstacle``, one with a sphere."""
    scenario, grid = getattr(result, "scenario", None), getattr(result, "grid", None)
    if not (isinstance(scenario, Scenario) and isinstance(grid, Grid)):
        raise fail(func, "result", f"expected the result of exploration.run_scenario, got {type(result).__name__}")
    if obstacle and (result.obstacle is None or result.loop is None or result.points is None):
        raise fail(func, "result", "the scenario has no obstacle (a sphere with points): nothing to draw")
    return result


def _codes(value, func: str, name: str, n: int, allowed) -> np.ndarray:
    """One whole-number code per node, each in ``allowed``."""
    a = array(value, func, name, (n,))
    if np.any(a != np.round(a)) or not np.all(np.isin(a, list(allowed))):
        raise fail(func, name, f"expected {n} codes from {sorted(allowed)}")
    return a.astype(int)


def plot_nodes(ax, result, plane="xy", labels=None, legend=True):
    """Nodes coloured by label on the plane "xy" or "xz" (occupied drawn last, on top).

    ``labels``: one label code per node (default: the result's own labels).
    """
    func = "plot_nodes"
    ax, result = axes(ax, func, optional=False), _result(result, func)
    plane, legend = choice(plane, func, "plane", _AXES), flag(legend, func, "legend")
    nodes = result.grid.nodes
    lab = result.labels.labels if labels is None else _codes(labels, func, "labels", len(nodes), COLORS)
    return _plot_nodes(ax, result, plane, lab, legend)


def _plot_nodes(ax, result, plane, lab, legend):
    i, j = _AXES[plane]
    nodes = result.grid.nodes
    for code in (NOT_SEEN, SEEN, ANALYSED, OCCUPIED):
        m = lab == code
        if m.any():
            ax.scatter(nodes[m, i], nodes[m, j], s=22, c=COLORS[code], label=f"{LABEL_NAMES[code]} nodes", zorder=3)
    if result.points is not None:
        ax.scatter(result.points[:, i], result.points[:, j], s=2, c="0.55", label="sphere points", zorder=2)
    if result.obstacle is not None:
        c = result.obstacle.center
        ax.add_patch(plt.Circle((c[i], c[j]), result.obstacle.radius, fill=False, color="k", lw=0.8))
    _rays(ax, result, plane)
    o = result.view.position
    ax.plot(o[i], o[j], marker="^", ms=9, color="k", zorder=4, label="robot")
    ax.set_aspect("equal")
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)" if plane == "xy" else "z (cm)")
    g = result.grid
    hi = np.asarray(g.origin) + g.spacing * (np.asarray(g.shape) - 1)
    pad = g.spacing if plane == "xy" else g.spacing / 2
    ax.set_xlim(g.origin[i] - g.spacing, hi[i] + g.spacing)
    ax.set_ylim(g.origin[j] - pad, hi[j] + pad)
    if legend:
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    return ax


def plot_scenario(result, title=None):
    """Figure with the x-y view and the x-z view (all y rows projected) of a labelled scenario."""
    result, title = _result(result, "plot_scenario"), optional_text(title, "plot_scenario", "title")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1, 1.25]})
    _plot_nodes(a1, result, "xy", result.labels.labels, False)
    _plot_nodes(a2, result, "xz", result.labels.labels, True)
    a1.set_title("x-y view")
    a2.set_title("x-z view (all rows of y projected; z stretched)")
    a2.set_aspect("auto")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def plot_occupancy_steps(result, counts=(1, 3, 6, None), window=45.0):
    """Figure 3.6: the nearest-node loop of exploration (3.1) after the given numbers of steps.

    x-y view: the two layers of z are drawn on top of each other.  ``counts``: numbers of steps (None: all of
    them), one panel each; ``window``: the half-width of the view around the sphere's centre.
    """
    func = "plot_occupancy_steps"
    result = _result(result, func, obstacle=True)
    if not isinstance(counts, (list, tuple)) or not 1 <= len(counts) <= 12:
        raise fail(func, "counts", f"expected 1 to 12 numbers of steps (or None), got {counts!r}")
    counts = [None if k is None else integer(k, func, "counts", low=0) for k in counts]
    window = coord(window, func, "window", low=0.0, strict_low=True)
    loop, pts, nodes = result.loop, result.points, result.grid.nodes
    fig, axes = plt.subplots(1, len(counts), figsize=(3.3 * len(counts), 3.6), sharey=True)
    c = np.asarray(result.obstacle.center)
    for ax, k in zip(axes, counts):
        steps = loop.steps if k is None else loop.steps[:k]
        occ = sorted({n for _, n, ok in steps if ok})
        ana = sorted({n for _, n, ok in steps if not ok} - set(occ))
        left = np.ones(len(pts), bool)
        for n in occ:
            left &= ~np.all((pts >= nodes[n]) & (pts < nodes[n] + result.grid.spacing), axis=1)
        ax.scatter(pts[left, 0], pts[left, 1], s=3, c="0.55", label="sphere points left")
        ax.scatter(*nodes[ana][:, :2].T, s=60, c=COLORS[ANALYSED], label="analysed", zorder=3)
        ax.scatter(*nodes[occ][:, :2].T, s=60, c=COLORS[OCCUPIED], label="occupied", zorder=4)
        near = np.all(np.abs(nodes[:, :2] - c[:2]) <= window, axis=1)
        ax.scatter(*nodes[near][:, :2].T, s=12, facecolors="none", edgecolors="0.3", zorder=2)
        ax.set_xlim(c[0] - window, c[0] + window)
        ax.set_ylim(c[1] - window, c[1] + window)
        ax.set_aspect("equal")
        ax.set_title(f"step {len(steps)}: {len(occ)} occupied, {len(ana)} analysed", fontsize=9)
        ax.set_xlabel("x (cm)")
    axes[0].set_ylabel("y (cm)")
    axes[-1].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    fig.tight_layout()
    return fig


def plot_disagreements(result, codes, names):
    """x-y and x-z views of where the document's rule and 3D ray casting differ, coloured by reason.

    ``codes``: one code 0-3 per node (:func:`cga_lessons.exploration.ray_cast_disagreements`); ``names``: the
    reason of each code (:data:`cga_lessons.exploration.DISAGREEMENTS`).
    """
    func = "plot_disagreements"
    result = _result(result, func, obstacle=True)
    codes = _codes(codes, func, "codes", len(result.grid.nodes), range(4))
    if not isinstance(names, dict) or any(not isinstance(names.get(k), str) for k in range(4)):
        raise fail(func, "names", "expected a dict code -> reason (str) for the codes 0, 1, 2 and 3")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1, 1.25]})
    colors = {0: "0.8", 1: "tab:purple", 2: "tab:orange", 3: "tab:cyan"}
    nodes = result.grid.nodes
    for ax, plane in zip(axes, ("xy", "xz")):
        i, j = _AXES[plane]
        for code in sorted(colors):
            m = codes == code
            if m.any():
                ax.scatter(nodes[m, i], nodes[m, j], s=22, c=colors[code], label=names[code], zorder=3 if code else 2)
        c = result.obstacle.center
        ax.add_patch(plt.Circle((c[i], c[j]), result.obstacle.radius, fill=False, color="k", lw=0.8))
        _rays(ax, result, plane)
        ax.plot(result.view.position[i], result.view.position[j], "k^", ms=9)
        ax.set_xlabel("x (cm)")
        ax.set_ylabel("y (cm)" if plane == "xy" else "z (cm)")
    axes[0].set_aspect("equal")
    axes[1].legend(loc="upper center", bbox_to_anchor=(0.4, -0.18), fontsize=8)
    fig.tight_layout()
    return fig


def _detour(detour, func: str) -> None:
    """The answer of :func:`cga_lessons.exploration.detour`: a drawable path, crossings and tangent points."""
    if not all(hasattr(detour, k) for k in ("path", "crossings", "tangent_points")):
        raise fail(func, "detour", f"expected the answer of exploration.detour, got {type(detour).__name__}")
    coords(detour.path, func, "detour", (None, 2), at_least=2)
    for part in (detour.crossings, detour.tangent_points):
        if part is not None:
            coords(part, func, "detour", (None, 2))


def plot_detour(start, goal, center, radius, detour, crossings_document=None, ax=None):
    """Figure 3.10: the straight path, its crossings with the circle, the part removed and the smooth detour.

    ``detour`` is :func:`cga_lessons.exploration.detour`'s answer; ``crossings_document`` (k, 2), optional, the
    crossings by the document's algebra.
    """
    func = "plot_detour"
    s, g, c = (coords(v, func, k, (2,)) for k, v in (("start", start), ("goal", goal), ("center", center)))
    radius = coord(radius, func, "radius", low=0.0, strict_low=True)
    _detour(detour, func)
    if crossings_document is not None:
        crossings_document = coords(crossings_document, func, "crossings_document", (None, 2))
    if axes(ax, func) is None:
        _, ax = plt.subplots(figsize=(7, 5))
    ax.add_patch(plt.Circle(c, radius, fill=False, color="k", lw=1.2, label="obstacle (3.3)"))
    ax.plot(*np.c_[s, g], ":", color="0.5", label="straight path (3.2)")
    if detour.crossings is not None:
        ax.plot(*detour.crossings.T, "r-", lw=2.5, label="part inside, removed")
        ax.plot(*detour.crossings.T, "o", mfc="none", mec="r", ms=11, label="point pair (conformal, 2.131)")
    if crossings_document is not None:
        ax.plot(*crossings_document.T, "kx", ms=7, label="crossings (document's algebra)")
    ax.plot(*detour.path.T, "-", color="tab:blue", lw=2, label="smooth detour")
    if detour.tangent_points is not None:
        ax.plot(*detour.tangent_points.T, "s", color="tab:blue", ms=5, label="tangent points")
    ax.plot(*s, "k^", ms=9, label="robot")
    ax.plot(*g, "k*", ms=12, label="goal")
    ax.set_aspect("equal")
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    return ax
