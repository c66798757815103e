"""The scoring of entity detections against a scene's ground truth: position errors, matches, precision and recall.

:func:`evaluate` matches the detections of :func:`cga_lessons.stereo.detect_entities` to the true entities of a
test scene (:mod:`cga_lessons.stereo.detect_scenes`) by kind and position, largest detection first, and counts
per kind.  It returns a :class:`DetectionScore`: a :class:`KindScore` per kind and over all kinds, the
:class:`DetectionMatch` pairs with their :class:`DetectionError`, and the tolerance used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks

from . import validate as vd
from .detect_scenes import KINDS, DetectScene, TruthEntity
from .detect_search import DetectedEntity

__all__ = ["DetectionError", "DetectionMatch", "KindScore", "DetectionScore", "entity_errors", "evaluate"]


@dataclass(frozen=True)
class DetectionError:
    """Position errors of a detection against a true entity of its kind (metres, degrees; None: not of the kind).

    ``center``: plane, the distance between the centres (the detection's inliers' centroid on its plane, the
    patch's centre); line, the true point's distance along the detected line from the detection's point; sphere
    and circle, the distance between the centres.  ``angle``: between the normals (plane, circle) or directions
    (line).  ``offset``: the true centre's distance from the detected plane, the true point's distance from the
    detected line.  ``radius``: the radii's difference (sphere, circle).
    """

    center: float
    angle: float | None = None
    offset: float | None = None
    radius: float | None = None

    def __post_init__(self):
        checks.record(self, center=checks.length, angle=checks.length, offset=checks.length, radius=checks.length)


@dataclass(frozen=True)
class DetectionMatch:
    """A detection matched to a true entity: the ``detection``'s index, the ``truth``'s index and their ``errors``."""

    detection: int
    truth: int
    errors: DetectionError

    def __post_init__(self):
        f = "DetectionMatch"
        for name in ("detection", "truth"):
            object.__setattr__(self, name, checks.integer(getattr(self, name), f, name, low=0))
        checks.instance(self.errors, f, "errors", DetectionError, "a DetectionError (entity_errors)")


@dataclass(frozen=True)
class KindScore:
    """The score of one kind (or of all): ``tp`` detections matched to a true entity, of ``detected`` detections
    and ``truth`` true entities; ``precision`` = tp / detected and ``recall`` = tp / truth (1 when there are none)."""

    precision: float
    recall: float
    tp: int
    detected: int
    truth: int

    def __post_init__(self):
        f = "KindScore"
        for name in ("precision", "recall"):
            object.__setattr__(self, name, checks.real(getattr(self, name), f, name, low=0.0, high=1.0))
        for name in ("tp", "detected", "truth"):
            object.__setattr__(self, name, checks.integer(getattr(self, name), f, name, low=0))


@dataclass(frozen=True, eq=False)
class DetectionScore:
    """What :func:`evaluate` returns: ``kinds`` (kind -> :class:`KindScore`, for ``"plane"``, ``"sphere"``,
    ``"circle"``, ``"line"``), ``all`` (the same over every kind), ``matches`` (a tuple of
    :class:`DetectionMatch`) and ``tolerance`` (the position tolerance used, metres)."""

    kinds: dict
    all: KindScore
    matches: tuple
    tolerance: float

    def __post_init__(self):
        f = "DetectionScore"
        kinds = checks.instance(self.kinds, f, "kinds", dict, "a dict kind -> KindScore")
        for kind, score in kinds.items():
            checks.choice(kind, f, "kinds", KINDS)
            checks.instance(score, f, "kinds", KindScore, "KindScore values")
        checks.instance(self.all, f, "all", KindScore, "a KindScore")
        matches = checks.instance(self.matches, f, "matches", (tuple, list), "a tuple of DetectionMatch")
        for m in matches:
            checks.instance(m, f, "matches", DetectionMatch, "DetectionMatch items")
        object.__setattr__(self, "matches", tuple(matches))
        object.__setattr__(self, "tolerance", checks.real(self.tolerance, f, "tolerance", low=0.0))


def _angle(a, b) -> float:
    return float(np.degrees(np.arccos(np.clip(abs(float(np.dot(a, b))), 0.0, 1.0))))


def entity_errors(det, truth: TruthEntity) -> DetectionError:
    """Position errors of a detection against a true entity of the same kind (metres, degrees)."""
    p, t = det.params, truth.params
    if truth.kind == "plane":
        return DetectionError(angle=_angle(p.normal, t.normal), offset=abs(p.normal @ t.center - p.distance),
                              center=float(np.linalg.norm(p.center - t.center)))  # fmt: skip
    if truth.kind == "line":
        w = t.point - p.point
        return DetectionError(angle=_angle(p.direction, t.direction),
                              offset=float(np.linalg.norm(w - (w @ p.direction) * p.direction)),
                              center=float(abs(w @ p.direction)))  # fmt: skip
    angle = _angle(p.normal, t.normal) if truth.kind == "circle" else None
    return DetectionError(center=float(np.linalg.norm(p.center - t.center)), radius=abs(p.radius - t.radius),
                          angle=angle)  # fmt: skip


def _within(kind, err: DetectionError, truth: TruthEntity, tol: float) -> bool:
    """Kind-specific position test: tol in metres; angles within atan(tol / extent); centres of flats and
    lines within the object's own extent (a detection elsewhere on the same infinite plane is not it)."""
    ang = np.degrees(np.arctan2(tol, truth.extent))
    if kind in ("plane", "line"):
        return err.angle <= ang and err.offset <= tol and err.center <= truth.extent + tol
    ok = err.center <= tol and err.radius <= tol
    return ok and (kind == "sphere" or err.angle <= ang)


def _matches(scene: DetectScene, detections, tol: float) -> list:
    used, matches = set(), []
    for i, det in enumerate(detections):
        cands = []
        for j, t in enumerate(scene.truth):
            if j in used or t.kind != det.kind:
                continue
            err = entity_errors(det, t)
            if _within(det.kind, err, t, tol):
                cands.append(((err.offset if err.offset is not None else 0.0) + err.center, j, err))
        if cands:
            _, j, err = min(cands, key=lambda c: c[0])
            used.add(j)
            matches.append(DetectionMatch(i, j, err))
    return matches


def evaluate(scene: DetectScene, detections, position_tol: float | None = None) -> DetectionScore:
    """Precision and recall per kind: a detection is right when a true entity of its kind is within tolerance.

    Detections are matched largest first, each to the unmatched true entity of
    its kind with the smallest position error that passes the test
    (``position_tol`` metres, default 4 x :meth:`DetectScene.noise_scale`).

    Returns
    -------
    DetectionScore
        ``kinds[kind]`` and ``all``: :class:`KindScore` (``precision``, ``recall``, ``tp``, ``detected``,
        ``truth``); ``matches``: :class:`DetectionMatch` ``(detection, truth, errors)``; ``tolerance``.
    """
    f = "evaluate"
    scene = checks.instance(scene, f, "scene", DetectScene, "a DetectScene (stereo_scene, cloud_scene)")
    detections = checks.instance(detections, f, "detections", (list, tuple), "a list of DetectedEntity")
    for d in detections:
        checks.instance(d, f, "detections", DetectedEntity, "DetectedEntity items (detect_entities)")
    if position_tol is None:
        tol = 4.0 * scene.noise_scale()
    else:
        tol = checks.real(position_tol, f, "position_tol", low=0.0, high=vd.LIMIT)
    matches = _matches(scene, detections, tol)
    scores = {}
    for kind in KINDS + ("all",):
        det = [d for d in detections if kind in ("all", d.kind)]
        tru = [t for t in scene.truth if kind in ("all", t.kind)]
        tp = sum(1 for m in matches if kind in ("all", scene.truth[m.truth].kind))
        scores[kind] = KindScore(precision=tp / len(det) if det else 1.0, recall=tp / len(tru) if tru else 1.0,
                                 tp=tp, detected=len(det), truth=len(tru))  # fmt: skip
    total = scores.pop("all")
    return DetectionScore(kinds=scores, all=total, matches=tuple(matches), tolerance=tol)
