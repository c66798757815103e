"""Exercises of chapter 4, section 4.2 (notebook 08): the stereo chain as a 4x4, the erratum of (4.3), rotor order.

The truths are rotation matrices by Rodrigues' formula and 4x4 homogeneous matrices multiplied here, from the
numbers of the default :class:`~cga_lessons.map3d.robot.RobotGeometry` (data, not the chain code), and a closed form
worked out by hand for the printed (4.3).
"""

from __future__ import annotations

import numpy as np

from cga_lessons.stereo import rotation_matrix  # Rodrigues in plain NumPy: independent of the algebra

from .answers import Malformed, Wrong, as_array
from .checking import exercise
from .compare import compare_expression, compare_matrix, compare_vector


def _h(R=None, t=None) -> np.ndarray:
    H = np.eye(4)
    if R is not None:
        H[:3, :3] = R
    if t is not None:
        H[:3, 3] = t
    return H


def _nearest_point(p1, d1, p2, d2) -> np.ndarray:
    """Midpoint of the common perpendicular of two lines p + s d (closest points by the normal equations)."""
    p1, d1, p2, d2 = (np.asarray(v, float) for v in (p1, d1, p2, d2))
    A = np.array([[d1 @ d1, -(d1 @ d2)], [d1 @ d2, -(d2 @ d2)]])
    s = np.linalg.solve(A, [(p2 - p1) @ d1, (p2 - p1) @ d2])
    return 0.5 * ((p1 + s[0] * d1) + (p2 + s[1] * d2))


def _geometry():
    from cga_lessons.map3d import RobotGeometry

    return RobotGeometry()


_STATE = dict(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2)


def _camera_pose(order="pan-tilt", position=True) -> np.ndarray:
    """World-from-left-camera 4x4 of the default robot at ``_STATE``, as a plain matrix chain."""
    g = _geometry()
    s = _STATE
    eje = _nearest_point(g.pan_point, g.pan_direction, g.tilt_point, g.tilt_direction)
    pan, tilt = rotation_matrix(g.pan_direction, s["pan"]), rotation_matrix(g.tilt_direction, s["tilt"])
    head = pan @ tilt if order == "pan-tilt" else tilt @ pan
    base = _h(rotation_matrix([0, 0, 1], s["theta"]), [s["x"], s["y"], 0.0] if position else None)
    return base @ _h(t=eje) @ _h(head) @ _h(t=g.eye_offset)


@exercise(
    "ch4.1",
    title="the pose of the left camera, M_eu of (4.9), as a 4x4 matrix at x=1.5, y=-0.5, theta=2.0, pan=0.3, "
    "tilt=0.2 (default robot)",
    notebook="08_fused_3d_map",
    kind="compute",
    expects="a NumPy array of shape (4, 4): world from camera, [[R, t], [0, 0, 0, 1]]",
    equations=("4.5", "4.6", "4.7", "4.8", "4.9"),
)
def _ch4_1(answer):
    from cga_lessons.algebra import Multivector

    if isinstance(answer, Multivector):
        raise Malformed("that is the motor itself; give its 4x4 matrix (cga.motor_to_matrix)")
    truth = _camera_pose()
    printed = truth.copy()
    printed[:3, 3] -= [_STATE["x"], _STATE["y"], 0.0]  # R_pt in place of M_mpt: the robot's position drops out
    H = as_array(answer, (4, 4))
    if not np.allclose(H[3], [0, 0, 0, 1], atol=1e-9):
        raise Wrong("the last row of a homogeneous pose is (0, 0, 0, 1).")
    if not (np.allclose(H[:3, :3] @ H[:3, :3].T, np.eye(3), atol=1e-7) and np.linalg.det(H[:3, :3]) > 0):
        raise Wrong("the upper-left 3x3 block is not a rotation (R R^T = I, det R = 1).")
    if np.allclose(H[:3, :3], truth[:3, :3], atol=1e-7) and not np.allclose(H[:3, 3], truth[:3, 3], atol=1e-7):
        if np.allclose(H[:3, 3], printed[:3, 3], atol=1e-7):
            raise Wrong(
                "the rotation is right but the robot's position is missing: that is (4.9) as printed, with the "
                "rotor R_pt where the motor M_mpt of (4.8) belongs."
            )
        raise Wrong("the rotation is right; the camera's position is off.")
    hints = [
        (np.linalg.inv(truth), "that is the inverse: camera from world. The exercise asks for world from camera."),
        (
            _camera_pose(order="tilt-pan"),
            "the turns are in the wrong order: in R_pt = R_pos R_pan R_tilt (4.6) the tilt acts first.",
        ),
    ]
    if not np.allclose(H, truth, atol=1e-7) and not any(np.allclose(H, c, atol=1e-7) for c, _ in hints):
        good_t = np.allclose(H[:3, 3], truth[:3, 3], atol=1e-7)
        raise Wrong(
            "the rotation is off, and the camera's position is "
            + ("right." if good_t else "off too: check each factor of (4.5)-(4.9) against its definition.")
        )
    compare_matrix(H, truth, atol=1e-7, hints=hints)
    return "The motor chain and the 4x4 chain agree: a motor is a rigid motion, and its matrix is read off M e_i ~M."


