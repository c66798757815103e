"""Test scenes with ground truth for entity detection: entities placed in front of a stereo head, and clutter.

A scene holds several plane patches (boards), sphere caps (balls, the part
both cameras see), circles (rims, rings) and line segments (handles), placed
at random in front of a stereo head without touching one another, plus
clutter points.  Two ways to see it:

* :func:`cloud_scene`: the true points plus isotropic Gaussian noise (metres);
* :func:`stereo_scene`: every point projected into both cameras of the rig
  (A.5), perturbed by Gaussian pixel noise, and triangulated (A.14), as
  :func:`cga_lessons.stereo.observe` and :func:`cga_lessons.stereo.triangulation.triangulate`
  do for section 4.1.  The per-point covariances of the triangulated points
  (:func:`~cga_lessons.stereo.detect_noise.triangulation_covariance`) are the
  sensor fact handed to the detector: depth noise grows with the square of the
  distance, so a plane at 2.8 m is ~5x noisier than one at 1.2 m.

The default head is a robot's wide stereo pair (40 cm baseline, 1200 px focal
length, 1600 x 1200): at 2 m and 1 px its depth noise is ~1.2 cm.  (The bundled
head of ``data/stereo_rig.json``, 12 cm and 700 px, has ~6.7 cm there: too
noisy for balls of 15-30 cm; use it with a nearer ``depth``.)

:func:`~cga_lessons.stereo.detect_scores.evaluate` matches detections to the
truth by kind and position and returns precision and recall per kind.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import DegenerateGeometryError, GeometryError
from cga_lessons.checks import degenerate
from cga_lessons.conformal import CircleParameters, LineParameters, PlaneParameters, SphereParameters

from . import head as st
from . import validate as vd
from .detect_noise import triangulation_covariance
from .detect_params import PatchParameters, indices, of_kind
from .experiments import random_points_in_view
from .rig import StereoRig, stereo_head
from .triangulation import triangulate

__all__ = ["SceneConfig", "TruthEntity", "DetectScene", "scene_rig", "cloud_scene", "stereo_scene"]

KINDS = ("plane", "sphere", "circle", "line")


@dataclass(frozen=True)
class SceneConfig:
    """How a test scene is made (lengths in metres).

    ``n_*``: entities of each kind; ``*_sides``/``*_radius``/``line_length``:
    uniform size ranges; ``surface_density`` (points per m^2 of visible
    surface) and ``curve_density`` (points per m of curve); ``clutter``: extra
    points uniform in the view between the ``depth`` limits; ``gap``: least
    clearance between the bounding spheres of two entities; ``noise_m``: 3D
    noise of :func:`cloud_scene`; ``noise_px``: pixel noise of
    :func:`stereo_scene`; ``baseline``, ``focal_px``, ``image_size``, ``tilt``:
    the stereo head (:func:`cga_lessons.stereo.rig.stereo_head`).
    """

    n_planes: int = 3
    n_spheres: int = 3
    n_circles: int = 3
    n_lines: int = 3
    plane_sides: tuple = (0.35, 0.7)
    sphere_radius: tuple = (0.15, 0.3)
    circle_radius: tuple = (0.12, 0.25)
    line_length: tuple = (0.5, 0.9)
    surface_density: float = 1500.0
    curve_density: float = 100.0
    clutter: int = 300
    depth: tuple = (1.2, 2.8)
    gap: float = 0.1
    noise_m: float = 0.005
    noise_px: float = 0.75
    baseline: float = 0.4
    focal_px: float = 1200.0
    image_size: tuple = (1600, 1200)
    tilt: float = 0.3

    def __post_init__(self):
        f, big = "SceneConfig", 10**7
        for name in ("n_planes", "n_spheres", "n_circles", "n_lines", "clutter"):
            object.__setattr__(self, name, checks.integer(getattr(self, name), f, name, low=0, high=big))
        for name in ("plane_sides", "sphere_radius", "circle_radius", "line_length", "depth"):
            object.__setattr__(self, name, vd.interval(getattr(self, name), f, name, "a range (low, high)"))
        for name in ("surface_density", "curve_density", "baseline", "focal_px", "noise_px"):
            object.__setattr__(
                self, name, checks.real(getattr(self, name), f, name, low=0.0, strict_low=True, high=1e9)
            )
        for name in ("gap", "noise_m"):
            object.__setattr__(self, name, checks.real(getattr(self, name), f, name, low=0.0, high=1e9))
        object.__setattr__(self, "image_size", vd.image_size(self.image_size, f))
        object.__setattr__(self, "tilt", checks.real(self.tilt, f, "tilt"))


@dataclass(frozen=True, eq=False)
class TruthEntity:
    """A true entity: ``kind``, ``params`` (as in :class:`cga_lessons.stereo.detect_search.DetectedEntity`: a plane's
    ``center`` and ``sides`` are the patch's, a :class:`~cga_lessons.stereo.detect_params.PatchParameters`, a line's
    ``length`` the segment's), ``extent`` (radius of its
    bounding sphere) and the indices of its points in the scene's cloud."""

    kind: str
    params: PlaneParameters | SphereParameters | CircleParameters | LineParameters
    extent: float
    indices: np.ndarray

    def __post_init__(self):
        f = "TruthEntity"
        kind, params = of_kind(self.kind, self.params, f)
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "extent", checks.real(self.extent, f, "extent", low=0.0))
        object.__setattr__(self, "indices", indices(self.indices, f, "indices"))


