"""A synthetic stereo head, its scene, and conformal entities from two views (section 4.1).

The robot's stereo head is two calibrated pinhole cameras (appendix A,
:mod:`cga_lessons.stereo.camera`).  The scene holds the objects the thesis
reconstructs in figure 4.2: points, a segment (a broom handle), a circle (a
plate's rim), a plane (a board) and a sphere (a ball).  Their points are
projected into both images with seeded pixel noise, triangulated, lifted to
the conformal model with (2.62) and combined into entities exactly as 4.1
describes: point (2.62, 2.114), point pair (2.68, 2.131), line (2.81,
2.126-2.129), circle (2.80, 2.119-2.124), plane (2.77) and sphere (2.75,
2.115, 2.116, 2.73).

World frame: x forward, y to the left, z up, metres (see ``data/stereo_make.py``).

Companion modules: :mod:`cga_lessons.stereo.rig` (the head),
:mod:`cga_lessons.conformal.fitting` (least-squares fits in the conformal model, RANSAC),
:mod:`cga_lessons.stereo.render` (OpenCV images of the scene),
:mod:`cga_lessons.stereo.real` (the Middlebury motorcycle pair) and
:mod:`cga_lessons.stereo.experiments` (the notebook's tables and curves).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import degenerate, fail

from . import camera as cam
from . import validate as vd
from .entities import SceneCircle, SceneLine, ScenePair, ScenePlane, ScenePoints, SceneSphere
from .polylines import frame
from .rig import StereoRig, check_rig

__all__ = [
    "StereoScene",
    "load_scene",
    "random_scene",
    "sample_scene",
    "observe",
]


# ---------------------------------------------------------------- the scene
def _unit(v, func: str = "stereo", name: str = "direction") -> np.ndarray:
    return vd.direction(v, func, name)


def check_scene(scene, func: str, name: str = "scene"):
    """``scene`` if it is a :class:`StereoScene` (the argument check of every function taking one)."""
    return checks.instance(scene, func, name, StereoScene, "a StereoScene (load_scene, random_scene)")


@dataclass(frozen=True)
class StereoScene:
    """The objects of figure 4.2, in world coordinates (metres).

    ``segment`` is (2, 3); the circle lies in the plane through
    ``circle_center`` orthogonal to ``circle_normal``; the board is a
    rectangle ``board_size = (width, height)`` centred at ``board_center``
    with normal ``board_normal`` and height direction ``board_up``.
    """

    points: np.ndarray
    segment: np.ndarray
    circle_center: np.ndarray
    circle_normal: np.ndarray
    circle_radius: float
    board_center: np.ndarray
    board_normal: np.ndarray
    board_up: np.ndarray
    board_size: tuple
    sphere_center: np.ndarray
    sphere_radius: float

    def __post_init__(self):
        f, out = "StereoScene", {}
        out["points"] = vd.array(self.points, f, "points", (None, 3), at_least=1)
        out["segment"] = vd.array(self.segment, f, "segment", (2, 3))
        if np.array_equal(*out["segment"]):
            raise degenerate(f, "segment", "its endpoints coincide")
        for name in ("circle_center", "board_center", "sphere_center"):
            out[name] = vd.array(getattr(self, name), f, name, (3,))
        for name in ("circle_normal", "board_normal", "board_up"):
            out[name] = vd.array(getattr(self, name), f, name, (3,))
            _unit(out[name], f, name)
        if np.linalg.norm(np.cross(_unit(out["board_normal"]), _unit(out["board_up"]))) < 1e-6:
            raise degenerate(f, "board_up", "is parallel to board_normal: the board has no height direction")
        for name in ("circle_radius", "sphere_radius"):
            out[name] = checks.real(getattr(self, name), f, name, low=0.0, strict_low=True, high=vd.LIMIT)
        w, h = vd.array(self.board_size, f, "board_size", (2,))
        if not (w > 0 and h > 0):
            raise fail(f, "board_size", f"must be (width, height) > 0, got {self.board_size!r}")
        out["board_size"] = (float(w), float(h))
        for name, value in out.items():
            object.__setattr__(self, name, value)

    def board_corners(self) -> np.ndarray:
        """The board's four corners (4, 3), counter-clockwise seen from the side the normal points to."""
        u, v = frame(self.board_normal, self.board_up)
        w, h = self.board_size
        signs = ((-1, -1), (1, -1), (1, 1), (-1, 1))
        return np.array([self.board_center + 0.5 * (sx * w * u + sy * h * v) for sx, sy in signs])

    def truth(self) -> dict:
        """The true entities, in the format of :func:`reconstruct_entities` (entity name -> record of
        :mod:`cga_lessons.stereo.entities`; the plane is drawn about the board's centre, with its half diagonal)."""
        a, b = self.segment
        r = _unit(b - a)
        n, m = _unit(self.board_normal), _unit(self.circle_normal)
        c, rho, s, p = self.circle_center, self.circle_radius, self.sphere_center, self.board_center
        u, v = frame(m)
        ball = s + self.sphere_radius * np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0], [-1.0, 0, 0]])
        try:  # the blades in the dual forms reconstruct_entities builds (2.62, 2.68, 2.75, 2.77, 2.80, 2.81)
            blades = (cga.up(self.points), cga.point_pair(a, b), cga.line_from_points(a, b),
                      cga.circle_from_points(c + rho * u, c + rho * v, c - rho * u),
                      cga.plane_from_points(*self.board_corners()[:3]), cga.sphere_from_points(*ball))  # fmt: skip
        except GeometryError as exc:
            raise degenerate("StereoScene.truth", "self", f"the scene's objects are degenerate: {exc}") from None
        return {
            "point": ScenePoints(points=np.array(self.points, dtype=float), blade=blades[0]),
            "pair": ScenePair(endpoints=np.array(self.segment, dtype=float), blade=blades[1]),
            "line": SceneLine(direction=r, closest_point=a - np.dot(a, r) * r, length=float(np.linalg.norm(b - a)),
                              midpoint=0.5 * (a + b), blade=blades[2]),
            "circle": SceneCircle(center=c, radius=rho, normal=m, center_via_plane=c, blade=blades[3]),
            "plane": ScenePlane(normal=n, distance=float(np.dot(n, p)), center=p,
                                radius=0.5 * float(np.hypot(*self.board_size)), blade=blades[4]),
            "sphere": SceneSphere(center=s, radius=self.sphere_radius, blade=blades[5]),
        }  # fmt: skip


