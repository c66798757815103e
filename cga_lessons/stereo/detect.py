"""Automatic registration of conformal entities in a 3D point cloud (the thesis's future work, 6.2.2).

Section 4.1 fits spheres, planes, circles and lines to points chosen for it.
:func:`detect_entities` finds them in a raw cloud (e.g. triangulated stereo
points) without being told which points belong together:

1. **Search** (RANSAC with local minimal sets).  Each round draws, for every
   kind, ``hypotheses`` minimal sets: a random seed point and 1-3 more among
   its k nearest free points (k drawn from ``neighbourhoods``, so that small
   and large objects are both sampled well).  Each set is turned into its
   conformal entity (sphere ``a ^ b ^ c ^ d`` 2.75, plane ``e ^ a ^ b ^ c``
   2.77, circle ``a ^ b ^ c`` 2.80, line ``e ^ a ^ b`` 2.81) and scored by its
   number of inliers on a random subset of the free points.
2. **Refinement** (local optimisation).  The best hypothesis of each kind is
   refitted by the conformal least squares of section 4.1 on its inliers
   (:mod:`cga_lessons.stereo.detect_models`), its inliers recomputed, and so on
   until they stop changing; inliers are always the largest connected piece
   (neighbours closer than ``connect_radius``), so that one entity never
   collects far-away points of another object that happens to lie on it.
3. **Model selection**.  The largest refined support S could be any of
   several kinds: points on a circle also lie on its plane and on a pencil of
   spheres, points on a plane on spheres of huge radius, points on a line on a
   pencil of planes.  Every kind is fitted to S and regrown on the free points
   (polished to maximum likelihood, :mod:`cga_lessons.stereo.detect_ml`).
   *Dimension* first: a curve (line, circle) wins when its support is within
   ``selection_z`` Poisson standard deviations of the best surface's (a
   surface through a ring gains only stray clutter).  Then the *nested pair*
   of that dimension (the plane is the sphere through infinity, 2.77; the line
   the circle through infinity, 2.81) is decided by a likelihood-ratio test:
   the sphere (or circle) is kept only if its truncated Mahalanobis cost
   ``sum min(m, gate)`` over both supports is lower than the plane's (line's)
   by more than the ``selection_confidence`` quantile of chi-square with the
   extra degrees of freedom (1 for the sphere, 2 for the circle).  So a sphere
   whose radius is so large that its curvature is lost in the noise is a
   plane, at the stated confidence.
4. **Acceptance**.  The chosen entity is kept if it has at least
   ``min_surface_inliers`` / ``min_curve_inliers`` points and significantly
   more than clutter would put in its gate (a Poisson test at ``significance``
   standard deviations; the clutter density is that of the free points, an
   overestimate early on, and the gate's volume is the entity's area or
   length times its cross-section).  Its points, with the wider
   ``removal_confidence`` gate, are removed and the search starts again,
   until ``max_failures`` rounds in a row find nothing acceptable.
5. **Non-maximum suppression**.  Detections of the same kind whose supports
   come within ``2 connect_radius`` and whose union one entity explains (at
   least ``merge_fraction`` of the union in its gate) are merged.

Thresholds come from the noise model (:mod:`cga_lessons.stereo.detect_noise`):
a point is an inlier when its squared Mahalanobis residual is below the
``confidence`` quantile of chi-square with 1 (surfaces) or 2 (curves)
degrees of freedom; the noise is a sensor fact (a sigma, or per-point
covariances from :func:`~cga_lessons.stereo.detect_noise.triangulation_covariance`)
or estimated from the cloud (:func:`~cga_lessons.stereo.detect_noise.estimate_noise`).
The only length that is not a noise level is ``connect_radius``, a multiple
of the cloud's median point spacing.  Each detection carries the covariance
of its parameters (:func:`~cga_lessons.stereo.detect_ml.covariance`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.checks import fail

from . import detect_models as dm
from . import validate as vd
from .detect_noise import as_noise_model
from .detect_search import Search, merge

__all__ = ["DetectConfig", "detect_entities"]


@dataclass(frozen=True)
class DetectConfig:
    """Settings of :func:`detect_entities` (defaults suit clouds of 10^3-10^4 points of objects 10 cm - 1 m).

    Attributes
    ----------
    kinds : tuple of str
        Kinds to look for, among ``"plane", "sphere", "circle", "line"``.
    confidence : float
        Inlier gate: the chi-square quantile of the Mahalanobis residual (0.99: 1 % of true points missed).
    removal_confidence : float
        Wider gate for removing an accepted entity's points (so its tails do not seed false entities).
    merge_fraction : float
        Share of the union of two detections one entity must explain to merge them (0.9: the 0.99 gate's 99 %,
        less room for clutter).
    selection_z : float
        A curve beats a surface when its support is within this many Poisson deviations of the surface's.
    selection_confidence : float
        Confidence of the likelihood-ratio test that keeps a sphere over a plane, a circle over a line.
    hypotheses : int
        Minimal sets per kind per round.
    neighbourhoods : tuple of int
        Neighbourhood sizes (in points) from which the rest of a minimal set is drawn around its seed.
    score_points : int
        Hypotheses are scored on at most this many random free points.
    min_conditioning : float
        Minimal sets flatter than this are skipped (see :func:`~cga_lessons.stereo.detect_models.hypotheses`).
    refine_iterations : int
        Refit / re-select rounds of the local optimisation.
    connect_factor : float
        ``connect_radius`` = this times the median nearest-neighbour distance of the cloud (6: curves sampled
        at random keep gaps up to ~ln(n) times their mean spacing, and must not fall apart).
    connect_radius : float or None
        Neighbours closer than this are connected (metres); None derives it from ``connect_factor``.
    min_surface_inliers, min_curve_inliers : int
        Smallest accepted supports.
    significance : float
        Required excess over the clutter expected in the gate, in Poisson standard deviations.
    max_entities, max_failures : int
        Stop after this many entities, or this many fruitless rounds in a row.
    """

    kinds: tuple = ("plane", "sphere", "circle", "line")
    confidence: float = 0.99
    removal_confidence: float = 0.999
    merge_fraction: float = 0.9
    selection_z: float = 3.0
    selection_confidence: float = 0.999
    hypotheses: int = 100
    neighbourhoods: tuple = (16, 48, 144)
    score_points: int = 1500
    min_conditioning: float = 0.05
    refine_iterations: int = 8
    connect_factor: float = 6.0
    connect_radius: float | None = None
    min_surface_inliers: int = 40
    min_curve_inliers: int = 15
    significance: float = 5.0
    max_entities: int = 50
    max_failures: int = 3

    def __post_init__(self):
        f, put = "DetectConfig", lambda name, value: object.__setattr__(self, name, value)
        kinds = checks.instance(self.kinds, f, "kinds", (tuple, list), f"a tuple of distinct kinds among {dm.KINDS}")
        kinds = tuple(checks.choice(k, f, "kinds", dm.KINDS) for k in kinds)
        if not kinds or len(set(kinds)) != len(kinds):
            raise fail(f, "kinds", f"must be a non-empty tuple of distinct kinds among {dm.KINDS}, got {self.kinds!r}")
        put("kinds", kinds)
        for name in ("confidence", "removal_confidence", "merge_fraction", "selection_confidence"):
            put(name, checks.real(getattr(self, name), f, name, low=0.0, high=1.0, strict_low=True, strict_high=True))
        if self.removal_confidence < self.confidence:
            raise fail(f, "removal_confidence", f"must be >= confidence ({self.confidence})")
        for name in ("hypotheses", "score_points", "refine_iterations", "min_surface_inliers", "min_curve_inliers",
                     "max_entities", "max_failures"):  # fmt: skip
            put(name, checks.integer(getattr(self, name), f, name, low=1, high=10**9))
        hoods = checks.instance(self.neighbourhoods, f, "neighbourhoods", (tuple, list, np.ndarray), "whole numbers")
        hoods = tuple(checks.integer(k, f, "neighbourhoods", low=3, high=10**6) for k in np.ravel(hoods))
        if not hoods:
            raise fail(f, "neighbourhoods", "must hold at least one neighbourhood size")
        put("neighbourhoods", hoods)
        for name in ("min_conditioning", "connect_factor", "significance", "selection_z"):
            put(name, checks.real(getattr(self, name), f, name, low=0.0, high=1e9))
        if self.connect_radius is not None:
            put("connect_radius", checks.real(self.connect_radius, f, "connect_radius", low=0.0, strict_low=True))


def _check_cloud(X, func: str, at_least: int) -> np.ndarray:
    X = vd.array(X, func, "X", (None, 3), at_least=at_least)  # numbers, shape (N, 3), finite, bounded, count
    if np.ptp(X, axis=0).max() == 0:
        raise fail(func, "X", "all points coincide")
    return X


def detect_entities(X, rng: np.random.Generator, config: DetectConfig | None = None, noise=None) -> list:
    """Detect planes, spheres, circles and lines in a point cloud (see the module docstring for the method).

    Parameters
    ----------
    X : array_like, shape (N, 3)
        The cloud (metres), e.g. triangulated stereo points.
    rng : numpy.random.Generator
        Source of every random choice: the same seed gives the same detections.
    config : DetectConfig, optional
    noise : None, float, array (N, 3, 3) or NoiseModel
        The points' noise: None estimates an isotropic sigma from the cloud;
        a float is an isotropic sigma (metres); an array gives per-point
        covariances (e.g. :func:`~cga_lessons.stereo.detect_noise.triangulation_covariance`).

    Returns
    -------
    list of DetectedEntity
        Largest support first.  Each point belongs to at most one entity.

    Raises
    ------
    InvalidInputError
        Wrong shapes, NaN/inf, too few points (fewer than the smallest support
        the configuration accepts), a bad ``rng``, ``config`` or ``noise``.
    """
    func = "detect_entities"
    config = DetectConfig() if config is None else config
    checks.instance(config, func, "config", DetectConfig, "a DetectConfig")
    checks.generator(rng, func)
    small = min(config.min_curve_inliers if dm.CODIM[k] == 2 else config.min_surface_inliers for k in config.kinds)
    X = _check_cloud(X, func, max(small, max(dm.MINIMAL.values()) + 1))
    from scipy.spatial import cKDTree

    model = as_noise_model(noise, X, func)
    eps = config.connect_radius
    if eps is None:
        nn, _ = cKDTree(X).query(X, k=2)
        eps = config.connect_factor * float(np.median(nn[:, 1]))
        eps = eps if eps > 0 else float(np.ptp(X, axis=0).max()) * 1e-3
    search = Search(X, model, config, eps)
    free = np.ones(len(X), dtype=bool)
    ents: list = []
    failures = 0
    while len(ents) < config.max_entities and failures < config.max_failures:
        fidx = np.flatnonzero(free)
        if len(fidx) < small:
            break
        best = search.best_support(fidx, rng)
        if best is None:
            failures += 1
            continue
        sel, start, sizes = search.select(best[2], fidx)
        if sel is None:
            failures += 1
            continue
        prm, final = start
        if not search.significant(sel, prm, final, fidx):
            failures += 1
            continue
        failures = 0
        ents.append(search.entity(sel, prm, final, sizes))
        wide = search.consensus(sel, prm, fidx, search.wide)
        near, _ = cKDTree(X[final]).query(X[wide], k=1)
        free[wide[near <= eps]] = False
        free[final] = False
    ents = merge(search, ents)
    return sorted(ents, key=lambda e: (-len(e.inliers), e.inliers[0]))