@dataclass(frozen=True, eq=False)
class DetectScene:
    """A cloud with ground truth.

    ``points`` (N, 3) as measured; ``true_points`` (N, 3) before noise;
    ``labels`` (N,) index into ``truth`` or -1 for clutter; ``noise``: the
    sensor fact for the detector (a sigma, or (N, 3, 3) covariances);
    ``rig``: the stereo head.
    """

    points: np.ndarray
    true_points: np.ndarray
    labels: np.ndarray
    truth: tuple
    noise: object
    rig: StereoRig

    def noise_scale(self) -> float:
        """RMS over the points of their largest noise standard deviation (metres): the scale of the tolerances."""
        if np.ndim(self.noise) == 0:
            return float(self.noise)
        return float(np.sqrt(np.mean(np.linalg.eigvalsh(self.noise)[:, -1])))


def scene_rig(cfg: SceneConfig) -> StereoRig:
    """The stereo head of ``cfg`` (at 1.2 m height, looking along +x, tilted down by ``cfg.tilt``)."""
    f = "scene_rig"
    cfg = checks.instance(cfg, f, "cfg", SceneConfig, "a SceneConfig")
    try:
        return stereo_head(cfg.baseline, cfg.focal_px, tuple(cfg.image_size), tilt=cfg.tilt)
    except GeometryError as exc:
        raise degenerate(f, "cfg", f"describes no valid stereo head: {exc}") from None


def _unit(v):
    return v / np.linalg.norm(v)


def _frame(n, rng):
    u = _unit(np.cross(n, rng.normal(size=3)))
    return u, np.cross(n, u)


def _place(rng, rig, cfg, extent, placed):
    """A centre whose bounding sphere (radius ``extent``) is in both views and clear of the entities placed."""
    Kinv = np.linalg.inv(rig.K)
    w, h = rig.image_size
    cube = np.vstack([rig.R1, -rig.R1])  # the sphere's extreme points along the camera's axes
    for _ in range(2000):
        ray = rig.R1.T @ Kinv @ np.array([rng.uniform(0.1, 0.9) * w, rng.uniform(0.1, 0.9) * h, 1.0])
        p = rig.C1 + rng.uniform(*cfg.depth) * ray
        if not np.all(rig.in_view(p + extent * cube, margin=5)):
            continue
        if all(np.linalg.norm(p - q) > extent + e + cfg.gap for q, e in placed):
            return p
    raise DegenerateGeometryError("stereo_detect_scenes: could not place an entity; use fewer or smaller ones")


def _facing(rng, p, rig):
    """A unit normal within ~60 degrees of the direction from p to the head."""
    to_cam = _unit(0.5 * (rig.C1 + rig.C2) - p)
    for _ in range(1000):
        n = _unit(to_cam + rng.normal(scale=0.6, size=3))
        if n @ to_cam > 0.5:
            return n
    return to_cam


def _orient(v):
    return v if v[np.argmax(np.abs(v))] > 0 else -v


