"""Figures for notebook 11 (the thesis's future work, chapter 6): Monte Carlo localization in a line map.

:func:`mcl_figure` draws rows of snapshots of a particle filter
(:class:`~cga_lessons.relocalization.mcl.MonteCarloLocalizer`) over the map: the particles (darker where they
weigh more), the log's pose and the filter's estimate with its covariance ellipse; a snapshot may zoom on the
estimate, where the ellipse is centimetres wide.  :func:`error_trace_figure` plots the estimate's error per
scan, with the scans where the filter said "converged" and where the robot was kidnapped.

The arms of section 6.2.2 are drawn by :mod:`cga_lessons.viz.future_work_arms` and the detected entities by
:mod:`cga_lessons.viz.future_work_stereo`.  Every public function checks its input and raises
:class:`~cga_lessons.algebra.InvalidInputError` (a ``ValueError``) naming itself and the argument.
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons.checks import array, fail, integer, magnitude, real, text
from cga_lessons.relocalization import MCLEstimate

from .inputs import LIMIT, WHY, axes, colormap, coord, coords, optional_text, texts, vector
from .inputs import color as a_color
from .inputs import figsize as fig_size
from .laser import draw_walls

__all__ = ["metric_box", "Snapshot", "covariance_ellipse", "draw_particles", "draw_pose", "mcl_figure",
           "error_trace_figure"]  # fmt: skip

TRUTH_COLOR, ESTIMATE_COLOR, PARTICLE_CMAP = "k", "tab:red", "Blues"
TOLERANCE = (0.10, float(np.radians(2.0)))  #: located: within 10 cm and 2 degrees (chapter 5's tolerance)


def metric_box(ax, pts, pad: float = 0.0):
    """Fit a 3D axes to points ``(N, 3)`` (plus ``pad`` metres) with one metre the same length on every axis.

    A box thinner than a millimetre along an axis is widened to one (matplotlib needs a box of some size).
    """
    ax = axes(ax, "metric_box", three_d=True, optional=False)
    pts = coords(pts, "metric_box", "pts", (None, 3), at_least=1)
    pad = coord(pad, "metric_box", "pad", low=0.0)
    _metric_box(ax, pts, pad)


def _metric_box(ax, pts: np.ndarray, pad: float) -> None:
    lo, hi = pts.min(axis=0) - pad, pts.max(axis=0) + pad
    thin = hi - lo < 1e-3
    lo, hi = np.where(thin, (lo + hi) / 2 - 5e-4, lo), np.where(thin, (lo + hi) / 2 + 5e-4, hi)
    for setter, k in ((ax.set_xlim, 0), (ax.set_ylim, 1), (ax.set_zlim, 2)):
        setter(lo[k], hi[k])
    ax.set_box_aspect(hi - lo)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(plt.MaxNLocator(4))


def _covariance(cov, func: str, name: str = "cov") -> np.ndarray:
    """A (2, 2) or a pose's (3, 3) covariance: its x-y block, symmetric positive semi-definite, drawable."""
    c = array(cov, func, name, (None, None))
    if c.shape not in ((2, 2), (3, 3)):
        raise fail(func, name, f"expected a (2, 2) or (3, 3) array, got {c.shape}")
    c = c[:2, :2]
    magnitude(c, func, name, limit=LIMIT, why=WHY)
    if not np.allclose(c, c.T, atol=1e-12 * max(1.0, np.abs(c).max())) or np.linalg.eigvalsh(c).min() < -1e-12:
        raise fail(func, name, "not symmetric positive semi-definite")
    return c


