"""The robot *geometer*'s fixed geometry and its five degrees of freedom (section 4.2.2), with their checks.

:class:`RobotGeometry` holds the dimensions (metres, radians) of the base, the laser mount, the pan-tilt axes and
the stereo head; :class:`RobotState` the five degrees of freedom ``x, y, theta, pan, tilt``.  The motor chains
that join them are :mod:`cga_lessons.map3d.robot`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from cga_lessons import checks

__all__ = ["DOFS", "RobotGeometry", "RobotState"]

#: The five degrees of freedom of section 4.2.3, in the thesis's order.
DOFS = ("x", "y", "theta", "pan", "tilt")


# ----------------------------------------------------------------- geometry and state
@dataclass(frozen=True)
class RobotGeometry:
    """The fixed dimensions of geometer, metres and radians, in the base frame at pan = tilt = 0.

    The thesis prints no dimensions (figure 4.1 is a photograph of the scale
    model); every default is *our choice* for a small wheeled base with a laser
    at the front of its deck and a stereo head on a mast, except ``baseline``,
    ``focal_px`` and ``image_size``, which are the stereo head of section 4.1
    in this project (``data/stereo_rig.json``), and the camera height, about
    1.2 m as there.

    Attributes
    ----------
    base_size : (float, float, float)
        Length (x), width (y) and height (z) of the body, drawn as a box.
    base_clearance : float
        Height of the body's underside above the floor (the wheels).
    laser_mount : (float, float, float, float)
        ``(x, y, height, yaw)`` of the laser's origin: the 2D laser-robot
        transform of (3.16) plus the height of its scanning plane (4.2.2).
    pan_point, pan_direction : (3,) each
        A point of the pan axis ``L_pan`` and its direction.
    tilt_point, tilt_direction : (3,) each
        A point of the tilt axis ``L_tilt`` (at pan = 0) and its direction.
    eye_offset : (3,)
        Left camera centre minus the point nearest both axes, at pan = tilt = 0
        (the translation of ``T_ojo``).
    baseline, focal_px, image_size
        The stereo pair: right camera ``baseline`` metres to the right of the left.
    pan_limits, tilt_limits : (float, float)
        Joint ranges enforced by :class:`Robot` (the chain functions accept any angle).
    """

    base_size: tuple = (0.50, 0.40, 0.25)
    base_clearance: float = 0.06
    laser_mount: tuple = (0.30, 0.0, 0.35, 0.0)
    pan_point: tuple = (-0.10, 0.0, 1.0)
    pan_direction: tuple = (0.0, 0.0, 1.0)
    tilt_point: tuple = (-0.10, 0.0, 1.10)
    tilt_direction: tuple = (0.0, 1.0, 0.0)
    eye_offset: tuple = (0.05, 0.06, 0.06)
    baseline: float = 0.12
    focal_px: float = 700.0
    image_size: tuple = (640, 480)
    pan_limits: tuple = (-np.radians(170.0), np.radians(170.0))
    tilt_limits: tuple = (-np.radians(45.0), np.radians(80.0))

    def __post_init__(self):
        f = "RobotGeometry"
        for name, n in _VECTORS.items():
            v = checks.magnitude(
                checks.array(getattr(self, name), f, name, (n,)), f, name, why="the chains' squares overflow a float"
            )
            object.__setattr__(self, name, tuple(float(x) for x in v))
        if min(self.base_size) <= 0:
            raise checks.fail(f, "base_size", f"must be > 0, got {self.base_size}")
        object.__setattr__(self, "base_clearance", checks.real(self.base_clearance, f, "base_clearance", low=0.0))
        for name in ("baseline", "focal_px"):
            object.__setattr__(self, name, checks.real(getattr(self, name), f, name, low=0.0, strict_low=True))
        size = checks.array(self.image_size, f, "image_size", (2,))
        object.__setattr__(
            self, "image_size", tuple(checks.integer(v, f, "image_size", low=1, high=10**5) for v in size)
        )
        for name in ("pan_limits", "tilt_limits"):
            lo, hi = getattr(self, name)
            if lo > hi:
                raise checks.fail(f, name, f"must have low <= high, got {(lo, hi)}")
        _check_axes(self.pan_direction, self.tilt_direction, f)


#: The fields of :class:`RobotGeometry` that are vectors, and their lengths.
_VECTORS = {"base_size": 3, "laser_mount": 4, "pan_point": 3, "pan_direction": 3, "tilt_point": 3,
            "tilt_direction": 3, "eye_offset": 3, "pan_limits": 2, "tilt_limits": 2}  # fmt: skip


def _check_axes(pan, tilt, func: str) -> None:
    """The pan and tilt directions: not zero, not parallel (a single point is nearest both axes, T_eje)."""
    units = []
    for name, d in (("pan_direction", pan), ("tilt_direction", tilt)):
        d = np.asarray(d) / max(float(np.max(np.abs(d))), 1e-300)
        n = float(np.linalg.norm(d))
        if n < 1e-12:
            raise checks.degenerate(func, name, "is the zero vector: an axis needs a direction")
        units.append(d / n)
    c = float(units[0] @ units[1])
    if 1.0 - c * c < 1e-12:
        raise checks.degenerate(func, "pan_direction, tilt_direction", "the pan and tilt axes are parallel; no single "
                                "point is nearest both (T_eje, 4.5)")  # fmt: skip


@dataclass(frozen=True)
class RobotState:
    """The five degrees of freedom: position ``x, y`` (m), heading ``theta``, ``pan``, ``tilt`` (rad)."""

    x: float = 0.0
    y: float = 0.0
    theta: float = 0.0
    pan: float = 0.0
    tilt: float = 0.0

    def __post_init__(self):
        for name in DOFS:
            limit = 2.0**52 if name in ("theta", "pan", "tilt") else None  # beyond: no precision left for an angle
            v = checks.real(getattr(self, name), "RobotState", name, low=-limit if limit else None, high=limit)
            object.__setattr__(self, name, v)

    @property
    def pose(self) -> np.ndarray:
        """The planar pose ``(x, y, theta)`` of chapter 3, shape (3,)."""
        return np.array([self.x, self.y, self.theta])

    def replace(self, **changes) -> RobotState:
        return replace(self, **check_changes(changes, "RobotState.replace"))

    def changed(self, other: RobotState) -> tuple:
        """Names of the degrees of freedom in which ``other`` differs from this state."""
        return tuple(n for n in DOFS if getattr(self, n) != getattr(other, n))


def check_changes(changes: dict, func: str) -> dict:
    """Changes of degrees of freedom (name -> finite number), unknown names refused."""
    for name in changes:
        if name not in DOFS:
            raise checks.fail(func, name, f"unknown degree of freedom; use {', '.join(DOFS)}")
    angle = 2.0**52  # beyond: no float precision left for an angle
    return {k: checks.real(v, func, k, low=-angle if k in _ANGLES else None, high=angle if k in _ANGLES else None)
            for k, v in changes.items()}  # fmt: skip


_ANGLES = ("theta", "pan", "tilt")
