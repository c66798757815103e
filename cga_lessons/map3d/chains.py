"""The motor chains of the robot *geometer*, one function per equation (4.1)-(4.10), and their fixed parts.

Each function takes the motors it multiplies, so the thesis's formula reads off
the code; :class:`cga_lessons.map3d.robot.Robot` keeps the motors up to date and
:data:`cga_lessons.map3d.robot.MOTOR_INPUTS` says which function builds which motor.
Degrees of freedom may be scalars or (N,) arrays (one configuration per entry).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector, finite_multivector
from cga_lessons.conformal import G41
from cga_lessons.kinematics import motor_coefficients
from cga_lessons.mapping2d import robot_motor

if TYPE_CHECKING:
    from .state import RobotGeometry

_Z = np.array([0.0, 0.0, 1.0])


# ----------------------------------------------------------------- input checks
#: The largest angle (radians) a rotor reads: beyond 2^52 no float precision is left for the angle itself.
ANGLE_LIMIT = 2.0**52
ANGLES = ("theta", "pan", "tilt")


def check_dof(v, func: str, name: str):
    """A degree of freedom: a finite number, or a non-empty (N,) array of them (one configuration per entry).

    The angles (``theta``, ``pan``, ``tilt``) are at most :data:`ANGLE_LIMIT` in magnitude.
    """
    scalar = not isinstance(v, (list, tuple)) and np.ndim(v) == 0
    out = checks.real(v, func, name) if scalar else checks.array(v, func, name, (None,), at_least=1)
    if name in ANGLES and np.any(np.abs(out) > ANGLE_LIMIT):
        raise checks.fail(func, name, f"angles beyond {ANGLE_LIMIT:.3g} rad have no float precision left")
    return out


def check_dofs(func: str, **dofs) -> dict:
    """Every degree of freedom checked (:func:`check_dof`); the arrays among them of one length."""
    out = {k: check_dof(v, func, k) for k, v in dofs.items()}
    arrays = {k: v for k, v in out.items() if isinstance(v, np.ndarray)}
    if len(arrays) > 1:
        checks.same_length(func, **arrays)
    return out


def check_motor(M, func: str, name: str) -> Multivector:
    """A numeric motor of G(4,1) (a rotor, a translator or their product), one or a batch (N,)."""
    motor_coefficients(M, func, name)  # the kinematics' reading of a motor's numbers refuses what is not one
    return M


def check_entity(X, func: str, name: str = "X") -> Multivector:
    """A conformal entity of G(4,1) with finite numeric coefficients (one, or a batch)."""
    checks.instance(X, func, name, Multivector, "a conformal entity (Multivector)")
    if X.algebra is not G41:
        raise checks.fail(func, name, f"expected an entity of G(4,1), got a multivector of {X.algebra!r}")
    for v in X.coeffs.values():
        a = np.asarray(v)
        if checks.is_symbolic(v) or a.dtype.kind not in "iuf":
            raise checks.fail(func, name, f"expected real numeric coefficients, got {type(v).__name__}")
        if not np.all(np.isfinite(a)):
            raise checks.fail(func, name, "contains NaN or inf")
    return X


def same_batch(func: str, **motors) -> None:
    """Motors (or entities) whose batches can multiply: one shape, or single ones with a batch."""
    shapes = {k: M.shape for k, M in motors.items() if M.shape}
    if len(set(shapes.values())) > 1:
        got = " and ".join(map(str, shapes.values()))
        raise checks.fail(func, ", ".join(shapes), f"batches of different shapes {got}")


# ----------------------------------------------------------------- fixed parts
def axis_line(point, direction, func):
    d = np.asarray(direction, float)
    if np.linalg.norm(d) < 1e-12:
        raise checks.degenerate(func, "direction", "an axis direction is the zero vector")
    p = np.asarray(point, float)
    return cga.line_from_points(p, p + d / np.linalg.norm(d))  # (2.81)


def axes_nearest_point(L1: Multivector, L2: Multivector) -> np.ndarray:
    """The point with the least distance to both lines: the midpoint of their common perpendicular.

    Directions (2.127) and closest points to the origin (2.129) of the two
    conformal lines give ``p_i + s_i r_i``; the feet of the common
    perpendicular solve a 2x2 system.  For axes that meet, it is their
    intersection.  Raises :class:`DegenerateGeometryError` for parallel lines
    (every point between them is as near).

    >>> import numpy as np
    >>> L1 = cga.line_from_points([0, 0, 0], [0, 0, 1.0]); L2 = cga.line_from_points([0.1, 0, 1], [0.1, 1, 1.0])
    >>> (axes_nearest_point(L1, L2) + 0.0).round(12).tolist()
    [0.05, 0.0, 1.0]
    """
    r1, r2 = np.asarray(cga.line_direction(L1), float), np.asarray(cga.line_direction(L2), float)
    p1, p2 = np.asarray(cga.line_closest_point(L1), float), np.asarray(cga.line_closest_point(L2), float)
    c = float(r1 @ r2)
    if 1.0 - c * c < 1e-12:
        raise checks.degenerate("axes_nearest_point", "L1, L2", "the two axes are parallel; no single nearest point")
    w = p1 - p2
    s1 = (c * (r2 @ w) - (r1 @ w)) / (1.0 - c * c)
    s2 = ((r2 @ w) - c * (r1 @ w)) / (1.0 - c * c)
    return 0.5 * ((p1 + s1 * r1) + (p2 + s2 * r2))


def laser_mount_motor(geometry: RobotGeometry) -> Multivector:
    """``M_lsr``: base frame to laser frame, (3.16) lifted by the laser's height (section 4.2.2).

    ``M_lsr = T_height M_laser-robot`` with ``M_laser-robot = T R`` of (3.16)
    (:func:`cga_lessons.mapping2d.conformal.robot_motor` of the mount).
    """
    lx, ly, h, yaw = (float(v) for v in geometry.laser_mount)
    return cga.translator([0.0, 0.0, h]) * robot_motor([lx, ly, yaw])


# ----------------------------------------------------------------- the chains, one function per equation
def base_rotor(theta) -> Multivector:
    """``R_pos``: rotor about z by the heading theta (2.96; the angle of 3.6). Scalar or (N,) theta."""
    return cga.rotor(_Z, check_dof(theta, "base_rotor", "theta"))


def base_translator(x, y) -> Multivector:
    """``T_pos``: translator by ``t = (x, y, 0)`` (2.100; the position of 3.7). Scalars or (N,) arrays."""
    v = check_dofs("base_translator", x=x, y=y)
    x, y = np.broadcast_arrays(np.asarray(v["x"]), np.asarray(v["y"]))
    return cga.translator(np.stack([x, y, np.zeros_like(x)], axis=-1))


def turned_laser_mount(R_pos: Multivector, M_lsr: Multivector) -> Multivector:
    """``M_cl = R_pos M_lsr ~R_pos``, Eq. (4.1): the laser mount turned with the robot."""
    return R_pos * M_lsr * ~R_pos


def base_motor(T_pos: Multivector, R_pos: Multivector) -> Multivector:
    """``M_pos = T_pos R_pos``, Eq. (4.2) corrected: the robot's motion (printed ``T_pos R_lsr``)."""
    return T_pos * R_pos


