"""Tests of the robot geometer's motor chains (cga_lessons.map3d.robot, thesis 4.1-4.10).

The truth is the same mechanism written with plain 4x4 homogeneous matrices
(Rodrigues rotations), built here from scratch; motors are compared through
the images of the basis vectors and the origin (M e_i ~M, M e0 ~M), which
read off the rotation and the translation without the large coefficients of
conformal points far from the origin.
"""

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons import map3d as rb
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.map3d.chains import axes_nearest_point, to_unified
from cga_lessons.map3d.motors import MOTOR_INPUTS
from cga_lessons.mapping2d.conformal import laser_motor

N = 1000
TOL = 1e-12


# ---------------------------------------------------------------- independent 4x4 truth
def _rod(axis, angle):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    ang = np.asarray(angle, float)[..., None, None]
    return np.eye(3) + np.sin(ang) * K + (1 - np.cos(ang)) * K @ K


def _H(R=None, t=None, n=N):
    H = np.tile(np.eye(4), (n, 1, 1))
    if R is not None:
        H[:, :3, :3] = R
    if t is not None:
        H[:, :3, 3] = t
    return H


def _about(point, direction, angle):
    R = _rod(direction, angle)
    p = np.asarray(point, float)
    return _H(R, p - R @ p)


def _nearest(p1, d1, p2, d2):
    d1, d2 = np.asarray(d1, float) / np.linalg.norm(d1), np.asarray(d2, float) / np.linalg.norm(d2)
    w = np.asarray(p1, float) - np.asarray(p2, float)
    A = np.array([[d1 @ d1, -d1 @ d2], [d1 @ d2, -d2 @ d2]])
    s, t = np.linalg.solve(A, [-(w @ d1), -(w @ d2)])
    return 0.5 * (p1 + s * d1 + p2 + t * d2)


def _truth(g, c):
    """4x4 poses of every frame of the chains for configurations c (dict of (N,) arrays)."""
    z = [0, 0, 1.0]
    Rz = _rod(z, c["theta"])
    t_pos = np.column_stack([c["x"], c["y"], np.zeros(N)])
    lx, ly, h, yaw = g.laser_mount
    H_lsr = _H(_rod(z, yaw)[None].repeat(N, 0), [lx, ly, h])
    eje = _nearest(np.array(g.pan_point), g.pan_direction, np.array(g.tilt_point), g.tilt_direction)
    R_pt = Rz @ _rod(g.pan_direction, c["pan"]) @ _rod(g.tilt_direction, c["tilt"])
    H_pos = _H(Rz, t_pos)
    H_cam = H_pos @ _about(g.pan_point, g.pan_direction, c["pan"]) @ _about(g.tilt_point, g.tilt_direction, c["tilt"])
    H_cam = H_cam @ _H(None, eje + np.asarray(g.eye_offset))
    return {
        "R_pos": _H(Rz),
        "T_pos": _H(None, t_pos),
        "M_pos": H_pos,
        "M_cl": _H(Rz) @ H_lsr @ _H(np.swapaxes(Rz, 1, 2)),
        "M_lu": H_pos @ H_lsr,
        "T_ep": _H(None, Rz @ eje),
        "R_pt": _H(R_pt),
        "T_opt": _H(None, R_pt @ np.asarray(g.eye_offset)),
        "M_mpt": _H(R_pt, t_pos),
        "M_eu": H_cam,
        "M_eu_lines": H_cam,
    }


def _matrices(M):
    """4x4 matrices (N, 4, 4) of a batch of motors, from M e_i ~M and M e0 ~M."""
    H = _H()
    for k, e in enumerate((cga.e1, cga.e2, cga.e3)):
        H[:, :3, k] = cga.euclidean(M * e * ~M)
    H[:, :3, 3] = cga.euclidean(M * cga.eo * ~M)
    return H


def _configs(seed=0, g=None):
    g = g or rb.RobotGeometry()
    rng = np.random.default_rng(seed)
    return {
        "x": rng.uniform(-20, 20, N),
        "y": rng.uniform(-20, 20, N),
        "theta": rng.uniform(-np.pi, np.pi, N),
        "pan": rng.uniform(*g.pan_limits, N),
        "tilt": rng.uniform(*g.tilt_limits, N),
    }


