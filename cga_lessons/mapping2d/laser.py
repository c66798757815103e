"""A 2D laser scanner, robot odometry and laser log reading (chapter 3, section 3.1).

The thesis's robot carries a laser that scans 180 degrees in front of it with a
range of 5 m (chapter 4's description of the robot *geometer*).  This module
simulates that sensor in polygonal scenes, makes drifting odometry from a
ground-truth trajectory with a stated noise model, and reads real laser logs in
the CARMEN text format.

Conventions
-----------
* A pose is ``(x, y, theta)``: position in metres and heading in radians of a
  frame (robot or laser) in the world frame.  ``compose(a, b)`` is the pose
  ``b`` given in frame ``a``, expressed in the world: the rigid motion (3.4).
* A scan is a pair ``(ranges, angles)`` of arrays of shape ``(n,)``: beam
  angles in radians in the laser frame (counter-clockwise, 0 straight ahead)
  and ranges in metres, ``inf`` where the beam returned nothing.
"""

from __future__ import annotations

import gzip
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cga_lessons.algebra import InvalidInputError

from .laser_facts import no_return_codes

__all__ = [
    "Scene",
    "load_scene",
    "beam_angles",
    "simulate_scan",
    "simulate_scans",
    "scan_points",
    "scans_to_world",
    "compose",
    "invert",
    "relative",
    "wrap_angle",
    "OdometryModel",
    "simulate_odometry",
    "CarmenLog",
    "read_carmen_log",
    "no_return_codes",
]


# --------------------------------------------------------------------------- poses


def wrap_angle(angle):
    """Wrap angles to ``[-pi, pi)``.

    >>> float(wrap_angle(3 * np.pi / 2))
    -1.5707963267948966
    """
    return np.mod(np.asarray(angle, float) + np.pi, 2 * np.pi) - np.pi


