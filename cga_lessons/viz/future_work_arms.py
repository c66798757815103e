"""Figures for notebook 11, section 6.2.2: arms as chains of motors drawn in 3D (matplotlib).

An arm is drawn as a skeleton: a polyline through points fixed to its links.  A point fixed to the link after
joint k sits at ``p`` at home (q = 0); at the configuration q it is ``M_1(q_1) ... M_k(q_k) p`` (2.103), the
forward kinematics of the chain cut after joint k (:func:`cga_lessons.kinematics.forward_matrix`).  So the
picture is the motors' own output, nothing recomputed with matrices.  :func:`dh_home_points` gives the points
of a Denavit-Hartenberg arm (the origins of its link frames, walked once with rotors and translators);
without them, :func:`chain_points` uses a point of each joint's axis line and the tool.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import kinematics as kin
from cga_lessons.checks import array, fail, flag, instance, integer, magnitude, real, same_length
from cga_lessons.checks import batch as one_or_many
from cga_lessons.kinematics import DHParameters

from .future_work import metric_box
from .inputs import axes, colormap, coord, coords, optional_text
from .inputs import color as a_color
from .inputs import figsize as fig_size

__all__ = ["dh_home_points", "chain_points", "axis_segments", "draw_arm", "draw_frame", "arm_figure", "ik_figure"]

_X, _Z = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])


def dh_home_points(p: DHParameters):
    """The origins of a DH arm's link frames at home, and after how many joints each one is fixed.

    The frames are walked with motors as :func:`cga_lessons.kinematics.arms.dh_chain` walks them (standard:
    ``Rz Tz Tx Rx`` per link, frame i fixed to link i; modified: ``Rx Tx Rz Tz``, then the flange).

    Returns
    -------
    points : ndarray (K, 3)
        Base origin first, the flange last.
    attached : ndarray (K,) of int
        Point j moves with joints 1..attached[j].
    """
    instance(p, "dh_home_points", "p", DHParameters, "DHParameters")
    F = cga.G41.scalar(1.0)
    pts, attached = [np.zeros(3)], [0]
    for i, (d, a, alpha) in enumerate(zip(p.d, p.a, p.alpha)):
        if p.convention == "standard":
            F = F * cga.translator(d * _Z) * cga.translator(a * _X) * cga.rotor(_X, alpha)
            pts.append(cga.motor_to_matrix(F)[:3, 3])
        else:  # the joint's own frame (on its axis), then the offset along it
            F = F * cga.rotor(_X, alpha) * cga.translator(a * _X)
            pts.append(cga.motor_to_matrix(F)[:3, 3])
            F = F * cga.translator(d * _Z)
            pts.append(cga.motor_to_matrix(F)[:3, 3])
            attached.append(i + 1)
        attached.append(i + 1)
    if p.flange:
        F = F * cga.translator(float(p.flange) * _Z)
        pts.append(cga.motor_to_matrix(F)[:3, 3])
        attached.append(len(p.d))
    return np.array(pts), np.array(attached)


def _check_chain(ch, func):
    instance(ch, func, "chain", kin.Chain, "a kinematics.Chain")


def _configurations(q, func: str, name: str, n: int, *, batch: bool = True) -> np.ndarray:
    """Joint values ``(n,)``, or ``(N, n)`` when ``batch``: finite, within +-1e6 (radians or metres)."""
    if batch:
        a, single = one_or_many(q, func, name, (n,))
        a = a[0] if single else a
    else:
        a = array(q, func, name, (n,))
    return magnitude(a, func, name, limit=1e6, why="joint values are radians or metres of an arm on a table")


def _default_points(ch):
    pts = [np.array(j.point) for j in ch.joints] + [cga.motor_to_matrix(ch.home)[:3, 3]]
    return np.array(pts), np.array(list(range(ch.n)) + [ch.n])


def chain_points(ch, q, points=None, attached=None) -> np.ndarray:
    """Where the link points are at the configurations q: (K, 3) for q of shape (n,), (N, K, 3) for (N, n).

    ``points`` (K, 3) are home positions, ``attached`` (K,) how many joints move each (0: the base).  Default:
    each joint's axis point (:attr:`Joint.point`, moved by the joints before it) and the tool (the home
    motor's position, moved by all of them).
    """
    func = "chain_points"
    _check_chain(ch, func)
    qa = _configurations(q, func, "q", ch.n)
    pts, att = _link_points(ch, points, attached, func)
    return _chain_points(ch, qa, pts, att)


def _link_points(ch, points, attached, func: str) -> tuple[np.ndarray, np.ndarray]:
    """The home points (K, 3) and how many joints move each (K,), checked; the default ones for ``points=None``."""
    if points is None:
        if attached is not None:
            raise fail(func, "attached", "given without points: attached says which joints move each point")
        return _default_points(ch)
    pts = coords(points, func, "points", (None, 3), at_least=1)
    att = np.zeros(len(pts), int) if attached is None else array(attached, func, "attached", (len(pts),))
    if np.any(att != np.round(att)) or att.min() < 0 or att.max() > ch.n:
        raise fail(func, "attached", f"expected {len(pts)} integers in 0..{ch.n}")
    return pts, att.astype(int)


def _chain_points(ch, qa: np.ndarray, pts: np.ndarray, att: np.ndarray) -> np.ndarray:
    q2 = qa.reshape(-1, ch.n)
    out = np.broadcast_to(pts, (len(q2), len(pts), 3)).copy()
    for k in np.unique(att[att > 0]):
        H = kin.forward_matrix(kin.chain(ch.joints[:k]), q2[:, :k])  # M_1 ... M_k, the chain cut after joint k
        sel = att == k
        out[:, sel] = np.einsum("nij,kj->nki", H[:, :3, :3], pts[sel]) + H[:, None, :3, 3]
    return out[0] if qa.ndim == 1 else out


def draw_arm(ax, pts, color="tab:blue", lw: float = 3.0, alpha: float = 1.0, label=None):
    """The skeleton (K, 3) on a 3D axes: links as a thick polyline, joints as dots.  Returns the Line3D."""
    func = "draw_arm"
    ax, p = axes(ax, func, three_d=True, optional=False), coords(pts, func, "pts", (None, 3), at_least=2)
    color, label = a_color(color, func), optional_text(label, func)
    lw, alpha = real(lw, func, "lw", low=0.0, high=100.0), real(alpha, func, "alpha", low=0.0, high=1.0)
    return _draw_arm(ax, p, color, lw, alpha, label)


def _draw_arm(ax, p, color, lw, alpha, label):
    (line,) = ax.plot(*p.T, "-", color=color, lw=lw, alpha=alpha, solid_capstyle="round", label=label)
    ax.scatter(*p[:-1].T, s=14, color="k", alpha=alpha, depthshade=False)
    ax.scatter(*p[-1], s=30, marker="s", color=color, alpha=alpha, depthshade=False)
    return line


def draw_frame(ax, H, length: float = 0.1, lw: float = 2.0):
    """A 4x4 pose as three arrows x (red), y (green), z (blue) from its origin, ``length`` long."""
    func = "draw_frame"
    ax, H = axes(ax, func, three_d=True, optional=False), coords(H, func, "H", (4, 4))
    length = coord(length, func, "length", low=0.0, strict_low=True)
    lw = real(lw, func, "lw", low=0.0, high=100.0)
    _draw_frame(ax, H, length, lw)


def _draw_frame(ax, H, length, lw):
    for k, col in enumerate(("tab:red", "tab:green", "tab:blue")):
        ax.quiver(*H[:3, 3], *(length * H[:3, k]), color=col, lw=lw, arrow_length_ratio=0.25)


def axis_segments(ch, q, pts, half: float = 0.12) -> np.ndarray:
    """The joints' axis lines at the configuration q (n,), as segments (n, 2, 3) of half-length ``half``.

    Each axis is a column ``(omega, v)`` of the spatial Jacobian (the home axis moved by the joints before it,
    2.103); its direction is omega and its point nearest the origin ``omega x v``.  A segment is centred on the
    point of the skeleton ``pts`` (K, 3) nearest its line.
    """
    func = "axis_segments"
    _check_chain(ch, func)
    q = _configurations(q, func, "q", ch.n, batch=False)
    P = coords(pts, func, "pts", (None, 3), at_least=1)
    half = coord(half, func, "half", low=0.0, strict_low=True)
    return _axis_segments(ch, q, P, half)


def _axis_segments(ch, q, P, half):
    J = kin.spatial_jacobian(ch, q)
    out = []
    for w, v in zip(J[:3].T, J[3:].T):
        if np.linalg.norm(w) < 0.5:  # a slide: its direction is v, drawn through the skeleton's first point
            d, c = v / np.linalg.norm(v), P[0]
        else:
            d, p0 = w, np.cross(w, v)
            t = (P - p0) @ d
            near = np.argmin(np.linalg.norm(P - p0 - t[:, None] * d, axis=1))
            c = p0 + t[near] * d
        out.append([c - half * d, c + half * d])
    return np.array(out)


def arm_figure(ch, qs, points=None, attached=None, n_drawn: int = 6, title=None, elev=24.0, azim=-60.0,
               cmap="viridis", axes: bool = True, figsize=(7.0, 5.5)):  # fmt: skip
    """An arm moving along the configurations ``qs`` (N, n): ``n_drawn`` of them drawn, the tool's whole path.

    Colours run from the first configuration to the last (``cmap``); with ``axes``, the joints' axis lines at
    the first configuration are drawn dashed (:func:`axis_segments`).  Returns the figure; its axes holds the
    drawn skeletons as its first ``n_drawn`` lines, in order, then the tool path, then the axis lines.
    """
    func = "arm_figure"
    _check_chain(ch, func)
    q = _configurations(qs, func, "qs", ch.n)
    if q.ndim != 2 or len(q) < 2:
        raise fail(func, "qs", f"expected at least 2 configurations (N, {ch.n}), got {q.shape}")
    if isinstance(n_drawn, (bool, np.bool_)) or not isinstance(n_drawn, (int, np.integer)):
        raise fail(func, "n_drawn", f"expected an integer in 1..{len(q)}, got {n_drawn!r}")
    n_drawn = integer(n_drawn, func, "n_drawn", low=1, high=len(q))
    pts, att = _link_points(ch, points, attached, func)
    title, cmap, axes_on = optional_text(title, func, "title"), colormap(cmap, func), flag(axes, func, "axes")
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    figsize = fig_size(figsize, func)
    P = _chain_points(ch, q, pts, att)
    fig = plt.figure(figsize=figsize)
    ax = fig.add_subplot(projection="3d")
    colors = plt.get_cmap(cmap)(np.linspace(0.0, 0.9, n_drawn))
    picks = np.round(np.linspace(0, len(q) - 1, n_drawn)).astype(int)
    for c, i in zip(colors, picks):
        _draw_arm(ax, P[i], c, 3.0, 0.9, None)
    ax.plot(*P[:, -1].T, "--", color="tab:red", lw=1.5, label="tool path")
    boxed = P.reshape(-1, 3)
    if axes_on:
        segs = _axis_segments(ch, q[0], P[0], 0.12)
        for k, seg in enumerate(segs):
            ax.plot(*seg.T, ":", color="k", lw=1.2, label="joint axes (first pose)" if k == 0 else None)
        boxed = np.vstack([boxed, segs.reshape(-1, 3)])
    ax.scatter(0, 0, 0, s=60, marker="^", color="k", label="base")
    metric_box(ax, boxed, pad=0.08)
    ax.view_init(elev=elev, azim=azim)
    ax.legend(loc="upper left", fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig


def ik_figure(ch, q_start, q_end, target, position_errors, rotation_errors, points=None, attached=None,
              elev=24.0, azim=-60.0, figsize=(12.0, 5.0)):  # fmt: skip
    """Inverse kinematics: the arm at the start (grey) and at the solution (blue) with the target frame (4x4),
    and the errors per iteration (m, rad; log scale).  Returns the figure."""
    func = "ik_figure"
    _check_chain(ch, func)
    qa, qb = (_configurations(v, func, k, ch.n, batch=False) for k, v in (("q_start", q_start), ("q_end", q_end)))
    target = coords(target, func, "target", (4, 4))
    pe = coords(position_errors, func, "position_errors", (None,), at_least=1)
    re = coords(rotation_errors, func, "rotation_errors", (None,))
    same_length(func, position_errors=pe, rotation_errors=re)
    if np.any(pe < 0) or np.any(re < 0):
        raise fail(func, "position_errors" if np.any(pe < 0) else "rotation_errors", "errors must be >= 0")
    pts, att = _link_points(ch, points, attached, func)
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    fig = plt.figure(figsize=fig_size(figsize, func))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    a, b = _chain_points(ch, qa, pts, att), _chain_points(ch, qb, pts, att)
    _draw_arm(ax, a, "0.6", 3.0, 1.0, "start")
    _draw_arm(ax, b, "tab:blue", 3.0, 1.0, "solution")
    _draw_frame(ax, target, 0.12, 2.0)
    ax.plot([], [], color="tab:red", label="target frame (x red, y green, z blue)")
    metric_box(ax, np.vstack([a, b, target[None, :3, 3]]), pad=0.08)
    ax.view_init(elev=elev, azim=azim)
    ax.legend(loc="upper left", fontsize=8)
    ax2 = fig.add_subplot(1, 2, 2)
    it = np.arange(len(pe))
    ax2.semilogy(it, np.maximum(pe, 1e-17), "o-", label="position error (m)")
    ax2.semilogy(it, np.maximum(re, 1e-17), "s-", label="rotation error (rad)")
    ax2.set_xlabel("iteration")
    ax2.set_ylabel("error")
    ax2.grid(True, which="major", alpha=0.3)
    ax2.legend(fontsize=9)
    fig.tight_layout()
    return fig