def covariance_ellipse(mean, cov, n_sigma: float = 3.0, n: int = 72) -> np.ndarray:
    """Points (n, 2) of the ellipse ``(x - mean)^T C^-1 (x - mean) = n_sigma^2`` of the x-y block C of ``cov``.

    ``mean`` holds at least x and y (a pose (3,) is fine); ``cov`` is (2, 2) or a pose covariance (3, 3).

    >>> e = covariance_ellipse([1.0, 2.0], [[4.0, 0.0], [0.0, 1.0]], n_sigma=1.0, n=4)
    >>> e.round(12) + 0.0  # the half-axes: 1 along y, 2 along x
    array([[ 1.,  3.],
           [ 3.,  2.],
           [ 1.,  1.],
           [-1.,  2.]])
    """
    func = "covariance_ellipse"
    m = vector(mean, func, "mean", (2, 3))[:2]
    c = _covariance(cov, func)
    n_sigma = real(n_sigma, func, "n_sigma", low=0.0, strict_low=True, high=1e3)
    n = integer(n, func, "n", low=3, high=100_000)
    return _ellipse(m, c, n_sigma, n)


def _ellipse(m: np.ndarray, c: np.ndarray, n_sigma: float, n: int) -> np.ndarray:
    vals, vecs = np.linalg.eigh(c)
    t = np.linspace(0.0, 2 * np.pi, int(n), endpoint=False)
    circle = np.column_stack([np.cos(t), np.sin(t)]) * np.sqrt(np.maximum(vals, 0.0))
    return m + n_sigma * circle @ vecs.T


def draw_particles(ax, particles, log_w=None, *, s: float = 2.0, cmap: str = PARTICLE_CMAP):
    """Scatter the particles' positions (N, 3) on ``ax``, darker where they weigh more (``log_w`` (N,)).

    Returns the PathCollection; its offsets are the particles' x, y (the heaviest drawn last, on top).
    """
    func = "draw_particles"
    ax = axes(ax, func, optional=False)
    p = coords(particles, func, "particles", (None, 3), at_least=1)
    lw = None if log_w is None else _log_weights(log_w, func, len(p))
    s, cmap = real(s, func, "s", low=0.0, strict_low=True, high=1e4), colormap(cmap, func)
    return _draw_particles(ax, p, lw, s, cmap)


def _log_weights(log_w, func: str, n: int, name: str = "log_w") -> np.ndarray:
    """``n`` log-weights: not NaN, not +inf, at least one finite (-inf: a particle of weight zero)."""
    lw = array(log_w, func, name, (None,), finite=False)
    if lw.shape != (n,) or np.any(np.isnan(lw)) or np.any(lw == np.inf) or not np.any(np.isfinite(lw)):
        raise fail(func, name, f"expected {n} numbers (not NaN or +inf, one at least finite), got {lw.shape}")
    return lw


def _draw_particles(ax, p: np.ndarray, lw, s: float, cmap: str):
    order = np.arange(len(p))
    if lw is None:
        shade = np.full(len(p), 0.75)
    else:
        w = np.exp(lw - lw.max())
        shade = 0.15 + 0.85 * w
        order = np.argsort(w, kind="stable")  # the heavy ones on top
    return ax.scatter(p[order, 0], p[order, 1], s=s, c=shade[order], cmap=cmap, vmin=0.0, vmax=1.0, lw=0, zorder=3)


def draw_pose(ax, pose, color=TRUTH_COLOR, length: float = 0.6, label=None, **kw):
    """An arrow from the pose's position along its heading (a pose is x, y, theta), ``length`` long."""
    func = "draw_pose"
    ax, (x, y, th) = axes(ax, func, optional=False), vector(pose, func, "pose", (3,))
    color, length = a_color(color, func), coord(length, func, "length", low=0.0, strict_low=True)
    label = optional_text(label, func)
    return ax.annotate("", xy=(x + length * np.cos(th), y + length * np.sin(th)), xytext=(x, y), zorder=6,
                       arrowprops=dict(arrowstyle="-|>", color=color, lw=kw.pop("lw", 1.8), shrinkA=0, shrinkB=0),
                       label=label, **kw)  # fmt: skip


