"""Tests of the kinematic chains of motors (cga_lessons.kinematics*, the thesis's future work 6.2.2).

The truths are independent of the code under test:

* Denavit-Hartenberg forward kinematics with plain 4x4 matrices, written here from the published tables
  (standard DH for the UR5, modified DH for the Panda);
* a peer library, pytransform3d (product of exponentials with its own exponential map, and its logarithm);
* central finite differences of the forward kinematics for the Jacobian;
* the robot geometer's motors as today's ``cga_lessons.map3d.robot`` builds them (4.1-4.10);
* the package's own G(4,1) products, rotors about lines (2.109), translators (2.100) and logarithms.
"""

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons import kinematics as kin
from cga_lessons import map3d as rb
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.conformal import motor_log
from cga_lessons.kinematics.arms import DHParameters, dh_chain, panda, ur5
from cga_lessons.kinematics.ik import IKOptions, inverse_kinematics, twist_error
from cga_lessons.kinematics.motor_numbers import multiply_batches
from cga_lessons.map3d import geometer_chains

N = 1000
TOL = 1e-12
RNG_SEED = 20070607

# The published tables, typed in again here (not imported from the code under test).
UR5 = dict(  # Universal Robots, standard DH
    d=[0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823],
    a=[0.0, -0.425, -0.39225, 0.0, 0.0, 0.0],
    alpha=[np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0],
)
PANDA = dict(  # Franka Emika, modified DH (Craig): row i holds a_{i-1}, d_i, alpha_{i-1}; then the flange
    a=[0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088],
    d=[0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0],
    alpha=[0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2],
    flange=0.107,
)


# ---------------------------------------------------------------- independent 4x4 truth
def dh_standard(q, d, a, alpha):
    """T = prod_i Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i), q of shape (N, n)."""
    q = np.atleast_2d(q)
    T = np.tile(np.eye(4), (len(q), 1, 1))
    for i in range(q.shape[1]):
        ct, st, ca, sa = np.cos(q[:, i]), np.sin(q[:, i]), np.cos(alpha[i]), np.sin(alpha[i])
        A = np.zeros((len(q), 4, 4))
        A[:, 0] = np.stack([ct, -st * ca, st * sa, a[i] * ct], -1)
        A[:, 1] = np.stack([st, ct * ca, -ct * sa, a[i] * st], -1)
        A[:, 2, 1:] = [sa, ca, d[i]]
        A[:, 3, 3] = 1.0
        T = T @ A
    return T


def dh_modified(q, d, a, alpha, flange=0.0):
    """T = prod_i Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i), then Tz(flange)."""
    q = np.atleast_2d(q)
    T = np.tile(np.eye(4), (len(q), 1, 1))
    for i in range(q.shape[1]):
        ct, st, ca, sa = np.cos(q[:, i]), np.sin(q[:, i]), np.cos(alpha[i]), np.sin(alpha[i])
        A = np.zeros((len(q), 4, 4))
        A[:, 0] = np.stack([ct, -st, np.zeros_like(ct), np.full_like(ct, a[i])], -1)
        A[:, 1] = np.stack([st * ca, ct * ca, np.full_like(ct, -sa), np.full_like(ct, -sa * d[i])], -1)
        A[:, 2] = np.stack([st * sa, ct * sa, np.full_like(ct, ca), np.full_like(ct, ca * d[i])], -1)
        A[:, 3, 3] = 1.0
        T = T @ A
    F = np.eye(4)
    F[2, 3] = flange
    return T @ F


def ur5_truth(q):
    return dh_standard(q, **UR5)


def panda_truth(q):
    return dh_modified(q, **PANDA)


def pose_errors(H, T):
    """Largest position error (m) and largest rotation-matrix entry error over a batch."""
    return float(np.abs(H[..., :3, 3] - T[..., :3, 3]).max()), float(np.abs(H[..., :3, :3] - T[..., :3, :3]).max())


ARMS = {"ur5": (ur5, ur5_truth, 6), "panda": (panda, panda_truth, 7)}


@pytest.fixture
def rng():
    """A fresh generator per test: each test draws the same numbers however the tests are selected."""
    return np.random.default_rng(RNG_SEED)