TURNED = rb.RobotGeometry(laser_mount=(0.2, 0.05, 0.35, 0.4))  # a laser turned 23 degrees on the robot
SKEW = rb.RobotGeometry(  # calibrated axes that miss each other by 1.5 cm and lean by about 1 degree
    pan_point=(0.01, -0.005, 1.0), pan_direction=(0.01, 0.015, 1.0),
    tilt_point=(0.025, 0.0, 1.1), tilt_direction=(0.02, 1.0, -0.01),
)  # fmt: skip


# ---------------------------------------------------------------- the chains against 4x4 matrices
@pytest.mark.parametrize("geometry", [rb.RobotGeometry(), TURNED], ids=["straight", "turned"])
def test_laser_chain_4_1_to_4_3_equals_homogeneous_matrices(geometry):
    c = _configs(1, geometry)
    m, H = rb.chain_motors(geometry, **c), _truth(geometry, c)
    for name in ("R_pos", "T_pos", "M_cl", "M_pos", "M_lu"):
        assert np.abs(_matrices(getattr(m, name)) - H[name]).max() < TOL, name


def test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices():
    c = _configs(2)
    g = rb.RobotGeometry()
    m, H = rb.chain_motors(g, **c), _truth(g, c)
    for name in ("T_ep", "R_pt", "T_opt", "M_mpt", "M_eu", "M_eu_lines"):
        assert np.abs(_matrices(getattr(m, name)) - H[name]).max() < TOL, name


def test_chain_about_lines_2_109_is_exact_for_axes_that_miss():
    c = _configs(3, SKEW)
    m, H = rb.chain_motors(SKEW, **c), _truth(SKEW, c)
    assert np.abs(_matrices(m.M_eu_lines) - H["M_eu_lines"]).max() < TOL
    # the thesis's chain (rotors about the axis directions at the nearest point) is then an approximation
    err = np.linalg.norm(_matrices(m.M_eu)[:, :3, 3] - H["M_eu"][:, :3, 3], axis=1)
    assert 1e-3 < err.max() < 0.05
    # ... whose rotation is still exact: both turn by the same axes' directions
    assert np.abs(_matrices(m.M_eu)[:, :3, :3] - H["M_eu"][:, :3, :3]).max() < TOL


def test_eq_4_2_erratum_printed_form_ignores_the_heading():
    c = _configs(4)
    g = rb.RobotGeometry()
    m, H = rb.chain_motors(g, **c), _truth(g, c)
    R_lsr = cga.rotor([0, 0, 1.0], g.laser_mount[3])  # the laser's mounting rotor (identity: it looks ahead)
    printed = rb.base_motor_as_printed(m.T_pos, R_lsr)
    assert np.abs(_matrices(m.M_pos) - H["M_pos"]).max() < TOL
    err = np.abs(_matrices(printed) - H["M_pos"])[:, :3, :3].max(axis=(1, 2))
    assert np.all(err[np.abs(c["theta"]) > 0.1] > 0.05)


def test_eq_4_3_erratum_printed_order_needs_a_straight_laser():
    for g, printed_ok in ((rb.RobotGeometry(), True), (TURNED, False)):
        c = _configs(5, g)
        m, H = rb.chain_motors(g, **c), _truth(g, c)
        printed = rb.laser_chain_as_printed(m.M_cl, m.M_pos)
        assert np.abs(_matrices(m.M_lu) - H["M_lu"]).max() < TOL
        err = np.abs(_matrices(printed) - H["M_lu"]).max()
        assert (err < TOL) if printed_ok else (err > 0.1)
    # corrected (4.3) = M_pos M_lsr, the 3D form of the corrected (3.17)
    assert np.abs(_matrices(m.M_lu) - _matrices(m.M_pos * m.M_lsr)).max() < TOL


def test_eq_4_9_erratum_rotor_alone_loses_the_position():
    c = _configs(6)
    g = rb.RobotGeometry()
    m, H = rb.chain_motors(g, **c), _truth(g, c)
    printed = rb.stereo_chain_as_printed(m.T_opt, m.T_ep, m.R_pt)
    miss = np.linalg.norm(_matrices(printed)[:, :3, 3] - H["M_eu"][:, :3, 3], axis=1)
    assert np.allclose(miss, np.hypot(c["x"], c["y"]), atol=1e-9)
    assert np.abs(_matrices(m.M_eu) - H["M_eu"]).max() < TOL