def _as_pose(pose, name="pose", func="compose"):
    p = np.asarray(pose, float)
    if p.shape[-1:] != (3,):
        raise InvalidInputError(f"{func}: {name} must have shape (3,) or (N, 3) as (x, y, theta), got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise InvalidInputError(f"{func}: {name} has non-finite values")
    return p


def compose(a, b):
    """The pose ``b`` (given in the frame of pose ``a``) in the world frame.

    This is the rigid motion of (3.4), ``v' = R(theta_a) v + T_a``, applied to
    the position of ``b``, with the headings added.

    Parameters
    ----------
    a, b : array_like, shape (3,) or (N, 3)
        Poses ``(x, y, theta)``; they broadcast against each other.

    Returns
    -------
    ndarray, shape (3,) or (N, 3)

    >>> compose([1.0, 0.0, np.pi / 2], [1.0, 0.0, 0.0]).round(12)
    array([1.        , 1.        , 1.57079633])
    """
    a, b = _as_pose(a, "a"), _as_pose(b, "b")
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    x = a[..., 0] + c * b[..., 0] - s * b[..., 1]
    y = a[..., 1] + s * b[..., 0] + c * b[..., 1]
    return np.stack([x, y, wrap_angle(a[..., 2] + b[..., 2])], axis=-1)


def invert(a):
    """The inverse pose: ``compose(a, invert(a))`` is the identity.

    >>> compose([1.0, 2.0, 0.5], invert([1.0, 2.0, 0.5])).round(12) + 0.0
    array([0., 0., 0.])
    """
    a = _as_pose(a, "a", "invert")
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    x = -(c * a[..., 0] + s * a[..., 1])
    y = -(-s * a[..., 0] + c * a[..., 1])
    return np.stack([x, y, wrap_angle(-a[..., 2])], axis=-1)


def relative(a, b):
    """The pose ``b`` seen from the frame of pose ``a`` (the odometry increment from ``a`` to ``b``)."""
    return compose(invert(a), b)


# --------------------------------------------------------------------------- scenes


@dataclass
class Scene:
    """A 2D world of closed polygons with a ground-truth trajectory.

    Attributes
    ----------
    name : str
    polygons : list of ndarray, each shape (k, 2)
        Closed polygons (walls with thickness, furniture), metres.
    trajectory : ndarray, shape (T, 3)
        Ground-truth robot poses ``(x, y, theta)``, one per laser scan.
    description : str
    walls : ndarray, shape (W, 2, 2)
        Every polygon edge as a segment ``[[x0, y0], [x1, y1]]`` (derived).
    """

    name: str
    polygons: list
    trajectory: np.ndarray
    description: str = ""
    walls: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        self.polygons = [np.asarray(p, float) for p in self.polygons]
        for i, p in enumerate(self.polygons):
            if p.ndim != 2 or p.shape[1] != 2 or len(p) < 2 or not np.all(np.isfinite(p)):
                raise InvalidInputError(f"Scene {self.name!r}: polygon {i} must be a finite (k >= 2, 2) array")
        self.trajectory = _as_pose(self.trajectory, "trajectory", f"Scene {self.name!r}").reshape(-1, 3)
        segs = [np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in self.polygons]
        self.walls = np.concatenate(segs) if segs else np.zeros((0, 2, 2))

    @classmethod
    def from_json(cls, path) -> Scene:
        """Read a scene written by ``data/scenes/make_scenes.py``."""
        d = json.loads(Path(path).read_text())
        return cls(d["name"], d["polygons"], np.asarray(d["trajectory"], float), d.get("description", ""))


def load_scene(name) -> Scene:
    """A bundled scene by name (``"room"``, ``"corridor"``, ``"office"``) or a scene JSON file by path.

    >>> load_scene("room").trajectory.shape[1]
    3
    """
    from cga_lessons.paths import data_path

    p = Path(name)
    if not p.suffix:
        p = data_path("scenes", f"{name}.json")
    if not p.is_file():
        raise InvalidInputError(f"load_scene: no scene file {str(p)!r}")
    return Scene.from_json(p)


# --------------------------------------------------------------------------- the laser


def beam_angles(n_beams: int = 361, fov: float = np.pi) -> np.ndarray:
    """Beam angles of a laser spanning ``fov`` radians symmetrically about straight ahead.

    The robot's laser: 180 degrees in 0.5 degree steps, 361 beams, from -pi/2 to +pi/2.

    >>> a = beam_angles(); a.shape, round(float(np.degrees(a[1] - a[0])), 9)
    ((361,), 0.5)
    """
    if int(n_beams) < 2:
        raise InvalidInputError(f"beam_angles: need at least 2 beams, got {n_beams}")
    return np.linspace(-fov / 2, fov / 2, int(n_beams))


def _ray_cast(origin, directions, walls, max_range):
    """Distance along each unit direction from ``origin`` to the nearest wall (inf if none within range)."""
    if len(walls) == 0:
        return np.full(len(directions), np.inf)
    a = walls[:, 0, :]  # (W, 2)
    e = walls[:, 1, :] - a  # (W, 2)
    d = directions  # (B, 2)
    w = a - origin  # (W, 2)
    den = d[:, None, 0] * e[None, :, 1] - d[:, None, 1] * e[None, :, 0]  # cross(d, e) (B, W)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[None, :, 0] * e[None, :, 1] - w[None, :, 1] * e[None, :, 0]) / den  # along the beam
        s = (w[None, :, 0] * d[:, None, 1] - w[None, :, 1] * d[:, None, 0]) / den  # along the wall
    ok = (np.abs(den) > 1e-12) & (t > 1e-9) & (s >= 0.0) & (s <= 1.0)
    t = np.where(ok, t, np.inf)
    r = t.min(axis=1)
    r[r > max_range] = np.inf
    return r


def simulate_scan(
    scene,
    pose,
    rng=None,
    *,
    n_beams: int = 361,
    fov: float = np.pi,
    max_range: float = 5.0,
    range_noise: float = 0.01,
    mount=(0.0, 0.0, 0.0),
):
    """One laser scan of ``scene`` from the robot at ``pose``.

    Parameters
    ----------
    scene : Scene or ndarray, shape (W, 2, 2)
        The world (its ``walls``) or wall segments directly.
    pose : array_like, shape (3,)
        Robot pose ``(x, y, theta)`` in the world.
    rng : numpy.random.Generator, optional
        Source of the range noise; ``None`` gives a noise-free scan.
    n_beams, fov : int, float
        Beam count and field of view (default 361 beams over pi: 0.5 degree steps).
    max_range : float
        Beyond this distance (m) a beam returns nothing (``inf``).
    range_noise : float
        Standard deviation (m) of the Gaussian noise added to each range.
    mount : array_like, shape (3,)
        Pose of the laser on the robot (the laser-robot transform of 3.16).

    Returns
    -------
    ranges : ndarray, shape (n_beams,)
        Metres, ``inf`` for no return.
    angles : ndarray, shape (n_beams,)
        Beam angles in the laser frame, radians.

    >>> r, a = simulate_scan(load_scene("room"), [3.0, 2.0, 0.0])
    >>> float(r[180])  # straight ahead: the east wall at x = 6
    3.0
    """
    walls = scene.walls if isinstance(scene, Scene) else np.asarray(scene, float).reshape(-1, 2, 2)
    pose = _as_pose(pose, "pose", "simulate_scan")
    if pose.shape != (3,):
        raise InvalidInputError(f"simulate_scan: pose must have shape (3,), got {pose.shape}")
    if not (max_range > 0 and range_noise >= 0):
        raise InvalidInputError("simulate_scan: max_range must be > 0 and range_noise >= 0")
    laser = compose(pose, _as_pose(mount, "mount", "simulate_scan"))
    angles = beam_angles(n_beams, fov)
    phi = laser[2] + angles
    ranges = _ray_cast(laser[:2], np.stack([np.cos(phi), np.sin(phi)], axis=1), walls, max_range)
    if rng is not None and range_noise > 0:
        hit = np.isfinite(ranges)
        ranges[hit] += rng.normal(0.0, range_noise, hit.sum())
        ranges[hit & (ranges > max_range)] = np.inf
        ranges[hit] = np.maximum(ranges[hit], 1e-3)
    return ranges, angles


def simulate_scans(scene, poses=None, rng=None, **kwargs):
    """Scans along a trajectory (default the scene's own): a list of ``(ranges, angles)``."""
    poses = scene.trajectory if poses is None else np.asarray(poses, float).reshape(-1, 3)
    return [simulate_scan(scene, p, rng, **kwargs) for p in poses]


def scan_points(ranges, angles):
    """Cartesian points of the returning beams in the laser frame.

    Returns
    -------
    points : ndarray, shape (k, 2)
    index : ndarray of int, shape (k,)
        Beam index of each point (beams with no return, inf or NaN, are dropped).
    """
    r = np.asarray(ranges, float)
    a = np.asarray(angles, float)
    if r.shape != a.shape or r.ndim != 1:
        raise InvalidInputError(f"scan_points: ranges and angles must be 1-D of equal length, got {r.shape}, {a.shape}")
    ok = np.isfinite(r) & (r > 0)
    idx = np.flatnonzero(ok)
    return np.stack([r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok])], axis=1), idx