def base_motor_as_printed(T_pos: Multivector, R_lsr: Multivector) -> Multivector:
    """Eq. (4.2) as printed, ``M_pos = T_pos R_lsr`` (``R_lsr`` the laser's mounting rotor): an erratum."""
    f = "base_motor_as_printed"
    same_batch(f, T_pos=check_motor(T_pos, f, "T_pos"), R_lsr=check_motor(R_lsr, f, "R_lsr"))
    return T_pos * R_lsr


def laser_chain(T_pos: Multivector, M_cl: Multivector, R_pos: Multivector) -> Multivector:
    """``M_lu = T_pos M_cl R_pos = M_pos M_lsr``, Eq. (4.3) corrected: laser frame to unified frame.

    As printed, ``M_lu = M_cl M_pos`` (:func:`laser_chain_as_printed`) equals this
    only when the laser is not turned on the robot (then ``M_cl`` is a
    translation and commutes with ``T_pos``).
    """
    return T_pos * M_cl * R_pos


def laser_chain_as_printed(M_cl: Multivector, M_pos: Multivector) -> Multivector:
    """Eq. (4.3) as printed, ``M_lu = M_cl M_pos``: right only for a laser with no yaw on the robot."""
    f = "laser_chain_as_printed"
    same_batch(f, M_cl=check_motor(M_cl, f, "M_cl"), M_pos=check_motor(M_pos, f, "M_pos"))
    return M_cl * M_pos


