"""Figures for the chapter-2 notebooks (sections 2.1-2.4 of the thesis).

Each ``fig_*`` function draws one figure of the course and returns the
matplotlib ``Figure`` (end the notebook cell with ``;`` so that nbval sees no
repr).  The drawing functions that take conformal entities read their
Euclidean parameters back with :mod:`cga_lessons.conformal` (centre, radius,
direction, ...), so a figure that looks right is also a check of the
extraction formulas of section 2.4.

Besides drawing, two small helpers prepare what a figure or a table shows:
:func:`product_table` (the text of the product table (2.10)) and
:func:`point_pair_accuracy` (the experiment behind the accuracy figure of
(2.131)).
"""

from __future__ import annotations

import io

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import FancyArrowPatch, Polygon

from cga_lessons import conformal as cga
from cga_lessons.algebra import Algebra, GeometryError
from cga_lessons.checks import fail, instance, integer, same_length

from ._inputs import (
    LIMIT,
    axes,
    coord,
    coords,
    entity,
    figure,
    floats,
    generator,
    optional_text,
    relabel,
    texts,
    vector,
)
from ._inputs import legend_loc as legend_location
from ._inputs import points as point_rows

__all__ = [
    "DPI",
    "show",
    "product_table",
    "fig_bivectors",
    "fig_stereographic_1d",
    "fig_null_cone",
    "fig_minkowski_plane",
    "fig_entities",
    "grid_lines",
    "fig_inversion_grid",
    "fig_two_reflections",
    "fig_screw_helix",
    "set_equal_3d",
    "point_pair_accuracy",
    "fig_point_pair_accuracy",
]

#: Resolution of every figure (kept low so that the stored notebooks stay small).
DPI = 80

_COLORS = {
    "point": "black",
    "point_pair": "tab:red",
    "sphere": "tab:blue",
    "plane": "tab:green",
    "line": "tab:orange",
    "circle": "tab:purple",
}


def show(fig, colors=256):
    """Display a figure in a notebook as a 256-colour PNG, then close it.

    Line drawings lose nothing visible in the palette, and the stored
    notebook gets two to three times smaller than with the default RGBA PNG.
    Outside IPython this is ``plt.show()``.  ``colors``: the palette's size, 2 to 256.
    """
    fig = figure(fig, "show")
    colors = integer(colors, "show", "colors", low=2, high=256)
    try:
        from IPython import get_ipython
        from IPython.display import Image, display
    except ImportError:  # pragma: no cover - IPython ships with the notebook extras
        get_ipython = None
    if get_ipython is None or get_ipython() is None:
        plt.show()
        return
    from PIL import Image as PILImage

    raw = io.BytesIO()
    fig.savefig(raw, format="png", bbox_inches="tight")
    plt.close(fig)
    raw.seek(0)
    out = io.BytesIO()
    PILImage.open(raw).convert("RGB").quantize(colors).save(out, format="PNG", optimize=True)
    display(Image(data=out.getvalue()))


# ------------------------------------------------------------------ tables
def product_table(alg: Algebra) -> str:
    """The geometric product of every pair of basis blades of ``alg`` as text, from (2.10).

    Row ``A``, column ``B`` holds ``A B``: a signed blade name, or ``0`` when a
    null basis vector is squared.
    """
    alg = instance(alg, "product_table", "alg", Algebra, "an Algebra (cga_lessons.algebra.Algebra)")
    names = [alg.blade_names[b] for b in alg.blade_order]
    cells = []
    for a in names:
        row = []
        for b in names:
            items = (alg.blade(a) * alg.blade(b)).items()
            if not items:
                row.append("0")
            else:
                ((name, coeff),) = items
                row.append(("-" if coeff < 0 else "+") + name)
        cells.append(row)
    width = max(len(c) for row in cells for c in row + names) + 1
    squares = ", ".join(f"e{lab}^2 = {m:+d}" if m else f"e{lab}^2 = 0" for lab, m in zip(alg.labels, alg.metric))
    lines = [f"G{alg.signature}: {squares}", " " * width + " |" + "".join(n.rjust(width) for n in names)]
    lines.append("-" * (width + 2 + width * len(names)))
    for n, row in zip(names, cells):
        lines.append(n.rjust(width) + " |" + "".join(c.rjust(width) for c in row))
    return "\n".join(lines)