def scans_to_world(scans, poses, max_range: float = np.inf, mount=(0.0, 0.0, 0.0), step: int = 1) -> np.ndarray:
    """All the points of a sequence of scans placed in the world with the given robot poses.

    Parameters
    ----------
    scans : sequence of (ranges, angles)
    poses : array_like, shape (T, 3)
    max_range : float
        Readings at or beyond this (m) are left out.
    mount : array_like, shape (3,)
        The laser's pose on the robot.
    step : int
        Use every ``step``-th scan.

    Returns
    -------
    ndarray, shape (k, 2)
    """
    poses = np.asarray(poses, float).reshape(-1, 3)
    out = []
    for (r, a), pose in list(zip(scans, poses))[::step]:
        r = np.asarray(r, float)
        pts, _ = scan_points(np.where(r < max_range, r, np.inf), a)
        lp = compose(pose, mount)
        c, s = np.cos(lp[2]), np.sin(lp[2])
        out.append(pts @ np.array([[c, s], [-s, c]]) + lp[:2])
    return np.concatenate(out) if out else np.zeros((0, 2))


# --------------------------------------------------------------------------- odometry


@dataclass(frozen=True)
class OdometryModel:
    """Odometry drift model: noise on each step's translation and rotation.

    For each step of the true trajectory, with increment ``(dx, dy, dtheta)``
    in the frame of the previous pose and length ``d = hypot(dx, dy)``, the
    odometer reports::

        (dx, dy) + N(0, sigma_xy^2 d I)
        dtheta + heading_bias d + N(0, sigma_heading^2 d + sigma_turn^2 |dtheta|)

    and the odometry is the composition of these reported increments from the
    true first pose.  Errors grow like a random walk plus a steady heading drift
    (``heading_bias``, radians per metre), as with unequal wheel radii.

    Attributes
    ----------
    sigma_xy : float
        Translation noise, m per sqrt(m) travelled.
    sigma_heading : float
        Heading noise from driving, rad per sqrt(m).
    sigma_turn : float
        Heading noise from turning, rad per sqrt(rad) turned.
    heading_bias : float
        Systematic heading drift, rad per m travelled.
    """

    sigma_xy: float = 0.02
    sigma_heading: float = 0.01
    sigma_turn: float = 0.03
    heading_bias: float = 0.005

    def increments(self, trajectory, rng) -> np.ndarray:
        """Noisy increments ``(T - 1, 3)`` of a trajectory ``(T, 3)``."""
        traj = _as_pose(trajectory, "trajectory", "OdometryModel.increments").reshape(-1, 3)
        inc = relative(traj[:-1], traj[1:])
        d = np.hypot(inc[:, 0], inc[:, 1])
        n = len(inc)
        noisy = inc.copy()
        noisy[:, :2] += rng.normal(size=(n, 2)) * (self.sigma_xy * np.sqrt(d))[:, None]
        sd = np.sqrt(self.sigma_heading**2 * d + self.sigma_turn**2 * np.abs(inc[:, 2]))
        noisy[:, 2] += self.heading_bias * d + rng.normal(size=n) * sd
        return noisy

    def step_covariance(self, increment) -> np.ndarray:
        """Covariance (3, 3) of the reported increment ``(dx, dy, dtheta)`` of one step under this model.

        Position variance ``sigma_xy^2 d`` per axis; heading variance
        ``sigma_heading^2 d + sigma_turn^2 |dtheta| + (heading_bias d)^2``, the
        steady drift counted as one more error of the step.

        >>> np.round(np.diag(OdometryModel().step_covariance([1.0, 0.0, 0.0])), 6).tolist()
        [0.0004, 0.0004, 0.000125]
        """
        inc = np.asarray(increment, float).reshape(3)
        d = float(np.hypot(inc[0], inc[1]))
        v_xy = self.sigma_xy**2 * d
        v_th = self.sigma_heading**2 * d + self.sigma_turn**2 * abs(inc[2]) + (self.heading_bias * d) ** 2
        return np.diag([v_xy, v_xy, v_th])