# ---------------------------------------------------------------- (4.4) and (4.10) on entities
def test_eq_4_4_moves_laser_entities_like_the_matrix():
    rng = np.random.default_rng(7)
    robot = rb.Robot(TURNED, rb.RobotState(2.0, -1.5, 0.8))
    H = _truth(TURNED, {k: np.full(N, getattr(robot.state, k)) for k in rb.DOFS})["M_lu"][0]
    pts = np.column_stack([rng.uniform(-4, 4, (20, 2)), np.zeros(20)])  # laser points, z = 0 in its frame
    moved = cga.down(robot.laser_to_unified(cga.up(pts)))
    assert np.allclose(moved, pts @ H[:3, :3].T + H[:3, 3], atol=1e-12)
    assert np.allclose(moved[:, 2], TURNED.laser_mount[2])  # at the laser's height
    PP = robot.laser_to_unified(cga.point_pair(pts[0], pts[1]))
    ends = np.array(cga.point_pair_endpoints(PP))
    assert np.allclose(np.sort(ends, axis=0), np.sort(moved[:2], axis=0), atol=1e-9)
    # in the plane it is chapter 3's corrected laser motor (3.17)
    lx, ly, h, yaw = TURNED.laser_mount
    M3 = laser_motor(robot.state.pose, (lx, ly, yaw))
    flat = cga.down(M3 * cga.up(pts) * ~M3)
    assert np.allclose(flat[:, :2], moved[:, :2], atol=1e-12) and np.allclose(flat[:, 2], 0.0, atol=1e-12)


def test_eq_4_10_moves_stereo_entities_like_the_matrix():
    rng = np.random.default_rng(8)
    state = rb.RobotState(3.0, 1.0, -2.0, 0.7, 0.4)
    robot = rb.Robot(state=state)
    H = _truth(robot.geometry, {k: np.full(N, getattr(state, k)) for k in rb.DOFS})["M_eu"][0]
    a, b, c, d = rng.normal(size=(4, 3)) + [2.0, 0.0, 0.0]
    w = lambda p: H[:3, :3] @ p + H[:3, 3]  # noqa: E731
    S = robot.stereo_to_unified(cga.sphere_from_points(a, b, c, d))
    c0, r0 = cga.sphere_center_radius(cga.sphere_from_points(w(a), w(b), w(c), w(d)))
    assert np.allclose(cga.sphere_center_radius(S)[0], c0) and np.isclose(cga.sphere_center_radius(S)[1], r0)
    P = robot.stereo_to_unified(cga.plane_from_points(a, b, c))
    n, dist = cga.plane_normal_distance(P)
    n0, d0 = cga.plane_normal_distance(cga.plane_from_points(w(a), w(b), w(c)))
    assert np.allclose(n, n0) and np.isclose(dist, d0)
    L = robot.stereo_to_unified(cga.line_from_points(a, b))
    assert np.allclose(cga.line_direction(L), (w(b) - w(a)) / np.linalg.norm(b - a))
    assert np.isclose(cga.point_line_distance(w(a), L), 0.0, atol=1e-9)
    Z = robot.stereo_to_unified(cga.circle_from_points(a, b, c))
    cz, rz, _ = cga.circle_center_radius(Z)
    cz0, rz0, _ = cga.circle_center_radius(cga.circle_from_points(w(a), w(b), w(c)))
    assert np.allclose(cz, cz0) and np.isclose(rz, rz0)


# ---------------------------------------------------------------- the robot object
EXPECTED = {  # which motors contain each degree of freedom, read off equations 4.1-4.9 (and 2.109)
    "x": {"T_pos", "M_pos", "M_lu", "M_mpt", "M_eu", "M_eu_lines"},
    "y": {"T_pos", "M_pos", "M_lu", "M_mpt", "M_eu", "M_eu_lines"},
    "theta": {"R_pos", "M_cl", "M_pos", "M_lu", "T_ep", "R_pt", "T_opt", "M_mpt", "M_eu", "M_eu_lines"},
    "pan": {"R_pan", "R_pt", "T_opt", "M_mpt", "M_eu", "R_Lpan", "M_eu_lines"},
    "tilt": {"R_tilt", "R_pt", "T_opt", "M_mpt", "M_eu", "R_Ltilt", "M_eu_lines"},
}