# ---------------------------------------------------------------- forward kinematics
@pytest.mark.parametrize("arm", sorted(ARMS))
def test_forward_kinematics_equals_dh_matrices_over_1000_configurations(arm, rng):
    build, truth, n = ARMS[arm]
    ch = build()
    q = rng.uniform(-np.pi, np.pi, (N, n))
    H = kin.forward_matrix(ch, q)
    T = truth(q)
    pos, rot = pose_errors(H, T)
    print(f"\n{arm}: FK vs DH over {N} configurations: position {pos:.2e} m, rotation {rot:.2e}")
    assert pos <= TOL and rot <= TOL
    # one configuration at a time gives the same, as matrix and as motor
    for i in range(3):
        assert np.allclose(kin.forward_matrix(ch, q[i]), T[i], rtol=0, atol=TOL)
        assert np.allclose(cga.motor_to_matrix(kin.forward_motor(ch, q[i])), T[i], rtol=0, atol=TOL)
    assert kin.forward_motor(ch, q).shape == (N,)
    # the home motor is the pose at q = 0
    assert np.allclose(cga.motor_to_matrix(ch.home), truth(np.zeros((1, n)))[0], rtol=0, atol=TOL)


def peer_forward(S, M, q):
    """Product of exponentials with pytransform3d's batched exponential map and concatenation (its docs' way)."""
    ptr = pytest.importorskip("pytransform3d.trajectories")
    T = ptr.transforms_from_exponential_coordinates(S[0] * q[:, :1])
    for i in range(1, len(S)):
        # extrinsic convention, B2C left-multiplied: concat_many_to_many(A2B, B2C) = B2C A2B, so T <- T exp(S_i q_i)
        T = ptr.concat_many_to_many(ptr.transforms_from_exponential_coordinates(S[i] * q[:, i : i + 1]), T)
    return ptr.concat_one_to_many(M, T)  # T M


def screw_axes_from_dh(truth, n):
    """Screw axes (omega, p x omega) and home M from the DH truth itself: frame i-1 (standard) at q = 0."""
    S = []
    for i in range(n):
        if truth is ur5_truth:
            F = dh_standard(np.zeros((1, i)), **{k: v[:i] for k, v in UR5.items()})[0] if i else np.eye(4)
        else:  # the frame of joint i after Rx(alpha_{i-1}) Tx(a_{i-1}) (its z is the axis)
            d = PANDA["d"][:i] + [0.0]
            F = dh_modified(np.zeros((1, i + 1)), d, PANDA["a"][: i + 1], PANDA["alpha"][: i + 1])[0]
        z, p = F[:3, 2], F[:3, 3]
        S.append(np.r_[z, np.cross(p, z)])
    return np.array(S), truth(np.zeros((1, n)))[0]


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_forward_kinematics_equals_pytransform3d_product_of_exponentials(arm, rng):
    pytest.importorskip("pytransform3d")
    build, truth, n = ARMS[arm]
    S, M = screw_axes_from_dh(truth, n)
    q = rng.uniform(-np.pi, np.pi, (N, n))
    P = peer_forward(S, M, q)
    assert pose_errors(P, truth(q)) <= (1e-12, 1e-12)  # the peer agrees with DH (our axes are not involved)
    pos, rot = pose_errors(kin.forward_matrix(build(), q), P)
    print(f"\n{arm}: FK vs pytransform3d over {N} configurations: position {pos:.2e} m, rotation {rot:.2e}")
    assert pos <= TOL and rot <= TOL
    # our Jacobian at q = 0 is the list of screw axes (the axis lines at home)
    assert np.allclose(kin.spatial_jacobian(build(), np.zeros(n)).T, S, rtol=0, atol=TOL)


def random_motors(rng, n=200):
    axes, angles = rng.normal(size=(n, 3)), rng.uniform(0.0, np.pi * 0.999, n)
    angles[:5] = [0.0, 1e-9, 1e-5, 5e-3, 2e-2]  # the series near theta = 0 and its hand-over
    ts = rng.normal(size=(n, 3)) * 2.0
    c = np.array([kin.motor_coefficients(cga.motor(a, t_, s)) for a, t_, s in zip(axes, angles, ts)])
    return axes, angles, ts, c


