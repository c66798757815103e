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

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from cga_lessons import checks

from .inputs import numbers, pose, reach
from .poses import compose_unchecked, relative_unchecked

__all__ = [
    "Scene",
    "load_scene",
    "beam_angles",
    "simulate_scan",
    "simulate_scans",
    "OdometryModel",
    "simulate_odometry",
]


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
        f = "Scene"
        self.name = checks.text(self.name, f, "name", empty=True)
        self.description = checks.text(self.description, f, "description", empty=True)
        if isinstance(self.polygons, (str, bytes)) or not hasattr(self.polygons, "__iter__"):
            raise checks.fail(f, "polygons", f"expected a list of (k, 2) arrays, got {type(self.polygons).__name__}")
        self.polygons = [
            checks.array(p, f, f"polygons: polygon {i}", (None, 2), at_least=2) for i, p in enumerate(self.polygons)
        ]
        self.trajectory = checks.batch(self.trajectory, f, "trajectory", (3,))[0]
        segs = [np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in self.polygons]
        self.walls = np.concatenate(segs) if segs else np.zeros((0, 2, 2))

    @classmethod
    def from_json(cls, path) -> Scene:
        """Read a scene written by ``data/scenes/make_scenes.py``."""
        return _read_scene(checks.existing_path(path, "Scene.from_json", "path"), "Scene.from_json", "path")


def _read_scene(path: Path, func: str, name: str) -> Scene:
    """The scene of a JSON file; any problem with the file is an error of ``func``'s argument ``name``."""
    try:
        d = json.loads(path.read_text(encoding="utf-8"))
        return Scene(d["name"], d["polygons"], d["trajectory"], d.get("description", ""))
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError, AttributeError) as exc:
        why = f"missing field {exc}" if isinstance(exc, KeyError) else str(exc)
        raise checks.fail(func, name, f"{str(path)!r} is not a scene file ({why})") from None


def load_scene(name) -> Scene:
    """A bundled scene by name (``"room"``, ``"corridor"``, ``"office"``) or a scene JSON file by path.

    >>> load_scene("room").trajectory.shape[1]
    3
    """
    from cga_lessons.paths import data_path

    if not isinstance(name, Path):
        name = checks.text(name, "load_scene", "name")
    p = Path(name)
    if not p.suffix:
        folder = data_path("scenes")
        p = folder / f"{name}.json"
        if not p.is_file():
            known = sorted(q.stem for q in folder.glob("*.json"))
            raise checks.fail("load_scene", "name", f"no bundled scene {str(name)!r} (there are {', '.join(known)})")
    return _read_scene(checks.existing_path(p, "load_scene", "name"), "load_scene", "name")


# --------------------------------------------------------------------------- the laser


def beam_angles(n_beams: int = 361, fov: float = np.pi) -> np.ndarray:
    """Beam angles of a laser spanning ``fov`` radians symmetrically about straight ahead.

    The robot's laser: 180 degrees in 0.5 degree steps, 361 beams, from -pi/2 to +pi/2.

    >>> a = beam_angles(); a.shape, round(float(np.degrees(a[1] - a[0])), 9)
    ((361,), 0.5)
    """
    n_beams, fov = _beams("beam_angles", n_beams, fov)
    return np.linspace(-fov / 2, fov / 2, n_beams)


def _beams(func: str, n_beams, fov) -> tuple[int, float]:
    """The checked beam count (>= 2) and field of view (in (0, 2 pi]) of a laser."""
    n = checks.integer(n_beams, func, "n_beams", low=2)
    return n, checks.real(fov, func, "fov", low=0.0, strict_low=True, high=2 * np.pi)


def _walls(scene, func: str) -> np.ndarray:
    """The wall segments (W, 2, 2) of a :class:`Scene` or of an array of segments (W, 2, 2) or (W, 4)."""
    if isinstance(scene, Scene):
        return scene.walls
    if isinstance(scene, (str, bytes)) or scene is None or isinstance(scene, (int, float)):
        raise checks.fail(func, "scene", f"expected a Scene or wall segments (W, 2, 2), got {type(scene).__name__}")
    walls = numbers(scene, func, "scene")
    walls = checks.array(walls, func, "scene", (None, 4) if walls.ndim == 2 else (None, 2, 2))
    return walls.reshape(-1, 2, 2)


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
    f = "simulate_scan"
    walls, where = _walls(scene, f), checks.array(pose, f, "pose", (3,))
    settings = _settings(f, n_beams, fov, max_range, range_noise, mount)
    return _simulate(walls, where, checks.generator(rng, f, "rng", optional=True), *settings)


