"""What the stereo head's two cameras see, drawn with OpenCV (for the notebook of section 4.1).

The scene of :mod:`cga_lessons.stereo` is painted object by object, far ones
first, through each camera's projection (A.5): the floor's grid, the board, the
plate (its rim drawn with the rotor construction of 4.1), the ball (its
silhouette is the circle where the cone of rays from the camera touches it),
the broom handle and the loose points.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import degenerate

from . import camera as cam
from . import validate as vd
from .head import StereoScene, check_scene, seen
from .polylines import circle_polyline
from .rig import StereoRig, check_rig

__all__ = ["render_views"]

_SUB = 16  # OpenCV's fixed-point drawing: 4 fractional bits


def _px(P, X) -> np.ndarray:
    """OpenCV's fixed-point pixels of points in front of the camera (far off-image ones clipped to fit an int)."""
    return np.round(np.clip(cam.project(P, X), -(2**26), 2**26) * _SUB).astype(np.int32)


def _floor(P, size) -> np.ndarray:
    """A pale background with the floor's 0.5 m grid (x 0.5-8 m, y -4-4 m)."""
    import cv2

    w, h = size
    img = np.full((h, w, 3), (226, 230, 236), np.uint8)
    t = np.linspace(0.0, 1.0, 60)[:, None]
    lines = [np.array([[x, -4.0, 0.0], [x, 4.0, 0.0]]) for x in np.arange(0.5, 8.01, 0.5)]
    lines += [np.array([[0.5, y, 0.0], [8.0, y, 0.0]]) for y in np.arange(-4.0, 4.01, 0.5)]
    for a, b in lines:
        x, d = cam.project(P, a + t * (b - a), return_depth=True)
        pts = np.round(x[d > 0.05] * _SUB).astype(np.int32)
        if len(pts) > 1:
            cv2.polylines(img, [pts], False, (170, 165, 158), 1, cv2.LINE_AA, shift=4)
    return img


def _draw(img, P, C, focal, scene: StereoScene, what: str) -> None:
    import cv2

    aa = cv2.LINE_AA
    if what == "board":
        corners = _px(P, scene.board_corners())
        cv2.fillPoly(img, [corners], (150, 110, 70), aa, shift=4)
        cv2.polylines(img, [corners], True, (90, 60, 30), 2, aa, shift=4)
    elif what == "plate":
        rim = _px(P, circle_polyline(scene.circle_center, scene.circle_normal, scene.circle_radius, 96))
        cv2.fillPoly(img, [rim], (245, 245, 240), aa, shift=4)
        cv2.polylines(img, [rim], True, (60, 90, 160), 2, aa, shift=4)
    elif what == "ball":
        S, r = scene.sphere_center, scene.sphere_radius
        D = np.linalg.norm(C - S)
        axis = (C - S) / D
        cv2.fillPoly(img, [_px(P, _ball_rim(C, S, r))], (200, 60, 40), aa, shift=4)
        shine = axis + np.array([0.0, 0.0, 0.8])
        hl = _px(P, S + 0.5 * r * shine / np.linalg.norm(shine))[0]
        cv2.circle(img, tuple(int(v) for v in hl), int(_SUB * 0.25 * r * focal / D), (235, 150, 130), -1, aa, shift=4)
    elif what == "broom":
        a, b = _px(P, scene.segment)
        cv2.line(img, tuple(int(v) for v in a), tuple(int(v) for v in b), (140, 100, 40), 5, aa, shift=4)


def _ball_rim(C, S, r, n: int = 96) -> np.ndarray:
    """The ball's silhouette seen from C: the circle where the cone of rays from C touches it."""
    D = np.linalg.norm(C - S)
    axis = (C - S) / D
    return circle_polyline(S + r * r / D * axis, axis, r * np.sqrt(1 - (r / D) ** 2), n)


def _in_front(rig: StereoRig, scene: StereoScene, samples, func: str) -> None:
    """Every object of the scene (and every key point of ``samples``) must lie in front of both cameras."""
    rim = circle_polyline(scene.circle_center, scene.circle_normal, scene.circle_radius, 16)
    seen(rig, np.vstack([scene.points, scene.segment, scene.board_corners(), rim]), func, "rig, scene")
    for k, (P, C) in enumerate(((rig.P1, rig.C1), (rig.P2, rig.C2)), 1):
        if not np.linalg.norm(C - scene.sphere_center) > scene.sphere_radius:
            raise degenerate(func, "rig, scene", f"camera {k} is inside the ball (sphere_center, sphere_radius)")
        if np.any(cam.project(P, _ball_rim(C, scene.sphere_center, scene.sphere_radius, 16), True)[1] <= 0):
            raise degenerate(func, "rig, scene", f"the ball is (partly) behind camera {k}: it cannot see it")
    if samples is not None:
        samples = checks.instance(samples, func, "samples", dict, "a dict as sample_scene returns, or None")
        for k in ("circle_key", "plane_key", "sphere_key"):
            if k not in samples:
                raise checks.fail(func, "samples", f"has no {k!r} (sample_scene's key points)")
            seen(rig, vd.array(samples[k], func, f"samples[{k!r}]", (None, 3)), func, f"rig, samples[{k!r}]")


def render_views(rig: StereoRig, scene: StereoScene, samples: dict | None = None):
    """What the two cameras see (painter's algorithm, far objects first).

    Parameters
    ----------
    rig : StereoRig
    scene : StereoScene
    samples : dict, optional
        Output of :func:`~cga_lessons.stereo.sample_scene`; its key points
        (the minimal sets of 4.1) are marked with green crosses.

    Returns
    -------
    left, right : ndarray, shape (h, w, 3), uint8, RGB
    """
    f = "render_views"
    rig = check_rig(rig, f)
    scene = check_scene(scene, f)
    _in_front(rig, scene, samples, f)
    import cv2

    images = []
    for P, C in ((rig.P1, rig.C1), (rig.P2, rig.C2)):
        img = _floor(P, rig.image_size)
        centres = {
            "board": scene.board_center,
            "plate": scene.circle_center,
            "ball": scene.sphere_center,
            "broom": scene.segment.mean(axis=0),
        }
        for what in sorted(centres, key=lambda k: -np.linalg.norm(centres[k] - C)):
            _draw(img, P, C, rig.K[0, 0], scene, what)
        for q in _px(P, scene.points):
            cv2.circle(img, tuple(int(v) for v in q), 4 * _SUB, (30, 30, 30), -1, cv2.LINE_AA, shift=4)
        if samples is not None:
            for k in ("circle_key", "plane_key", "sphere_key"):
                for q in _px(P, samples[k]) // _SUB:
                    cv2.drawMarker(img, tuple(int(v) for v in q), (20, 150, 20), cv2.MARKER_CROSS, 9, 2)
        images.append(img)
    return images[0], images[1]