@dataclass(frozen=True)
class Snapshot:
    """One panel of :func:`mcl_figure`: the particles (N, 3) and their log-weights after an update.

    ``estimate`` is the filter's :class:`~cga_lessons.relocalization.mcl.MCLEstimate` (or None: not drawn),
    ``truth`` the log's pose (or None), ``zoom`` the half-width (m) of a window around the estimate (None: the
    whole map).
    """

    title: str
    particles: np.ndarray
    log_w: np.ndarray | None = None
    estimate: object = None
    truth: np.ndarray | None = None
    zoom: float | None = None

    def __post_init__(self):
        func, put = "Snapshot", lambda name, value: object.__setattr__(self, name, value)
        put("title", text(self.title, func, "title", empty=True))
        put("particles", coords(self.particles, func, "particles", (None, 3), at_least=1))
        put("log_w", None if self.log_w is None else _log_weights(self.log_w, func, len(self.particles)))
        if self.estimate is not None and not isinstance(self.estimate, MCLEstimate):
            raise fail(func, "estimate", f"expected an MCLEstimate or None, got {type(self.estimate).__name__}")
        put("truth", None if self.truth is None else vector(self.truth, func, "truth", (3,)))
        if self.zoom is not None:
            put("zoom", coord(self.zoom, func, "zoom", low=0.0, strict_low=True))
            if self.estimate is None and self.truth is None:
                raise fail(func, "zoom", "a zoom needs a centre: give an estimate or a truth")


def _panel(ax, segments, snap: Snapshot, n_sigma):
    draw_walls(segments, ax=ax, color="0.35", lw=1.2, alpha=0.9)
    draw_particles(ax, snap.particles, snap.log_w, s=1.5 if snap.zoom is None else 8.0)
    length = 1.6 if snap.zoom is None else snap.zoom / 2.5
    e = snap.estimate
    if e is not None:
        draw_pose(ax, e.pose, ESTIMATE_COLOR, length, lw=2.2)
        ring = covariance_ellipse(e.pose, e.covariance, n_sigma)
        ax.plot(*np.vstack([ring, ring[:1]]).T, color=ESTIMATE_COLOR, lw=1.2, zorder=5)
        if snap.zoom is None:  # a ring to find a cloud a few centimetres wide on a map tens of metres wide
            ax.plot(*e.pose[:2], "o", ms=16, mfc="none", mec=ESTIMATE_COLOR, mew=1.5, zorder=5)
    if snap.truth is not None:
        draw_pose(ax, snap.truth, TRUTH_COLOR, length, lw=1.2)
        ax.plot(*snap.truth[:2], "x", color=TRUTH_COLOR, ms=5 if snap.zoom is None else 8, zorder=7)
    if snap.zoom is not None:
        centre = (e.pose if e is not None else snap.truth)[:2]
        ax.set_xlim(centre[0] - snap.zoom, centre[0] + snap.zoom)
        ax.set_ylim(centre[1] - snap.zoom, centre[1] + snap.zoom)
    ax.set_aspect("equal")
    ax.set_title(snap.title, fontsize=9)
    ax.tick_params(labelsize=7)


def mcl_figure(map_segments, rows, row_titles=None, n_sigma: float = 3.0, panel: float = 3.4):
    """Rows of :class:`Snapshot` panels over the map segments (M, 2, 2): particles, log pose, estimate, ellipse.

    Black arrow: the log's pose; red arrow and ellipse: the filter's estimate and its ``n_sigma`` covariance
    ellipse (x-y block of :attr:`MCLEstimate.covariance`).  Returns the figure; its axes are row by row.
    """
    func = "mcl_figure"
    segs = map_segments.segments if hasattr(map_segments, "segments") else map_segments
    segs = coords(segs, func, "map_segments", (None, 2, 2), at_least=1)
    if not isinstance(rows, (list, tuple)) or not rows or not all(isinstance(r, (list, tuple)) and r for r in rows):
        raise fail(func, "rows", "expected a non-empty list of non-empty lists of Snapshot")
    if not all(isinstance(s, Snapshot) for r in rows for s in r):
        raise fail(func, "rows", "expected a non-empty list of non-empty lists of Snapshot")
    if row_titles is not None:
        row_titles = texts(row_titles, func, "row_titles", len(rows))
    n_sigma = real(n_sigma, func, "n_sigma", low=0.0, strict_low=True, high=1e3)
    panel = real(panel, func, "panel", low=0.5, high=20.0)
    ncols = max(len(r) for r in rows)
    fig, axes = plt.subplots(len(rows), ncols, figsize=(panel * ncols, panel * len(rows) + 0.3), squeeze=False)
    for i, row in enumerate(rows):
        for j in range(ncols):
            if j < len(row):
                _panel(axes[i, j], segs, row[j], n_sigma)
            else:
                axes[i, j].set_axis_off()
        if row_titles is not None:
            axes[i, 0].set_ylabel(row_titles[i], fontsize=10)
    handles = [
        plt.Line2D([], [], color=TRUTH_COLOR, lw=2, label="the log's pose"),
        plt.Line2D([], [], color=ESTIMATE_COLOR, lw=2, label=f"estimate, {n_sigma:g}-sigma ellipse"),
        plt.Line2D([], [], color="tab:blue", marker=".", lw=0, label="particles (darker: heavier)"),
    ]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=9, frameon=False)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return fig