@exercise(
    "ch4.2",
    title="derive how far (4.3) as printed, M_cl M_pos, puts the laser from where it is, for a laser turned by phi "
    "on a robot at (x, y, theta)",
    notebook="08_fused_3d_map",
    kind="derive",
    expects="a SymPy expression in x, y, theta, phi (a distance, for 0 < phi < pi)",
    equations=("4.1", "4.2", "4.3"),
)
def _ch4_2(answer):
    import sympy

    names = ("x", "y", "theta", "phi")
    s = {n: sympy.Symbol(n, real=True) for n in names}
    x, y, th, phi = s.values()
    # printed: R_pos t_lsr + R_phi t_pos; corrected: t_pos + R_pos t_lsr  ->  |R_phi t_pos - t_pos|
    truth = 2 * sympy.sqrt(x**2 + y**2) * sympy.sin(phi / 2)
    compare_expression(
        answer,
        truth,
        s,
        hints=[
            (sympy.Integer(0), "zero is what a laser that looks straight ahead (phi = 0) gives; this one is turned."),
            (
                sympy.sqrt(x**2 + y**2) * phi,
                "that is the arc length, the first-order approximation; give the exact (chord) distance.",
            ),
        ],
    )
    return (
        "The printed chain turns the robot's position t_pos by the mount's yaw: the laser lands 2 |t_pos| "
        "sin(phi/2) away, whatever the heading, and far from the origin even a small yaw puts it metres off."
    )


_TURN = dict(theta=0.3, pan=1.2, tilt=0.5)


@exercise(
    "ch4.3",
    title="where the camera looks (its +x axis, in the world) if (4.6) is written R_pos R_tilt R_pan, "
    "at theta=0.3, pan=1.2, tilt=0.5",
    notebook="08_fused_3d_map",
    kind="break",
    expects="a NumPy array of shape (3,): a unit vector",
    equations=("4.6", "2.99"),
)
def _ch4_3(answer):
    g = _geometry()
    Rz = rotation_matrix([0, 0, 1], _TURN["theta"])
    pan, tilt = rotation_matrix(g.pan_direction, _TURN["pan"]), rotation_matrix(g.tilt_direction, _TURN["tilt"])
    x = np.array([1.0, 0.0, 0.0])
    truth = Rz @ tilt @ pan @ x
    right = Rz @ pan @ tilt @ x
    compare_vector(
        answer,
        truth,
        atol=1e-9,
        hints=[
            (right, "that is where the camera looks with the thesis's order R_pos R_pan R_tilt; swap the two."),
            (tilt @ pan @ x, "the robot's heading is missing: R_pos still turns everything."),
            (Rz @ pan @ x, "the tilt is missing."),
        ],
    )
    return (
        "With the tilt applied after the pan it turns about the robot's fixed y axis, not across the head: "
        "the camera rolls and looks the wrong way. The rightmost rotor acts first."
    )
