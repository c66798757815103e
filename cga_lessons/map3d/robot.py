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

from dataclasses import replace

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .chains import (
    axes_nearest_point,
    axis_line,
    base_motor,
    base_rotor,
    base_translator,
    check_dofs,
    check_entity,
    eye_translator,
    head_motor,
    head_rotor,
    head_translator,
    laser_chain,
    laser_mount_motor,
    stereo_chain,
    stereo_chain_about_lines,
    turned_laser_mount,
    unified,
)
from .state import DOFS, RobotGeometry, RobotState, check_changes

__all__ = ["Robot", "chain_motors", "MOTOR_INPUTS"]


# ----------------------------------------------------------------- dependency graph
def _axis_rotor(angle, axis):
    """The thesis's R_pan / R_tilt: a rotor about the axis *direction* (2.96), placed by T_eje in (4.5)-(4.9)."""
    return cga.rotor(axis, angle)


def _line_rotor(angle, L):
    """R_L = exp(-angle/2 L) about the axis line itself (2.109; the footnote of 4.2.2)."""
    return cga.rotor_about_line(L, angle)


#: Each motor of the chains: ``(degrees of freedom it reads, parts it is built from, function)``; the
#: function takes the degrees of freedom, then the parts.  Insertion order is a topological order.
MOTOR_INPUTS = {
    "R_pos": (("theta",), (), base_rotor),
    "T_pos": (("x", "y"), (), base_translator),
    "M_cl": ((), ("R_pos", "M_lsr"), turned_laser_mount),
    "M_pos": ((), ("T_pos", "R_pos"), base_motor),
    "M_lu": ((), ("T_pos", "M_cl", "R_pos"), laser_chain),
    "R_pan": (("pan",), ("pan_axis",), _axis_rotor),
    "R_tilt": (("tilt",), ("tilt_axis",), _axis_rotor),
    "T_ep": ((), ("R_pos", "T_eje"), head_translator),
    "R_pt": ((), ("R_pos", "R_pan", "R_tilt"), head_rotor),
    "T_opt": ((), ("R_pt", "T_ojo"), eye_translator),
    "M_mpt": ((), ("T_pos", "R_pt"), head_motor),
    "M_eu": ((), ("T_opt", "T_ep", "M_mpt"), stereo_chain),
    "R_Lpan": (("pan",), ("L_pan",), _line_rotor),
    "R_Ltilt": (("tilt",), ("L_tilt",), _line_rotor),
    "M_eu_lines": ((), ("T_pos", "R_pos", "R_Lpan", "R_Ltilt", "M_eye"), stereo_chain_about_lines),
}
_FIXED = ("M_lsr", "T_eje", "T_ojo", "M_eye", "L_pan", "L_tilt", "pan_axis", "tilt_axis")


def _dof_sets() -> dict:
    out = {}
    for name, (dofs, inputs, _) in MOTOR_INPUTS.items():
        out[name] = frozenset(dofs).union(*(out.get(i, frozenset()) for i in inputs))
    return out


_DEPENDS = _dof_sets()


def _fixed_parts(geometry: RobotGeometry) -> dict:
    g = geometry
    L_pan = axis_line(g.pan_point, g.pan_direction, "Robot")
    L_tilt = axis_line(g.tilt_point, g.tilt_direction, "Robot")
    eje = axes_nearest_point(L_pan, L_tilt)
    T_eje, T_ojo = cga.translator(eje), cga.translator(np.asarray(g.eye_offset, float))
    return {
        "M_lsr": laser_mount_motor(g),
        "T_eje": T_eje,
        "T_ojo": T_ojo,
        "M_eye": T_eje * T_ojo,
        "L_pan": L_pan,
        "L_tilt": L_tilt,
        "eje_point": eje,
        "pan_axis": np.asarray(cga.line_direction(L_pan), float),
        "tilt_axis": np.asarray(cga.line_direction(L_tilt), float),
    }


def _build(name: str, m: dict, v: dict) -> Multivector:
    dofs, inputs, func = MOTOR_INPUTS[name]
    return func(*(v[d] for d in dofs), *(m[i] for i in inputs))


def chain_motors(geometry: RobotGeometry | None = None, *, x=0.0, y=0.0, theta=0.0, pan=0.0, tilt=0.0) -> dict:
    """Every motor of (4.1)-(4.9) (and the 2.109 variant) for one or many configurations.

    Degrees of freedom may be scalars or arrays of one shape (N,): the motors
    then hold (N,) coefficient arrays, one configuration per entry.

    Returns
    -------
    dict
        name -> Multivector for the names of :data:`MOTOR_INPUTS`, and the fixed
        parts ``M_lsr``, ``T_eje``, ``T_ojo``, ``M_eye = T_eje T_ojo``, the axis
        lines ``L_pan``, ``L_tilt`` and their unit directions ``pan_axis``,
        ``tilt_axis`` (arrays).
    """
    f = "chain_motors"
    if geometry is not None:
        checks.instance(geometry, f, "geometry", RobotGeometry, "a RobotGeometry or None")
    vals = check_dofs(f, x=x, y=y, theta=theta, pan=pan, tilt=tilt)
    fixed = _fixed_parts(geometry or RobotGeometry())
    m = {k: fixed[k] for k in _FIXED}
    for name in MOTOR_INPUTS:
        m[name] = _build(name, m, vals)
    return m


# ----------------------------------------------------------------- the robot
class Robot:
    """Geometer: fixed geometry, current :class:`RobotState` and every motor of its chains, kept up to date.

    ``robot.update(pan=0.3)`` changes one degree of freedom and recomputes
    only the motors that depend on it (:data:`MOTOR_INPUTS`); it returns their
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
        self._fixed = _fixed_parts(self.geometry)
        self.motors = {k: self._fixed[k] for k in _FIXED}
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
            if _DEPENDS[name] & changed:
                self.motors[name] = _build(name, self.motors, vals)
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

    def frames(self) -> dict:
        """4x4 poses (world from frame): ``base``, ``laser``, ``head`` (pan-tilt point), ``camera_left/right``."""
        M = self.motors
        out = {
            "base": cga.motor_to_matrix(M["M_pos"]),
            "laser": cga.motor_to_matrix(M["M_lu"]),
            "head": cga.motor_to_matrix(M["T_ep"] * M["M_mpt"]),
            "camera_left": cga.motor_to_matrix(M["M_eu"]),
        }
        right = np.eye(4)
        right[1, 3] = -self.geometry.baseline
        out["camera_right"] = out["camera_left"] @ right
        return out