def _events(events, func: str) -> list:
    """``(update index, label)`` pairs."""
    if not isinstance(events, (list, tuple)):
        raise fail(func, "events", f"expected a list of (update index, label), got {type(events).__name__}")
    out = []
    for k, e in enumerate(events):
        if not isinstance(e, (list, tuple)) or len(e) != 2:
            raise fail(func, f"events[{k}]", f"expected (update index, label), got {e!r}")
        at, label = integer(e[0], func, f"events[{k}]", low=0, high=10**9), text(e[1], func, f"events[{k}]", empty=True)
        out.append((at, label))
    return out


def error_trace_figure(position_error, heading_error, converged, events=(), tolerance=TOLERANCE,
                       figsize=(9.0, 3.6)):  # fmt: skip
    """Position and heading error of the estimate per update (log scale), converged updates filled.

    ``events`` is a sequence of ``(update index, label)`` drawn as vertical lines (a kidnapping);
    ``tolerance`` (m, rad) is drawn dashed.  Returns the figure.
    """
    func = "error_trace_figure"
    pe = coords(position_error, func, "position_error", (None,), at_least=1)
    he = coords(heading_error, func, "heading_error", (None,), at_least=1)
    conv = np.asarray(converged) if isinstance(converged, (list, tuple, np.ndarray)) else None
    if len(he) != len(pe) or conv is None or conv.shape != pe.shape or conv.dtype != bool:
        raise fail(func, "heading_error, converged", f"heading_error and converged (bools) must match "
                   f"position_error's {pe.shape}")  # fmt: skip
    events = _events(events, func)
    tolerance = magnitude(array(tolerance, func, "tolerance", (2,)), func, "tolerance", limit=LIMIT, why=WHY)
    if not np.all(tolerance > 0):
        raise fail(func, "tolerance", f"expected (metres, radians) > 0, got {tolerance.tolist()}")
    figsize = fig_size(figsize, func)
    fig, axes = plt.subplots(1, 2, figsize=figsize)
    k = np.arange(1, len(pe) + 1)
    for ax, err, tol, unit, scale in ((axes[0], pe, tolerance[0], "m", 1.0),
                                      (axes[1], np.abs(he), tolerance[1], "deg", 180 / np.pi)):  # fmt: skip
        y = np.maximum(err * scale, 1e-4 * scale)
        ax.semilogy(k, y, color="0.4", lw=1)
        ax.scatter(k[conv], y[conv], s=22, color=ESTIMATE_COLOR, zorder=3, label="converged")
        ax.scatter(k[~conv], y[~conv], s=22, facecolor="none", edgecolor="0.3", zorder=3, label="not converged")
        ax.axhline(tol * scale, ls="--", color="tab:green", lw=1, label="tolerance")
        for at, label in events:
            ax.axvline(at + 0.5, color="tab:purple", lw=1.2)
            ax.text(
                at + 0.3,
                0.97,
                label + " ",
                color="tab:purple",
                fontsize=8,
                va="top",
                ha="right",
                transform=ax.get_xaxis_transform(),
            )
        ax.set_xlabel("update (scan)")
        ax.set_ylabel(f"error of the estimate ({unit})")
    axes[0].set_title("position", fontsize=10)
    axes[1].set_title("heading", fontsize=10)
    axes[0].legend(fontsize=8, loc="center right")
    fig.tight_layout()
    return fig