# ----------------------------------------------------------- section 2.1
def _arrow(ax, p, q, color="k", lw=1.5, style="-|>", **kw):
    ax.add_patch(FancyArrowPatch(p, q, arrowstyle=style, mutation_scale=14, color=color, lw=lw, **kw))


def _circulation(ax, center, radius, ccw, color):
    """A curved arrow (three quarters of a circle) around ``center`` showing a sense of rotation."""
    t = np.linspace(0.25 * np.pi, 1.75 * np.pi, 60)
    if not ccw:
        t = t[::-1]
    pts = np.asarray(center) + radius * np.column_stack([np.cos(t), np.sin(t)])
    ax.plot(pts[:-1, 0], pts[:-1, 1], color=color, lw=1.5)
    _arrow(ax, pts[-6], pts[-1], color=color, lw=1.5)


def fig_bivectors(a, b):
    """Figures 2.1-2.3: the unit bivector e12, the parallelogram a ^ b, and a ^ b = -b ^ a (2.6, 2.7)."""
    a, b = coords(a, "fig_bivectors", "a", (2,)), coords(b, "fig_bivectors", "b", (2,))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.5), dpi=DPI, gridspec_kw={"width_ratios": [1, 1.1, 1.7]})
    o = np.zeros(2)
    e1, e2 = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    # Fig. 2.1: e12, the oriented unit square
    ax = axes[0]
    ax.add_patch(Polygon([o, e1, e1 + e2, e2], color="tab:blue", alpha=0.25))
    _arrow(ax, o, e1, "tab:red")
    _arrow(ax, o, e2, "tab:red")
    ax.text(1.02, -0.12, "$e_1$", fontsize=13)
    ax.text(-0.15, 1.02, "$e_2$", fontsize=13)
    _circulation(ax, np.array([0.5, 0.5]), 0.22, True, "tab:blue")
    ax.text(0.5, 0.5, "$e_{12}$", ha="center", va="center", fontsize=14)
    ax.set_title("Fig. 2.1: bivector $e_{12}=e_1e_2$, area 1")
    # Fig. 2.2: the parallelogram of a and b
    ax = axes[1]
    area = a[0] * b[1] - a[1] * b[0]
    ax.add_patch(Polygon([o, a, a + b, b], color="tab:blue", alpha=0.25))
    _arrow(ax, o, a, "tab:red")
    _arrow(ax, o, b, "tab:green")
    ax.text(*(a * 1.05), "$a$", fontsize=13)
    ax.text(*(b * 1.05), "$b$", fontsize=13)
    ax.text(*((a + b) / 2), f"$a\\wedge b = {area:g}\\,e_{{12}}$", ha="center", va="center", fontsize=12)
    ax.set_title(f"Fig. 2.2: area $|a_1b_2-a_2b_1| = {abs(area):g}$")
    # Fig. 2.3: a ^ b and b ^ a, opposite senses
    ax = axes[2]
    shift = np.array([a[0] + b[0] + 0.8, 0.0])
    for off, first, second, ccw, color, label in (
        (o, a, b, area > 0, "tab:blue", "$a\\wedge b$"),
        (shift, b, a, area < 0, "tab:orange", "$b\\wedge a$"),
    ):
        ax.add_patch(Polygon([off, off + first, off + first + second, off + second], color=color, alpha=0.25))
        _arrow(ax, off, off + first, "k")
        _arrow(ax, off + first, off + first + second, "k")
        c = off + (first + second) / 2
        _circulation(ax, c, 0.45, ccw, color)
        ax.text(c[0], c[1], label, ha="center", va="center", fontsize=12)
    ax.set_title("Fig. 2.3: $a\\wedge b=-\\,b\\wedge a$ (2.7)")
    for ax in axes:
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.grid(alpha=0.3)
        ax.set_xlabel("$e_1$")
        ax.set_ylabel("$e_2$")
    axes[0].set_xlim(-0.3, 1.4)
    axes[0].set_ylim(-0.3, 1.4)
    pts = np.array([o, a, b, a + b])
    axes[1].set_xlim(pts[:, 0].min() - 0.5, pts[:, 0].max() + 0.8)
    axes[1].set_ylim(pts[:, 1].min() - 0.5, pts[:, 1].max() + 0.5)
    axes[2].set_xlim(pts[:, 0].min() - 0.5, shift[0] + pts[:, 0].max() + 0.5)
    axes[2].set_ylim(pts[:, 1].min() - 0.9, pts[:, 1].max() + 0.5)
    fig.tight_layout()
    return fig