def load_scene(path=None) -> StereoScene:
    """The scene described in ``data/stereo_scene.json`` (made by ``data/stereo_make.py``)."""
    f = "load_scene"
    d = vd.json_object(path, "stereo_scene.json", f, ("points", "segment", "circle", "plane", "sphere"))
    try:
        c, p, s = d["circle"], d["plane"], d["sphere"]
        return StereoScene(
            d["points"], [d["segment"]["a"], d["segment"]["b"]],
            c["center"], _unit(c["normal"], f, "circle normal"), c["radius"],
            p["center"], _unit(p["normal"], f, "plane normal"), _unit(p["up"], f, "plane up"),
            tuple(p["size"]), s["center"], s["radius"],
        )  # fmt: skip
    except (KeyError, TypeError) as exc:
        raise fail(f, "path", f"is not a scene file: no {exc}") from None
    except GeometryError as exc:
        raise fail(f, "path", f"describes no valid scene: {exc}") from None


def random_scene(rng: np.random.Generator, rig: StereoRig, depth=(1.5, 4.0)) -> StereoScene:
    """Random objects in front of ``rig``, all inside both images (for tests of generality).

    Each object's size is a random fraction (5-25 %) of the width the left
    camera sees at its depth; surfaces face the rig within 60 degrees so that
    they are seen at a usable angle.
    """
    f = "random_scene"
    rng, rig, depth = checks.generator(rng, f), check_rig(rig, f), vd.depth_range(depth, f)
    mid = 0.5 * (rig.C1 + rig.C2)
    Kinv = np.linalg.inv(rig.K)
    w, h = rig.image_size

    def place(extent):
        """A centre p and size r such that the cube p +- r lies inside both views."""
        for _ in range(2000):
            z = rng.uniform(*depth)
            ray = rig.R1.T @ Kinv @ np.array([rng.uniform(0.2, 0.8) * w, rng.uniform(0.2, 0.8) * h, 1.0])
            p = rig.C1 + z * ray
            r = extent * rng.uniform(0.05, 0.25) * z * w / rig.K[0, 0]
            cube = p + r * np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)])
            if np.all(rig.in_view(cube, margin=5)):
                return p, r
        raise degenerate(f, "rig, depth", "could not place an object inside both views at these depths")

    def facing(p):
        to_cam = _unit(mid - p)
        for _ in range(1000):
            n = _unit(to_cam + rng.normal(scale=0.6, size=3))
            if np.dot(n, to_cam) > 0.5:
                return n
        return to_cam

    pts = np.array([place(0.0)[0] for _ in range(6)])
    seg = np.array([place(0.0)[0], place(0.0)[0]])
    cc, rc = place(1.0)
    sc, rs = place(1.0)
    bc, rb = place(1.0)
    ratio = rng.uniform(0.5, 1.0)
    size = (2 * rb / np.hypot(1, ratio), 2 * rb * ratio / np.hypot(1, ratio))
    return StereoScene(pts, seg, cc, facing(cc), rc, bc, facing(bc), np.array([0.0, 0.0, 1.0]), size, sc, rs)


