"""Fuzz cases of the 2D laser line map (cga_lessons.mapping2d: laser, lines, map building, corrections, logs).

The valid calls are tiny: a 4 m x 3 m room seen from three poses by a laser of 61 beams, a log of three FLASER
lines, a handful of segments.  Readers of one kind of thing are given another (a list of segments where a
segment set goes, a sphere where a conformal point or a point pair goes, a map's parameters where its geometry
goes): each must be refused.
"""

from __future__ import annotations

import gzip
import json
import tempfile
from pathlib import Path

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import mapping2d as m2
from cga_lessons.mapping2d import (
    CorrespondenceParams,
    ExtractionParams,
    LoopParams,
    MapBuilder,
    MapParams,
    OdometryModel,
    PlainGeometry,
    PoseGraph,
    Scene,
    Segment,
    SegmentSet,
)
from fuzz.harness import Case, temporary_folder

_DIR = temporary_folder("cga-fuzz-mapping2d-")

ROOM = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]])
BOX = np.array([[2.6, 1.8], [3.1, 1.8], [3.1, 2.2], [2.6, 2.2]])
TRAJ = np.array([[1.0, 1.0, 0.0], [1.2, 1.05, 0.05], [1.4, 1.1, 0.1]])
SCENE = Scene("box", [ROOM, BOX], TRAJ)
SCANS = m2.simulate_scans(SCENE, n_beams=61)
RANGES, ANGLES = SCANS[0]
RANGES_FEW = np.where(np.isfinite(RANGES), RANGES, 4.0)

SEG_A = Segment([0.0, 0.0], [2.0, 0.0], 10)
SEG_B = Segment([2.0, 0.0], [2.0, 1.5], 8)
SEG_C = Segment([0.05, 0.02], [1.9, 0.03], 9)
SEGS = [SEG_A, SEG_B]
G_SET = SegmentSet.from_segments([SEG_A, SEG_B])
L_SET = SegmentSet.from_segments([SEG_C, Segment([2.02, 0.1], [2.01, 1.4], 7)])
WALLS = SCENE.walls[:6]
POINTS = np.array([[0.0, 0.1], [1.0, 0.0], [2.0, 0.05], [2.0, 1.0], [2.1, 1.5]])

