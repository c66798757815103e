"""The 3D figures of chapter 2: the entities of table 2.1 read back from their conformal forms, and the helix
of a repeated screw motion (2.110).

:func:`fig_entities` reads each entity's Euclidean parameters back with :mod:`cga_lessons.conformal` (centre,
radius, direction, ...), so a figure that looks right is also a check of the extraction formulas of section 2.4.
:func:`set_equal_3d` gives a 3D axes equal scales around some points.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons.checks import fail

from .inputs import DPI, axes, coord, entity_parameters, optional_text, texts, vector
from .inputs import points as point_rows

__all__ = ["set_equal_3d", "fig_entities", "fig_screw_helix"]

_COLORS = {
    "point": "black",
    "point_pair": "tab:red",
    "sphere": "tab:blue",
    "plane": "tab:green",
    "line": "tab:orange",
    "circle": "tab:purple",
}


def _orthonormal_pair(n):
    """Two unit vectors completing the unit vector n to a right-handed basis."""
    n = np.asarray(n, dtype=float)
    helper = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    u = np.cross(n, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(n, u)


def set_equal_3d(ax, pts, pad=0.3, labels=("$e_1$", "$e_2$", "$e_3$")):
    """Equal scales on a 3D axes around the points ``pts`` (N, 3) (with a margin ``pad``), axes labelled ``labels``."""
    func = "set_equal_3d"
    ax = axes(ax, func, three_d=True, optional=False)
    pts = point_rows(pts, func, "pts")
    pad = coord(pad, func, "pad", low=0.0)
    labels = _labels3(labels, func)
    _equal_3d(ax, pts, pad, labels)


def _labels3(value, func: str) -> list:
    return texts(value, func, "labels", 3)


def _equal_3d(ax, pts, pad, labels):
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c, r = (lo + hi) / 2, (hi - lo).max() / 2 + pad
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.set_zlabel(labels[2])


def fig_entities(points=None, point_pair=None, sphere=None, plane=None, line=None, circle=None, title=None):
    """The entities of table 2.1 in one 3D scene, each drawn from its conformal form.

    ``points`` is an (N, 3) array; the others are multivectors: a point pair
    (2.68), a sphere (2.72 or 2.75), a plane (2.77 or 2.89), a line (2.81) and
    a circle (2.80).  Their parameters are read back with
    ``cga.point_pair_endpoints``, ``cga.sphere_center_radius``,
    ``cga.plane_normal_distance``, ``cga.line_closest_point`` /
    ``cga.line_direction`` and ``cga.circle_center_radius``.
    """
    func = "fig_entities"
    pts = None if points is None else point_rows(points, func, "points")
    given = {"point_pair": point_pair, "sphere": sphere, "plane": plane, "line": line, "circle": circle}
    read = {name: entity_parameters(X, func, name) for name, X in given.items() if X is not None}
    title = optional_text(title, func, "title")
    fig = plt.figure(figsize=(7, 6.2), dpi=DPI)
    ax = fig.add_subplot(projection="3d")
    extent = []
    if pts is not None:
        ax.scatter(*pts.T, color=_COLORS["point"], s=25, label="points $\\underline{x}$ (2.62)")
        extent.append(pts)
    if "sphere" in read:
        c, r = read["sphere"]
        u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 30), np.linspace(0, np.pi, 16))
        xyz = c[:, None, None] + r * np.array([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])
        ax.plot_wireframe(*xyz, color=_COLORS["sphere"], alpha=0.35, lw=0.6)
        ax.plot([], [], color=_COLORS["sphere"], label=f"sphere, $\\rho$ = {r:.2f}")
        extent.append(xyz.reshape(3, -1).T)
    if "circle" in read:
        c, r, n = read["circle"]
        u, v = _orthonormal_pair(n)
        t = np.linspace(0, 2 * np.pi, 100)
        xyz = c + r * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)
        ax.plot(*xyz.T, color=_COLORS["circle"], lw=2, label=f"circle, $\\rho$ = {r:.2f}")
        extent.append(xyz)
    if "line" in read:
        p, d = read["line"]
        seg = p + np.linspace(-2.5, 2.5, 2)[:, None] * d
        ax.plot(*seg.T, color=_COLORS["line"], lw=2.5, label="line")
        extent.append(seg)
    if "point_pair" in read:
        p1, p2 = read["point_pair"]
        ax.plot(*np.array([p1, p2]).T, color=_COLORS["point_pair"], ls=":", lw=1)
        ax.scatter(*np.array([p1, p2]).T, color=_COLORS["point_pair"], s=60, marker="D", label="point pair")
        extent.append(np.array([p1, p2]))
    if "plane" in read:
        n, d = read["plane"]
        u, v = _orthonormal_pair(n)
        s, t = np.meshgrid(np.linspace(-2.2, 2.2, 2), np.linspace(-2.2, 2.2, 2))
        middle = np.vstack(extent).mean(axis=0) if extent else np.zeros(3)
        foot = middle - (middle @ n - d) * n  # the scene's centre projected onto the plane
        xyz = foot[:, None, None] + s * u[:, None, None] + t * v[:, None, None]
        ax.plot_surface(*xyz, color=_COLORS["plane"], alpha=0.2)
        ax.plot([], [], color=_COLORS["plane"], lw=6, alpha=0.4, label="plane")
    _equal_3d(ax, np.vstack(extent) if extent else np.zeros((1, 3)), 0.3, ("$e_1$", "$e_2$", "$e_3$"))
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title(title or "Table 2.1: conformal entities")
    fig.tight_layout()
    return fig


def fig_screw_helix(points, axis_point, axis_direction, title="A point under a repeated screw motion (2.110)"):
    """The orbit of a point under powers of a screw motor: a helix around the screw axis (``points`` (N, 3))."""
    func = "fig_screw_helix"
    pts = point_rows(points, func, "points")
    axis_point = vector(axis_point, func, "axis_point", (3,))
    if not np.linalg.norm(vector(axis_direction, func, "axis_direction", (3,))) > 0:
        raise fail(func, "axis_direction", "must not be the zero vector")
    title = optional_text(title, func, "title")
    fig = plt.figure(figsize=(7, 7), dpi=DPI)
    ax = fig.add_subplot(projection="3d")
    ax.plot(*pts.T, color="tab:blue", lw=1)
    ax.scatter(*pts.T, c=np.arange(len(pts)), cmap="viridis", s=18)
    ax.scatter(*pts[0], color="tab:red", s=60, label="start")
    d = np.asarray(axis_direction, dtype=float)
    d = d / np.linalg.norm(d)
    proj = (pts - axis_point) @ d
    seg = np.asarray(axis_point) + np.array([proj.min() - 0.3, proj.max() + 0.3])[:, None] * d
    ax.plot(*seg.T, "k--", lw=1.5, label="screw axis")
    _equal_3d(ax, np.vstack([pts, seg]), 0.2, ("$e_1$", "$e_2$", "$e_3$"))
    ax.view_init(*_side_view(d))
    ax.legend(loc="upper left")
    ax.set_title(title)
    fig.tight_layout()
    return fig


def _side_view(direction):
    """(elev, azim) in degrees of a camera looking as nearly perpendicular to ``direction`` as possible."""
    el, az = np.meshgrid(np.radians([15, 20, 25, 30, 35]), np.radians(np.arange(-180, 180, 5)))
    view = np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)
    k = np.unravel_index(np.argmin(np.abs(view @ np.asarray(direction, dtype=float))), el.shape)
    return float(np.degrees(el[k])), float(np.degrees(az[k]))
