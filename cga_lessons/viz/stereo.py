"""Matplotlib figures for the stereo chapter (appendix A and section 4.1)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import stereo as st
from cga_lessons.checks import array, fail, instance, real, relabel

from .inputs import axes, coords, optional_text, texts
from .inputs import figsize as fig_size

__all__ = [
    "plot_views",
    "plot_epipolar_lines",
    "plot_triangulation_curve",
    "plot_entities_3d",
    "plot_plane_segmentation",
]

_COLORS = plt.cm.tab10(np.arange(10))


def _image(value, func: str, name: str) -> np.ndarray:
    """An image (H, W) or (H, W, 3 or 4) of finite values 0..255 (floats: 0..1 is full scale), as given."""
    ndim = np.asarray(value, dtype=object).ndim  # ragged rows: one dimension, refused by the check
    img = array(value, func, name, (None,) * (ndim if ndim in (2, 3) else 2))
    if not img.size or (img.ndim == 3 and img.shape[2] not in (3, 4)) or img.min() < 0 or img.max() > 255:
        raise fail(func, name, f"expected an image (H, W) or (H, W, 3 or 4) of values 0..255, got {img.shape}")
    return np.asarray(value)


def plot_views(left, right, titles=("left camera", "right camera"), figsize=(9, 3.4)):
    """The two images side by side (each (H, W) or (H, W, 3 or 4): values 0-255, or 0-1 as floats)."""
    func = "plot_views"
    left, right = _image(left, func, "left"), _image(right, func, "right")
    titles, figsize = texts(titles, func, "titles", 2), fig_size(figsize, func)
    fig, axes = plt.subplots(1, 2, figsize=figsize)
    for ax, img, t in zip(axes, (left, right), titles):
        ax.imshow(img)
        ax.set_title(t)
        ax.set_axis_off()
    fig.tight_layout()
    return fig


def _draw_line(ax, line, w, h, **kw):
    """Draw ``a x + b y + c = 0`` across a w x h image."""
    a, b, c = line
    if abs(b) > abs(a):
        xs = np.array([0.0, w - 1.0])
        ys = -(a * xs + c) / b
    else:
        ys = np.array([0.0, h - 1.0])
        xs = -(b * ys + c) / a
    ax.plot(xs, ys, **kw)


def plot_epipolar_lines(left, right, x1, x2, F, figsize=(9, 3.4)):
    """Points of each view and their epipolar lines ``F x`` / ``F^T x'`` (A.6) in the other view."""
    func = "plot_epipolar_lines"
    left, right = _image(left, func, "left"), _image(right, func, "right")
    x1, x2, F = coords(x1, func, "x1", (None, 2)), coords(x2, func, "x2", (None, 2)), coords(F, func, "F", (3, 3))
    if len(x1) != len(x2):
        raise fail(func, "x2", f"expected as many points as x1 ({len(x1)}), got {len(x2)}")
    if not np.abs(F).max() > 0:
        raise fail(func, "F", "the zero matrix is no fundamental matrix")
    figsize = fig_size(figsize, func)
    h, w = left.shape[:2]
    with relabel(func, "F"):
        l2 = st.epipolar_lines(F, x1)
        l1 = st.epipolar_lines(F.T, x2)
    fig, axes = plt.subplots(1, 2, figsize=figsize)
    for ax, img, pts, lines, t in (
        (axes[0], left, x1, l1, "left: x and F^T x'"),
        (axes[1], right, x2, l2, "right: x' and F x"),
    ):
        ax.imshow(img, alpha=0.75)
        for i, (p, ln) in enumerate(zip(pts, lines)):
            col = _COLORS[i % 10]
            _draw_line(ax, ln, w, h, color=col, lw=1.0)
            ax.plot(*p, "o", color=col, ms=5, mec="k", mew=0.6)
        ax.set_xlim(0, w - 1)
        ax.set_ylim(h - 1, 0)
        ax.set_title(t)
        ax.set_axis_off()
    fig.tight_layout()
    return fig