def test_twist_error_is_the_logarithm_of_motor_log_eq_2_110(rng):
    axes, angles, ts, c = random_motors(rng)
    tw, t, angle = twist_error(c)
    assert np.allclose(t, ts, rtol=0, atol=1e-12) and np.allclose(angle, angles, rtol=0, atol=1e-12)
    for i in (0, 1, 2, 3, 4, 50, 120):
        B = motor_log(cga.motor(axes[i], angles[i], ts[i]))  # -theta/2 l + e ^ w: the inverse of (2.110)
        b = [B[k] for k in ("1", "e12", "e13", "e23", "e1-", "e2-", "e3-", "e123-")]
        assert np.allclose(kin.twist_of_bivector(b), tw[i], rtol=0, atol=1e-12)
    raises(r"twist_error: D: expected shape \(N, 8\), got \(200, 6\)", twist_error, c[:, :6])


def test_twist_error_is_pytransform3d_logarithm(rng):
    pt = pytest.importorskip("pytransform3d.trajectories")
    _, _, _, c = random_motors(rng)
    tw, _, _ = twist_error(c)
    peer = pt.exponential_coordinates_from_transforms(kin.coefficients_to_matrix(c))
    assert np.allclose(tw, peer, rtol=0, atol=1e-10)


def test_joint_motors_are_exp_of_the_axis_lines_eq_2_100_2_107_to_2_109(rng):
    """M(q) = M_1(q_1) ... M_n(q_n) M0 with M_i = exp(-q_i/2 L_i) (2.109) or exp(e d q/2) (2.100)."""
    joints = [kin.revolute(rng.normal(size=3), rng.normal(size=3)), kin.prismatic(rng.normal(size=3)),
              kin.revolute(rng.normal(size=3), rng.normal(size=3))]  # fmt: skip
    home = cga.motor(rng.normal(size=3), 0.8, rng.normal(size=3))
    ch = kin.chain(joints, home)
    for j in (joints[0], joints[2]):  # the axis is the unit line of (2.107): L* = e (t ^ r) + r E, L = L* Ic
        r, t = np.array(j.direction), np.array(j.point)
        Ld = cga.einf * (cga.vector(t) ^ cga.vector(r)) + cga.vector(r) * cga.E
        assert j.line.isclose(cga.standard_form(Ld)) and np.isclose(float((j.line * j.line).scalar()), -1.0)
    for q in rng.uniform(-4, 4, (5, 3)):
        M = cga.rotor_about_line(joints[0].line, q[0]) * cga.translator(q[1] * np.array(joints[1].direction))
        M = M * cga.exp(joints[2].line * (-q[2] / 2)) * home  # (2.109) through the package's exp (2.37)
        assert np.allclose(kin.forward_matrix(ch, q), cga.motor_to_matrix(M), rtol=0, atol=TOL)
        assert kin.forward_motor(ch, q).isclose(M, atol=1e-12) or kin.forward_motor(ch, q).isclose(-M, atol=1e-12)


def test_motor_numbers_products_and_matrices_match_the_algebra(rng):
    for _ in range(20):
        A = cga.motor(rng.normal(size=3), rng.uniform(-6, 6), rng.normal(size=3) * 5)
        B = cga.screw(rng.normal(size=3), rng.normal(size=3), rng.uniform(0.1, 3), rng.normal())
        a, b = kin.motor_coefficients(A), kin.motor_coefficients(B)
        assert np.allclose(multiply_batches(a[None], b[None])[0], kin.motor_coefficients(A * B), rtol=0, atol=1e-14)
        assert np.allclose(kin.coefficients_to_matrix(a), cga.motor_to_matrix(A), rtol=0, atol=1e-14)
        assert kin.coefficients_to_motor(a).isclose(A * (1.0 / float(np.linalg.norm(a[:4]))) * np.linalg.norm(a[:4]))
    assert np.allclose(kin.motor_coefficients(A * 3.0), kin.motor_coefficients(A))  # s M: the same motion


# ---------------------------------------------------------------- Jacobian
def fd_twists(ch, q, h=1e-5):
    """Central differences of the FK matrices, read as spatial twists: [omega^] = dR R^T, v = dp - omega x p."""
    H = kin.forward_matrix(ch, q)
    cols = []
    for i in range(ch.n):
        dq = np.zeros(ch.n)
        dq[i] = h
        dH = (kin.forward_matrix(ch, q + dq) - kin.forward_matrix(ch, q - dq)) / (2 * h)
        W = dH[:, :3, :3] @ np.swapaxes(H[:, :3, :3], 1, 2)
        w = np.stack([W[:, 2, 1], W[:, 0, 2], W[:, 1, 0]], -1)
        cols.append(np.concatenate([w, dH[:, :3, 3] - np.cross(w, H[:, :3, 3])], -1))
    return np.stack(cols, -1)