@pytest.mark.parametrize("dof", rb.DOFS)
def test_update_recomputes_only_the_motors_it_touches(dof):
    robot = rb.Robot(state=rb.RobotState(1.0, 2.0, 0.3, 0.2, 0.1))
    before = dict(robot.motors)
    counts = dict(robot.evaluations)
    done = robot.update(**{dof: getattr(robot.state, dof) + 0.25})
    assert set(done) == EXPECTED[dof]
    for name, M in robot.motors.items():
        if name in EXPECTED[dof]:
            assert robot.evaluations[name] == counts[name] + 1
        else:
            assert M is before[name]  # untouched: the very same object
    fresh = rb.Robot(state=robot.state)
    for name in MOTOR_INPUTS:
        assert robot[name].isclose(fresh[name], atol=1e-14), name
    assert robot.update() == ()  # nothing changed, nothing recomputed


def test_axes_nearest_point():
    L1 = cga.line_from_points([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    L2 = cga.line_from_points([0.02, -1.0, 1.1], [0.02, 1.0, 1.1])
    assert np.allclose(axes_nearest_point(L1, L2), [0.01, 0.0, 1.1], atol=1e-12)
    rng = np.random.default_rng(9)
    for _ in range(20):
        p1, d1, p2, d2 = rng.normal(size=(4, 3))
        got = axes_nearest_point(cga.line_from_points(p1, p1 + d1), cga.line_from_points(p2, p2 + d2))
        assert np.allclose(got, _nearest(p1, d1, p2, d2), atol=1e-9)
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        axes_nearest_point(L1, cga.line_from_points([1.0, 0, 0], [1.0, 0, 2.0]))


def test_stereo_rig_and_frames_match_the_chain():
    robot = rb.Robot(state=rb.RobotState(1.0, -0.5, 0.6, -0.4, 0.3))
    rig = robot.stereo_rig()
    assert np.allclose(rig.C1, 0.0) and np.allclose(rig.C2, [0.0, -robot.geometry.baseline, 0.0])
    assert np.allclose(rig.R1[2], [1.0, 0.0, 0.0])  # optical axis along the stereo frame's x
    F = robot.frames()
    H = _truth(robot.geometry, {k: np.full(N, getattr(robot.state, k)) for k in rb.DOFS})
    assert np.allclose(F.camera_left, H["M_eu"][0], atol=1e-12)
    assert np.allclose(F.laser, H["M_lu"][0], atol=1e-12) and np.allclose(F.base, H["M_pos"][0], atol=1e-12)
    assert np.allclose(F.camera_right[:3, 3], F.camera_left[:3, 3] - 0.12 * F.camera_left[:3, 1])


def test_bad_input_raises():
    with pytest.raises(InvalidInputError, match="theta"):
        rb.RobotState(theta=np.nan)
    with pytest.raises(InvalidInputError, match="unknown"):
        rb.RobotState().replace(roll=1.0)
    robot = rb.Robot()
    with pytest.raises(InvalidInputError, match="tilt"):
        robot.update(tilt=2.0)
    assert robot.state.tilt == 0.0  # a refused change leaves the robot as it was
    with pytest.raises(InvalidInputError, match="laser_mount"):
        rb.RobotGeometry(laser_mount=(0.1, 0.0, 0.3))
    with pytest.raises(InvalidInputError, match="RobotGeometry: baseline: is NaN or inf"):
        rb.RobotGeometry(baseline=np.inf)
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        rb.Robot(rb.RobotGeometry(tilt_direction=(0.0, 0.0, 1.0)))
    with pytest.raises(InvalidInputError, match="chain_motors: x: contains NaN or inf"):
        rb.chain_motors(x=np.array([0.0, np.inf]))
    with pytest.raises(InvalidInputError, match="no motor"):
        robot["M_xyz"]
    with pytest.raises(InvalidInputError, match="Multivector"):
        to_unified(robot["M_lu"], np.zeros(3))
    sphere = cga.sphere([0.0, 0.0, 0.0], 1.0)
    with pytest.raises(InvalidInputError, match="base_motor_as_printed: R_lsr: not an even versor"):
        rb.base_motor_as_printed(robot["T_pos"], sphere)  # a motor argument given a sphere
    with pytest.raises(InvalidInputError, match="Robot.update: roll: unknown degree of freedom"):
        robot.update(roll=0.1)
    with pytest.raises(InvalidInputError, match="base_rotor: theta: contains NaN or inf"):
        rb.base_rotor(np.array([0.0, np.nan]))
