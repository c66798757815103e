"""The robot's stereo head: two calibrated pinhole cameras (appendix A, used by section 4.1).

World frame: x forward, y to the left, z up, metres.  Camera frame: x right,
y down, z forward (OpenCV).  The bundled head is ``data/stereo_rig.json``
(made by ``data/stereo_make.py``).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.paths import data_path

from . import camera as cam
from .camera import as_matrix

__all__ = ["StereoRig", "stereo_head", "random_rig", "load_rig", "rotation_matrix", "look_at_rotation"]


def rotation_matrix(axis, angle: float) -> np.ndarray:
    """Rotation matrix about ``axis`` by ``angle`` radians (Rodrigues' formula).

    Parameters
    ----------
    axis : array_like, shape (3,)
        Rotation axis (need not be unit).
    angle : float
        Right-handed angle in radians.

    Returns
    -------
    R : ndarray, shape (3, 3)
    """
    axis = as_matrix(axis, (3,), "rotation_matrix", "axis")
    n = np.linalg.norm(axis)
    if n == 0:
        raise DegenerateGeometryError("rotation_matrix: the axis is the zero vector")
    a, b, c = axis / n
    k = np.array([[0.0, -c, b], [c, 0.0, -a], [-b, a, 0.0]])  # [n]_x as in (A.12)
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def look_at_rotation(center, target, up=(0.0, 0.0, 1.0)) -> np.ndarray:
    """World-to-camera rotation of a camera at ``center`` looking at ``target``.

    Camera axes: z along the viewing direction, x to the right, y down in the
    image (so ``up`` appears upwards).

    Parameters
    ----------
    center, target, up : array_like, shape (3,)

    Returns
    -------
    R : ndarray, shape (3, 3)
        Rows are the camera's x, y, z axes expressed in world coordinates.
    """
    center = as_matrix(center, (3,), "look_at_rotation", "center")
    target = as_matrix(target, (3,), "look_at_rotation", "target")
    up = as_matrix(up, (3,), "look_at_rotation", "up")
    z = target - center
    if np.linalg.norm(z) == 0:
        raise DegenerateGeometryError("look_at_rotation: center and target coincide")
    z = z / np.linalg.norm(z)
    x = np.cross(z, up)
    if np.linalg.norm(x) < 1e-12:
        raise DegenerateGeometryError("look_at_rotation: the viewing direction is parallel to 'up'")
    x = x / np.linalg.norm(x)
    return np.vstack([x, np.cross(z, x), z])


@dataclass(frozen=True)
class StereoRig:
    """Two calibrated cameras ``P_i = K R_i [I | -C_i]`` (A.1).

    Attributes
    ----------
    K : ndarray, shape (3, 3)
        Shared calibration matrix (A.2).
    R1, R2 : ndarray, shape (3, 3)
        World-to-camera rotations of the left and right camera.
    C1, C2 : ndarray, shape (3,)
        Camera centres in the world (metres).
    image_size : tuple of int
        ``(width, height)`` in pixels.
    """

    K: np.ndarray
    R1: np.ndarray
    C1: np.ndarray
    R2: np.ndarray
    C2: np.ndarray
    image_size: tuple

    @property
    def P1(self) -> np.ndarray:
        return cam.projection_matrix(self.K, self.R1, self.C1)

    @property
    def P2(self) -> np.ndarray:
        return cam.projection_matrix(self.K, self.R2, self.C2)

    @property
    def baseline(self) -> float:
        """Distance between the camera centres (metres)."""
        return float(np.linalg.norm(self.C2 - self.C1))

    @property
    def F(self) -> np.ndarray:
        """The true fundamental matrix, ``x2^T F x1 = 0`` (A.6)."""
        return cam.fundamental_from_cameras(self.P1, self.P2)

    def project(self, X):
        """Pixel coordinates ``(x1, x2)`` of world points X (N, 3) in both views (A.5)."""
        return cam.project(self.P1, X), cam.project(self.P2, X)

    def in_view(self, X, margin: float = 0.0) -> np.ndarray:
        """Mask (N,) of points in front of both cameras and inside both images."""
        w, h = self.image_size
        ok = np.ones(len(np.atleast_2d(X)), dtype=bool)
        for P in (self.P1, self.P2):
            x, depth = cam.project(P, X, return_depth=True)
            ok &= (depth > 0) & (x[:, 0] >= margin) & (x[:, 0] <= w - 1 - margin)
            ok &= (x[:, 1] >= margin) & (x[:, 1] <= h - 1 - margin)
        return ok


def stereo_head(
    baseline=0.12,
    focal_px=700.0,
    image_size=(640, 480),
    principal_point=None,
    position=(0.0, 0.0, 1.2),
    yaw=0.0,
    tilt=0.35,
) -> StereoRig:
    """A parallel stereo head at ``position`` looking along world +x turned by ``yaw``, tilted down by ``tilt``.

    Parameters
    ----------
    baseline : float
        Distance between the two centres (metres), along the cameras' x axis.
    focal_px : float
        Focal length in pixels (square pixels, no skew).
    image_size : (int, int)
        ``(width, height)``.
    principal_point : (float, float), optional
        Defaults to the image centre ``((w - 1)/2, (h - 1)/2)``.
    position : array_like, shape (3,)
        Midpoint of the two centres.
    yaw, tilt : float
        Heading (about world z) and downward tilt, radians.
    """
    w, h = image_size
    if principal_point is None:
        principal_point = ((w - 1) / 2.0, (h - 1) / 2.0)
    if not baseline > 0:
        raise InvalidInputError(f"stereo_head: baseline must be positive, got {baseline}")
    K = cam.calibration_matrix(focal_px, focal_px, *principal_point)
    fwd = np.array([np.cos(yaw) * np.cos(tilt), np.sin(yaw) * np.cos(tilt), -np.sin(tilt)])
    pos = np.asarray(position, dtype=float)
    R = look_at_rotation(pos, pos + fwd)
    right = R[0]
    return StereoRig(K, R, pos - 0.5 * baseline * right, R.copy(), pos + 0.5 * baseline * right, (int(w), int(h)))


def random_rig(rng: np.random.Generator, target=(2.5, 0.0, 0.5)) -> StereoRig:
    """A random rig looking roughly at ``target``: random baseline (5-40 cm), focal
    length (400-1200 px), principal point, skew-free K, head pose and convergence
    (each camera aimed at its own point near the target)."""
    target = np.asarray(target, dtype=float)
    w, h = int(rng.integers(480, 1025)), int(rng.integers(360, 769))
    K = cam.calibration_matrix(
        rng.uniform(400, 1200), rng.uniform(400, 1200), w / 2 + rng.uniform(-20, 20), h / 2 + rng.uniform(-20, 20)
    )
    d = rng.normal(size=3)
    d[0] = -abs(d[0]) - 1.0
    head = target + rng.uniform(2.0, 3.5) * d / np.linalg.norm(d)
    fwd = (target - head) / np.linalg.norm(target - head)
    side = np.cross([0.0, 0.0, 1.0], fwd)
    side /= np.linalg.norm(side)
    side = rotation_matrix(fwd, rng.uniform(-0.3, 0.3)) @ side
    b = rng.uniform(0.05, 0.4)
    C1, C2 = head + 0.5 * b * side, head - 0.5 * b * side
    R1 = look_at_rotation(C1, target + rng.normal(scale=0.1, size=3))
    R2 = look_at_rotation(C2, target + rng.normal(scale=0.1, size=3))
    return StereoRig(K, R1, C1, R2, C2, (w, h))


def load_rig(path=None) -> StereoRig:
    """The stereo head described in ``data/stereo_rig.json`` (made by ``data/stereo_make.py``)."""
    d = json.loads(Path(path or data_path("stereo_rig.json")).read_text())
    return stereo_head(
        d["baseline_m"], d["focal_px"], tuple(d["image_size"]), tuple(d["principal_point"]),
        d["head_position_m"], d["yaw_rad"], d["tilt_rad"],
    )  # fmt: skip