def plot_triangulation_curve(curve, theory=None, figsize=(6, 3.6)):
    """RMS 3D error against pixel noise for midpoint (A.14) and DLT triangulation.

    ``curve``: a :class:`~cga_lessons.stereo.TriangulationCurve` (its ``noise_px``, ``midpoint`` and ``dlt`` are
    drawn); ``theory``, optional, is an array of the same length (metres) drawn as a dashed line.
    """
    func = "plot_triangulation_curve"
    instance(curve, func, "curve", st.TriangulationCurve, "a TriangulationCurve (triangulation_error_curve)")
    s = coords(curve.noise_px, func, "curve.noise_px", (None,), at_least=1)
    curve = {k: coords(getattr(curve, k), func, f"curve.{k}", s.shape) for k in ("midpoint", "dlt")}
    theory = None if theory is None else coords(theory, func, "theory", s.shape)
    fig, ax = plt.subplots(figsize=fig_size(figsize, func))
    ax.plot(s, 1e3 * curve["midpoint"], "o-", label="midpoint (A.14, fig. A.4)")
    ax.plot(s, 1e3 * curve["dlt"], "s--", label="linear (DLT)", mfc="none")
    if theory is not None:
        ax.plot(s, 1e3 * np.asarray(theory), ":", color="grey", label="first-order prediction")
    ax.set_xlabel("pixel noise (std, px)")
    ax.set_ylabel("RMS 3D error (mm)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


def _sphere_wire(ax, center, radius, **kw):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 19), np.linspace(0, np.pi, 10))
    x = center[0] + radius * np.cos(u) * np.sin(v)
    y = center[1] + radius * np.sin(u) * np.sin(v)
    z = center[2] + radius * np.cos(v)
    ax.plot_wireframe(x, y, z, axlim_clip=True, **kw)


def _entities(ax, ent: dict, color, style, label):
    """Draw one set of entities with the procedures of 4.1 (clipped to the axes' box)."""
    kw = {"color": color, "ls": style, "lw": 1.6, "axlim_clip": True}
    ax.plot([], [], [], color=color, ls=style, label=label)
    if "point" in ent:
        ax.scatter(*ent["point"].points.T, color=color, s=14, depthshade=False, axlim_clip=True)
    t = np.linspace(0.0, 1.0, 40)[:, None]  # dense, so that clipping hides only the part outside
    if "line" in ent and "pair" in ent:
        a, b = st.line_polyline(ent["line"].blade, ent["pair"].blade)
        ax.plot(*(a + t * (b - a)).T, **kw)
    elif "pair" in ent:
        a, b = ent["pair"].endpoints
        ax.plot(*(a + t * (b - a)).T, **kw)
    if "circle" in ent:
        c = ent["circle"]
        ax.plot(*st.circle_polyline(c.center, c.normal, c.radius).T, **kw)
    if "plane" in ent:
        p = ent["plane"]
        ax.plot(*st.square_polyline(p.center, p.normal, p.radius).T, **kw)
    if "sphere" in ent:
        s = ent["sphere"]
        _sphere_wire(ax, s.center, s.radius, color=color, lw=0.6, alpha=0.8)


