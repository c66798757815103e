"""How good is the fused 3D map: laser against stereo on the objects both saw, and both against the truth.

:func:`residual_table` gives one row per object of the world (and one for the
room's walls) with the errors of the stereo entity and of the laser's view
against the ground truth, and the *residual between the two sensors* where
both saw the object: a board (the laser's line of its face against the
stereo plane) and the posts (the laser's circle centre at its height against
the stereo axis at that height).  Distances in centimetres, angles in
degrees, so the table reads at a glance.  Rows are frozen records (:class:`ResidualRow`, and
:class:`ViewErrorRow` of :func:`view_errors`); NaN marks an entry that does not apply or was not measured.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.conformal import LineParameters

from .fused_map import FusedMap
from .parameters import count

__all__ = [
    "residual_table",
    "match_board_segment",
    "line_at_height",
    "wall_errors",
    "view_errors",
    "COLUMNS",
    "ResidualRow",
    "ViewErrorRow",
]

_NAN = float("nan")


@dataclass(frozen=True)
class ViewErrorRow:
    """One object in one stereo view (:func:`view_errors`): ``view`` (its index), ``object`` (the world object's
    name), ``entity`` (the kind fitted), ``distance_m`` (robot to the object's points, metres), ``points`` (how many
    the view fitted), and the stereo entity against the truth as in :class:`ResidualRow`: ``stereo_pos_cm``,
    ``stereo_angle_deg`` and ``stereo_radius_cm`` (NaN where the entity has no such quantity)."""

    view: int
    object: str
    entity: str
    distance_m: float
    points: int
    stereo_pos_cm: float
    stereo_angle_deg: float = _NAN
    stereo_radius_cm: float = _NAN

    def __post_init__(self):
        checks.record(self, view=count, points=count, object=checks.text, entity=checks.text, distance_m=checks.length,
                      stereo_pos_cm=checks.measure, stereo_angle_deg=checks.measure,
                      stereo_radius_cm=checks.measure)  # fmt: skip


@dataclass(frozen=True)
class ResidualRow:
    """One object of the world (or the room's walls) in :func:`residual_table`: ``object`` (its name), ``entity``
    (its true kind), ``seen_by`` (``"stereo"``, ``"laser"``, ``"stereo + laser"`` or ``"-"``), ``views`` (stereo
    views fused), ``laser_n`` (the laser's support), and in centimetres and degrees ``stereo_pos_cm``,
    ``stereo_angle_deg``, ``stereo_radius_cm`` (stereo vs truth), ``laser_pos_cm`` (laser vs truth),
    ``laser_stereo_cm`` and ``laser_stereo_deg`` (laser vs stereo); NaN where an entry does not apply.  Each
    quantity is defined in :func:`residual_table`."""

    object: str
    entity: str
    seen_by: str
    views: int
    laser_n: int
    stereo_pos_cm: float = _NAN
    stereo_angle_deg: float = _NAN
    stereo_radius_cm: float = _NAN
    laser_pos_cm: float = _NAN
    laser_stereo_cm: float = _NAN
    laser_stereo_deg: float = _NAN

    def __post_init__(self):
        measures = ("stereo_pos_cm", "stereo_angle_deg", "stereo_radius_cm", "laser_pos_cm", "laser_stereo_cm",
                    "laser_stereo_deg")  # fmt: skip
        checks.record(self, object=checks.text, entity=checks.text, seen_by=checks.text, views=count, laser_n=count,
                      **dict.fromkeys(measures, checks.measure))  # fmt: skip


#: Column order of :func:`residual_table`: the fields of :class:`ResidualRow` (for
#: :func:`cga_lessons.stereo.format_table`).
COLUMNS = [fld.name for fld in dataclasses.fields(ResidualRow)]


def _angle(u, v) -> float:
    """Angle (degrees) between two unoriented directions."""
    u, v = np.asarray(u, float), np.asarray(v, float)
    c = abs(float(u @ v)) / (np.linalg.norm(u) * np.linalg.norm(v))
    return float(np.degrees(np.arccos(min(1.0, c))))


def line_at_height(params: LineParameters, z: float) -> np.ndarray:
    """The point (3,) of a line (its ``direction`` and ``point``) at height ``z``; raises for a horizontal line."""
    d, p = np.asarray(params.direction, float), np.asarray(params.point, float)
    if abs(d[2]) < 1e-9:
        raise checks.degenerate(
            "line_at_height", "params", "the line is horizontal; it has no single point at a height"
        )
    return p + (z - p[2]) / d[2] * d


def _seg_dist(pts, a, b):
    """Distance of points (k, 2) to the segment a-b."""
    v = b - a
    t = np.clip((pts - a) @ v / max(v @ v, 1e-300), 0.0, 1.0)
    return np.linalg.norm(pts - (a + t[:, None] * v), axis=1)


def match_board_segment(fused: FusedMap, name: str, max_offset: float = 0.15, max_angle_deg: float = 10.0):
    """The laser map's segment of the board face ``name`` the cameras saw, or None.

    Candidates lie within ``max_offset`` of the stereo plane at both ends,
    run parallel to it within ``max_angle_deg``, and face the same way: the
    laser sees a face on the left of a segment's direction (chapter 3), the
    stereo normal is turned towards the cameras that saw it.  The longest
    candidate wins.
    """
    obj = fused.objects.get(name)
    if obj is None or obj.kind != "plane":
        return None
    n, d = obj.params.normal, obj.params.distance
    cams = np.array([e.state.pose[:2] for e in fused.views if e.name == name])
    if (np.append(cams.mean(axis=0), fused.laser_height) @ n - d) < 0:
        n, d = -n, -d
    best, best_len = None, 0.0
    for k, s in enumerate(fused.laser.segments):
        ends = np.array([[*s.start, fused.laser_height], [*s.end, fused.laser_height]])
        off = np.abs(ends @ n - d)
        face = -s.normal  # towards the laser that saw it
        if off.max() > max_offset or _angle(np.append(s.direction, 0.0), np.cross(n, [0, 0, 1.0])) > max_angle_deg:
            continue
        if face @ n[:2] <= 0 or s.length <= best_len:
            continue
        best, best_len = k, s.length
    return best


def _truth_outlines(world):
    """Every outline the laser can see (room walls and object footprints): list of (name, segments (k, 2, 2))."""
    out = [("walls", world.wall_segments())]
    for o in world.objects:
        fp = o.footprint()
        if fp is not None:
            out.append((o.name, np.stack([fp, np.roll(fp, -1, axis=0)], axis=1)))
    return out


def wall_errors(fused: FusedMap) -> dict:
    """Distance (m) of every laser map segment's ends to the nearest true outline, grouped by what they hit.

    Returns
    -------
    dict
        outline name -> ndarray of end point distances (walls, board, pedestal, posts ...).
    """
    outlines = _truth_outlines(fused.tour.world)
    out = {}
    for s in fused.laser.segments:
        ends = np.array([s.start, s.end])
        best = min(
            (
                (nm, max(min(_seg_dist(ends[i : i + 1], a, b)[0] for a, b in segs) for i in range(2)))
                for nm, segs in outlines
            ),
            key=lambda t: t[1],
        )
        out.setdefault(best[0], []).append(best[1])
    return {k: np.array(v) for k, v in out.items()}


def view_errors(fused: FusedMap) -> list:
    """Per stereo view and object: its distance and the main error against the truth.

    Returns
    -------
    list of ViewErrorRow
        One row per object seen in a view; ``stereo_angle_deg`` or ``stereo_radius_cm`` NaN where the entity has
        no direction or no radius.
    """
    checks.instance(fused, "view_errors", "fused", FusedMap, "a FusedMap (build_fused_map)")
    rows = []
    for e in fused.views:
        t = fused.tour.world.object(e.name).truth()
        row = {"view": e.view, "object": e.name, "entity": e.kind, "points": len(e.points_world),
               "distance_m": float(np.linalg.norm(e.points_world.mean(axis=0)[:2] - e.state.pose[:2]))}  # fmt: skip
        row.update(_stereo_vs_truth(e.kind, e.params, t, fused.laser_height))
        rows.append(ViewErrorRow(**row))
    return rows


def _stereo_vs_truth(kind, p, t, laser_height) -> dict:
    if kind in ("sphere", "circle"):
        row = {"stereo_pos_cm": 100 * float(np.linalg.norm(p.center - t.center)),
               "stereo_radius_cm": 100 * (p.radius - t.radius)}  # fmt: skip
        if kind == "circle":
            row["stereo_angle_deg"] = _angle(p.normal, t.normal)
        return row
    if kind == "plane":
        return {"stereo_pos_cm": 100 * abs(float(p.normal @ t.center) - p.distance),
                "stereo_angle_deg": _angle(p.normal, t.normal)}  # fmt: skip
    if kind == "line":
        q = line_at_height(p, laser_height)
        return {"stereo_pos_cm": 100 * float(np.linalg.norm(q[:2] - t.point[:2])),
                "stereo_angle_deg": _angle(p.direction, t.direction)}  # fmt: skip
    raise checks.fail("residual_table", "fused", f"unknown entity kind {kind!r}")


def residual_table(fused: FusedMap) -> list:
    """One row per object (and one for the room's walls): stereo vs truth, laser vs truth, laser vs stereo.

    ``stereo_pos_cm``: sphere and circle centre error; plane: distance of the
    true face's centre from the stereo plane; line: horizontal distance of the
    stereo axis from the true axis at the laser's height.  ``laser_pos_cm``:
    board: largest distance of the laser segment's ends from the true face;
    post: distance of the laser's centre from the true one; walls and
    pedestal: RMS distance of the map's segment ends from the true outline.
    ``laser_stereo_cm``: board: RMS distance of the laser segment's ends (at
    laser height) from the stereo plane; post: horizontal distance of the
    laser's centre from the stereo axis at the laser's height.
    ``laser_stereo_deg``: the angle between the laser's virtual wall and the
    stereo plane.  ``laser_n``: the laser's support: points on the board's
    segment, scans that found the post, map segments on the pedestal or the
    walls.  Missing entries are NaN (``format_table`` prints '-').

    Returns
    -------
    list of ResidualRow
        One row per object of the world, then one for the walls.
    """
    checks.instance(fused, "residual_table", "fused", FusedMap, "a FusedMap (build_fused_map)")
    h = fused.laser_height
    world = fused.tour.world
    werr = wall_errors(fused)
    rows = []
    for o in world.objects:
        t = o.truth()
        row = dict.fromkeys(COLUMNS, np.nan)
        obj = fused.objects.get(o.name)
        row.update(object=o.name, entity=t.kind, views=obj.n_views if obj else 0, laser_n=0)
        laser_seen = False
        if obj is not None:
            row.update(_stereo_vs_truth(obj.kind, obj.params, t, h))
        if t.kind == "plane":
            k = match_board_segment(fused, o.name) if obj is not None else None
            if k is None and o.name in werr:  # the laser saw it; the cameras did not (or no match)
                row["laser_pos_cm"] = 100 * float(werr[o.name].max())
                laser_seen = True
            if k is not None:
                s = fused.laser.segments[k]
                ends = np.array([[*s.start, h], [*s.end, h]])
                row["laser_pos_cm"] = 100 * float(np.abs(ends @ t.normal - t.distance).max())
                n, d = obj.params.normal, obj.params.distance
                row["laser_stereo_cm"] = 100 * float(np.sqrt(np.mean((ends @ n - d) ** 2)))
                row["laser_stereo_deg"] = _angle(np.append(s.normal, 0.0), n)
                row["laser_n"] = int(s.n_points)
                laser_seen = True
        elif t.kind == "line":
            groups = fused.laser_post_groups
            if groups:
                dist = [np.linalg.norm(gp.center[:2] - t.point[:2]) for gp in groups]
                gp = groups[int(np.argmin(dist))]
                if min(dist) < 3 * t.radius + 0.1:
                    row["laser_pos_cm"] = 100 * float(min(dist))
                    row["laser_n"] = int(gp.n)
                    laser_seen = True
                    if obj is not None:
                        q = line_at_height(obj.params, h)
                        row["laser_stereo_cm"] = 100 * float(np.linalg.norm(q[:2] - gp.center[:2]))
        elif t.kind == "box" and o.name in werr:
            row["laser_pos_cm"] = 100 * float(np.sqrt(np.mean(werr[o.name] ** 2)))
            row["laser_n"] = len(werr[o.name])
            laser_seen = True
        row["seen_by"] = " + ".join(s for s, ok in (("stereo", obj is not None), ("laser", laser_seen)) if ok) or "-"
        rows.append(ResidualRow(**row))
    walls = dict.fromkeys(COLUMNS, np.nan)
    w = werr.get("walls", np.zeros(0))
    walls.update(object="walls", entity="virtual walls", seen_by="laser", views=0, laser_n=len(w),
                 laser_pos_cm=100 * float(np.sqrt(np.mean(w**2))) if len(w) else np.nan)  # fmt: skip
    rows.append(ResidualRow(**walls))
    return rows
