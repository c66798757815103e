"""The robot *geometer*: five degrees of freedom and its sensors as motor chains (section 4.2.2, Eqs. 4.1-4.10).

The robot drives on the floor (x, y, theta), carries a 2D laser at a fixed
height and a stereo head on a pan-tilt unit (pan, tilt): five degrees of
freedom in all (section 4.2.3).  Each sensor reaches the unified (world) frame
through a product of rotors, translators and motors of G(4,1):

laser (4.1)-(4.4)::

    M_cl = R_pos M_lsr ~R_pos            (4.1)  the laser mount, turned with the robot
    M_pos = T_pos R_pos                  (4.2)  the robot's motion (printed: T_pos R_lsr, an erratum)
    M_lu = T_pos M_cl R_pos              (4.3)  = M_pos M_lsr (printed: M_cl M_pos, see below)
    x' = M_lu x ~M_lu                    (4.4)

stereo head (4.5)-(4.10)::

    T_ep = R_pos T_eje ~R_pos            (4.5)  to the point nearest both pan-tilt axes
    R_pt = R_pos R_pan R_tilt            (4.6)  every turn: robot, pan, tilt
    T_opt = R_pt T_ojo ~R_pt             (4.7)  on to the left camera, turned
    M_mpt = T_pos R_pt                   (4.8)
    M_eu = T_opt T_ep M_mpt              (4.9)  (printed: ... R_mpt, an erratum)
    x' = M_eu x ~M_eu                    (4.10)

Errata (see :mod:`cga_lessons.equations.registry.ch4`): (4.2) as printed uses the laser's
rotor ``R_lsr`` where the robot's heading ``R_pos`` belongs; (4.3) as printed,
``M_cl M_pos``, translates by ``R_pos t_lsr + R_phi t_pos`` instead of ``t_pos +
R_pos t_lsr`` and so is right only for a laser that is not turned on the robot
(``phi = 0``, the geometer's forward-looking laser), the same slip as (3.17);
(4.9) names ``R_mpt``, which (4.8) defines as the motor ``M_mpt`` (its rotor
alone would drop the robot's position).

The same chains as plain 4x4 matrices, which the simulator renders with, are
:func:`cga_lessons.map3d.tour.homogeneous_chains`.

Frames (metres, radians): the world and the robot's base frame have x forward,
y to the left, z up (the laser of chapter 3 looks along +x); the base frame's
origin is the odometry point on the floor.  The stereo frame is at the left
camera's centre with axes parallel to the head (x forward, y left, z up); its
pinhole cameras (appendix A) are :meth:`Robot.stereo_rig`.  Pan turns about the
(nearly) vertical axis, positive to the left; tilt about the horizontal axis
across the head (the thesis's "x", our y because our robot drives along x),
positive looking *down*.

:class:`Robot` keeps every motor of the chains and, when one degree of freedom
changes, recomputes only the motors whose equations contain it (section 4.2.3:
"si cambia el valor de alguno de ellos, es necesario realizar el cálculo del
motor, rotor, o traslador en el cual intervenga").  The chain functions accept
arrays for the degrees of freedom, so 1,000 configurations cost one batch.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .chains import check_entity, unified
from .motors import FIXED_PARTS, MOTOR_DOFS, MOTOR_INPUTS, build_motor, fixed_parts
from .parameters import pose_matrix
from .state import DOFS, RobotGeometry, RobotState, check_changes

__all__ = ["Robot", "RobotFrames"]


@dataclass(frozen=True, eq=False)
class RobotFrames:
    """The robot's frames as 4x4 poses (world from frame, :meth:`Robot.frames`): ``base``, ``laser``, ``head``
    (at the point nearest both pan-tilt axes), ``camera_left`` and ``camera_right``, each an array (4, 4)."""

    base: np.ndarray
    laser: np.ndarray
    head: np.ndarray
    camera_left: np.ndarray
    camera_right: np.ndarray

    def __post_init__(self):
        checks.record(self, **{f.name: pose_matrix for f in fields(self)})


# ----------------------------------------------------------------- the robot
class Robot:
    """Geometer: fixed geometry, current :class:`RobotState` and every motor of its chains, kept up to date.

    ``robot.update(pan=0.3)`` changes one degree of freedom and recomputes
    only the motors that depend on it (:data:`~cga_lessons.map3d.motors.MOTOR_INPUTS`); it returns their
    names, and ``robot.evaluations`` counts how often each motor was built.

    >>> r = Robot()
    >>> r.update(pan=0.3)
    ('R_pan', 'R_pt', 'T_opt', 'M_mpt', 'M_eu', 'R_Lpan', 'M_eu_lines')
    >>> r.update(x=1.0)
    ('T_pos', 'M_pos', 'M_lu', 'M_mpt', 'M_eu', 'M_eu_lines')
    """

    def __init__(self, geometry: RobotGeometry | None = None, state: RobotState | None = None):
        if geometry is not None:
            checks.instance(geometry, "Robot", "geometry", RobotGeometry, "a RobotGeometry or None")
        if state is not None:
            checks.instance(state, "Robot", "state", RobotState, "a RobotState or None")
        self.geometry = geometry or RobotGeometry()
        self._fixed = fixed_parts(self.geometry)
        self.motors = {k: self._fixed[k] for k in FIXED_PARTS}
        self.evaluations = dict.fromkeys(MOTOR_INPUTS, 0)
        self.state = RobotState()
        self._check(state or self.state, "Robot", "state")
        self.state = state or self.state
        self.last_updated = self._recompute(set(DOFS))

    # -- fixed parts
    @property
    def L_pan(self) -> Multivector:
        """The pan axis as a conformal line (dual form, 2.81), base frame."""
        return self._fixed["L_pan"]

    @property
    def L_tilt(self) -> Multivector:
        """The tilt axis at pan = 0 as a conformal line (dual form, 2.81), base frame."""
        return self._fixed["L_tilt"]

    @property
    def eje_point(self) -> np.ndarray:
        """The point nearest both pan-tilt axes (the translation of ``T_eje``), base frame, shape (3,)."""
        return self._fixed["eje_point"].copy()

    def __getitem__(self, name: str) -> Multivector:
        if name not in self.motors:
            raise checks.fail("Robot", "name", f"no motor {name!r}; known: {sorted(self.motors)}")
        return self.motors[name]

    # -- state changes
    def _check(self, state: RobotState, func: str, arg: str | None):
        """``state`` within the joint ranges; errors name ``arg`` (None: the degree of freedom itself)."""
        checks.instance(state, func, arg or "state", RobotState, "a RobotState")
        for name, (lo, hi) in (("pan", self.geometry.pan_limits), ("tilt", self.geometry.tilt_limits)):
            v = getattr(state, name)
            if not lo <= v <= hi:
                raise checks.fail(func, arg or name, f"{name} = {v:.4f} rad is outside its range [{lo:.4f}, {hi:.4f}]")

    def _recompute(self, changed: set) -> tuple:
        vals = {n: getattr(self.state, n) for n in DOFS}
        done = []
        for name in MOTOR_INPUTS:
            if MOTOR_DOFS[name] & changed:
                self.motors[name] = build_motor(name, self.motors, vals)
                self.evaluations[name] += 1
                done.append(name)
        return tuple(done)

    def set_state(self, state: RobotState) -> tuple:
        """Move to ``state``; recompute only the motors touched by the changed degrees of freedom."""
        self._check(state, "Robot.set_state", "state")
        return self._move(state)

    def _move(self, state: RobotState) -> tuple:
        changed = set(self.state.changed(state))
        self.state = state
        self.last_updated = self._recompute(changed)
        return self.last_updated

    def update(self, **dofs) -> tuple:
        """Change some degrees of freedom (``x=..., pan=...``); returns the names of the recomputed motors."""
        f = "Robot.update"
        state = replace(self.state, **check_changes(dofs, f))
        self._check(state, f, None)
        return self._move(state)

    # -- using the chains
    def laser_to_unified(self, X: Multivector) -> Multivector:
        """An entity seen by the laser, in the unified frame: ``M_lu X ~M_lu`` (4.4)."""
        f = "Robot.laser_to_unified"
        return unified(self.motors["M_lu"], check_entity(X, f), f)

    def stereo_to_unified(self, X: Multivector, about_lines: bool = False) -> Multivector:
        """An entity seen by the stereo head, in the unified frame: ``M_eu X ~M_eu`` (4.10).

        ``about_lines=True`` uses the chain about the axis lines (2.109) instead.
        """
        f = "Robot.stereo_to_unified"
        about_lines = checks.flag(about_lines, f, "about_lines")
        return unified(self.motors["M_eu_lines" if about_lines else "M_eu"], check_entity(X, f), f)

    def stereo_rig(self):
        """The stereo pair in the stereo frame: left camera at the origin looking along +x (a :class:`StereoRig`)."""
        from cga_lessons.stereo import stereo_head

        g = self.geometry
        return stereo_head(g.baseline, g.focal_px, tuple(g.image_size), None, (0.0, -g.baseline / 2, 0.0), 0.0, 0.0)

    def frames(self) -> RobotFrames:
        """4x4 poses (world from frame): ``base``, ``laser``, ``head`` (pan-tilt point), ``camera_left/right``."""
        M = self.motors
        right = np.eye(4)
        right[1, 3] = -self.geometry.baseline
        left = cga.motor_to_matrix(M["M_eu"])
        return RobotFrames(
            base=cga.motor_to_matrix(M["M_pos"]),
            laser=cga.motor_to_matrix(M["M_lu"]),
            head=cga.motor_to_matrix(M["T_ep"] * M["M_mpt"]),
            camera_left=left,
            camera_right=left @ right,
        )