def head_translator(R_pos: Multivector, T_eje: Multivector) -> Multivector:
    """``T_ep = R_pos T_eje ~R_pos``, Eq. (4.5): to the point nearest the pan-tilt axes, turned with the robot."""
    return R_pos * T_eje * ~R_pos


def head_rotor(R_pos: Multivector, R_pan: Multivector, R_tilt: Multivector) -> Multivector:
    """``R_pt = R_pos R_pan R_tilt``, Eq. (4.6): all the turns of robot and pan-tilt (tilt first)."""
    return R_pos * R_pan * R_tilt


def eye_translator(R_pt: Multivector, T_ojo: Multivector) -> Multivector:
    """``T_opt = R_pt T_ojo ~R_pt``, Eq. (4.7): on to the left camera, turned by every turn."""
    return R_pt * T_ojo * ~R_pt


def head_motor(T_pos: Multivector, R_pt: Multivector) -> Multivector:
    """``M_mpt = T_pos R_pt``, Eq. (4.8): the robot's position with every turn."""
    return T_pos * R_pt


def stereo_chain(T_opt: Multivector, T_ep: Multivector, M_mpt: Multivector) -> Multivector:
    """``M_eu = T_opt T_ep M_mpt``, Eq. (4.9) corrected: stereo frame to unified frame (printed ``... R_mpt``)."""
    return T_opt * T_ep * M_mpt


def stereo_chain_as_printed(T_opt: Multivector, T_ep: Multivector, R_pt: Multivector) -> Multivector:
    """Eq. (4.9) as printed, ``T_opt T_ep R_mpt``, with ``R_mpt`` read as the rotor of ``M_mpt`` (= R_pt)."""
    f = "stereo_chain_as_printed"
    motors = {k: check_motor(M, f, k) for k, M in (("T_opt", T_opt), ("T_ep", T_ep), ("R_pt", R_pt))}
    same_batch(f, **motors)
    return T_opt * T_ep * R_pt


def stereo_chain_about_lines(
    T_pos: Multivector, R_pos: Multivector, R_Lpan: Multivector, R_Ltilt: Multivector, M_eye: Multivector
) -> Multivector:
    """The stereo chain with the pan-tilt turns about the axis lines themselves (2.109; the footnote of 4.2.2).

    ``M = T_pos R_pos R_Lpan R_Ltilt M_eye`` with ``R_L = exp(-angle/2 L)``
    about ``L_pan`` and ``L_tilt`` (home configuration, base frame) and
    ``M_eye = T_eje T_ojo`` the left camera at home.  It equals (4.9) when the
    axes meet at the point of ``T_eje``; for calibrated axes that miss each
    other it stays exact where (4.5)-(4.9) approximate.
    """
    return T_pos * R_pos * R_Lpan * R_Ltilt * M_eye


def to_unified(M: Multivector, X: Multivector) -> Multivector:
    """``x' = M x ~M``, Eqs. (4.4), (4.10): any entity (point, pair, line, circle, plane, sphere) to the unified frame.

    ``M`` may hold a batch of motors (N,) matching a batch of entities (N,):
    entity i is moved by motor i.
    """
    return unified(check_motor(M, "to_unified", "M"), check_entity(X, "to_unified"), "to_unified")


def unified(M: Multivector, X: Multivector, func: str) -> Multivector:
    """:func:`to_unified` of a checked motor and entity; ``func`` names the caller in errors."""
    same_batch(func, M=M, X=X)
    return finite_multivector(cga.apply(M, X), func, "X: the moved entity")