# ----------------------------------------------------------- section 2.3
def _stereo(x):
    """The stereographic image (2.48) of x on the e1 axis: (a, b) on the unit circle."""
    x = np.asarray(x, dtype=float)
    return 2 * x / (x**2 + 1), (x**2 - 1) / (x**2 + 1)


def fig_stereographic_1d(xs):
    """Figure 2.4: stereographic projection of points x e1 onto the unit circle from n = e+ (2.38-2.48)."""
    xs = coords(xs, "fig_stereographic_1d", "xs", (None,), at_least=1)
    fig, ax = plt.subplots(figsize=(7, 5), dpi=DPI)
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(t), np.sin(t), "k", lw=1)
    span = max(2.0, np.abs(xs).max() + 0.5)
    ax.axhline(0, color="grey", lw=0.8)
    ax.axvline(0, color="grey", lw=0.8)
    ax.plot(0, 1, "ko")
    ax.text(0.08, 1.08, "$n = e_+$", fontsize=12)
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(xs)))
    for x, c in zip(xs, colors):
        a, b = _stereo(x)
        far = (x, 0.0) if abs(x) >= abs(a) else (a, b)
        ax.plot([0, far[0]], [1, far[1]], color=c, lw=1)
        ax.plot(x, 0, "o", color=c)
        ax.plot(a, b, "s", color=c, mfc="white")
        ax.annotate(f"$x={x:g}$", (x, 0), textcoords="offset points", xytext=(-12, -16), fontsize=10, color=c)
    ax.plot([], [], "ko", label="$x\\,e_1$ (2.38)")
    ax.plot([], [], "ks", mfc="white", label="$x'$ on the circle (2.48)")
    ax.legend(loc="lower right")
    ax.set_xlim(-span, span)
    ax.set_ylim(-1.4, 1.4)
    ax.set_aspect("equal")
    ax.set_xlabel("$e_1$")
    ax.set_ylabel("$e_+$")
    ax.set_title("Fig. 2.4: stereographic projection in 1D")
    fig.tight_layout()
    return fig