def plot_entities_3d(scene, estimates: dict, rig=None, ax=None, title=None, elev=18, azim=-150, figsize=(7, 5.5)):
    """The scene's objects (grey, dotted) and sets of reconstructed entities (colours) in 3D.

    Lines are drawn from their direction and closest point (2.127, 2.129), circles
    by turning a perpendicular vector with rotors, planes as squares (section 4.1).
    The view box is the scene's (entities reaching outside it are clipped).

    Parameters
    ----------
    scene : StereoScene
    estimates : dict
        ``label -> entities``, each a dict ``entity name -> record`` as :func:`~cga_lessons.stereo.reconstruct_entities`
        returns (the fits of :mod:`cga_lessons.conformal` may stand for its circle, plane and sphere).
    rig : StereoRig, optional
        Camera centres are drawn when given.
    ax : Axes3D, optional
    """
    func = "plot_entities_3d"
    sc = instance(scene, func, "scene", st.StereoScene, "a StereoScene")
    if not isinstance(estimates, dict) or not all(isinstance(e, dict) for e in estimates.values()):
        raise fail(func, "estimates", "expected a dict label -> dict of entities (reconstruct_entities)")
    if rig is not None:
        instance(rig, func, "rig", st.StereoRig, "a StereoRig or None")
    ax, title = axes(ax, func, three_d=True), optional_text(title, func, "title")
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    figsize = fig_size(figsize, func)  # for a new axes only
    if ax is None:
        fig = plt.figure(figsize=figsize)
        ax = fig.add_subplot(projection="3d")
    sc = scene
    grey = {"color": "0.45", "lw": 1.2, "ls": ":"}
    ax.plot(*sc.segment.T, **grey, label="truth")
    ax.plot(*st.circle_polyline(sc.circle_center, sc.circle_normal, sc.circle_radius).T, **grey)
    ax.plot(*np.vstack([sc.board_corners(), sc.board_corners()[:1]]).T, **grey)
    _sphere_wire(ax, sc.sphere_center, sc.sphere_radius, color="0.6", lw=0.4)
    ax.scatter(*np.asarray(sc.points).T, color="0.4", s=16, marker="x")
    pts = [sc.points, sc.segment, sc.board_corners(), [sc.sphere_center], [sc.circle_center]]
    if rig is not None:
        C = np.vstack([rig.C1, rig.C2])
        ax.plot(*C.T, "k^-", ms=6, label="cameras")
        pts.append(C)
    box = np.vstack(pts)
    lo, hi = box.min(axis=0) - 0.25, box.max(axis=0) + 0.25
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(max(lo[2], 0.0), hi[2])
    for i, (label, ent) in enumerate(estimates.items()):
        try:
            _entities(ax, ent, _COLORS[(2 * i + 1) % 10], "-" if i == 0 else "--", str(label))
        except (KeyError, TypeError, IndexError, ValueError, AttributeError) as exc:
            raise fail(func, f"estimates[{label!r}]", f"not the entities of reconstruct_entities ({exc})") from None
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(plt.MaxNLocator(4))
    ax.view_init(elev=elev, azim=azim)
    ax.set_box_aspect(hi - np.array([lo[0], lo[1], max(lo[2], 0.0)]), zoom=1.12)
    ax.legend(loc="upper left", fontsize=8)
    if title:
        ax.set_title(title)
    return ax.figure


def plot_plane_segmentation(image, labels, fits, names=None, figsize=(5.4, 3.9)):
    """Planes found in a real scene, painted over the (greyed) left image, with a legend (name, points, RMS).

    ``labels`` (H, W): the plane of each pixel (-1: none); ``fits``: one :class:`~cga_lessons.conformal.PlaneFit` per
    plane (:func:`~cga_lessons.conformal.segment_planes`; its ``inliers`` and ``rms`` are shown).
    """
    from matplotlib.patches import Patch

    func = "plot_plane_segmentation"
    image = array(image, func, "image", (None, None, 3))
    if not image.size or image.min() < 0 or image.max() > 255:
        raise fail(func, "image", f"expected an RGB image (H, W, 3) of values 0..255, got {image.shape}")
    labels = array(labels, func, "labels", image.shape[:2])
    if not isinstance(fits, (list, tuple)):
        raise fail(func, "fits", f"expected a list of plane fits (PlaneFit), got {type(fits).__name__}")
    for i, f in enumerate(fits):
        instance(f, func, f"fits[{i}]", cga.PlaneFit, "a PlaneFit (segment_planes)")
        real(f.inliers, func, f"fits[{i}]", low=0), real(f.rms, func, f"fits[{i}]", low=0)
    names = None if names is None else texts(names, func, "names", len(fits))
    fig, ax = plt.subplots(figsize=fig_size(figsize, func))
    grey = image.astype(float).mean(axis=2, keepdims=True) / 255.0  # grey photo: colours read as planes
    over = np.repeat(0.3 + 0.7 * grey, 3, axis=2)
    handles = []
    for i, f in enumerate(fits):
        m = labels == i
        col = _COLORS[i % 10][:3]
        over[m] = 0.45 * over[m] + 0.55 * col
        name = names[i] if names else f"plane {i}"
        handles.append(Patch(color=col, label=f"{name}: {f.inliers} pts, rms {1e3 * f.rms:.1f} mm"))
    ax.imshow(over)
    ax.set_axis_off()
    ax.set_title("RANSAC + conformal least-squares planes")
    ax.legend(handles=handles, loc="lower right", fontsize=8, framealpha=0.9)
    fig.tight_layout()
    return fig
