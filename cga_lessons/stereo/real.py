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

import numpy as np

from cga_lessons.algebra import InvalidInputError

from . import camera as cam

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
    c = calib or MOTORCYCLE_CALIBRATION
    K1 = cam.calibration_matrix(c["focal_px"], c["focal_px"], c["cx"], c["cy"])
    K2 = cam.calibration_matrix(c["focal_px"], c["focal_px"], c["cx"] + c["doffs"], c["cy"])
    R = np.eye(3)
    return cam.projection_matrix(K1, R, np.zeros(3)), cam.projection_matrix(K2, R, [c["baseline_m"], 0.0, 0.0])


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
    c = calib or MOTORCYCLE_CALIBRATION
    disp = np.asarray(disp, dtype=float)
    if disp.ndim != 2:
        raise InvalidInputError(f"disparity_to_points: disp must have shape (H, W), got {disp.shape}")
    if not (isinstance(step, int | np.integer) and step >= 1):
        raise InvalidInputError(f"disparity_to_points: step must be a positive integer, got {step!r}")
    rows, cols = np.mgrid[0 : disp.shape[0] : step, 0 : disp.shape[1] : step]
    d = disp[rows, cols]
    ok = np.isfinite(d) & (d + c["doffs"] > 0)
    u, v, d = cols[ok].astype(float), rows[ok].astype(float), d[ok]
    Z = c["focal_px"] * c["baseline_m"] / (d + c["doffs"])
    X = np.column_stack([(u - c["cx"]) * Z / c["focal_px"], (v - c["cy"]) * Z / c["focal_px"], Z])
    keep = Z <= max_depth
    return X[keep], np.column_stack([u, v])[keep]


def label_image(shape, pixels, labels, step: int = 1) -> np.ndarray:
    """Paint per-point labels back into an image grid: each sample fills its ``step`` x ``step`` block.

    Returns
    -------
    ndarray of int, shape ``shape``
        -1 where no labelled point fell.
    """
    out = np.full(shape, -1, dtype=int)
    pixels = np.asarray(pixels).astype(int)
    for dr in range(step):
        for dc in range(step):
            r = np.clip(pixels[:, 1] + dr, 0, shape[0] - 1)
            cc = np.clip(pixels[:, 0] + dc, 0, shape[1] - 1)
            out[r, cc] = labels
    return out