def simulate_odometry(trajectory, rng, model: OdometryModel | None = None) -> np.ndarray:
    """Drifting odometry along a ground-truth trajectory, by :class:`OdometryModel`.

    Parameters
    ----------
    trajectory : array_like, shape (T, 3)
        True poses.
    rng : numpy.random.Generator
    model : OdometryModel, optional
        The drift model (default parameters if omitted).

    Returns
    -------
    ndarray, shape (T, 3)
        Odometry poses; the first equals the first true pose (3.4, footnote: the
        robot starts at its own origin).
    """
    if rng is None:
        raise InvalidInputError("simulate_odometry: pass rng=numpy.random.default_rng(seed)")
    traj = _as_pose(trajectory, "trajectory", "simulate_odometry").reshape(-1, 3)
    model = model or OdometryModel()
    inc = model.increments(traj, rng)
    out = np.empty_like(traj)
    out[0] = traj[0]
    for k in range(len(inc)):
        out[k + 1] = compose(out[k], inc[k])
    return out


# --------------------------------------------------------------------------- CARMEN logs


@dataclass
class CarmenLog:
    """The laser scans and poses of a CARMEN log.

    Attributes
    ----------
    ranges : ndarray, shape (T, n)
        Metres; ``inf`` where the beam returned nothing.
    angles : ndarray, shape (n,)
        Beam angles in the laser frame, radians.
    poses : ndarray, shape (T, 3)
        The logged laser pose of each scan (in the "corrected" logs: the SLAM
        solution, used as ground truth).
    odometry : ndarray, shape (T, 3)
        The logged odometry pose of each scan.
    timestamps : ndarray, shape (T,)
    laser_offset : float
        ``robot_frontlaser_offset`` from the log's PARAM lines (m), 0 if absent.
    no_return_codes : tuple of float
        The values the log uses to say "no return" that :func:`no_return_codes` found (their readings, and all
        readings above the smallest, are ``inf`` in ``ranges``).
    """

    ranges: np.ndarray
    angles: np.ndarray
    poses: np.ndarray
    odometry: np.ndarray
    timestamps: np.ndarray
    laser_offset: float = 0.0
    no_return_codes: tuple = ()

    @property
    def scans(self) -> list:
        """The scans as a list of ``(ranges, angles)`` pairs."""
        return [(r, self.angles) for r in self.ranges]

    def __len__(self):
        return len(self.ranges)


