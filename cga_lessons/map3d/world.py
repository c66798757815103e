"""The synthetic world of the fused 3D map (section 4.2.3): a room and its objects.

The room is a set of walls of a stated height; the objects are the entities
of section 4.1, solid enough for a laser to hit where they reach its plane:

* a **ball** (sphere) on the floor, below the laser's plane: only the cameras see it;
* a **board** (a thin upright panel, its face a plane rectangle), seen by both sensors;
* a **plate** (a disc: its rim a circle) lying on a **pedestal** (a box the
  laser sees as short walls: section 4.2.3's warning that a virtual wall may
  be furniture);
* **posts** (thin upright cylinders: their axis a line), seen by both.

Each object knows its footprint in the laser's plane, the points a camera
pair sees of it (:meth:`sample`) and its true entity (:meth:`truth`).
:func:`default_world` is the bundled layout; the tour that records it is
:mod:`cga_lessons.map3d.tour`.

Frames: world x east, y north, z up, metres; see :mod:`cga_lessons.map3d.robot`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.conformal import CircleParameters, SphereParameters
from cga_lessons.mapping2d import Scene

from .parameters import BoardTruth, BoxTruth, PostTruth

__all__ = ["Ball", "Board", "Plate", "Pedestal", "Post", "World3D", "default_world"]

_UP = np.array([0.0, 0.0, 1.0])


def _unit(v, func):
    v = np.asarray(v, float)
    n = np.linalg.norm(v)
    if v.shape != (3,) or not np.isfinite(n) or n < 1e-12:
        raise checks.degenerate(func, "cameras", f"need a finite non-zero 3-vector, got {v!r}")
    return v / n


def _cap(center, radius, cameras, n, rng, max_angle=1.2217304763960306):
    """Points of a sphere whose normal is within ``max_angle`` (default 70 degrees) of the direction to every camera."""
    to_c = [_unit(C - center, "sample") for C in cameras]
    dirs = np.empty((0, 3))
    for _ in range(50):
        d = rng.normal(size=(8 * n, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        ok = np.all([d @ t > np.cos(max_angle) for t in to_c], axis=0)
        dirs = np.vstack([dirs, d[ok]])
        if len(dirs) >= n:
            break
    return center + radius * dirs[:n]


# ----------------------------------------------------------------- objects
@dataclass(frozen=True)
class Ball:
    """A sphere of ``radius`` resting on the floor at ``(x, y)``."""

    name: str
    xy: tuple
    radius: float

    @property
    def center(self) -> np.ndarray:
        return np.array([self.xy[0], self.xy[1], self.radius], float)

    def footprint(self):
        return None  # below the laser's plane for the default robot (checked in World3D)

    def top(self) -> float:
        return 2 * self.radius

    def sample(self, cameras, rng, n=300) -> np.ndarray:
        return _cap(self.center, self.radius, cameras, n, rng)

    def truth(self) -> SphereParameters:
        """The true sphere."""
        return SphereParameters(center=self.center, radius=float(self.radius))


@dataclass(frozen=True)
class Board:
    """An upright panel on the floor: ``width`` x ``height``, ``thickness`` deep, front face towards ``facing``.

    ``xy`` is the centre of the front face at floor level; ``facing`` is the
    heading (radians) of the front face's outward normal.
    """

    name: str
    xy: tuple
    facing: float
    width: float
    height: float
    thickness: float = 0.03

    @property
    def normal(self) -> np.ndarray:
        return np.array([np.cos(self.facing), np.sin(self.facing), 0.0])

    @property
    def along(self) -> np.ndarray:
        return np.array([-np.sin(self.facing), np.cos(self.facing), 0.0])

    @property
    def face_center(self) -> np.ndarray:
        return np.array([self.xy[0], self.xy[1], self.height / 2])

    def face_corners(self) -> np.ndarray:
        """The front face's corners (4, 3), counter-clockwise seen from the front."""
        c, u, h = self.face_center, self.along, self.height / 2
        w = self.width / 2
        return np.array([c - w * u - h * _UP, c + w * u - h * _UP, c + w * u + h * _UP, c - w * u + h * _UP])[::-1]

    def footprint(self) -> np.ndarray:
        c, u, n = np.asarray(self.xy, float), self.along[:2], self.normal[:2]
        w, t = self.width / 2, self.thickness
        return np.array([c - w * u, c + w * u, c + w * u - t * n, c - w * u - t * n])

    def top(self) -> float:
        return self.height

    def sample(self, cameras, rng, n=200) -> np.ndarray:
        if not all((C - self.face_center) @ self.normal > 0 for C in cameras):
            return np.zeros((0, 3))  # the back of the board: not this object's face
        st = rng.uniform(-0.5, 0.5, size=(n, 2)) * [self.width, self.height]
        return self.face_center + st[:, :1] * self.along + st[:, 1:] * _UP

    def truth(self) -> BoardTruth:
        """The true front face: its plane, centre and corners."""
        return BoardTruth(normal=self.normal, distance=float(self.normal @ self.face_center), center=self.face_center,
                          corners=self.face_corners())  # fmt: skip


@dataclass(frozen=True)
class Pedestal:
    """A box ``size = (sx, sy, height)`` on the floor, centred at ``xy`` (axis-aligned)."""

    name: str
    xy: tuple
    size: tuple

    def footprint(self) -> np.ndarray:
        (x, y), (sx, sy) = self.xy, self.size[:2]
        return np.array([[x - sx / 2, y - sy / 2], [x + sx / 2, y - sy / 2], [x + sx / 2, y + sy / 2],
                         [x - sx / 2, y + sy / 2]])  # fmt: skip

    def top(self) -> float:
        return float(self.size[2])

    def sample(self, cameras, rng, n=0) -> np.ndarray:
        return np.zeros((0, 3))  # furniture: the laser maps it, the cameras do not look for it

    def truth(self) -> BoxTruth:
        """The true box."""
        return BoxTruth(center=np.array([*self.xy, self.size[2] / 2]), size=np.asarray(self.size, float))