def fig_null_cone(xs):
    """Figure 2.6: the homogeneous model of the 1D stereographic projection in (e1, e+, e-).

    The null cone e-^2 = e1^2 + e+^2, the unit circle lifted to the plane
    e- = 1 (2.49), and the horosphere (2.50-2.51): the conformal points
    x e1 + (x^2-1)/2 e+ + (x^2+1)/2 e-, where the cone meets the hyperplane
    X . e = -1.
    """
    xs = coords(xs, "fig_null_cone", "xs", (None,), at_least=1, limit=1e6)
    fig = plt.figure(figsize=(7, 6.2), dpi=DPI)
    ax = fig.add_subplot(projection="3d")
    h = 2.6
    th = np.linspace(0, 2 * np.pi, 60)
    r = np.linspace(0, h, 12)
    T, Rr = np.meshgrid(th, r)
    ax.plot_wireframe(Rr * np.cos(T), Rr * np.sin(T), Rr, color="grey", alpha=0.25, lw=0.6)
    ax.plot(np.cos(th), np.sin(th), np.ones_like(th), "k", lw=1.5, label="unit circle at $e_-=1$ (2.49)")
    u = np.linspace(-2.05, 2.05, 200)
    ax.plot(u, (u**2 - 1) / 2, (u**2 + 1) / 2, color="tab:red", lw=2, label="horosphere: points (2.51)")
    # the hyperplane X . e = -1, i.e. e- - e+ = 1, which cuts the cone in the horosphere
    gx, gp = np.meshgrid(np.linspace(-2.2, 2.2, 2), np.linspace(-0.5, 1.6, 2))
    ax.plot_surface(gx, gp, gp + 1, color="tab:red", alpha=0.08)
    ax.plot([], [], color="tab:red", alpha=0.2, lw=6, label="hyperplane $X\\cdot e=-1$")
    ax.plot([-2.5, 2.5], [0, 0], [0, 0], color="tab:blue", lw=1.5, label="$\\mathbb{R}$: the $e_1$ axis")
    for x in xs:
        a, b = _stereo(x)
        X = np.array([x, (x**2 - 1) / 2, (x**2 + 1) / 2])
        ax.plot([0, X[0]], [0, X[1]], [0, X[2]], color="tab:green", lw=0.9, ls="--")
        ax.scatter([x], [0], [0], color="tab:blue", s=18)
        ax.scatter([a], [b], [1], color="black", s=18)
        ax.scatter(*X, color="tab:red", s=22)
    ax.scatter([0], [-0.5], [0.5], color="tab:red", marker="*", s=120, label="$e_0$ (x = 0)")
    ax.plot([0, 0], [0, 1.3], [0, 1.3], color="tab:purple", lw=2, label="direction of $e = e_- + e_+$")
    ax.set_xlabel("$e_1$")
    ax.set_ylabel("$e_+$")
    ax.set_zlabel("$e_-$")
    ax.set_xlim(-2.5, 2.5)
    ax.set_ylim(-2.5, 2.5)
    ax.set_zlim(0, h)
    ax.view_init(elev=14, azim=-62)
    ax.legend(loc="upper left", fontsize=9)
    ax.set_title("Fig. 2.6: null cone, lifted circle and horosphere")
    fig.tight_layout()
    return fig


def fig_minkowski_plane():
    """Figure 2.5: basis vectors and null lines of the Minkowski plane R^{1,1} (2.52-2.55)."""
    fig, ax = plt.subplots(figsize=(6, 6), dpi=DPI)
    ax.add_patch(Polygon([(0, 0), (1, 0), (1, 1), (0, 1)], color="tab:blue", alpha=0.2))
    _circulation(ax, np.array([0.72, 0.28]), 0.15, True, "tab:blue")
    ax.text(0.72, 0.28, "$E$", ha="center", va="center", fontsize=15)
    s = np.linspace(-1.8, 1.8, 2)
    ax.plot(s, s, "k--", lw=1)
    ax.plot(s, -s, "k--", lw=1)
    t = np.linspace(-1.3, 1.3, 200)
    for sgn in (1, -1):
        ax.plot(sgn * np.cosh(t), np.sinh(t), color="grey", lw=0.8, ls=":")
        ax.plot(np.sinh(t), sgn * np.cosh(t), color="grey", lw=0.8, ls=":")
    for vec, name, color in (
        ((1, 0), "$e_+$", "tab:red"),
        ((0, 1), "$e_-$", "tab:red"),
        ((1, 1), "$e = e_- + e_+$", "tab:purple"),
        ((-0.5, 0.5), "$e_0 = (e_- - e_+)/2$", "tab:green"),
    ):
        _arrow(ax, (0, 0), vec, color, lw=2)
        offset = (-150, 6) if vec[0] < 0 else (6, 4)
        ax.annotate(name, vec, textcoords="offset points", xytext=offset, fontsize=12, color=color)
    ax.text(1.0, 1.35, "null line $x^2=0$", rotation=45, fontsize=10)
    ax.text(-1.45, 1.2, "null line $x^2=0$", rotation=-45, fontsize=10)
    ax.text(1.45, 0.2, "$x^2=+1$", fontsize=9, color="grey")
    ax.text(0.1, -1.6, "$x^2=-1$", fontsize=9, color="grey")
    ax.set_xlim(-1.8, 1.8)
    ax.set_ylim(-1.8, 1.8)
    ax.set_aspect("equal")
    ax.axhline(0, color="grey", lw=0.6)
    ax.axvline(0, color="grey", lw=0.6)
    ax.set_xlabel("$e_+$ coefficient")
    ax.set_ylabel("$e_-$ coefficient")
    ax.set_title("Fig. 2.5: the Minkowski plane $\\mathbb{R}^{1,1}$")
    fig.tight_layout()
    return fig


