"""A small, backend-free description of a 3D scene, and its matplotlib drawing.

The scene is a flat list of *primitives* (frozen dataclasses) in metres, in one
world frame.  The same list feeds :func:`~cga_lessons.viz.scene3d_matplotlib.draw_matplotlib` (a static
figure that nbval can store) and :mod:`cga_lessons.viz.meshcat_scene` (the live browser
viewer and the offline HTML export), so both views show the same geometry at
1:1 scale.

Every primitive has a ``name``: a slash path such as ``"robot/base"`` or
``"walls/3"`` (the meshcat scene-tree path; objects under a common prefix can
be hidden together there).  Colours are ``(r, g, b)`` floats in ``[0, 1]``.
Constructors copy and validate their arrays (shapes, finiteness, degenerate
sizes) with :mod:`cga_lessons.checks` and raise
:class:`~cga_lessons.algebra.InvalidInputError` or
:class:`~cga_lessons.algebra.DegenerateGeometryError` with a message naming
the class, the field and the primitive (``"Box: size: edge lengths must be >
0, got [...] (primitive 'robot/base')"``).

>>> b = Box("robot/base", center=(0, 0, 0.1), size=(0.4, 0.3, 0.2), color=(0.2, 0.4, 0.8))
>>> b.center.tolist(), b.rotation.shape
([0.0, 0.0, 0.1], (3, 3))
>>> lo, hi = scene_bounds([b, Sphere("ball", (1, 0, 0.5), 0.1, (1, 0, 0))])
>>> lo.tolist(), hi.tolist()
([-0.2, -0.15, 0.0], [1.1, 0.15, 0.6])
"""

from __future__ import annotations

from collections.abc import Iterable
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from cga_lessons.algebra import GeometryError
from cga_lessons.checks import array, degenerate, fail, real, record, text

from .inputs import LIMIT, coords, slash_path

__all__ = [
    "Box",
    "Sphere",
    "Quad",
    "Cylinder",
    "Polyline",
    "PointCloud",
    "Frame",
    "PRIMITIVE_TYPES",
    "check_scene",
    "scene_bounds",
]

_ORTHO_TOL = 1e-6


# ---------------------------------------------------------------- validation (the shared checking layer)
def _check_name(obj):
    slash_path(obj.name, type(obj).__name__)


@contextmanager
def _naming(obj):
    """Add the primitive's name to the errors of its checks: ``"Box: center: contains NaN ... (primitive 'b')"``."""
    try:
        yield
    except GeometryError as exc:
        raise type(exc)(f"{exc} (primitive {obj.name!r})") from None


# The checkers of the fields, for :func:`cga_lessons.checks.record` (``check(value, func, name)``, ``func`` the
# primitive's class).
def _drawn(shape):
    """A checker: a read-only float copy of shape ``shape`` (``None`` = any length), finite and drawable."""

    def check(value, func: str, name: str) -> np.ndarray:
        arr = coords(value, func, name, shape).copy()
        arr.setflags(write=False)
        return arr

    return check


def _positive(value, func: str, name: str) -> float:
    x = real(value, func, name, high=LIMIT)
    if x <= 0:
        raise degenerate(func, name, f"must be > 0, got {x}")
    return x


def _opacity(value, func: str, name: str) -> float:
    return real(value, func, name, low=0.0, high=1.0)


def _color(value, func: str, name: str) -> tuple:
    arr = array(value, func, name, (3,))
    if np.any(arr < 0) or np.any(arr > 1):
        raise fail(func, name, f"colour components must be floats in [0, 1], got {arr.tolist()}")
    return tuple(float(c) for c in arr)


def _rotation(func: str, name: str, R):
    if np.abs(R.T @ R - np.eye(3)).max() > _ORTHO_TOL or np.linalg.det(R) < 0:
        raise fail(func, name, "not a proper rotation (R^T R != I or det R < 0)")


def _edge_lengths(value, func: str, name: str) -> np.ndarray:
    size = _drawn((3,))(value, func, name)
    if np.any(size <= 0):
        raise degenerate(func, name, f"edge lengths must be > 0, got {size.tolist()}")
    return size


