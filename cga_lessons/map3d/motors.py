"""Every motor of the robot *geometer*'s chains at once (section 4.2.2, Eqs. 4.1-4.10): which degrees of freedom
and parts each is built from, the fixed parts, and :func:`chain_motors` for one or many configurations.

:data:`MOTOR_INPUTS` is the dependency graph that :class:`~cga_lessons.map3d.robot.Robot` follows to recompute
only the motors a changed degree of freedom touches; :func:`chain_motors` builds them all, for arrays of
configurations in one batch, as a :class:`ChainMotors`.
"""

from __future__ import annotations

from dataclasses import dataclass

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
    same_batch,
    stereo_chain,
    stereo_chain_about_lines,
    turned_laser_mount,
)
from .fits import check_kind
from .state import RobotGeometry

__all__ = ["MOTOR_INPUTS", "FIXED_PARTS", "MOTOR_DOFS", "fixed_parts", "build_motor", "ChainMotors", "chain_motors"]


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
#: The parts of the chains that no degree of freedom changes (the robot's geometry alone).
FIXED_PARTS = ("M_lsr", "T_eje", "T_ojo", "M_eye", "L_pan", "L_tilt", "pan_axis", "tilt_axis")


def _dof_sets() -> dict:
    out = {}
    for name, (dofs, inputs, _) in MOTOR_INPUTS.items():
        out[name] = frozenset(dofs).union(*(out.get(i, frozenset()) for i in inputs))
    return out


#: Each motor's degrees of freedom, direct or through its parts: what :class:`~cga_lessons.map3d.robot.Robot`
#: recomputes when one changes.
MOTOR_DOFS = _dof_sets()


def fixed_parts(geometry: RobotGeometry) -> dict:
    """The parts of the chains fixed by ``geometry``: :data:`FIXED_PARTS` by name, and ``eje_point``, the point
    nearest both pan-tilt axes (3,)."""
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


def build_motor(name: str, m: dict, v: dict) -> Multivector:
    """Motor ``name`` of :data:`MOTOR_INPUTS` from the degrees of freedom ``v`` and the motors and parts ``m``."""
    dofs, inputs, func = MOTOR_INPUTS[name]
    return func(*(v[d] for d in dofs), *(m[i] for i in inputs))


def _even(M, func: str, name: str) -> Multivector:
    """A numeric multivector of G(4,1) with finite coefficients on even blades only, as every motor is (the full
    test, :func:`cga_lessons.map3d.chains.check_motor`, normalises: it refuses translations near 1e300 m)."""
    check_entity(M, func, name)
    odd = sorted(k for k in M.coeffs if bin(k).count("1") % 2)
    if odd:
        raise checks.fail(func, name, f"a motor has even blades only, got odd ones {odd}")
    return M


@dataclass(frozen=True, eq=False)
class ChainMotors:
    """Every motor of the geometer's chains (:func:`chain_motors`), named as in section 4.2.2.

    Each field is a Multivector (one motor, or a batch: (N,) coefficient arrays), except the two axis directions.

    Attributes
    ----------
    R_pos, T_pos : Multivector
        The robot's heading and position (2.96, 2.100).
    M_cl, M_pos, M_lu : Multivector
        The laser's chain (4.1), (4.2), (4.3).
    R_pan, R_tilt : Multivector
        The pan and tilt rotors about the axes' directions.
    T_ep, R_pt, T_opt, M_mpt, M_eu : Multivector
        The stereo head's chain (4.5)-(4.9).
    R_Lpan, R_Ltilt, M_eu_lines : Multivector
        Pan and tilt about the axis lines themselves and the camera's chain through them (2.109).
    M_lsr, T_eje, T_ojo, M_eye : Multivector
        The fixed parts: the laser's mount, the translators to the point nearest both axes and on to the left
        camera, and ``M_eye = T_eje T_ojo``.
    L_pan, L_tilt : Multivector
        The pan and tilt axes as conformal lines (2.81), at home.
    pan_axis, tilt_axis : ndarray (3,)
        Their unit directions (2.127).
    """

    R_pos: Multivector
    T_pos: Multivector
    M_cl: Multivector
    M_pos: Multivector
    M_lu: Multivector
    R_pan: Multivector
    R_tilt: Multivector
    T_ep: Multivector
    R_pt: Multivector
    T_opt: Multivector
    M_mpt: Multivector
    M_eu: Multivector
    R_Lpan: Multivector
    R_Ltilt: Multivector
    M_eu_lines: Multivector
    M_lsr: Multivector
    T_eje: Multivector
    T_ojo: Multivector
    M_eye: Multivector
    L_pan: Multivector
    L_tilt: Multivector
    pan_axis: np.ndarray
    tilt_axis: np.ndarray

    def __post_init__(self):
        f = "ChainMotors"
        for name in (*MOTOR_INPUTS, "M_lsr", "T_eje", "T_ojo", "M_eye"):
            _even(getattr(self, name), f, name)
        for name in ("L_pan", "L_tilt"):
            check_kind(getattr(self, name), "line", f, name)
        checks.record(self, pan_axis=checks.vector3, tilt_axis=checks.vector3)
        # one batch for all (the robot's configurations), or single motors (those that no batched value reaches)
        same_batch(f, **{name: getattr(self, name) for name in MOTOR_INPUTS})


def chain_motors(geometry: RobotGeometry | None = None, *, x=0.0, y=0.0, theta=0.0, pan=0.0, tilt=0.0) -> ChainMotors:
    """Every motor of (4.1)-(4.9) (and the 2.109 variant) for one or many configurations.

    Degrees of freedom may be scalars or arrays of one shape (N,): the motors
    then hold (N,) coefficient arrays, one configuration per entry.

    Returns
    -------
    ChainMotors
        The motors named as in :data:`MOTOR_INPUTS`, and the fixed
        parts ``M_lsr``, ``T_eje``, ``T_ojo``, ``M_eye = T_eje T_ojo``, the axis
        lines ``L_pan``, ``L_tilt`` and their unit directions ``pan_axis``,
        ``tilt_axis`` (arrays).
    """
    f = "chain_motors"
    if geometry is not None:
        checks.instance(geometry, f, "geometry", RobotGeometry, "a RobotGeometry or None")
    vals = check_dofs(f, x=x, y=y, theta=theta, pan=pan, tilt=tilt)
    fixed = fixed_parts(geometry or RobotGeometry())
    m = {k: fixed[k] for k in FIXED_PARTS}
    for name in MOTOR_INPUTS:
        m[name] = build_motor(name, m, vals)
    return ChainMotors(**m)