@pytest.mark.parametrize("arm", ["ur5", "panda", "geometer"])
def test_spatial_jacobian_equals_central_differences(arm, rng):
    ch = geometer_chains().camera if arm == "geometer" else ARMS[arm][0]()
    q = rng.uniform(-np.pi, np.pi, (300, ch.n))
    J = kin.spatial_jacobian(ch, q)
    err = float(np.abs(J - fd_twists(ch, q)).max())
    print(f"\n{arm}: Jacobian vs central differences (h = 1e-5) over 300 configurations: {err:.2e}")
    assert err <= 1e-9
    assert np.allclose(kin.spatial_jacobian(ch, q[7]), J[7], rtol=0, atol=1e-15)


def test_jacobian_columns_are_the_axis_lines_moved_by_the_joints_before(rng):
    ch = ur5()
    q = rng.uniform(-np.pi, np.pi, 6)
    J = kin.spatial_jacobian(ch, q)
    P = cga.G41.scalar(1.0)
    for i, j in enumerate(ch.joints):
        L = cga.apply(P, j.line)  # (2.103) on the axis line, with the package's sandwich
        r, m = np.asarray(cga.line_direction(L), float), np.asarray(cga.line_moment(L), float)
        assert np.allclose(J[:, i], np.r_[r, m], rtol=0, atol=1e-12)
        P = P * cga.rotor_about_line(j.line, q[i])


# ---------------------------------------------------------------- inverse kinematics
def ik_run(ch, truth, start, rng, n_targets=500):
    qt = rng.uniform(-np.pi, np.pi, (n_targets, ch.n))
    T = truth(qt)
    if start == "perturbed":
        q0 = qt + rng.uniform(-0.3, 0.3, qt.shape)
    else:
        q0 = rng.uniform(-np.pi, np.pi, qt.shape)
    r = inverse_kinematics(ch, T, q0, IKOptions(max_iterations=50))
    H = truth(r.q)  # checked with the independent FK
    pos = np.linalg.norm(H[:, :3, 3] - T[:, :3, 3], axis=1)
    rot = np.abs(H[:, :3, :3] - T[:, :3, :3]).max(axis=(1, 2))
    reached = r.converged & (pos <= 1e-9) & (rot <= 1e-9) & (r.iterations <= 50)
    it = r.iterations[r.converged]
    print(f"\n{ch.name} IK, {start} start, {n_targets} targets: reached {reached.mean():.1%} "
          f"(reported converged {r.converged.mean():.1%}); iterations median {np.median(it):.0f}, "
          f"95th percentile {np.percentile(it, 95):.0f}, max {it.max()}; worst position error "
          f"{pos[reached].max():.1e} m")  # fmt: skip
    assert np.all(r.converged <= ((pos <= 1e-9) & (rot <= 1e-9)))  # "converged" is never claimed falsely
    assert np.all(r.position_error[r.converged] <= 1e-10) and np.all(r.iterations <= 50)
    return reached.mean()


def geometer_truth(q):
    return kin.forward_matrix(geometer_chains().camera, q)


@pytest.mark.parametrize("arm", ["ur5", "panda"])
def test_ik_reaches_99_percent_of_targets_from_a_perturbed_start(arm, rng):
    build, truth, _ = ARMS[arm]
    assert ik_run(build(), truth, "perturbed", rng) >= 0.99


@pytest.mark.parametrize("arm", ["ur5", "panda"])
def test_ik_from_a_random_start_reports_honestly(arm, rng):
    build, truth, _ = ARMS[arm]
    assert ik_run(build(), truth, "random", rng) >= 0.85  # measured ~0.92 (UR5), ~0.98 (Panda)