def _rotation_matrix(value, func: str, name: str) -> np.ndarray:
    R = _drawn((3, 3))(value, func, name)
    _rotation(func, name, R)
    return R


# ---------------------------------------------------------------- primitives
@dataclass(frozen=True, eq=False)
class Box:
    """A box with edge lengths ``size`` (3,) along the columns of ``rotation`` (3, 3), centred at ``center``."""

    name: str
    center: np.ndarray
    size: np.ndarray
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    color: tuple = (0.6, 0.6, 0.6)
    opacity: float = 1.0

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, center=_drawn((3,)), size=_edge_lengths, rotation=_rotation_matrix, color=_color,
                   opacity=_opacity)  # fmt: skip

    def corners(self) -> np.ndarray:
        """The 8 corners (8, 3); index bits (x, y, z) = (i & 1, i & 2, i & 4) pick the + side."""
        signs = np.array([[(i >> k & 1) * 2 - 1 for k in range(3)] for i in range(8)], float)
        return self.center + (signs * (self.size / 2)) @ self.rotation.T

    def extent(self) -> np.ndarray:
        return self.corners()


@dataclass(frozen=True, eq=False)
class Sphere:
    """A sphere of ``radius`` about ``center`` (3,)."""

    name: str
    center: np.ndarray
    radius: float
    color: tuple = (0.8, 0.2, 0.2)
    opacity: float = 1.0

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, center=_drawn((3,)), radius=_positive, color=_color, opacity=_opacity)

    def extent(self) -> np.ndarray:
        return np.array([self.center - self.radius, self.center + self.radius])


@dataclass(frozen=True, eq=False)
class Quad:
    """A flat quadrilateral with ``corners`` (4, 3) in order around its boundary (e.g. a wall patch)."""

    name: str
    corners: np.ndarray
    color: tuple = (0.7, 0.7, 0.7)
    opacity: float = 1.0

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, corners=_drawn((4, 3)))
            c = self.corners
            area2 = np.linalg.norm(np.cross(c[2] - c[0], c[3] - c[1]))  # twice the (vector) area
            scale = max(np.ptp(c, axis=0).max(), 1e-300)
            if area2 <= 1e-12 * scale * scale:
                raise degenerate("Quad", "corners", "the four corners enclose no area")
            record(self, color=_color, opacity=_opacity)

    def normal(self) -> np.ndarray:
        """Unit normal (3,) from the diagonals, right-handed with the corner order."""
        c = self.corners
        n = np.cross(c[2] - c[0], c[3] - c[1])
        return n / np.linalg.norm(n)

    def extent(self) -> np.ndarray:
        return self.corners


@dataclass(frozen=True, eq=False)
class Cylinder:
    """A solid cylinder of ``radius`` whose axis runs from ``start`` (3,) to ``end`` (3,)."""

    name: str
    start: np.ndarray
    end: np.ndarray
    radius: float
    color: tuple = (0.5, 0.5, 0.5)
    opacity: float = 1.0

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, start=_drawn((3,)), end=_drawn((3,)))
            a, b = self.start, self.end
            if np.linalg.norm(b - a) <= 1e-12 * max(1.0, np.abs(a).max(), np.abs(b).max()):
                raise degenerate("Cylinder", "end", "start and end coincide, the axis has no direction")
            record(self, radius=_positive, color=_color, opacity=_opacity)

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.end - self.start))

    def axis_rotation(self) -> np.ndarray:
        """A rotation (3, 3) whose third column is the unit axis start -> end."""
        return _frame_from_axis((self.end - self.start) / self.length)

    def extent(self) -> np.ndarray:
        # the end discs reach r * sqrt(1 - a_k^2) along world axis k (a = unit axis): a tight box
        a = (self.end - self.start) / self.length
        r = self.radius * np.sqrt(np.clip(1.0 - a * a, 0.0, 1.0))
        return np.array([self.start - r, self.start + r, self.end - r, self.end + r])


@dataclass(frozen=True, eq=False)
class Polyline:
    """An open polyline through ``points`` (N, 3), N >= 2, drawn ``width`` pixels wide."""

    name: str
    points: np.ndarray
    color: tuple = (0.1, 0.1, 0.1)
    width: float = 2.0

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, points=_drawn((None, 3)))
            if len(self.points) < 2:
                raise fail("Polyline", "points", f"a polyline needs at least 2 points, got {len(self.points)}")
            record(self, color=_color, width=_positive)

    def extent(self) -> np.ndarray:
        return self.points