@dataclass(frozen=True)
class Plate:
    """A disc of ``radius`` lying flat at height ``z`` centred over ``xy`` (e.g. on a pedestal)."""

    name: str
    xy: tuple
    z: float
    radius: float

    @property
    def center(self) -> np.ndarray:
        return np.array([self.xy[0], self.xy[1], self.z], float)

    def footprint(self):
        return None

    def top(self) -> float:
        return self.z

    def sample(self, cameras, rng, n=96) -> np.ndarray:
        if not all(C[2] > self.z + 0.05 for C in cameras):
            return np.zeros((0, 3))  # the rim is only clear from above
        t = rng.uniform(0.0, 2 * np.pi, n)
        return self.center + self.radius * np.column_stack([np.cos(t), np.sin(t), np.zeros(n)])

    def truth(self) -> CircleParameters:
        """The true rim."""
        return CircleParameters(center=self.center, radius=float(self.radius), normal=_UP.copy())


@dataclass(frozen=True)
class Post:
    """An upright cylinder of ``radius`` and ``height`` standing at ``xy``.

    The cameras find a post by the midline of its silhouette, which for a thin
    post is the image of its axis: the offset is about ``f (r/d)^2 tan(phi)``
    pixels (radius r at distance d, phi off the optical axis), 0.02 px for
    r = 5 cm at 2 m; so the synthetic images show points of the axis.
    """

    name: str
    xy: tuple
    radius: float
    height: float
    sides: int = 48

    def footprint(self) -> np.ndarray:
        t = np.arange(self.sides) * 2 * np.pi / self.sides
        # the polygon's sides touch the circle at their midpoints' circumscribed radius
        R = self.radius / np.cos(np.pi / self.sides)
        return np.asarray(self.xy, float) + R * np.column_stack([np.cos(t), np.sin(t)])

    def top(self) -> float:
        return self.height

    def sample(self, cameras, rng, n=60) -> np.ndarray:
        z = np.sort(rng.uniform(0.0, self.height, n))
        return np.column_stack([np.full(n, self.xy[0]), np.full(n, self.xy[1]), z])

    def truth(self) -> PostTruth:
        """The true axis, radius and ends."""
        return PostTruth(
            direction=_UP.copy(),
            point=np.array([self.xy[0], self.xy[1], 0.0]),
            radius=float(self.radius),
            ends=np.array([[self.xy[0], self.xy[1], 0.0], [self.xy[0], self.xy[1], self.height]]),
        )


# ----------------------------------------------------------------- the world
@dataclass
class World3D:
    """Walls (closed 2D polygons extruded to ``wall_height``) and objects.

    Attributes
    ----------
    walls : list of ndarray (k, 2)
        Closed polygons of the room (the inside of the outer wall and any partitions).
    wall_height : float
    objects : list
        :class:`Ball`, :class:`Board`, :class:`Plate`, :class:`Pedestal`, :class:`Post`.
    """

    walls: list
    wall_height: float
    objects: list = field(default_factory=list)

    def __post_init__(self):
        self.walls = [np.asarray(w, float) for w in self.walls]
        names = [o.name for o in self.objects]
        if len(set(names)) != len(names):
            raise checks.fail("World3D", "objects", f"object names must be unique, got {names}")
        self.wall_height = checks.real(self.wall_height, "World3D", "wall_height", low=0.0, strict_low=True)

    def object(self, name: str):
        for o in self.objects:
            if o.name == name:
                return o
        raise checks.fail("World3D.object", "name", f"no object named {name!r}; have {[o.name for o in self.objects]}")

    def laser_scene(self, laser_height: float, trajectory) -> Scene:
        """The chapter-3 scene the laser sees: walls and every object that reaches its plane."""
        polys = list(self.walls)
        for o in self.objects:
            fp = o.footprint()
            if fp is not None and o.top() > laser_height:
                polys.append(fp)
        return Scene("world3d", polys, np.asarray(trajectory, float).reshape(-1, 3))

    def wall_segments(self) -> np.ndarray:
        """The room's wall edges (W, 2, 2) (objects excluded), for map errors."""
        return np.concatenate([np.stack([p, np.roll(p, -1, axis=0)], axis=1) for p in self.walls])


def default_world() -> World3D:
    """The bundled room: 8 m x 6 m, walls 2.5 m high, a ball, a board, a plate on a pedestal and two posts.

    The robot's loop (:func:`simulate_tour`) runs 1.5 m inside the walls; the
    ball, the pedestal and the posts stand inside the loop, the board between
    the loop and the north wall facing the loop, so that the laser sees one
    face of it.
    """
    room = np.array([[0.0, 0.0], [8.0, 0.0], [8.0, 6.0], [0.0, 6.0]])
    objects = [
        Ball("ball", (3.3, 3.5), 0.11),
        Board("board", (4.2, 5.35), -np.pi / 2, 1.2, 1.0),
        Pedestal("pedestal", (4.8, 2.5), (0.4, 0.4, 0.7)),
        Plate("plate", (4.8, 2.5), 0.71, 0.12),
        Post("post_west", (2.6, 2.3), 0.05, 1.8),
        Post("post_east", (5.9, 3.7), 0.05, 1.8),
    ]
    return World3D([room], 2.5, objects)
