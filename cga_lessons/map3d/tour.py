"""A tour of the synthetic world: the robot scans with its laser and looks around with its stereo head.

:func:`simulate_tour` drives the robot along a closed loop scanning with the
laser of chapter 3 (odometry drifts), stopping at a few places to look around
with the stereo head at several pan/tilt settings.  The cameras are rendered
with the plain 4x4 chain of the mechanism (:func:`homogeneous_chains`), so the
motor chains that bring the entities back are checked against an independent
truth.  What the cameras see of each object is labelled by the simulator (the
matching problem of stereo is not the subject here, as in notebook 07);
objects do not occlude one another in the bundled layout.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from cga_lessons import checks, stereo
from cga_lessons.mapping2d import OdometryModel, simulate_odometry, simulate_scan

from .chains import check_dofs
from .parameters import pose_matrix
from .robot import Robot
from .state import RobotGeometry, RobotState
from .world import World3D, default_world

__all__ = [
    "HomogeneousChains",
    "homogeneous_chains",
    "waypoint_tour",
    "View",
    "Tour",
    "simulate_tour",
    "triangulate_view",
]

_Z = np.array([0.0, 0.0, 1.0])


# ----------------------------------------------------------------- the robot as plain 4x4 matrices (the truth)
def _rot(axis, angle):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    ang = np.asarray(angle, float)[..., None, None]
    K = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + np.sin(ang) * K + (1.0 - np.cos(ang)) * (K @ K)


def _h(R=None, t=None, shape=()):
    H = np.broadcast_to(np.eye(4), shape + (4, 4)).copy()
    if R is not None:
        H[..., :3, :3] = R
    if t is not None:
        H[..., :3, 3] = t
    return H


@dataclass(frozen=True, eq=False)
class HomogeneousChains:
    """The robot's poses as plain 4x4 matrices (:func:`homogeneous_chains`): ``base``, ``laser`` and
    ``camera_left`` (world from frame), each an array (4, 4), or (N, 4, 4) for N configurations."""

    base: np.ndarray
    laser: np.ndarray
    camera_left: np.ndarray

    def __post_init__(self):
        checks.record(self, **{f.name: pose_matrix for f in fields(self)})


def homogeneous_chains(
    geometry: RobotGeometry | None = None, *, x=0.0, y=0.0, theta=0.0, pan=0.0, tilt=0.0
) -> HomogeneousChains:
    """The laser and left-camera poses as plain 4x4 matrices (Rodrigues rotations), for one or many configurations.

    The mechanism as a robotics text writes it (product of exponentials):
    ``H_laser = H_pos H_lsr`` and ``H_cam = H_pos H_pan H_tilt H_eye`` with
    ``H_pan``, ``H_tilt`` rotations about the axis lines (home configuration)
    and ``H_eye`` the left camera at home.  The simulator renders with these;
    the tests hold the motor chains against them.

    Returns
    -------
    HomogeneousChains
        ``laser``, ``camera_left``, ``base``: arrays (4, 4) or (N, 4, 4).
    """
    f = "homogeneous_chains"
    if geometry is not None:
        checks.instance(geometry, f, "geometry", RobotGeometry, "a RobotGeometry or None")
    g = geometry or RobotGeometry()
    dofs = check_dofs(f, x=x, y=y, theta=theta, pan=pan, tilt=tilt).values()
    x, y, theta, pan, tilt = np.broadcast_arrays(*(np.asarray(v, float) for v in dofs))
    shape = x.shape
    H_pos = _h(_rot(_Z, theta), np.stack([x, y, np.zeros_like(x)], -1), shape)
    lx, ly, h, yaw = g.laser_mount
    H_lsr = _h(_rot(_Z, yaw), [lx, ly, h])

    def about(point, direction, angle):
        R = _rot(direction, angle)
        p = np.asarray(point, float)
        return _h(R, p - R @ p if R.ndim == 2 else p - np.einsum("...ij,j->...i", R, p), shape)

    q1, q2 = stereo.closest_points_on_rays([g.pan_point], [g.pan_direction], [g.tilt_point], [g.tilt_direction])
    H_eye = _h(None, 0.5 * (q1[0] + q2[0]) + np.asarray(g.eye_offset, float))
    H_cam = H_pos @ about(g.pan_point, g.pan_direction, pan) @ about(g.tilt_point, g.tilt_direction, tilt) @ H_eye
    return HomogeneousChains(base=H_pos, laser=H_pos @ H_lsr, camera_left=H_cam)


# ----------------------------------------------------------------- the tour
def waypoint_tour(waypoints, step: float = 0.15, turn_step: float = 0.2) -> np.ndarray:
    """Poses (T, 3) along straight legs between waypoints (x, y), turning in place at each by steps.

    >>> waypoint_tour([[0, 0], [1, 0], [1, 1]], step=0.5, turn_step=0.8).round(3).tolist()[-3:]
    [[1.0, 0.0, 1.571], [1.0, 0.5, 1.571], [1.0, 1.0, 1.571]]
    """
    f = "waypoint_tour"
    wp = checks.rows(waypoints, f, "waypoints", 2, at_least=2)
    step = checks.real(step, f, "step", low=0.0, strict_low=True)
    turn_step = checks.real(turn_step, f, "turn_step", low=0.0, strict_low=True)
    return _poses(wp, step, turn_step, f)


#: The most poses a tour may have (the bundled loop has 134).
MAX_POSES = 100_000


def _poses(wp: np.ndarray, step: float, turn_step: float, func: str) -> np.ndarray:
    """:func:`waypoint_tour` of checked waypoints (k, 2) and steps; at most :data:`MAX_POSES` poses."""
    legs = np.diff(wp, axis=0)
    lengths = np.hypot(legs[:, 0], legs[:, 1])
    if np.any(lengths < 1e-9):
        raise checks.fail(func, "waypoints", "two consecutive waypoints coincide")
    count = float(np.sum(np.maximum(1.0, np.round(lengths / step)))) + len(wp) * np.ceil(np.pi / turn_step)
    if not count <= MAX_POSES:
        raise checks.fail(func, "waypoints, step", f"the tour would take {count:.3g} poses; at most {MAX_POSES}")
    heading = float(np.arctan2(*(wp[1] - wp[0])[::-1]))
    poses = [[wp[0, 0], wp[0, 1], heading]]
    for a, b in zip(wp[:-1], wp[1:]):
        target = float(np.arctan2(b[1] - a[1], b[0] - a[0]))
        turn = (target - heading + np.pi) % (2 * np.pi) - np.pi
        n_turn = int(np.ceil(abs(turn) / turn_step))
        poses += [[a[0], a[1], heading + turn * k / n_turn] for k in range(1, n_turn + 1)]
        heading += turn
        n = max(1, int(round(np.hypot(*(b - a)) / step)))
        poses += [[*(a + (b - a) * k / n), heading] for k in range(1, n + 1)]
    out = np.array(poses)
    out[:, 2] = (out[:, 2] + np.pi) % (2 * np.pi) - np.pi
    return out


@dataclass
class View:
    """One stereo view: the scan index it was taken at, the true state and what each camera saw.

    ``pixels[name] = (x1, x2)`` pixel coordinates (with noise) of the object's
    points in the left and right image; ``points_true[name]`` the world points.
    """

    scan: int
    state: RobotState
    pixels: dict
    points_true: dict


@dataclass
class Tour:
    """Everything the robot recorded, and the truth behind it."""

    world: World3D
    geometry: RobotGeometry
    truth: np.ndarray  # (T, 3) true poses
    odometry: np.ndarray  # (T, 3)
    scans: list  # [(ranges, angles)]
    views: list  # [View]
    noise_px: float
    range_noise: float


def _in_both(rig, X_s, margin=2.0):
    return rig.in_view(X_s, margin=margin) if len(X_s) else np.zeros(0, bool)


def simulate_tour(
    rng: np.random.Generator,
    *,
    world: World3D | None = None,
    geometry: RobotGeometry | None = None,
    waypoints=((1.5, 1.5), (6.5, 1.5), (6.5, 4.5), (1.5, 4.5), (1.5, 1.6)),
    step: float = 0.15,
    stops=(12, 45, 80, 100, 120),
    pans=(-1.0, -0.3, 0.4, 1.1),
    tilts=(0.3, 0.6),
    noise_px: float = 0.5,
    range_noise: float = 0.01,
    min_points: int = 12,
    odometry_model=None,
) -> Tour:
    """Drive the loop, scan at every pose and look around at the ``stops`` (scan indices).

    At each stop the head visits every ``(pan, tilt)`` of ``pans x tilts``
    (radians; positive pan looks left, positive tilt down).  For each view and
    object, the object's visible points (:meth:`sample`) that fall inside both
    images are projected with the rig, and pixel noise of ``noise_px``
    (standard deviation per coordinate) is added; views with fewer than
    ``min_points`` points of an object do not record it.  Objects without a
    footprint (the ball, the plate) do not stop the laser's beams.

    Returns
    -------
    Tour
    """
    f = "simulate_tour"
    checks.generator(rng, f)
    world = default_world() if world is None else checks.instance(world, f, "world", World3D, "a World3D or None")
    if geometry is not None:
        checks.instance(geometry, f, "geometry", RobotGeometry, "a RobotGeometry or None")
    geometry = geometry or RobotGeometry()
    wp = checks.rows(waypoints, f, "waypoints", 2, at_least=2)
    truth = _poses(wp, checks.real(step, f, "step", low=0.0, strict_low=True), 0.2, f)
    stops = [checks.integer(k, f, "stops", low=0) for k in checks.array(stops, f, "stops", (None,))]
    if stops and max(stops) >= len(truth):
        raise checks.fail(f, "stops", f"must be scan indices below {len(truth)}, got {tuple(stops)}")
    noise_px = checks.real(noise_px, f, "noise_px", low=0.0)
    range_noise = checks.real(range_noise, f, "range_noise", low=0.0)
    min_points = checks.integer(min_points, f, "min_points", low=1)
    if odometry_model is not None:
        checks.instance(odometry_model, f, "odometry_model", OdometryModel, "an OdometryModel or None")
    for name, values, (lo, hi) in (("pans", pans, geometry.pan_limits), ("tilts", tilts, geometry.tilt_limits)):
        values = checks.array(values, f, name, (None,))
        if not all(lo <= v <= hi for v in values):
            raise checks.fail(f, name, f"{tuple(values.tolist())} leave the joint range [{lo:.3f}, {hi:.3f}]")
    lx, ly, h, yaw = geometry.laser_mount
    scene = world.laser_scene(h, truth)
    scans = [
        simulate_scan(scene, p, rng, range_noise=range_noise, mount=(lx, ly, yaw)) for p in truth
    ]  # the laser of 3.1: 180 deg, 5 m
    odometry = simulate_odometry(truth, rng, odometry_model)
    rig = Robot(geometry).stereo_rig()
    views = []
    for k in stops:
        for tilt in tilts:
            for pan in pans:
                state = RobotState(*truth[k], pan=pan, tilt=tilt)
                H = homogeneous_chains(geometry, **{d: getattr(state, d) for d in ("x", "y", "theta", "pan", "tilt")})
                H_cam = H.camera_left
                C1 = H_cam[:3, 3]
                C2 = C1 - geometry.baseline * H_cam[:3, 1]
                pixels, true_pts = {}, {}
                for o in world.objects:
                    X = o.sample((C1, C2), rng)
                    if len(X) == 0:
                        continue
                    X_s = (X - C1) @ H_cam[:3, :3]  # world -> stereo frame (the inverse rigid motion)
                    ok = _in_both(rig, X_s)
                    if ok.sum() < min_points:
                        continue
                    x1, x2 = rig.project(X_s[ok])
                    x1 = x1 + rng.normal(scale=noise_px, size=x1.shape)
                    x2 = x2 + rng.normal(scale=noise_px, size=x2.shape)
                    pixels[o.name], true_pts[o.name] = (x1, x2), X[ok]
                views.append(View(int(k), state, pixels, true_pts))
    return Tour(world, geometry, truth, odometry, scans, views, float(noise_px), float(range_noise))


def triangulate_view(geometry: RobotGeometry, view: View) -> dict:
    """Triangulated points (stereo frame) of each object seen in ``view`` (A.14, midpoint of figure A.4): object name
    -> points (N, 3)."""
    checks.instance(view, "triangulate_view", "view", View, "a View (simulate_tour)")
    rig = Robot(geometry).stereo_rig()
    return {name: stereo.triangulate(rig.P1, rig.P2, x1, x2) for name, (x1, x2) in view.pixels.items()}