# --------------------------------------------------------- 3D entities
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
    read = {name: _read_entity(X, func, name) for name, X in given.items() if X is not None}
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


_READERS = {
    "point_pair": ("point pair", cga.point_pair_endpoints),
    "sphere": ("sphere", cga.sphere_center_radius),
    "plane": ("plane", cga.plane_normal_distance),
    "line": ("line", lambda X: (cga.line_closest_point(X), cga.line_direction(X))),
    "circle": ("circle", cga.circle_center_radius),
}


def _read_entity(X, func: str, name: str) -> tuple:
    """The Euclidean parameters of the entity given as ``name`` (of its kind), checked drawable."""
    kind, read = _READERS[name]
    X = entity(X, func, name, (kind,))
    with relabel(func, name):
        out = read(X)
    values = np.concatenate([np.ravel(v) for v in out])
    if not np.all(np.isfinite(values)) or np.abs(values).max() > LIMIT:
        raise fail(func, name, f"its {kind}'s parameters cannot be drawn (not finite or beyond +-{LIMIT:g})")
    return out


# ----------------------------------------------------- section 2.3.4
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


def _planes(planes, func: str) -> list:
    """Two ``(normal, distance, label)`` triples, each normal with a part in the (e1, e2) plane."""
    if not isinstance(planes, (list, tuple, np.ndarray)) or len(planes) != 2:
        raise fail(func, "planes", f"expected two (normal, distance, label) triples, got {type(planes).__name__}")
    out = []
    for k, plane in enumerate(planes):
        if not isinstance(plane, (list, tuple, np.ndarray)) or len(plane) != 3:
            raise fail(func, f"planes[{k}]", "expected a triple (normal, distance, label)")
        n = vector(plane[0], func, f"planes[{k}] normal", (2, 3))
        if not np.hypot(n[0], n[1]) > 1e-12 * max(1.0, np.abs(n).max()):
            raise fail(func, f"planes[{k}] normal", "has no part in the (e1, e2) plane: its trace is not a line")
        distance = coord(plane[1], func, f"planes[{k}] distance")
        out.append((n, distance, optional_text(plane[2], func, f"planes[{k}] label")))
    return out


def _plane_trace(ax, normal, distance, span, color, label):
    """The trace of the plane n . x = delta in the (e1, e2) view: a line."""
    n = np.asarray(normal, dtype=float)[:2]
    n = n / np.linalg.norm(n)
    p0 = distance * n
    d = np.array([-n[1], n[0]])
    seg = p0 + np.linspace(-span, span, 2)[:, None] * d
    ax.plot(seg[:, 0], seg[:, 1], color=color, lw=2, label=label)
    _arrow(ax, p0, p0 + 0.5 * n, color, lw=1.5)


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
    planes, title = _planes(planes, func), optional_text(title, func, "title")
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