def sample_scene(scene: StereoScene, rig: StereoRig, rng: np.random.Generator, n_circle=48, n_board=64, n_sphere=96):
    """World points on each object: the minimal sets 4.1 uses and dense samples for fitting.

    Sphere points are drawn on the cap seen by both cameras at less than 70
    degrees from the surface normal.

    Returns
    -------
    dict of ndarray (M, 3)
        ``"points"``, ``"segment"`` (the two endpoints), ``"circle_key"`` (3
        points 120 degrees apart), ``"circle"``, ``"plane_key"`` (3 corners of
        the board), ``"plane"``, ``"sphere_key"`` (4 non-coplanar points on the
        visible cap), ``"sphere"``.
    """
    f = "sample_scene"
    scene, rig, rng = check_scene(scene, f), check_rig(rig, f), checks.generator(rng, f)
    n_circle, n_board, n_sphere = (
        checks.integer(n, f, name, low=0, high=10**8)
        for n, name in ((n_circle, "n_circle"), (n_board, "n_board"), (n_sphere, "n_sphere"))
    )
    u, v = frame(scene.circle_normal)
    ang0 = rng.uniform(0, 2 * np.pi)
    ring = lambda t: scene.circle_center + scene.circle_radius * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)  # noqa: E731
    out = {"points": np.array(scene.points, float), "segment": np.array(scene.segment, float)}
    out["circle_key"] = ring(ang0 + np.array([0.0, 2.0, 4.0]) * np.pi / 3)
    out["circle"] = ring(rng.uniform(0, 2 * np.pi, n_circle))
    corners = scene.board_corners()
    out["plane_key"] = corners[[0, 1, 3]]
    bu, bv = frame(scene.board_normal, scene.board_up)
    st = rng.uniform(-0.5, 0.5, size=(n_board, 2)) * np.asarray(scene.board_size)
    out["plane"] = scene.board_center + st[:, :1] * bu + st[:, 1:] * bv
    S, r = np.asarray(scene.sphere_center, float), scene.sphere_radius
    if min(np.linalg.norm(rig.C1 - S), np.linalg.norm(rig.C2 - S)) <= r:
        raise degenerate(f, "scene, rig", "a camera is inside the ball (sphere_center, sphere_radius)")
    to_c = [_unit(C - S) for C in (rig.C1, rig.C2)]
    if np.linalg.norm(to_c[0] + to_c[1]) < 1e-9:
        raise degenerate(f, "scene, rig", "the cameras see the ball from opposite sides: no common cap to sample")
    pole = _unit(to_c[0] + to_c[1])
    pu, pv = frame(pole)
    key = [pole] + [np.cos(0.9) * pole + np.sin(0.9) * (np.cos(a) * pu + np.sin(a) * pv) for a in (0.0, 2.1, 4.2)]
    out["sphere_key"] = S + r * np.array(key)
    dirs = np.empty((0, 3))
    for _ in range(1000):  # the common cap is at least a 40-degree one: a few rounds fill it
        if len(dirs) >= n_sphere:
            break
        d = rng.normal(size=(4 * n_sphere, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        ok = (d @ to_c[0] > np.cos(np.radians(70))) & (d @ to_c[1] > np.cos(np.radians(70)))
        dirs = np.vstack([dirs, d[ok]])
    if len(dirs) < n_sphere:
        raise degenerate(f, "scene, rig", "the two cameras see almost no common part of the sphere")
    out["sphere"] = S + r * dirs[:n_sphere]
    return out


def observe(rig: StereoRig, X, noise_px: float = 0.0, rng: np.random.Generator | None = None):
    """Pixel coordinates of X (N, 3) in both views, plus Gaussian noise of ``noise_px`` (std, per coordinate).

    Returns
    -------
    x1, x2 : ndarray, shape (N, 2)
    """
    f = "observe"
    rig, (X, _) = check_rig(rig, f), vd.batch(X, f, "X", (3,))
    noise_px = checks.real(noise_px, f, "noise_px", low=0.0, high=vd.LIMIT)
    rng = checks.generator(rng, f, optional=True)
    x1, x2 = seen(rig, X, f)
    if noise_px > 0:
        if rng is None:
            raise fail(f, "rng", "pass rng (numpy.random.default_rng(seed)) to add noise")
        x1 = x1 + rng.normal(scale=noise_px, size=x1.shape)
        x2 = x2 + rng.normal(scale=noise_px, size=x2.shape)
    return x1, x2


def seen(rig: StereoRig, X: np.ndarray, func: str, name: str = "X"):
    """Pixels ``(x1, x2)`` of checked points X (N, 3), which must lie in front of both cameras."""
    out = []
    for k, P in enumerate((rig.P1, rig.P2), 1):
        try:
            x, depth = cam.project(P, X, return_depth=True)
        except GeometryError as exc:
            raise degenerate(func, name, f"camera {k}: {exc}") from None
        behind = np.flatnonzero(depth <= 0)
        if behind.size:
            problem = f"{behind.size} point(s) behind camera {k} (first index {behind[0]}): it cannot see them"
            raise degenerate(func, name, problem)
        out.append(x)
    return out[0], out[1]