def read_carmen_log(path, *, no_return_range: float = 80.0, fov: float = np.pi, detect_codes: bool = True) -> CarmenLog:
    """Read the FLASER lines of a CARMEN log (plain text or gzip).

    Each line ``FLASER n r_1 ... r_n x y theta odom_x odom_y odom_theta
    timestamp host logger_timestamp`` is one scan of ``n`` beams from -90
    degrees (right) counter-clockwise: 1 degree apart for 180 or 181 beams,
    0.5 degree for 360 or 361 (as CARMEN's own reader assumes), otherwise
    spread evenly over ``fov``.  Other messages (ODOM, PARAM, NEFF, comments)
    are skipped.

    Parameters
    ----------
    path : str or Path
    no_return_range : float
        Ranges at or beyond this (m) mean "no return" and become ``inf``
        (SICK scanners in these logs report about 81.9 m).
    fov : float
        Field of view (radians) assumed for beam counts other than 180, 181, 360, 361.
    detect_codes : bool
        Also find the log's own "no return" values (:func:`no_return_codes`): their readings and any above the
        smallest become ``inf`` (recorded in ``CarmenLog.no_return_codes``).

    Returns
    -------
    CarmenLog

    Raises
    ------
    InvalidInputError
        On a malformed FLASER line (naming the file and line number), on scans
        of different lengths, or when the file holds no FLASER line.
    """
    path = Path(path)
    if not path.is_file():
        raise InvalidInputError(f"read_carmen_log: no such file {str(path)!r}")
    opener = gzip.open if path.suffix == ".gz" else open
    ranges, poses, odom, stamps, offset = [], [], [], [], 0.0
    n_beams = None
    with opener(path, "rt") as f:
        for lineno, line in enumerate(f, start=1):
            tok = line.split()
            if not tok or tok[0].startswith("#"):
                continue
            where = f"read_carmen_log: {path.name}, line {lineno}"
            if tok[0] == "PARAM" and len(tok) >= 3 and tok[1] == "robot_frontlaser_offset":
                try:
                    offset = float(tok[2])
                except ValueError as exc:
                    raise InvalidInputError(f"{where}: bad robot_frontlaser_offset {tok[2]!r}") from exc
            if tok[0] != "FLASER":
                continue
            try:
                n = int(tok[1])
            except (IndexError, ValueError) as exc:
                raise InvalidInputError(f"{where}: FLASER without a beam count") from exc
            if n < 2 or len(tok) < n + 9:
                raise InvalidInputError(
                    f"{where}: FLASER line truncated or malformed ({len(tok)} fields, expected {n + 11} for {n} beams)"
                )
            try:
                vals = np.array(tok[2 : n + 9], float)
            except ValueError as exc:
                raise InvalidInputError(f"{where}: non-numeric value in the FLASER fields ({exc})") from exc
            if not np.all(np.isfinite(vals)):
                raise InvalidInputError(f"{where}: non-finite value in the FLASER fields")
            if n_beams is None:
                n_beams = n
            elif n != n_beams:
                raise InvalidInputError(f"{where}: {n} beams, but earlier scans had {n_beams}")
            r = vals[:n].copy()
            r[(r >= no_return_range) | (r <= 0)] = np.inf
            ranges.append(r)
            poses.append(vals[n : n + 3])
            odom.append(vals[n + 3 : n + 6])
            stamps.append(vals[n + 6])
    if not ranges:
        raise InvalidInputError(f"read_carmen_log: {path.name} holds no FLASER line")
    poses = np.array(poses)
    odom = np.array(odom)
    poses[:, 2] = wrap_angle(poses[:, 2])
    odom[:, 2] = wrap_angle(odom[:, 2])
    ranges = np.array(ranges)
    codes = no_return_codes(ranges) if detect_codes else ()
    if codes:
        ranges[ranges >= codes[0]] = np.inf
    return CarmenLog(ranges, _carmen_angles(n_beams, fov), poses, odom, np.array(stamps), offset, codes)


def _carmen_angles(n: int, fov: float) -> np.ndarray:
    """Beam angles as CARMEN's own log reader guesses them for old FLASER lines.

    180/181 beams are 1 degree apart and 360/361 beams 0.5 degree apart, from
    -90 degrees (CARMEN's ``carmen_laser_guess_angle_increment``); other counts
    are spread evenly over ``fov``.
    """
    step = {180: np.pi / 180, 181: np.pi / 180, 360: np.pi / 360, 361: np.pi / 360}.get(n)
    if step is None:
        return beam_angles(n, fov)
    return -np.pi / 2 + step * np.arange(n)
