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

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.paths import data_path

from . import camera as cam
from .rig import StereoRig

__all__ = [
    "StereoScene",
    "load_scene",
    "random_scene",
    "sample_scene",
    "observe",
    "reconstruct_entities",
    "circle_center_via_plane",
    "entity_errors",
    "line_polyline",
    "circle_polyline",
    "square_polyline",
]


# ---------------------------------------------------------------- the scene
def _unit(v, func: str = "stereo") -> np.ndarray:
    v = np.asarray(v, dtype=float)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise InvalidInputError(f"{func}: a direction must be 3 finite numbers, got {v!r}")
    n = np.linalg.norm(v)
    if n == 0:
        raise DegenerateGeometryError(f"{func}: the zero vector is not a direction")
    return v / n


def _frame(normal, hint=(0.0, 0.0, 1.0)):
    """Two unit vectors u, v spanning the plane orthogonal to ``normal`` (v along ``hint`` if possible)."""
    n = _unit(normal, "frame")
    v = np.asarray(hint, dtype=float) - np.dot(hint, n) * n
    if np.linalg.norm(v) < 1e-6:
        v = np.eye(3)[np.argmin(np.abs(n))] - n * n[np.argmin(np.abs(n))]
    v = _unit(v)
    return np.cross(v, n), v


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

    def board_corners(self) -> np.ndarray:
        """The board's four corners (4, 3), counter-clockwise seen from the side the normal points to."""
        u, v = _frame(self.board_normal, self.board_up)
        w, h = self.board_size
        signs = ((-1, -1), (1, -1), (1, 1), (-1, 1))
        return np.array([self.board_center + 0.5 * (sx * w * u + sy * h * v) for sx, sy in signs])

    def truth(self) -> dict:
        """Ground-truth parameters in the format of :func:`reconstruct_entities`."""
        a, b = self.segment
        r = _unit(b - a)
        n = _unit(self.board_normal)
        return {
            "point": {"points": np.array(self.points, dtype=float)},
            "pair": {"endpoints": np.array(self.segment, dtype=float)},
            "line": {
                "direction": r,
                "closest_point": a - np.dot(a, r) * r,
                "length": float(np.linalg.norm(b - a)),
                "midpoint": 0.5 * (a + b),
            },
            "circle": {"center": self.circle_center, "radius": self.circle_radius, "normal": _unit(self.circle_normal)},
            "plane": {"normal": n, "distance": float(np.dot(n, self.board_center)), "point": self.board_center},
            "sphere": {"center": self.sphere_center, "radius": self.sphere_radius},
        }


def load_scene(path=None) -> StereoScene:
    """The scene described in ``data/stereo_scene.json`` (made by ``data/stereo_make.py``)."""
    d = json.loads(Path(path or data_path("stereo_scene.json")).read_text())
    a = np.asarray
    return StereoScene(
        a(d["points"], float), a([d["segment"]["a"], d["segment"]["b"]], float),
        a(d["circle"]["center"], float), _unit(d["circle"]["normal"]), float(d["circle"]["radius"]),
        a(d["plane"]["center"], float), _unit(d["plane"]["normal"]), _unit(d["plane"]["up"]),
        tuple(d["plane"]["size"]), a(d["sphere"]["center"], float), float(d["sphere"]["radius"]),
    )  # fmt: skip