def test_ik_on_the_geometer_and_its_single_target_form(rng):
    ch = geometer_chains().camera
    assert ik_run(ch, geometer_truth, "perturbed", rng, 200) >= 0.99
    target = kin.forward_motor(ch, [1.0, -2.0, 0.5, 0.3, 0.2])
    r = inverse_kinematics(ch, target, [0.5, -1.5, 0.0, 0.0, 0.0])
    assert r.converged is True and r.iterations > 0 and r.position_error <= 1e-10
    stuck = inverse_kinematics(ch, target, np.zeros(5), IKOptions(max_iterations=1))
    assert stuck.converged is False and stuck.iterations == 1  # out of iterations: reported as such


# ---------------------------------------------------------------- the robot geometer (4.1-4.10)
def geometer_samples(rng, n, g):
    return {
        "x": rng.uniform(-20, 20, n), "y": rng.uniform(-20, 20, n), "theta": rng.uniform(-np.pi, np.pi, n),
        "pan": rng.uniform(*g.pan_limits, n), "tilt": rng.uniform(*g.tilt_limits, n),
    }  # fmt: skip


def motor_matrices(M):
    return kin.coefficients_to_matrix(kin.motor_coefficients(M))


@pytest.mark.parametrize("skew", [False, True])
def test_geometer_chains_equal_todays_robot_code(skew, rng):
    g = rb.RobotGeometry(tilt_point=(-0.08, 0.0, 1.10), laser_mount=(0.3, 0.05, 0.35, 0.4)) if skew else None
    geo = geometer_chains(g)
    g = g or rb.RobotGeometry()
    c = geometer_samples(rng, N, g)
    q = np.column_stack([c[k] for k in rb.DOFS])
    m = rb.chain_motors(g, **c)
    cam = kin.forward_matrix(geo.camera, q)
    truth = m.M_eu_lines if skew else m.M_eu  # axes that miss: the footnote's chain about the lines
    assert pose_errors(cam, motor_matrices(truth)) <= (TOL, TOL)
    assert pose_errors(kin.forward_matrix(geo.laser, q[:, :3]), motor_matrices(m.M_lu)) <= (TOL, TOL)
    if not skew:  # the Robot class itself, one state at a time, read through the package's motor_to_matrix
        robot = rb.Robot(g)
        for i in range(20):
            robot.set_state(rb.RobotState(**{k: float(v[i]) for k, v in c.items()}))
            f = robot.frames()
            assert pose_errors(cam[i], f.camera_left) <= (TOL, TOL)
            assert pose_errors(kin.forward_matrix(geo.laser, q[i, :3]), f.laser) <= (TOL, TOL)


# ---------------------------------------------------------------- inputs
def raises(match, fn, *args, **kw):
    with pytest.raises(InvalidInputError, match=match):
        fn(*args, **kw)


