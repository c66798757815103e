"""Real stereo data: the Middlebury 2014 motorcycle pair shipped with scikit-image.

``skimage.data.stereo_motorcycle()`` works offline (the images are in the
wheel).  Its docstring gives the calibration of the 4x down-sampled, rectified
pair: focal length 994.978 px, principal point (311.193, 254.877) px,
principal-point offset between the views ``doffs`` = 31.086 px and baseline
193.001 mm.  Two facts differ from that docstring (checked in the tests):
unknown disparities are ``inf`` (not NaN), and the left pixel ``(row, col)``
matches the right pixel ``(row, col - d)`` (Middlebury's convention), not
``col + d``.

Depth from disparity is triangulation (A.14) for a rectified pair: with
``P_left = K [I | 0]`` and ``P_right = K' [I | -B e1]`` (K' has its principal
point shifted by doffs), the rays of ``(u, v)`` and ``(u - d, v)`` meet at
depth ``Z = f B / (d + doffs)``.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import fail

from . import camera as cam
from . import validate as vd

__all__ = ["MOTORCYCLE_CALIBRATION", "load_motorcycle", "motorcycle_cameras", "disparity_to_points", "label_image"]

#: Calibration of the down-sampled pair, from the docstring of ``skimage.data.stereo_motorcycle``.
MOTORCYCLE_CALIBRATION = {
    "focal_px": 994.978,
    "cx": 311.193,
    "cy": 254.877,
    "doffs": 31.086,
    "baseline_m": 0.193001,
}


def load_motorcycle():
    """The left and right images (H, W, 3) uint8, the disparity (H, W) float (inf = unknown) and the calibration."""
    from skimage import data

    left, right, disp = data.stereo_motorcycle()
    return left, right, disp, dict(MOTORCYCLE_CALIBRATION)


def motorcycle_cameras(calib: dict | None = None):
    """Projection matrices (A.1) of the rectified pair, in the left camera's frame (metres).

    Returns
    -------
    P_left, P_right : ndarray, shape (3, 4)
    """
    c = _calibration(calib, "motorcycle_cameras")
    K1 = cam.calibration_matrix(c["focal_px"], c["focal_px"], c["cx"], c["cy"])
    K2 = cam.calibration_matrix(c["focal_px"], c["focal_px"], c["cx"] + c["doffs"], c["cy"])
    R = np.eye(3)
    return cam.projection_matrix(K1, R, np.zeros(3)), cam.projection_matrix(K2, R, [c["baseline_m"], 0.0, 0.0])


def _calibration(calib, func: str) -> dict:
    """The checked calibration ``calib`` (None: the motorcycle's), as floats: positive focal length and baseline."""
    if calib is None:
        return dict(MOTORCYCLE_CALIBRATION)
    calib = checks.instance(calib, func, "calib", dict, "a dict with keys " + ", ".join(MOTORCYCLE_CALIBRATION))
    missing = [k for k in MOTORCYCLE_CALIBRATION if k not in calib]
    if missing:
        raise fail(func, "calib", f"has no {', '.join(map(repr, missing))}")
    out = {
        k: checks.real(calib[k], func, f"calib[{k!r}]", low=-vd.LIMIT, high=vd.LIMIT) for k in MOTORCYCLE_CALIBRATION
    }
    for k in ("focal_px", "baseline_m"):
        checks.real(out[k], func, f"calib[{k!r}]", low=0.0, strict_low=True)
    return out


def disparity_to_points(disp, calib: dict | None = None, step: int = 1, max_depth: float = np.inf):
    """3D points of the left camera frame from a disparity map: ``Z = f B / (d + doffs)``.

    Parameters
    ----------
    disp : array_like, shape (H, W)
        Disparities in pixels; non-finite entries (inf) are unknown and skipped.
    calib : dict, optional
        Keys ``focal_px, cx, cy, doffs, baseline_m`` (default: the motorcycle's).
    step : int
        Keep every ``step``-th row and column.
    max_depth : float
        Drop points farther than this (metres).

    Returns
    -------
    X : ndarray, shape (N, 3)
        Points (x right, y down, z forward), metres.
    pixels : ndarray, shape (N, 2)
        Their left-image coordinates ``(col, row)``.
    """
    f = "disparity_to_points"
    c = _calibration(calib, f)
    disp = vd.array(disp, f, "disp", (None, None), finite=False)
    step = checks.integer(step, f, "step", low=1)
    inf = isinstance(max_depth, float) and max_depth == math.inf  # the default: keep every depth
    max_depth = math.inf if inf else checks.real(max_depth, f, "max_depth", low=0.0, strict_low=True)
    rows, cols = np.mgrid[0 : disp.shape[0] : step, 0 : disp.shape[1] : step]
    d = disp[rows, cols]
    ok = np.isfinite(d) & (d + c["doffs"] > 0)
    u, v, d = cols[ok].astype(float), rows[ok].astype(float), d[ok]
    Z = c["focal_px"] * c["baseline_m"] / (d + c["doffs"])
    X = np.column_stack([(u - c["cx"]) * Z / c["focal_px"], (v - c["cy"]) * Z / c["focal_px"], Z])
    keep = Z <= max_depth
    return checks.finite_result(X[keep], f, "disp"), np.column_stack([u, v])[keep]


def label_image(shape, pixels, labels, step: int = 1) -> np.ndarray:
    """Paint per-point labels back into an image grid: each sample fills its ``step`` x ``step`` block.

    Returns
    -------
    ndarray of int, shape ``shape``
        -1 where no labelled point fell.
    """
    f = "label_image"
    if isinstance(shape, (str, bytes)) or not isinstance(shape, (tuple, list, np.ndarray)) or len(shape) != 2:
        raise fail(f, "shape", f"must be (rows, columns), got {shape!r:.40}")
    shape = tuple(checks.integer(n, f, "shape", low=1, high=2**31 - 1) for n in shape)
    if shape[0] * shape[1] > 10**9:
        raise fail(f, "shape", f"{shape} is too large an image (more than 10^9 pixels)")
    pixels = vd.array(pixels, f, "pixels", (None, 2))
    labels = vd.array(labels, f, "labels", (None,))
    if np.any(labels != np.round(labels)) or np.any(np.abs(labels) > 2**62):
        raise fail(f, "labels", "must be whole numbers (of at most 2^62)")
    checks.same_length(f, pixels=pixels, labels=labels)
    step = checks.integer(step, f, "step", low=1)
    out = np.full(shape, -1, dtype=int)
    # Blocks are clipped to the image's border: a pixel farther out than a block paints the same as one just
    # that far (and its index fits an int).
    pixels = np.clip(pixels, -step - 1, max(shape) + step).astype(int)
    labels = labels.astype(int)
    for dr in range(step):
        for dc in range(step):
            r = np.clip(pixels[:, 1] + dr, 0, shape[0] - 1)
            cc = np.clip(pixels[:, 0] + dc, 0, shape[1] - 1)
            out[r, cc] = labels
    return out
