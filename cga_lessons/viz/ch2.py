"""Figures for the chapter-2 notebooks (sections 2.1-2.4 of the thesis).

Each ``fig_*`` function draws one figure of the course and returns the
matplotlib ``Figure`` (end the notebook cell with ``;`` so that nbval sees no
repr).  The drawing functions that take conformal entities read their
Euclidean parameters back with :mod:`cga_lessons.conformal` (centre, radius,
direction, ...), so a figure that looks right is also a check of the
extraction formulas of section 2.4.

Besides drawing, :func:`product_table` prepares the text of the product table (2.10), and :func:`show`
displays any figure compactly.  The 3D figures (:mod:`cga_lessons.viz.ch2_3d`), the transformations'
(:mod:`cga_lessons.viz.ch2_transformations`) and the accuracy experiment (:mod:`cga_lessons.viz.ch2_accuracy`)
have modules of their own; the notebooks call their figures as ``ch2.<name>``, so ``ch2`` imports those
(and only those) by name.
"""

from __future__ import annotations

import io

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import FancyArrowPatch, Polygon

from cga_lessons.algebra import Algebra
from cga_lessons.checks import instance, integer

from .inputs import DPI, SQUARED, SQUARED_WHY, coords, figure

__all__ = [
    "show",
    "product_table",
    "fig_bivectors",
    "fig_stereographic_1d",
    "fig_null_cone",
    "fig_minkowski_plane",
]


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
    xs = coords(xs, "fig_null_cone", "xs", (None,), at_least=1, limit=SQUARED, why=SQUARED_WHY)
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