@dataclass(frozen=True, eq=False)
class PointCloud:
    """Points (N, 3), N >= 1, drawn as dots of ``size`` metres."""

    name: str
    points: np.ndarray
    color: tuple = (0.1, 0.3, 0.9)
    size: float = 0.02

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, points=_drawn((None, 3)))
            if len(self.points) < 1:
                raise fail("PointCloud", "points", "a point cloud needs at least one point")
            record(self, color=_color, size=_positive)

    def extent(self) -> np.ndarray:
        return self.points


@dataclass(frozen=True, eq=False)
class Frame:
    """A coordinate triad for the rigid ``pose`` (4, 4): x red, y green, z blue, axes ``scale`` metres long."""

    name: str
    pose: np.ndarray
    scale: float = 0.2

    def __post_init__(self):
        _check_name(self)
        with _naming(self):
            record(self, pose=_drawn((4, 4)))
            T = self.pose
            if np.abs(T[3] - [0, 0, 0, 1]).max() > _ORTHO_TOL:
                raise fail("Frame", "pose", f"last row must be [0, 0, 0, 1], got {T[3].tolist()}")
            _rotation("Frame", "pose", T[:3, :3])
            record(self, scale=_positive)

    def axes(self) -> np.ndarray:
        """Segments (3, 2, 3): origin to the tip of the x, y and z axes."""
        o = self.pose[:3, 3]
        return np.array([[o, o + self.scale * self.pose[:3, k]] for k in range(3)])

    def extent(self) -> np.ndarray:
        return self.axes().reshape(-1, 3)


PRIMITIVE_TYPES = (Box, Sphere, Quad, Cylinder, Polyline, PointCloud, Frame)
FRAME_COLORS = ((0.9, 0.1, 0.1), (0.1, 0.75, 0.1), (0.1, 0.2, 0.95))


def _frame_from_axis(z: np.ndarray) -> np.ndarray:
    """A right-handed rotation whose third column is the unit vector ``z``."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.column_stack([x, y, z])


# ---------------------------------------------------------------- scene-level helpers
def check_scene(primitives, func: str = "check_scene") -> list:
    """Flatten nested lists of primitives into one list; reject unknown objects and duplicate names.

    Names must also not be a prefix path of one another (``"robot"`` and ``"robot/base"``), since in a
    scene tree the first would own the second.  ``func`` is the name of the public function the scene was
    given to, for the error messages.
    """
    func = text(func, "check_scene", "func")
    out = []

    def walk(item, depth):
        if isinstance(item, PRIMITIVE_TYPES):
            out.append(item)
        elif isinstance(item, Iterable) and not isinstance(item, (str, bytes, np.ndarray, dict)) and depth < 32:
            for sub in item:
                walk(sub, depth + 1)
        else:
            raise fail(func, "primitives", "expected primitives from cga_lessons.viz.scene3d "
                       f"({', '.join(t.__name__ for t in PRIMITIVE_TYPES)}), got {type(item).__name__}")  # fmt: skip

    walk(primitives, 0)
    names = sorted(p.name for p in out)
    for a, b in zip(names, names[1:]):
        if a == b:
            raise fail(func, "primitives", f"two primitives are named {a!r}; names must be unique")
        if b.startswith(a + "/"):
            raise fail(func, "primitives", f"name {a!r} is a parent path of {b!r}; give {a!r} a leaf name")
    return out


def _bounds(prims, func: str) -> tuple[np.ndarray, np.ndarray]:
    if not prims:
        raise fail(func, "primitives", "the scene is empty")
    pts = np.vstack([np.atleast_2d(p.extent()) for p in prims])
    return pts.min(axis=0), pts.max(axis=0)


def scene_bounds(primitives) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned bounds ``(lo (3,), hi (3,))`` of all primitives (a bounding box of each shape)."""
    return _bounds(check_scene(primitives, "scene_bounds"), "scene_bounds")