PAIR = m2.segment_point_pair(SEG_A)
SPHERE = cga.sphere([0.0, 0.0, 0.0], 1.0)
CIRCLE = cga.circle_from_points([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
LINE = cga.line_from_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
POINT = cga.up([1.0, 2.0, 0.0])


def _log_text(n_scans: int = 3, n_beams: int = 181) -> str:
    lines = ["# a tiny CARMEN log", "PARAM robot_frontlaser_offset 0.0"]
    for k in range(n_scans):
        r = 2.0 + 0.5 * np.sin(np.linspace(0, 3, n_beams) + k)
        x, y, th = 0.1 * k, 0.0, 0.01 * k
        fields = [*r.round(3), x, y, th, x, y, th, 1.0 + k, "host", 1.0 + k]
        lines.append("FLASER " + str(n_beams) + " " + " ".join(map(str, fields)))
    return "\n".join(lines) + "\n"


LOG = _DIR / "tiny.log"
LOG.write_text(_log_text())
LOG_GZ = _DIR / "tiny.log.gz"
LOG_GZ.write_bytes(gzip.compress(_log_text().encode()))
SCENE_JSON = _DIR / "box.json"
SCENE_JSON.write_text(json.dumps({"name": "box", "polygons": [ROOM.tolist()], "trajectory": TRAJ.tolist()}))
BENCH_ROWS = [
    {
        "name": "intel",
        "seed": 0,
        "odo": 1.5,
        "rmse": 0.05,
        "heading_deg": 0.4,
        "rpe_cm": 1.2,
        "map_cm": 3.0,
        "loops": 2,
        "ms": 4.0,
        "verdict": "ok",
    },
    {
        "name": "intel",
        "seed": None,
        "odo": 0.0,
        "rmse": 0.01,
        "heading_deg": 0.1,
        "rpe_cm": 0.3,
        "map_cm": 1.0,
        "loops": 0,
        "ms": 4.0,
    },
]
BENCH = _DIR / "bench.json"
BENCH.write_text(json.dumps({"meta": {"date": "today"}, "rows": BENCH_ROWS}))


def _fields(result) -> dict:
    """A typed result as keyword arguments of its class."""
    return {k: getattr(result, k) for k in type(result).__dataclass_fields__}


def _viz_correction_class():
    from cga_lessons.viz.explore_conformal_map import ConformalCorrection

    return ConformalCorrection


def _conformal_correction():
    from cga_lessons.viz import explore_conformal_map as ecm

    local = m2.segment_point_pair([SEG_A, SEG_B])
    return _fields(ecm.conformal_correction(ecm.place(local, [0.0, 0.0, 0.0])[0], local, [0.5, 0.5]))


def _fresh_path(stem: str):
    """A path that does not exist yet (a new one for every call)."""
    return Path(tempfile.mkdtemp(dir=_DIR)) / stem


def _graph():
    g = PoseGraph()
    g.add(0, 1, [0.2, 0.05, 0.05], np.eye(3) * 1e-2)
    g.add(1, 2, [0.2, 0.05, 0.05], np.eye(3) * 1e-2)
    return g


def _registration_points():
    pts, _ = m2.scan_points(*SCANS[0])
    return pts


REG_SOURCE = _registration_points()
REG_TARGET = REG_SOURCE @ np.array([[np.cos(0.02), -np.sin(0.02)], [np.sin(0.02), np.cos(0.02)]]) + [0.03, 0.01]

GEOMETRY_KINDS = [MapParams(), SEGS]
SET_KINDS = [SEGS, SEG_A]

CASES = [
    # ------------------------------------------------------------------ poses
    Case(m2.compose, {"a": [1.0, 0.0, 0.5], "b": [1.0, 2.0, 0.1]}),
    Case(m2.compose, {"a": TRAJ, "b": TRAJ}, name="compose (batch)"),
    Case(m2.invert, {"a": [1.0, 2.0, 0.5]}),
    Case(m2.relative, {"a": [1.0, 0.0, 0.5], "b": TRAJ}),
    Case(m2.wrap_angle, {"angle": np.array([3.0, -4.0, 7.0])}),
    Case(m2.wrap_angle, {"angle": 4.0}, name="wrap_angle (scalar)"),
    # ------------------------------------------------------------------ scenes and the laser
    Case(
        Scene,
        {"name": "box", "polygons": [ROOM, BOX], "trajectory": TRAJ, "description": ""},
        extra={"polygons": [[], [ROOM[:1]], [np.zeros((4, 2))]]},
        strict=True,
    ),
    Case(Scene.from_json, {"path": SCENE_JSON}, label="Scene.from_json"),
    Case(m2.load_scene, {"name": "room"}),
    Case(
        m2.simulate_scan,
        {
            "scene": SCENE,
            "pose": [1.0, 1.0, 0.3],
            "rng": None,
            "n_beams": 31,
            "fov": np.pi,
            "max_range": 2.0,
            "range_noise": 0.01,
            "mount": (0.1, 0.0, 0.0),
        },
        kinds={"scene": [SEGS]},
        allow={"rng": ["None"]},
        strict=True,
    ),
    Case(
        m2.simulate_scan,
        {"scene": WALLS, "pose": [1.0, 1.0, 0.0], "rng": np.random.default_rng(1), "max_range": 2.0},
        name="simulate_scan (walls, noise)",
    ),
    Case(
        m2.simulate_scans,
        {"scene": SCENE, "poses": TRAJ, "rng": None, "n_beams": 11, "max_range": 2.0},
        allow={"poses": ["None"], "rng": ["None"]},
        strict=True,
    ),
    Case(m2.scan_points, {"ranges": RANGES, "angles": ANGLES}),
    Case(
        m2.scans_to_world,
        {"scans": SCANS, "poses": TRAJ, "max_range": 5.0, "mount": (0.0, 0.0, 0.0), "step": 1},
        strict=True,
    ),
    Case(
        m2.simulate_odometry,
        {"trajectory": TRAJ, "rng": np.random.default_rng(0), "model": OdometryModel()},
        allow={"model": ["None"]},
        kinds={"model": [MapParams()]},
    ),
    Case(
        OdometryModel.increments,
        {"self": OdometryModel(), "trajectory": TRAJ, "rng": np.random.default_rng(0)},
        label="OdometryModel.increments",
    ),
    Case(
        OdometryModel.step_covariance,
        {"self": OdometryModel(), "increment": [0.5, 0.1, 0.2]},
        label="OdometryModel.step_covariance",
    ),
    # ------------------------------------------------------------------ logs
    Case(m2.read_carmen_log, {"path": LOG, "no_return_range": 80.0, "fov": np.pi, "detect_codes": True}, strict=True),
    Case(m2.read_carmen_log, {"path": LOG_GZ}, name="read_carmen_log (gzip)"),
    Case(
        m2.CarmenLog,
        {
            "ranges": np.array([[2.0, 2.1, np.inf, 2.0, 1.9], [2.0, 2.0, 2.0, 2.0, 2.0]]),
            "angles": np.linspace(-1, 1, 5),
            "poses": TRAJ[:2],
            "odometry": TRAJ[:2],
            "timestamps": np.array([0.0, 1.0]),
            "laser_offset": 0.0,
            "no_return_codes": (),
        },
        strict=True,
    ),
    Case(m2.returns_reach, {"ranges": RANGES, "coverage": 0.99}, strict=True),
    Case(m2.odometry_repeats_poses, {"log": m2.read_carmen_log(LOG), "tol": 1e-6}, strict=True),
    # ------------------------------------------------------------------ lines
    Case(
        Segment,
        {
            "start": [0.0, 0.0],
            "end": [2.0, 1.0],
            "n_points": 5,
            "sums": None,
            "start_is_edge": False,
            "end_is_edge": True,
        },
        extra={"end": [[0.0, 0.0], [1e300, 1e300]], "start": [[-1e300, 0.0]]},
        allow={"sums": ["None"]},
        strict=True,
    ),
    Case(
        Segment.from_points, {"points": POINTS[:3]}, label="Segment.from_points", extra={"points": [np.zeros((3, 2))]}
    ),
    Case(Segment.transformed, {"self": SEG_A, "pose": [1.0, 2.0, 0.5]}, label="Segment.transformed"),
    Case(Segment.hough, {"self": SEG_A, "origin": (1.0, 1.0)}, label="Segment.hough"),
    Case(m2.split_points, {"points": POINTS, "xi": 0.1}, strict=True),
    Case(m2.diff_theta, {"theta_a": 6.2, "theta_b": 0.1, "theta_xi": 0.3}),
    Case(m2.diff_theta, {"theta_a": np.array([6.2, 1.0]), "theta_b": np.array([0.1, 1.1])}, name="diff_theta (arrays)"),
    Case(m2.diff_theta_as_printed, {"theta_a": 6.2, "theta_b": 0.1, "theta_xi": 0.3}),
    Case(
        m2.extract_segments,
        {
            "ranges": RANGES,
            "angles": ANGLES,
            "xi": 0.03,
            "phi_xi": 0.09,
            "min_points": 4,
            "min_length": 0.15,
            "max_gap": 0.2,
            "jump_ratio": 5.0,
            "max_range": 5.0,
            "edge_tolerance": 0.15,
        },
        strict=True,
    ),
    Case(m2.extract_segments, {"ranges": RANGES_FEW, "angles": ANGLES}, name="extract_segments (defaults)"),
    # ------------------------------------------------------------------ geometry and correspondence
    Case(SegmentSet, {"start": G_SET.start, "end": G_SET.end, "sums": G_SET.sums, "edge": G_SET.edge}),
    Case(SegmentSet.from_segments, {"segs": SEGS}, label="SegmentSet.from_segments", kinds={"segs": [G_SET]}),
    Case(PlainGeometry, {}),
    Case(m2.ConformalGeometry, {}),
    Case(
        m2.proximity_matrix,
        {"G": G_SET, "L": L_SET, "centre": [0.5, 0.5], "geometry": PlainGeometry(), "theta_xi": 0.3},
        kinds={"G": SET_KINDS, "L": SET_KINDS, "geometry": GEOMETRY_KINDS},
        allow={"geometry": ["None"]},
        strict=True,
    ),
    Case(
        m2.correspondences,
        {
            "G": G_SET,
            "L": L_SET,
            "centre": [0.5, 0.5],
            "params": CorrespondenceParams(),
            "geometry": m2.ConformalGeometry(),
        },
        kinds={"G": SET_KINDS, "L": SET_KINDS, "params": [PlainGeometry(), MapParams()], "geometry": GEOMETRY_KINDS},
        allow={"params": ["None"], "geometry": ["None"]},
        strict=True,
    ),
    # ------------------------------------------------------------------ corrections
    Case(
        m2.theta_correction,
        {"dth": [0.01, 0.03], "weights": [1.0, 2.0]},
        allow={"weights": ["None"]},
        extra={"weights": [[0.0, 0.0], [-1.0, 1.0]]},
    ),
    Case(
        m2.translation_correction,
        {
            "rho_g": [1.0, 2.0],
            "rho_l": [0.9, 2.3],
            "theta_l": [0.0, 1.5],
            "weights": [1.0, 1.0],
            "weak_ratio": 0.0,
            "along": None,
        },
        allow={"weights": ["None"]},
        extra={"weights": [[0.0, 0.0]]},
        strict=True,
    ),
    Case(
        m2.translation_correction,
        {"rho_g": [1.0], "rho_l": [0.9], "theta_l": [0.5], "along": ([[0.1, 0.2]], [1.0])},
        name="translation_correction (along)",
    ),
    Case(
        m2.pose_correction,
        {
            "dth": [0.02, 0.04],
            "var_theta": [1.0, 1.0],
            "offset": [0.0, 0.1],
            "var_offset": [1.0, 2.0],
            "normal": [[1.0, 0.0], [0.0, 1.0]],
            "lever": [[1.0, 0.0], [0.0, 1.0]],
            "prior_cov": np.diag([1.0, 1.0, 1.0]),
            "prior_offset": [0.0, 0.0, 0.0],
            "extra": None,
        },
        allow={"prior_cov": ["None"], "prior_offset": ["None"]},
        extra={"var_theta": [[0.0, 1.0], [-1.0, 1.0]], "prior_cov": [np.zeros((3, 3))]},
    ),
    Case(
        m2.line_variances,
        {"segs": G_SET, "centre": [0.5, 0.5], "range_noise": 0.01, "angle_floor": 0.0, "offset_floor": 0.003},
        kinds={"segs": SET_KINDS},
        strict=True,
    ),
    # ------------------------------------------------------------------ errors against the truth
    Case(m2.pose_errors, {"poses": TRAJ, "truth": TRAJ + 0.01}),
    Case(m2.map_errors, {"segments": SEGS, "walls": WALLS}, kinds={"segments": [G_SET, SEG_A]}),
    Case(m2.map_point_errors, {"segments": SEGS, "points": POINTS}, kinds={"segments": [G_SET, SEG_A]}),
    Case(m2.read_log_benchmark, {"path": BENCH}),
    Case(
        m2.format_log_benchmark,
        {"rows": BENCH_ROWS},
        extra={"rows": [[{"name": "x"}], [{**BENCH_ROWS[0], "odo": float("nan")}]]},
    ),
    Case(m2.absolute_trajectory_error, {"poses": TRAJ, "truth": TRAJ + 0.01, "align": "se2"}, strict=True),
    Case(m2.relative_pose_error, {"poses": TRAJ, "truth": TRAJ + [0.0, 0.0, 0.01], "delta": 0.2}, strict=True),
    Case(
        m2.write_tum,
        lambda: {"path": _fresh_path("t.tum"), "poses": TRAJ, "timestamps": [0.0, 1.0, 2.0], "overwrite": False},
        strict=True,
    ),
    # ------------------------------------------------------------------ the conformal version (3.13-3.21)
    Case(m2.e2c, {"xy": [3.0, 4.0]}),
    Case(m2.e2c, {"xy": POINTS}, name="e2c (batch)"),
    Case(m2.c2e, {"X": POINT}, kinds={"X": [SPHERE, PAIR, LINE, CIRCLE]}),
    Case(m2.segment_point_pair, {"segments": SEG_A}, kinds={"segments": [G_SET, POINTS]}),
    Case(m2.segment_point_pair, {"segments": SEGS}, name="segment_point_pair (list)"),
    Case(m2.point_pair_structure, {"PP": PAIR}, kinds={"PP": [SPHERE, POINT, LINE, CIRCLE]}),
    Case(m2.PointPairStructure, lambda: _fields(m2.point_pair_structure(PAIR)), strict=True),
    Case(m2.robot_motor, {"pose": [1.0, 2.0, 0.5]}),
    Case(m2.laser_motor, {"pose": [1.0, 2.0, 0.5], "mount": (0.1, 0.0, 0.2), "printed": False}, strict=True),
    Case(
        m2.sphere_case,
        {
            "g_start": [0.0, 0.0],
            "g_end": [2.0, 0.0],
            "l_start": [0.5, 0.02],
            "l_end": [1.5, 0.03],
            "angle_gate": 0.3,
            "xi_d": 0.3,
            "margin": 0.0,
        },
        extra={"l_end": [[0.5, 0.02]]},
        strict=True,
    ),
    Case(
        m2.register_scans,
        {"source": REG_SOURCE, "target": REG_TARGET, "initial": (0.0, 0.0, 0.0), "params": None},
        extra={"source": [np.zeros((5, 2))], "target": [np.zeros((5, 2))]},
        allow={"params": ["None"]},
        kinds={"params": [MapParams()]},
        strict=True,
    ),
    # ------------------------------------------------------------------ the map
    Case(PoseGraph, {}),
    Case(
        PoseGraph.add,
        {"self": PoseGraph(), "i": 0, "j": 1, "z": [0.2, 0.0, 0.1], "cov": np.eye(3) * 0.01, "loop": False},
        label="PoseGraph.add",
        extra={"cov": [np.zeros((3, 3)), -np.eye(3), [[1, 2, 0], [0, 1, 0], [0, 0, 1]]], "j": [0]},
        strict=True,
    ),
    Case(
        PoseGraph.optimize,
        lambda: {"self": _graph(), "poses": TRAJ, "iterations": 3, "robust": 3.0, "tol": 1e-4, "first_free": 1},
        label="PoseGraph.optimize",
        strict=True,
    ),
    Case(PoseGraph.errors, lambda: {"self": _graph(), "poses": TRAJ}, label="PoseGraph.errors"),
    Case(
        PoseGraph.errors,
        {"self": PoseGraph(), "poses": TRAJ},
        label="PoseGraph.errors",
        name="PoseGraph.errors (no edge)",
    ),
    Case(
        MapBuilder,
        {
            "geometry": PlainGeometry(),
            "params": MapParams(),
            "mount": (0.0, 0.0, 0.0),
            "max_range": 5.0,
            "index_cell": 4.0,
            "refit_tolerance": (0.005, 0.001),
        },
        kinds={"geometry": GEOMETRY_KINDS, "params": [PlainGeometry()]},
        allow={"index_cell": ["None"], "refit_tolerance": ["None"]},
        strict=True,
    ),
    Case(
        m2.build_map,
        {
            "scans": SCANS,
            "odometry": TRAJ,
            "method": "plain",
            "params": MapParams(loops=LoopParams(loop_closure=False)),
            "mount": (0.0, 0.0, 0.0),
            "max_range": 5.0,
            "extraction": {"min_points": 4},
            "record_history": True,
            "progress": None,
        },
        kinds={"params": [PlainGeometry()], "scans": [[SEG_A, SEG_B, SEG_A]]},
        allow={"params": ["None"], "extraction": ["None"], "progress": ["None"]},
        extra={"scans": [SCANS[:2], [(RANGES, ANGLES[:-1])] * 3], "extraction": [{"xi": -1.0}, {"nonsense": 1}]},
        strict=True,
    ),
    Case(m2.build_map, {"scans": SCANS[:2], "odometry": TRAJ[:2], "method": "conformal"}, name="build_map (conformal)"),
    Case(
        m2.build_map,
        {"scans": SCANS, "odometry": TRAJ, "extraction": ExtractionParams(min_points=4), "loop_closure": False},
        name="build_map (ExtractionParams, a flat override)",
        kinds={"extraction": [MapParams()]},
    ),
    Case(
        m2.MapResult,
        {
            "segments": SEGS,
            "poses": TRAJ,
            "predicted": TRAJ,
            "n_matches": np.array([0, 1, 2]),
            "corrected": np.array([False, True, True]),
            "method": "plain",
            "history": [],
            "loops": [],
        },
        kinds={"segments": [G_SET]},
        strict=True,
    ),
]

# viz.explore_conformal_map's typed result (the explorer's correction of notebook 06; its place is cases_viz.py)
CASES.append(Case(_viz_correction_class(), _conformal_correction, strict=True))

EXEMPT: dict[str, str] = {}