# ----------------------------------------------------- section 2.4.5
def point_pair_accuracy(separations, distance, rng, trials=20):
    """The experiment behind the accuracy figure of (2.131).

    For each separation, ``trials`` random pairs centred at ``distance`` from
    the origin (random directions) are built with ``cga.point_pair`` and read
    back twice with ``cga.point_pair_endpoints``: once with the guard switched
    off (``min_separation=0``) to measure the error of the formula, once with
    the default guard to see which pairs it refuses.

    Returns
    -------
    worst : array, the largest endpoint error over the trials, guard off (NaN if all raised)
    failed : array of int, how many trials raised a ``GeometryError`` with the guard off
    refused : array of int, how many trials the default guard refused
    """
    func = "point_pair_accuracy"
    separations = coords(separations, func, "separations", (None,), at_least=1, limit=1e6)
    if np.any(separations <= 0):
        raise fail(func, "separations", "must all be > 0 (two distinct points)")
    distance = coord(distance, func, "distance", low=0.0, limit=1e6)
    rng, trials = generator(rng, func), integer(trials, func, "trials", low=1, high=10**5)
    worst, failed, refused = [], [], []
    for s in separations:
        errs, bad, ref = [], 0, 0
        for _ in range(trials):
            m, d = rng.normal(size=3), rng.normal(size=3)
            m, d = distance * m / np.linalg.norm(m), d / np.linalg.norm(d)
            a, b = m - d * s / 2, m + d * s / 2
            PP = cga.point_pair(a, b)
            try:
                p1, p2 = cga.point_pair_endpoints(PP, min_separation=0.0)
                errs.append(max(np.linalg.norm(p1 - a), np.linalg.norm(p2 - b)))
            except GeometryError:
                bad += 1
            try:
                cga.point_pair_endpoints(PP)
            except GeometryError:
                ref += 1
        worst.append(max(errs) if errs else np.nan)
        failed.append(bad)
        refused.append(ref)
    return np.array(worst), np.array(failed), np.array(refused)


def _accuracy_curves(separations, curves, func: str):
    """The separations (> 0) and ``{label: (worst, failed, refused)}`` of :func:`point_pair_accuracy`, checked."""
    seps = coords(separations, func, "separations", (None,), at_least=1)
    if np.any(seps <= 0):
        raise fail(func, "separations", "must all be > 0 (a log scale)")
    if not isinstance(curves, dict) or not curves:
        raise fail(func, "curves", "expected a non-empty dict label -> (worst, failed, refused)")
    out = {}
    for name, curve in curves.items():
        where = f"curves[{name!r}]"
        if not isinstance(name, str) or not isinstance(curve, (list, tuple)) or len(curve) != 3:
            raise fail(func, where, "expected a label (str) -> (worst, failed, refused) of point_pair_accuracy")
        worst = floats(curve[0], func, f"{where} worst", (None,), finite=False)  # NaN: every trial raised
        same_length(func, separations=seps, **{f"{where} worst": worst})
        if np.any(worst < 0) or np.any(worst == np.inf):
            raise fail(func, f"{where} worst", "errors must be >= 0 (or NaN where every trial raised)")
        counts = [floats(c, func, f"{where} {k}", seps.shape) for k, c in zip(("failed", "refused"), curve[1:])]
        if any(np.any(c < 0) for c in counts):
            raise fail(func, where, "failed and refused are counts (>= 0)")
        out[name] = (worst, *counts)
    return seps, out


def fig_point_pair_accuracy(separations, curves):
    """Log-log error of (2.131) against the separation of the two points.

    ``curves`` maps a label to ``(worst, failed, refused)`` from
    :func:`point_pair_accuracy`.  Crosses at the top mark separations where
    some trials raised even with the guard off; the dashed vertical line of
    each curve is the largest separation that the default guard refused.
    """
    seps, curves = _accuracy_curves(separations, curves, "fig_point_pair_accuracy")
    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=DPI)
    ax.loglog(seps, seps, "k:", lw=1, label="error = separation")
    colors = plt.cm.viridis(np.linspace(0, 0.85, len(curves)))
    for k, ((label, (worst, failed, refused)), color) in enumerate(zip(curves.items(), colors)):
        ok = np.isfinite(worst)
        ax.loglog(seps[ok], worst[ok], "o-", color=color, ms=4, label=label)
        bad = failed > 0
        ax.plot(seps[bad], np.full(bad.sum(), 3.0 * 0.2**k), "x", color=color, ms=7)
        if np.any(refused > 0):
            ax.axvline(seps[refused > 0].max(), color=color, ls="--", lw=1.2)
    ax.plot([], [], "kx", label="some trials raised (guard off)")
    ax.plot([], [], "k--", lw=1.2, label="default guard refuses from here leftwards")
    ax.set_xlabel("separation $|a-b|$")
    ax.set_ylabel("worst endpoint error")
    ax.set_ylim(1e-17, 10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="lower left", fontsize=9)
    ax.set_title("Accuracy of the point-pair extraction (2.131)")
    fig.tight_layout()
    return fig
