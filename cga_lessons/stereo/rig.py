"""The robot's stereo head: two calibrated pinhole cameras (appendix A, used by section 4.1).

World frame: x forward, y to the left, z up, metres.  Camera frame: x right,
y down, z forward (OpenCV).  The bundled head is ``data/stereo_rig.json``
(made by ``data/stereo_make.py``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail

from . import camera as cam
from . import epipolar as epi
from . import validate as vd

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
    f = "rotation_matrix"
    axis, angle = vd.array(axis, f, "axis", (3,)), checks.real(angle, f, "angle")
    n = np.linalg.norm(axis)
    if n == 0:
        raise degenerate(f, "axis", "is the zero vector")
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
    f = "look_at_rotation"
    center, target, up = (vd.array(a, f, n, (3,)) for a, n in ((center, "center"), (target, "target"), (up, "up")))
    z = target - center
    if np.linalg.norm(z) == 0:
        raise degenerate(f, "target", "coincides with center: there is no viewing direction")
    return _look_along(z, up, f, "up")


def _look_along(z, up, func: str, name: str) -> np.ndarray:
    """The rotation looking along the checked, non-zero direction z; ``up`` parallel to it is ``name``'s fault."""
    z = z / np.linalg.norm(z)
    x = np.cross(z, up)
    if not np.linalg.norm(x) >= 1e-12 * max(1.0, np.linalg.norm(up)):
        raise degenerate(func, name, "'up' is zero or parallel to the viewing direction: the image has no up")
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

    def __post_init__(self):
        f = "StereoRig"
        fields = {"K": vd.calibration(self.K, f, "K"), "R1": vd.rotation(self.R1, f, "R1")}
        fields.update(C1=vd.array(self.C1, f, "C1", (3,)), R2=vd.rotation(self.R2, f, "R2"))
        fields.update(C2=vd.array(self.C2, f, "C2", (3,)), image_size=vd.image_size(self.image_size, f))
        C1, C2 = fields["C1"], fields["C2"]
        if not np.linalg.norm(C2 - C1) > 1e-12 * max(1.0, float(np.max(np.abs(C1)))):
            raise degenerate(f, "C2", "coincides with C1: cameras at one centre have no baseline")
        for name, value in fields.items():
            object.__setattr__(self, name, value)

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
        return epi.fundamental_from_cameras(self.P1, self.P2)

    def project(self, X):
        """Pixel coordinates ``(x1, x2)`` of world points X (N, 3) in both views (A.5)."""
        return cam.project(self.P1, X), cam.project(self.P2, X)

    def in_view(self, X, margin: float = 0.0) -> np.ndarray:
        """Mask (N,) of points in front of both cameras and inside both images."""
        f = "StereoRig.in_view"
        X, margin = vd.batch(X, f, "X", (3,))[0], checks.real(margin, f, "margin")
        w, h = self.image_size
        ok = np.ones(len(X), dtype=bool)
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
    f = "stereo_head"
    baseline, focal_px = (_length(a, f, n) for a, n in ((baseline, "baseline"), (focal_px, "focal_px")))
    w, h = vd.image_size(image_size, f)
    if principal_point is None:
        principal_point = ((w - 1) / 2.0, (h - 1) / 2.0)
    principal_point = vd.array(principal_point, f, "principal_point", (2,))
    pos = vd.array(position, f, "position", (3,))
    yaw, tilt = checks.real(yaw, f, "yaw"), checks.real(tilt, f, "tilt")
    K = cam.calibration_matrix(focal_px, focal_px, *principal_point)
    fwd = np.array([np.cos(yaw) * np.cos(tilt), np.sin(yaw) * np.cos(tilt), -np.sin(tilt)])
    z = (pos + fwd) - pos  # the viewing direction as look_at_rotation(pos, pos + fwd) sees it
    if not np.linalg.norm(z - fwd) < 1e-6:
        raise degenerate(f, "position", "is so large that the viewing direction is lost in its magnitude")
    R = _look_along(z, np.array([0.0, 0.0, 1.0]), f, "tilt")
    right = R[0]
    C1, C2 = pos - 0.5 * baseline * right, pos + 0.5 * baseline * right
    return _rig(K, R, C1, R.copy(), C2, (w, h), f, "position")


def check_rig(rig, func: str, name: str = "rig") -> StereoRig:
    """``rig`` if it is a :class:`StereoRig` (the argument check of every function taking one)."""
    return checks.instance(rig, func, name, StereoRig, "a StereoRig (stereo_head, random_rig, load_rig)")


def _length(value, func: str, name: str) -> float:
    """A positive length within the camera model's range."""
    return checks.real(value, func, name, low=0.0, strict_low=True, high=vd.LIMIT)


def _rig(K, R1, C1, R2, C2, size, func: str, name: str) -> StereoRig:
    """The rig of checked parts; a rig that is still invalid (cameras at one centre: the baseline lost in the
    magnitude of the position) is the fault of the argument ``name``."""
    try:
        return StereoRig(K, R1, C1, R2, C2, size)
    except GeometryError as exc:
        raise degenerate(func, name, f"gives no valid rig ({exc})") from None


def random_rig(rng: np.random.Generator, target=(2.5, 0.0, 0.5)) -> StereoRig:
    """A random rig looking roughly at ``target``: random baseline (5-40 cm), focal
    length (400-1200 px), principal point, skew-free K, head pose and convergence
    (each camera aimed at its own point near the target)."""
    f = "random_rig"
    rng, target = checks.generator(rng, f), vd.array(target, f, "target", (3,))
    if np.max(np.abs(target)) > 1e9:
        raise fail(f, "target", f"must lie within 1e9 m of the origin (the rig stands metres from it), got {target}")
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
    return _rig(K, R1, C1, R2, C2, (w, h), f, "target")


def load_rig(path=None) -> StereoRig:
    """The stereo head described in ``data/stereo_rig.json`` (made by ``data/stereo_make.py``)."""
    f = "load_rig"
    keys = ("baseline_m", "focal_px", "image_size", "principal_point", "head_position_m", "yaw_rad", "tilt_rad")
    d = vd.json_object(path, "stereo_rig.json", f, keys)
    try:
        return stereo_head(*(d[k] for k in keys))
    except GeometryError as exc:
        raise fail(f, "path", f"describes no valid stereo head: {exc}") from None