def _settings(func: str, n_beams, fov, max_range, range_noise, mount) -> tuple:
    """The checked laser settings: beam angles, max_range, range_noise, mount."""
    n, fov = _beams(func, n_beams, fov)
    max_range = reach(max_range, func, "max_range")
    range_noise = checks.real(range_noise, func, "range_noise", low=0.0)
    return np.linspace(-fov / 2, fov / 2, n), max_range, range_noise, pose(mount, func, "mount")


def _simulate(walls, pose, rng, angles, max_range, range_noise, mount):
    """:func:`simulate_scan` with checked arguments."""
    laser = compose_unchecked(pose, mount)
    phi = laser[2] + angles
    ranges = _ray_cast(laser[:2], np.stack([np.cos(phi), np.sin(phi)], axis=1), walls, max_range)
    if rng is not None and range_noise > 0:
        hit = np.isfinite(ranges)
        ranges[hit] += rng.normal(0.0, range_noise, hit.sum())
        ranges[hit & (ranges > max_range)] = np.inf
        ranges[hit] = np.maximum(ranges[hit], 1e-3)
    return ranges, angles.copy()


def simulate_scans(
    scene,
    poses=None,
    rng=None,
    *,
    n_beams: int = 361,
    fov: float = np.pi,
    max_range: float = 5.0,
    range_noise: float = 0.01,
    mount=(0.0, 0.0, 0.0),
):
    """Scans along a trajectory (default the scene's own): a list of ``(ranges, angles)``.

    The keyword arguments are those of :func:`simulate_scan`.
    """
    f = "simulate_scans"
    walls = _walls(scene, f)
    if poses is None:
        if not isinstance(scene, Scene):
            raise checks.fail(f, "poses", "wall segments have no trajectory of their own: pass poses")
        poses = scene.trajectory
    poses = checks.batch(poses, f, "poses", (3,))[0]
    rng = checks.generator(rng, f, "rng", optional=True)
    settings = _settings(f, n_beams, fov, max_range, range_noise, mount)
    return [_simulate(walls, p, rng, *settings) for p in poses]


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

    def __post_init__(self):
        for name in ("sigma_xy", "sigma_heading", "sigma_turn"):
            checks.real(getattr(self, name), "OdometryModel", name, low=0.0)
        checks.real(self.heading_bias, "OdometryModel", "heading_bias")

    def increments(self, trajectory, rng) -> np.ndarray:
        """Noisy increments ``(T - 1, 3)`` of a trajectory ``(T, 3)``."""
        f = "OdometryModel.increments"
        traj = checks.batch(trajectory, f, "trajectory", (3,))[0]
        return checks.finite_result(self._increments(traj, checks.generator(rng, f, "rng")), f, "trajectory")

    def _increments(self, traj, rng):
        inc = relative_unchecked(traj[:-1], traj[1:])
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
        f = "OdometryModel.step_covariance"
        with np.errstate(over="ignore"):
            cov = self.step_covariance_unchecked(pose(increment, f, "increment"))
        return checks.finite_result(cov, f, "increment")

    def step_covariance_unchecked(self, inc) -> np.ndarray:
        """:meth:`step_covariance` of a checked increment (the map builder's inner loop)."""
        d = np.hypot(inc[0], inc[1])
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
    f = "simulate_odometry"
    traj = checks.batch(trajectory, f, "trajectory", (3,), at_least=1)[0]
    if rng is None:
        raise checks.fail(f, "rng", "pass rng=numpy.random.default_rng(seed)")
    rng = checks.generator(rng, f, "rng")
    model = OdometryModel() if model is None else checks.instance(model, f, "model", OdometryModel, "an OdometryModel")
    inc = model._increments(traj, rng)
    out = np.empty_like(traj)
    out[0] = traj[0]
    for k in range(len(inc)):
        out[k + 1] = compose_unchecked(out[k], inc[k])
    return checks.finite_result(out, f, "trajectory")
