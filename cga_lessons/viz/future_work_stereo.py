"""Figures for notebook 11, section 6.2.2: conformal entities found automatically in stereo point clouds.

:func:`detections_figure` shows a generated cloud twice, side by side: coloured by the entity each point was
sampled from (the ground truth) and by the entity the detector (:func:`cga_lessons.stereo.detect.detect_entities`)
put it on, with the detected spheres, circles and lines drawn from their parameters; a detection matched to a true
entity takes that entity's colour.  :func:`detections_on_image` paints the detections of a real pair over its
left image, and :func:`depth_noise_figure` plots the depth noise of a stereo head against the distance.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Patch

from cga_lessons import stereo as st
from cga_lessons.checks import array, fail, integer, real, relabel
from cga_lessons.conformal import ENTITY_PARAMETERS
from cga_lessons.stereo import label_image

from .future_work import metric_box
from .inputs import coords, optional_text, texts
from .inputs import figsize as fig_size

__all__ = ["PALETTE", "detections_figure", "detections_on_image", "depth_noise", "depth_noise_figure"]

PALETTE = plt.get_cmap("tab20")(np.arange(20))[[0, 2, 4, 6, 8, 10, 12, 16, 18, 1, 3, 5, 7, 9, 11, 13, 17, 19]]
_KINDS = ("plane", "sphere", "circle", "line")
CLUTTER, UNMATCHED = (0.72, 0.72, 0.72, 1.0), (0.0, 0.0, 0.0, 1.0)
_PARAMS = tuple(ENTITY_PARAMETERS.values())


def _typed(e) -> bool:
    """A kind among the four, and parameters of that kind (:data:`cga_lessons.conformal.ENTITY_PARAMETERS`)."""
    kind, params = getattr(e, "kind", None), getattr(e, "params", None)
    return kind in _KINDS and isinstance(params, _PARAMS) and params.kind == kind


def _entities(entities, n_points, func, points: str = "points"):
    """Detections (:class:`~cga_lessons.stereo.DetectedEntity`: a kind, params, inliers into ``n_points``)."""
    if not isinstance(entities, (list, tuple)):
        raise fail(func, "entities", f"expected a list of detected entities, got {type(entities).__name__}")
    ents = list(entities)
    for k, e in enumerate(ents):
        idx = getattr(e, "inliers", None)
        if not _typed(e) or idx is None:
            raise fail(func, f"entities[{k}]", f"expected a DetectedEntity, got {type(e).__name__}")
        idx = np.asarray(idx)
        if idx.ndim != 1 or idx.dtype.kind not in "iu" or (len(idx) and (idx.min() < 0 or idx.max() >= n_points)):
            raise fail(func, f"entities[{k}].inliers", f"expected indices into the {n_points} rows of {points}")
        real(getattr(e, "rms", 0.0), func, f"entities[{k}].rms", low=0.0)
    return ents


def _sphere(ax, c, r, color):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 19), np.linspace(0, np.pi, 10))
    ax.plot_wireframe(c[0] + r * np.cos(u) * np.sin(v), c[1] + r * np.sin(u) * np.sin(v), c[2] + r * np.cos(v),
                      color=color, lw=0.5, alpha=0.6)  # fmt: skip


def _shape(ax, e, color):
    """An entity from its parameters: sphere wireframe, circle, line segment (planes: only their points)."""
    p = e.params
    if e.kind == "sphere":
        _sphere(ax, np.asarray(p.center), float(p.radius), color)
    elif e.kind == "circle":
        ax.plot(*st.circle_polyline(p.center, p.normal, p.radius).T, color=color, lw=2.0)
    elif e.kind == "line" and p.length is not None:
        a, d = np.asarray(p.point), np.asarray(p.direction) * float(p.length) / 2
        ax.plot(*np.array([a - d, a + d]).T, color=color, lw=2.5)


def _count(n: int, kind: str) -> str:
    return f"{n} {kind}" + ("" if n == 1 else "s")


def _matches(matches, ents: list, kinds: list, func: str) -> dict:
    """detection index -> truth index, from :class:`~cga_lessons.stereo.DetectionMatch` records or ``(detection,
    truth, ...)`` pairs, of the same kind."""
    if not isinstance(matches, (list, tuple, np.ndarray)):
        raise fail(func, "matches", f"expected (detection index, truth index, ...) pairs, got {type(matches).__name__}")
    to_truth = {}
    for m in matches:
        if isinstance(m, st.DetectionMatch):
            m = (m.detection, m.truth)
        if not isinstance(m, (list, tuple, np.ndarray)) or len(m) < 2:
            raise fail(func, "matches", f"expected (detection index, truth index, ...) pairs, got {m!r}")
        i, j = integer(m[0], func, "matches"), integer(m[1], func, "matches")
        if not (0 <= i < len(ents) and 0 <= j < len(kinds)) or ents[i].kind != kinds[j]:
            raise fail(func, "matches", f"({i}, {j}) pairs no detection with a true entity of its kind")
        to_truth[i] = j
    return to_truth


def detections_figure(points, labels, truth, entities, matches=(), elev=22.0, azim=-170.0,
                      figsize=(13.0, 6.2)):  # fmt: skip
    """Ground truth (left) and detections (right) of a cloud (N, 3) in 3D.

    ``labels`` (N,) holds each point's true entity (-1: clutter); ``truth`` the true entities (with ``kind``
    and ``params``, as :class:`~cga_lessons.stereo.TruthEntity`); ``entities`` the detections;
    ``matches`` the :class:`~cga_lessons.stereo.DetectionMatch` records of :func:`cga_lessons.stereo.evaluate`,
    or pairs ``(detection index, truth index, ...)``.  In the right panel, the i-th scatter
    holds the points of detection i.  Returns the figure.
    """
    func = "detections_figure"
    X = coords(points, func, "points", (None, 3), at_least=1)
    if not isinstance(truth, (list, tuple)):
        raise fail(func, "truth", f"expected a list of true entities (TruthEntity), got {type(truth).__name__}")
    truth = list(truth)
    if not all(_typed(t) for t in truth):
        raise fail(func, "truth", "expected entities with a kind and params of that kind (TruthEntity)")
    kinds = [t.kind for t in truth]
    lab = array(labels, func, "labels", (len(X),))
    if np.any(lab != np.round(lab)) or lab.min() < -1 or lab.max() >= len(kinds):
        raise fail(func, "labels", f"expected {len(X)} integers in -1..{len(kinds) - 1}")
    lab = lab.astype(int)
    ents = _entities(entities, len(X), func)
    to_truth = _matches(matches, ents, kinds, func)
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    figsize = fig_size(figsize, func)
    fig = plt.figure(figsize=figsize)
    left, right = fig.add_subplot(1, 2, 1, projection="3d"), fig.add_subplot(1, 2, 2, projection="3d")
    left.scatter(*X[lab < 0].T, s=2, color=CLUTTER, depthshade=False)
    for j, t in enumerate(truth):
        left.scatter(*X[lab == j].T, s=3, color=PALETTE[j % len(PALETTE)], depthshade=False)
        _shape(left, t, PALETTE[j % len(PALETTE)])
    free = np.ones(len(X), bool)
    for i, e in enumerate(ents):
        color = PALETTE[to_truth[i] % len(PALETTE)] if i in to_truth else UNMATCHED
        right.scatter(*X[e.inliers].T, s=3, color=color, depthshade=False)
        free[e.inliers] = False
    for i, e in enumerate(ents):
        _shape(right, e, PALETTE[to_truth[i] % len(PALETTE)] if i in to_truth else UNMATCHED)
    right.scatter(*X[free].T, s=2, color=CLUTTER, depthshade=False)
    count = {k: kinds.count(k) for k in dict.fromkeys(kinds)}
    found = {k: sum(e.kind == k for e in ents) for k in dict.fromkeys(kinds + [e.kind for e in ents])}
    left.set_title("ground truth: " + ", ".join(_count(n, k) for k, n in count.items()) + " + clutter (grey)",
                   fontsize=10)  # fmt: skip
    right.set_title("detected: " + ", ".join(_count(n, k) for k, n in found.items())
                    + f" ({len(to_truth)} matched; black: unmatched)", fontsize=10)  # fmt: skip
    for ax in (left, right):
        metric_box(ax, X)
        ax.view_init(elev=elev, azim=azim)
    fig.tight_layout()
    return fig


def detections_on_image(image, pixels, entities, step: int = 1, names=None, title=None, figsize=(7.0, 5.0)):
    """Detections painted over the (greyed) left image: point j of the cloud came from ``pixels[j]`` (col, row).

    Each detection's points fill ``step`` x ``step`` blocks in its colour; the legend gives its kind (or
    ``names[i]``), number of points and RMS distance.  Returns the figure.
    """
    func = "detections_on_image"
    img = array(image, func, "image", (None, None, 3))
    if not img.size or img.min() < 0 or img.max() > 255:
        raise fail(func, "image", f"expected an RGB image (H, W, 3) of values 0..255, got {img.shape}")
    px = coords(pixels, func, "pixels", (None, 2))
    ents = _entities(entities, len(px), func, "pixels")
    if names is not None:
        names = texts(names, func, "names", len(ents))
    step = integer(step, func, "step", low=1, high=1000)
    title, figsize = optional_text(title, func, "title"), fig_size(figsize, func)
    labels = np.full(len(px), -1)
    for i, e in enumerate(ents):
        labels[e.inliers] = i
    with relabel(func, "pixels"):
        painted = label_image(img.shape[:2], px, labels, step)
    grey = img.astype(float).mean(axis=2, keepdims=True) / 255.0
    over = np.repeat(0.3 + 0.7 * grey, 3, axis=2)
    handles = []
    for i, e in enumerate(ents):
        m, col = painted == i, PALETTE[i % len(PALETTE)][:3]
        over[m] = 0.4 * over[m] + 0.6 * col
        name = names[i] if names is not None else e.kind
        handles.append(Patch(color=col, label=f"{name}: {len(e.inliers)} pts, rms {1e3 * e.rms:.1f} mm"))
    fig, ax = plt.subplots(figsize=figsize)
    ax.imshow(over)
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=10)
    ax.legend(handles=handles, loc="lower right", fontsize=8, framealpha=0.9)
    fig.tight_layout()
    return fig


def depth_noise(z, baseline: float, focal_px: float, sigma_d: float = 1.0) -> np.ndarray:
    """Standard deviation of the depth of a rectified pair, ``z^2 sigma_d / (f B)`` (first order in the disparity).

    From ``z = f B / d``: ``dz/dd = -f B / d^2 = -z^2 / (f B)``, so ``sigma_z = z^2 sigma_d / (f B)``, with
    ``sigma_d`` the disparity's noise in pixels (``sqrt(2)`` times that of each image's coordinate).

    >>> float(depth_noise(2.0, 0.4, 1200.0))  # 4 / 480 m
    0.008333333333333333
    """
    func = "depth_noise"
    baseline, focal_px, sigma_d = _head(func, baseline, focal_px, sigma_d)
    return _depth_noise(_depths(z, func, "z"), baseline, focal_px, sigma_d)


def _head(func: str, baseline, focal_px, sigma_d, where: str = "") -> tuple[float, float, float]:
    """A baseline in (0, 1e3] m, a focal length in (0, 1e6] px and a disparity noise in (0, 1e3] px."""
    return tuple(real(v, func, f"{where}{k}", low=0.0, strict_low=True, high=hi) for k, v, hi in
                 (("baseline", baseline, 1e3), ("focal_px", focal_px, 1e6), ("sigma_d", sigma_d, 1e3)))  # fmt: skip


def _depths(z, func: str, name: str) -> np.ndarray:
    """Depths (a number or an array of them) in (0, 1e6] m."""
    ndim = np.asarray(z, dtype=object).ndim  # ragged rows: one dimension, refused by the check
    a = np.asarray(real(z, func, name)) if ndim == 0 else array(z, func, name, (None,) * ndim)
    if np.any(a <= 0) or np.any(a > 1e6):
        raise fail(func, name, "expected finite depths in (0, 1e6] m")
    return a


def _depth_noise(z: np.ndarray, baseline: float, focal_px: float, sigma_d: float) -> np.ndarray:
    return z**2 * sigma_d / (focal_px * baseline)


def depth_noise_figure(heads: dict, sigma_d: float = 1.0, figsize=(7.0, 3.8)):
    """Depth noise against depth for stereo heads ``{label: (baseline m, focal px, (near, far) m)}``.

    ``sigma_d`` is the disparity noise (px).
    Each head's curve is drawn over 0.3-3 m, thick over the depths its scenes use.  Returns the figure.
    """
    func = "depth_noise_figure"
    if not isinstance(heads, dict) or not heads:
        raise fail(func, "heads", "expected a non-empty dict label -> (baseline, focal_px, (near, far))")
    sigma_d = real(sigma_d, func, "sigma_d", low=0.0, strict_low=True, high=1e3)
    checked = {}
    for label, head in heads.items():
        where = f"heads[{label!r}]"
        if not isinstance(label, str) or not isinstance(head, (list, tuple)) or len(head) != 3:
            raise fail(func, where, "expected a label (str) -> (baseline, focal_px, (near, far))")
        baseline, focal, _ = _head(func, head[0], head[1], sigma_d, f"{where} ")
        near, far = array(head[2], func, f"{where} (near, far)", (2,))
        if not (0 < near < far <= 1e6):
            raise fail(func, where, f"expected 0 < near < far <= 1e6, got ({near}, {far})")
        checked[label] = (baseline, focal, near, far)
    fig, ax = plt.subplots(figsize=fig_size(figsize, func))
    z = np.linspace(0.3, 3.0, 200)
    for k, (label, (baseline, focal, near, far)) in enumerate(checked.items()):
        col = PALETTE[2 * k % len(PALETTE)]
        ax.plot(z, 100 * _depth_noise(z, baseline, focal, sigma_d), color=col, lw=1, alpha=0.6)
        zz = np.linspace(near, far, 50)
        ax.plot(zz, 100 * _depth_noise(zz, baseline, focal, sigma_d), color=col, lw=4, label=label)
    ax.set_xlabel("depth z (m)")
    ax.set_ylabel(f"depth noise (cm), disparity noise {sigma_d:.2g} px")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