def test_inputs_are_checked_and_named():
    ch = ur5()
    raises(r"forward_matrix: q: expected shape \(6,\)", kin.forward_matrix, ch, np.zeros(5))
    raises(r"forward_motor: q: expected shape", kin.forward_motor, ch, np.zeros((3, 6, 1)))
    raises(r"spatial_jacobian: q: contains NaN", kin.spatial_jacobian, ch, [0, 0, np.nan, 0, 0, 0])
    raises(r"forward_coefficients: q: contains NaN or inf", kin.forward_coefficients, ch, np.full(6, np.inf))
    raises(r"forward_matrix: q: must be an array of numbers", kin.forward_matrix, ch, np.array(["a"] * 6))
    raises(r"forward_matrix: chain: expected a Chain", kin.forward_matrix, "ur5", np.zeros(6))
    raises(r"revolute: axis: is the zero vector", kin.revolute, [0, 0, 0])
    raises(r"prismatic: direction: is the zero vector", kin.prismatic, [0.0, 0.0, 0.0])
    raises(r"prismatic: direction: contains NaN", kin.prismatic, [np.nan, 0.0, 1.0])
    raises(r"revolute: point: expected shape \(3,\), got \(2,\)", kin.revolute, [0, 0, 1], [1, 2])
    raises(r"revolute: axis: contains NaN or inf", kin.revolute, [0, np.inf, 1])
    circle = cga.circle_from_points([1, 0, 0], [0, 1, 0], [-1, 0, 0])
    raises(r"revolute: axis: not a line", kin.revolute, circle)  # a circle is grade 3 but not a line
    raises(r"revolute: axis: not a line", kin.revolute, cga.up([1.0, 2.0, 3.0]))  # a point
    raises(r"revolute: axis: not a line", kin.revolute, cga.sphere([0, 0, 0], 1.0))
    raises(r"chain: joints: expected a non-empty sequence", kin.chain, [])
    raises(r"chain: joints: expected a non-empty sequence", kin.chain, [cga.line_from_points([0, 0, 0], [0, 0, 1])])
    raises(r"chain: home: not an even versor", kin.chain, [kin.revolute([0, 0, 1])], cga.up([1.0, 0, 0]))
    raises(r"chain: home: .*reflection", kin.chain, [kin.revolute([0, 0, 1])], np.diag([1, 1, -1, 1]))
    raises(r"chain: home: contains NaN", kin.chain, [kin.revolute([0, 0, 1])], [np.nan, 0, 0])
    raises(r"DHParameters: d, a, alpha: must have the same length", DHParameters, "x", "standard", (1,), (1, 2), (0,))
    raises(r"DHParameters: convention", DHParameters, "x", "craig", (1,), (1,), (0,))
    raises(r"DHParameters: alpha: contains NaN", DHParameters, "x", "modified", (1,), (1,), (np.nan,))
    raises(r"dh_chain: p: expected DHParameters", dh_chain, UR5)
    raises(
        r"inverse_kinematics: target: expected shape \(4, 4\) or \(N, 4, 4\), got \(3, 3\)",
        inverse_kinematics,
        ch,
        np.eye(3),
        np.zeros(6),
    )
    raises(r"inverse_kinematics: target: contains NaN", inverse_kinematics, ch, np.full((4, 4), np.nan), np.zeros(6))
    raises(r"inverse_kinematics: q0: 2 starts for 3 targets", inverse_kinematics, ch, np.tile(np.eye(4), (3, 1, 1)),
           np.zeros((2, 6)))  # fmt: skip
    raises(r"inverse_kinematics: q0: expected shape", inverse_kinematics, ch, np.eye(4), np.zeros(7))
    raises(r"IKOptions: max_iterations", IKOptions, max_iterations=-1)
    raises(r"IKOptions: tol_position", IKOptions, tol_position=float("nan"))
    raises(r"geometer_chains: geometry", geometer_chains, "big")
    raises(r"Joint: kind", kin.Joint, "spherical", (0, 0, 1))
    raises(r"Joint: direction: is the zero vector", kin.Joint, "revolute", (0, 0, 0))
    raises(r"chain: home: not an even versor", kin.chain, [kin.revolute([0, 0, 1])], cga.sphere([0, 0, 0], 1.0))
    raises(r"forward_matrix: chain: expected a Chain", kin.forward_matrix, kin.revolute([0, 0, 1]), [0.0])
    raises(r"motor_coefficients: M: ", kin.motor_coefficients, cga.sphere([0, 0, 0], 1.0))
    with pytest.raises(DegenerateGeometryError, match=r"coefficients_to_matrix: c: the rotor part .* is zero"):
        kin.coefficients_to_matrix(np.zeros(8))
    assert issubclass(InvalidInputError, ValueError)


def test_inverse_kinematics_leaves_the_start_alone():
    arm = kin.chain([kin.revolute([0, 0, 1]), kin.revolute([0, 0, 1], point=[1, 0, 0])], home=[2.0, 0.0, 0.0])
    q0 = np.array([[0.3, 0.7], [0.1, -0.2]])
    before = q0.copy()
    r = inverse_kinematics(arm, kin.forward_motor(arm, np.array([[0.4, 0.9], [0.5, -0.1]])), q0)
    assert r.converged.all() and np.array_equal(q0, before)  # the solve works on a copy of q0


def test_joints_accept_lines_in_either_form_and_normalise_directions():
    L = cga.line_from_points([1.0, 2.0, 0.0], [1.0, 2.0, 5.0])
    a, b, c = kin.revolute(L), kin.revolute(cga.standard_form(L)), kin.revolute([0, 0, 1e-200], point=[1, 2, 7])
    for j in (a, b, c):
        assert np.allclose(j.direction, [0, 0, 1]) and np.allclose(j.point, [1, 2, 0])
    assert np.allclose(kin.prismatic([0, 3e200, 0]).direction, [0, 1, 0])