def _entities(rng, rig, cfg):
    """The true entities and their noise-free points."""
    kinds = ["plane"] * cfg.n_planes + ["sphere"] * cfg.n_spheres + ["circle"] * cfg.n_circles
    kinds += ["line"] * cfg.n_lines
    placed, out = [], []
    for kind in kinds:
        if kind == "plane":
            a, b = rng.uniform(*cfg.plane_sides, size=2)
            ext = 0.5 * np.hypot(a, b)
        elif kind == "sphere":
            ext = r = rng.uniform(*cfg.sphere_radius)
        elif kind == "circle":
            ext = r = rng.uniform(*cfg.circle_radius)
        else:
            length = rng.uniform(*cfg.line_length)
            ext = 0.5 * length
        p = _place(rng, rig, cfg, ext, placed)
        placed.append((p, ext))
        if kind == "plane":
            n = _orient(_facing(rng, p, rig))
            u, v = _frame(n, rng)
            m = int(round(cfg.surface_density * a * b))
            st_ = rng.uniform(-0.5, 0.5, size=(m, 2)) * [a, b]
            pts = p + st_[:, :1] * u + st_[:, 1:] * v
            prm = PatchParameters(normal=n, distance=float(n @ p), center=p, sides=(float(a), float(b)))
        elif kind == "sphere":
            to_c = [_unit(C - p) for C in (rig.C1, rig.C2)]
            d = rng.normal(size=(20000, 3))
            d /= np.linalg.norm(d, axis=1, keepdims=True)
            ok = (d @ to_c[0] > np.cos(np.radians(70))) & (d @ to_c[1] > np.cos(np.radians(70)))
            m = int(round(cfg.surface_density * 4 * np.pi * r * r * ok.mean()))
            pts = p + r * d[ok][:m]
            prm = SphereParameters(center=p, radius=float(r))
        elif kind == "circle":
            n = _orient(_facing(rng, p, rig))
            u, v = _frame(n, rng)
            t = rng.uniform(0, 2 * np.pi, int(round(cfg.curve_density * 2 * np.pi * r)))
            pts = p + r * (np.cos(t)[:, None] * u + np.sin(t)[:, None] * v)
            prm = CircleParameters(center=p, radius=float(r), normal=n)
        else:
            view = _unit(p - rig.C1)
            for _ in range(1000):
                d = _unit(rng.normal(size=3))
                if abs(d @ view) < 0.7:  # not nearly along the viewing ray
                    break
            d = _orient(d)
            pts = p + np.outer(rng.uniform(-0.5, 0.5, int(round(cfg.curve_density * length))) * length, d)
            prm = LineParameters(point=p, direction=d, length=float(length))
        out.append((kind, prm, float(ext), pts))
    return out


def _assemble(rng, rig, cfg, func: str):
    for attempt in range(20):  # a crowded layout can fail: start it again (same generator, so still seeded)
        try:
            ents = _entities(rng, rig, cfg)
            break
        except DegenerateGeometryError:
            if attempt == 19:
                raise degenerate(
                    func, "cfg", "could not place the entities in view; use fewer or smaller ones"
                ) from None
    try:
        clutter = random_points_in_view(rig, cfg.clutter, rng, depth=cfg.depth) if cfg.clutter else np.empty((0, 3))
    except GeometryError as exc:
        raise degenerate(func, "cfg", f"no clutter can be placed: {exc}") from None
    X = np.vstack([e[3] for e in ents] + [clutter])
    labels = np.concatenate([np.full(len(e[3]), i) for i, e in enumerate(ents)] + [np.full(len(clutter), -1)])
    order = rng.permutation(len(X))  # no information in the order of the points
    X, labels = X[order], labels[order]
    truth = tuple(TruthEntity(k, prm, ext, np.flatnonzero(labels == i)) for i, (k, prm, ext, _) in enumerate(ents))
    return X, labels, truth


def _check(cfg, rng, func):
    checks.instance(cfg, func, "cfg", SceneConfig, "a SceneConfig")
    checks.generator(rng, func)


def cloud_scene(rng: np.random.Generator, cfg: SceneConfig | None = None) -> DetectScene:
    """A scene whose points carry isotropic Gaussian noise ``cfg.noise_m`` (metres); ``noise`` is that sigma."""
    cfg = SceneConfig() if cfg is None else cfg
    _check(cfg, rng, "cloud_scene")
    rig = scene_rig(cfg)
    X, labels, truth = _assemble(rng, rig, cfg, "cloud_scene")
    noisy = X + rng.normal(scale=cfg.noise_m, size=X.shape)
    return DetectScene(noisy, X, labels, truth, float(cfg.noise_m), rig)


def stereo_scene(rng: np.random.Generator, cfg: SceneConfig | None = None, rig: StereoRig | None = None):
    """A scene seen by the stereo head: projected (A.5), ``cfg.noise_px`` pixel noise, triangulated (A.14).

    ``noise`` is the (N, 3, 3) first-order covariance of each triangulated point.
    """
    f = "stereo_scene"
    cfg = SceneConfig() if cfg is None else cfg
    _check(cfg, rng, f)
    if rig is not None:
        rig = checks.instance(rig, f, "rig", StereoRig, "a StereoRig (stereo_head, random_rig, load_rig) or None")
    rig = rig or scene_rig(cfg)
    X, labels, truth = _assemble(rng, rig, cfg, f)
    x1, x2 = st.observe(rig, X, cfg.noise_px, rng)
    Y = triangulate(rig.P1, rig.P2, x1, x2)
    cov = triangulation_covariance(rig.P1, rig.P2, x1, x2, cfg.noise_px)
    return DetectScene(Y, X, labels, truth, cov, rig)