def random_scene(rng: np.random.Generator, rig: StereoRig, depth=(1.5, 4.0)) -> StereoScene:
    """Random objects in front of ``rig``, all inside both images (for tests of generality).

    Each object's size is a random fraction (5-25 %) of the width the left
    camera sees at its depth; surfaces face the rig within 60 degrees so that
    they are seen at a usable angle.
    """
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
        raise DegenerateGeometryError("random_scene: could not place an object inside both views")

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
    u, v = _frame(scene.circle_normal)
    ang0 = rng.uniform(0, 2 * np.pi)
    ring = lambda t: scene.circle_center + scene.circle_radius * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)  # noqa: E731
    out = {"points": np.array(scene.points, float), "segment": np.array(scene.segment, float)}
    out["circle_key"] = ring(ang0 + np.array([0.0, 2.0, 4.0]) * np.pi / 3)
    out["circle"] = ring(rng.uniform(0, 2 * np.pi, n_circle))
    corners = scene.board_corners()
    out["plane_key"] = corners[[0, 1, 3]]
    bu, bv = _frame(scene.board_normal, scene.board_up)
    st = rng.uniform(-0.5, 0.5, size=(n_board, 2)) * np.asarray(scene.board_size)
    out["plane"] = scene.board_center + st[:, :1] * bu + st[:, 1:] * bv
    S, r = np.asarray(scene.sphere_center, float), scene.sphere_radius
    to_c = [_unit(C - S) for C in (rig.C1, rig.C2)]
    pole = _unit(to_c[0] + to_c[1])
    pu, pv = _frame(pole)
    key = [pole] + [np.cos(0.9) * pole + np.sin(0.9) * (np.cos(a) * pu + np.sin(a) * pv) for a in (0.0, 2.1, 4.2)]
    out["sphere_key"] = S + r * np.array(key)
    dirs = np.empty((0, 3))
    while len(dirs) < n_sphere:
        d = rng.normal(size=(4 * n_sphere, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        ok = (d @ to_c[0] > np.cos(np.radians(70))) & (d @ to_c[1] > np.cos(np.radians(70)))
        dirs = np.vstack([dirs, d[ok]])
    out["sphere"] = S + r * dirs[:n_sphere]
    return out


def observe(rig: StereoRig, X, noise_px: float = 0.0, rng: np.random.Generator | None = None):
    """Pixel coordinates of X (N, 3) in both views, plus Gaussian noise of ``noise_px`` (std, per coordinate).

    Returns
    -------
    x1, x2 : ndarray, shape (N, 2)
    """
    x1, x2 = rig.project(X)
    if noise_px > 0:
        if rng is None:
            raise InvalidInputError("observe: pass rng (numpy.random.default_rng(seed)) to add noise")
        x1 = x1 + rng.normal(scale=noise_px, size=x1.shape)
        x2 = x2 + rng.normal(scale=noise_px, size=x2.shape)
    return x1, x2


# ------------------------------------------------- conformal entities (4.1)
def circle_center_via_plane(Z):
    """Circle centre by the first way of 4.1: plane (2.119), axis (2.120), their meet (2.121).

    ``P_z* = z* ^ e`` is the circle's plane (2.119) and ``L_z* = z ^ e`` the
    axis through the centre (2.120).  Their intersection is the flat point
    ``e ^ s_e0`` of (2.121), where ``s_e0 = p_z + e0`` is the sphere centred
    at p_z through the origin.  As printed, (2.121) contracts the axis with
    the *dual* plane ``P_z*`` (a 4-blade), which gives a vector (zero); the
    flat point comes from the standard-form plane ``P_z = P_z* I_c``:
    ``L_z* . P_z = e ^ s_e0``.  Then ``s_e0 ~ -e0 . (e ^ s_e0)`` and p_z is
    its Euclidean part after normalising (2.115, 2.116).

    Parameters
    ----------
    Z : Multivector
        Circle in dual form ``a ^ b ^ c`` (grade 3).

    Returns
    -------
    ndarray, shape (3,)
    """
    z = cga.standard_form(Z)
    Pz = cga.standard_form(cga.circle_plane(Z))  # (2.119), standard form
    Lz = z ^ cga.einf  # (2.120)
    flat = Lz | Pz  # (2.121), corrected: e ^ s_e0
    s = -(cga.eo | flat)
    return cga.euclidean(cga.normalize_point(s, "circle_center_via_plane"))


def reconstruct_entities(rig: StereoRig, views: dict, method: str = "midpoint") -> dict:
    """Triangulate the minimal point sets and build every entity of 4.1 in G(4,1).

    Parameters
    ----------
    rig : StereoRig
    views : dict
        ``name -> (x1, x2)`` pixel coordinates for ``"points"`` (N),
        ``"segment"`` (2), ``"circle_key"`` (3), ``"plane_key"`` (3) and
        ``"sphere_key"`` (4), e.g. ``observe`` applied to :func:`sample_scene`.
    method : {"midpoint", "dlt"}
        Triangulation (A.14).

    Returns
    -------
    dict
        ``"point"``: points (N, 3) from up (2.62) and down (2.114), conformal
        ``blade``; ``"pair"``: ``endpoints`` (2.68, 2.131); ``"line"``:
        ``direction`` (2.127), ``closest_point`` (2.129), ``length`` (2.125);
        ``"circle"``: ``center`` (2.123, 2.115, 2.116), ``center_via_plane``
        (2.119-2.121), ``radius`` (2.122), ``normal`` (2.119); ``"plane"``:
        ``normal``, ``distance`` (2.77), and the circumcircle's ``center`` and
        ``radius`` used to draw it; ``"sphere"``: ``center`` and ``radius``
        (2.75, 2.115, 2.116, 2.73).  Each holds its conformal ``blade``.
    """
    tri = {k: cam.triangulate(rig.P1, rig.P2, *views[k], method=method) for k in views}
    out = {}
    X = cga.up(tri["points"])  # (2.62), a batch
    out["point"] = {"points": cga.down(X), "blade": X}  # (2.114)
    a, b = tri["segment"]
    PP = cga.point_pair(a, b)  # (2.68)
    out["pair"] = {"endpoints": np.array(cga.point_pair_endpoints(PP)), "blade": PP}  # (2.131)
    L = cga.line_from_points(a, b)  # (2.81)
    length = float(np.sqrt((L * L).scalar()))  # (2.125)
    out["line"] = {
        "direction": cga.line_direction(L),
        "closest_point": cga.line_closest_point(L),
        "length": length,
        "blade": L,
    }
    Z = cga.circle_from_points(*tri["circle_key"])  # (2.80)
    c, r, n = cga.circle_center_radius(Z)
    out["circle"] = {"center": c, "center_via_plane": circle_center_via_plane(Z), "radius": r, "normal": n, "blade": Z}
    Pl = cga.plane_from_points(*tri["plane_key"])  # (2.77)
    n, d = cga.plane_normal_distance(Pl)
    c, r, _ = cga.circle_center_radius(cga.circle_from_points(*tri["plane_key"]))
    out["plane"] = {"normal": n, "distance": d, "center": c, "radius": r, "blade": Pl}
    S = cga.sphere_from_points(*tri["sphere_key"])  # (2.75)
    c, r = cga.sphere_center_radius(S)
    out["sphere"] = {"center": c, "radius": r, "blade": S}
    return out


def _angle(u, v, signed=True) -> float:
    c = float(np.dot(_unit(u), _unit(v)))
    c = c if signed else abs(c)
    return float(np.arctan2(np.linalg.norm(np.cross(_unit(u), _unit(v))), c))


def entity_errors(truth: dict, est: dict) -> dict:
    """Errors of estimated entity parameters against the truth (metres, radians).

    Points and point pairs: largest position error.  Lines: direction angle,
    closest-point error and ``offset``, the distance of the true segment's
    midpoint from the estimated line.  Circles and spheres: centre and radius errors
    (and the circle's normal).  Planes: normal angle and ``offset``, the
    distance of the true object's centre from the estimated plane (the plane's
    distance to the world origin would mix in the normal error times a lever
    arm of metres).  Normals of circles and planes are compared as unoriented
    lines (their sign depends on the order of the points).

    Returns
    -------
    dict
        ``entity -> {quantity: error}`` for the entities present in both.
    """
    out = {}
    both = [k for k in ("point", "pair", "line", "circle", "plane", "sphere") if k in est and k in truth]
    for k in both:
        e, t = est[k], truth[k]
        if k in ("point", "pair"):
            key = "points" if k == "point" else "endpoints"
            out[k] = {"position": float(np.max(np.linalg.norm(e[key] - t[key], axis=1)))}
        elif k == "line":
            pos = float(np.linalg.norm(e["closest_point"] - t["closest_point"]))
            out[k] = {"direction": _angle(e["direction"], t["direction"]), "position": pos}
            if "midpoint" in t:
                m = t["midpoint"] - e["closest_point"]
                out[k]["offset"] = float(np.linalg.norm(m - np.dot(m, e["direction"]) * e["direction"]))
        elif k == "plane":
            offset = abs(float(np.dot(e["normal"], t["point"])) - e["distance"])
            out[k] = {"normal": _angle(e["normal"], t["normal"], signed=False), "offset": offset}
        else:
            out[k] = {"center": float(np.linalg.norm(e["center"] - t["center"]))}
            out[k]["radius"] = abs(e["radius"] - t["radius"])
            if k == "circle":
                out[k]["normal"] = _angle(e["normal"], t["normal"], signed=False)
    return out


# ------------------------------------------------------------ drawing (4.1)
def line_polyline(L, PP) -> np.ndarray:
    """The drawn segment of a line as 4.1 describes it (2.126, 2.127, 2.129, 2.131).

    The line is normalised, its direction r and the point p closest to the
    origin extracted; the endpoints of the stored point pair PP, projected onto
    the line, say how far from p to draw.

    Returns
    -------
    ndarray, shape (2, 3)
    """
    r, p = cga.line_direction(L), cga.line_closest_point(L)
    ends = np.array(cga.point_pair_endpoints(PP))
    t = (ends - p) @ r
    return p + t[:, None] * r


def circle_polyline(center, normal, radius, n: int = 64, phase: float = 0.0) -> np.ndarray:
    """Points on a circle drawn as in 4.1: a perpendicular vector turned by a rotor (2.96).

    A unit vector v orthogonal to the normal is scaled by the radius, turned
    about the normal by the rotors ``R_z(theta)`` (2.96, 2.98) and shifted by
    the centre.

    Returns
    -------
    ndarray, shape (n + 1, 3)
        Closed polyline (last point = first).
    """
    u, _ = _frame(normal)
    theta = phase + np.linspace(0.0, 2 * np.pi, n + 1)
    R = cga.rotor(_unit(normal, "circle_polyline"), theta)  # a batch of rotors about the normal
    v = cga.vector(radius * u)
    return np.asarray(center, float) + cga.euclidean(R * v * ~R)


def square_polyline(center, normal, half_diagonal) -> np.ndarray:
    """The square 4.1 draws for a plane: the circle construction with four 90-degree turns.

    Returns
    -------
    ndarray, shape (5, 3)
    """
    return circle_polyline(center, normal, half_diagonal, n=4, phase=np.pi / 4)
