"""Fuzz cases of the stereo package (cga_lessons.stereo: cameras, two-view geometry, the head, its scenes, the
detector and the real pair).

Everything runs on a tiny head (64 x 48 pixels, 50 px focal length) and a handful of points.  Camera readers are
given a rig and a rig's readers a camera matrix (``kinds``); degenerate geometry is added by hand (``extra``): a
matrix that is not a rotation, a calibration with zero focal length, two cameras at one centre, points behind the
camera, coincident points, parallel rays.  Cases holding conformal blades build their arguments in a function
(a deep copy of a blade would copy its algebra too, which the conformal layer rightly refuses).
"""

from __future__ import annotations

import json

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import data_path
from cga_lessons import stereo as st
from fuzz.harness import Case, temporary_folder

RIG = st.stereo_head(baseline=0.2, focal_px=50.0, image_size=(64, 48))
P1, P2 = RIG.P1, RIG.P2
F = RIG.F
K = RIG.K
X = st.random_points_in_view(RIG, 10, np.random.default_rng(0), depth=(1.0, 3.0))
X1, X2 = RIG.project(X)
BEHIND = 2.0 * RIG.C1 - X[:3]  # mirrored through the left camera's centre: behind it
BACKWARD = st.stereo_head(baseline=0.2, focal_px=50.0, image_size=(64, 48), yaw=np.pi)  # the scene is behind it
SCENE = st.load_scene()
SCENE_RIG = st.load_rig()
SAMPLES = st.sample_scene(SCENE, SCENE_RIG, np.random.default_rng(1), n_circle=6, n_board=6, n_sphere=6)
KEYS = ("points", "segment", "circle_key", "plane_key", "sphere_key")
VIEWS = {k: SCENE_RIG.project(SAMPLES[k]) for k in KEYS}
_S, _R = SCENE.sphere_center, np.eye(3)
AROUND_BALL = st.StereoRig(SCENE_RIG.K, _R, _S - [0.0, 0.0, 1.0], _R, _S + [0.0, 0.0, 1.0], (64, 48))  # ball between


def _fields(record) -> dict:
    """A typed result as keyword arguments of its class."""
    return {k: getattr(record, k) for k in type(record).__dataclass_fields__}


A3, B3, C3 = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]
CIRCLE = cga.circle_from_points(A3, B3, C3)
LINE = cga.line_from_points(A3, B3)
PAIR = cga.point_pair(A3, B3)
SPHERE = cga.sphere([0.0, 0.0, 0.0], 1.0)
PLANE = cga.plane([0.0, 0.0, 1.0], 1.0)

NOT_ROTATION = 2.0 * np.eye(3)
REFLECTION = np.diag([1.0, 1.0, -1.0])
ZERO_FOCAL = np.array([[0.0, 0.0, 32.0], [0.0, 50.0, 24.0], [0.0, 0.0, 1.0]])
RANK2 = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [1.0, 1.0, 0.0, 0.0]])
AFFINE = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]])

TINY_SCENE = st.SceneConfig(
    n_planes=1, n_spheres=0, n_circles=1, n_lines=0, surface_density=150.0, curve_density=40.0, clutter=5
)
DETECT_SCENE = st.stereo_scene(np.random.default_rng(2), TINY_SCENE)
DETECT = st.DetectConfig(
    kinds=("plane", "line"),
    hypotheses=5,
    neighbourhoods=(8,),
    score_points=40,
    refine_iterations=2,
    min_surface_inliers=10,
    min_curve_inliers=6,
    max_entities=2,
    max_failures=1,
)
_g = np.linspace(0.0, 0.5, 5)
CLOUD = np.array([[x, y, 0.0] for x in _g for y in _g])  # a plane of 25 points
DETECTIONS = st.detect_entities(CLOUD, np.random.default_rng(3), DETECT, noise=0.01)

DISP = np.array([[10.0, 12.0, np.inf, 11.0], [9.0, 10.0, 10.5, np.inf], [8.0, 9.0, 9.5, 10.0]])
MOTO = dict(st.MOTORCYCLE_CALIBRATION)

_DIR = temporary_folder("cga-fuzz-stereo-")
NOT_A_RIG = _DIR / "not_a_rig.json"
NOT_A_RIG.write_text(json.dumps({"baseline_m": 0.1}), encoding="utf-8")
BAD_RIG = _DIR / "bad_rig.json"
BAD_RIG.write_text(json.dumps({**json.loads(data_path("stereo_rig.json").read_text()), "focal_px": -5}))
NOT_A_SCENE = _DIR / "not_a_scene.json"
NOT_A_SCENE.write_text(json.dumps({"points": [[1, 2, 3]]}), encoding="utf-8")
JSON_LIST = _DIR / "list.json"
JSON_LIST.write_text("[1, 2, 3]", encoding="utf-8")


def _rig_fields(rig) -> dict:
    return {"K": rig.K, "R1": rig.R1, "C1": rig.C1, "R2": rig.R2, "C2": rig.C2, "image_size": rig.image_size}


def _scene_fields(s) -> dict:
    names = (
        "points",
        "segment",
        "circle_center",
        "circle_normal",
        "circle_radius",
        "board_center",
        "board_normal",
        "board_up",
        "board_size",
        "sphere_center",
        "sphere_radius",
    )
    return {n: getattr(s, n) for n in names}


def _rng() -> dict:
    return {"rng": np.random.default_rng(0)}


NOT_RIGS = [P1, SCENE]  # a camera matrix, a scene
NOT_SCENES = [RIG, SAMPLES]

CASES = [
    # ----------------------------------------------------------------- cameras (appendix A)
    Case(
        st.project,
        {"P": P1, "X": X[:3], "return_depth": False},
        strict=True,
        kinds={"P": [RIG]},
        extra={"P": [RANK2, np.zeros((3, 4))], "X": [[RIG.C1]]},
    ),
    Case(st.project, {"P": P1, "X": X[0], "return_depth": True}, name="project (one point, depth)", strict=True),
    Case(st.camera_center, {"P": P1}, kinds={"P": [RIG]}, extra={"P": [RANK2, AFFINE]}),
    Case(st.optical_planes, {"P": P1}, kinds={"P": [RIG]}, extra={"P": [RANK2, np.zeros((3, 4))]}),
    Case(
        st.projection_matrix_rt,
        {"K": K, "R": RIG.R1, "t": -RIG.R1 @ RIG.C1},
        extra={"K": [ZERO_FOCAL, np.zeros((3, 3))], "R": [NOT_ROTATION, REFLECTION, np.zeros((3, 3))]},
    ),
    Case(
        st.closest_points_on_rays,
        {
            "o1": np.zeros((2, 3)),
            "d1": [[1.0, 0, 0], [0, 1, 0]],
            "o2": [[0.0, 1, 0], [1, 0, 0]],
            "d2": [[0.0, 0, 1], [0, 0, 1]],
            "tol": 1e-12,
        },
        strict=True,
        extra={"d1": [np.zeros((2, 3)), [[0.0, 0, 1], [0, 0, 1]]], "o2": [np.zeros((3, 3))], "tol": [-1.0]},
    ),
    Case(
        st.triangulate,
        {"P1": P1, "P2": P2, "x1": X1[:3], "x2": X2[:3], "method": "midpoint"},
        kinds={"P1": [RIG]},
        extra={"P2": [P1, 2.0 * P1], "x2": [X2[:2]]},
    ),
    Case(
        st.triangulate,
        {"P1": P1, "P2": P2, "x1": X1[:3], "x2": X2[:3], "method": "dlt"},
        name="triangulate (dlt)",
        extra={"P2": [P1], "x1": [X1[:4]]},
    ),
    # ----------------------------------------------------------------- two views (A.6-A.13)
    Case(st.eight_point_matrix, {"x1": X1[:4], "x2": X2[:4]}, extra={"x2": [X2[:3]]}),
    Case(
        st.fundamental_8point,
        {"x1": X1, "x2": X2, "normalize": True, "rank2": True},
        strict=True,
        extra={"x1": [X1[:7], np.zeros((10, 2))], "x2": [X2[:9]]},
    ),
    Case(st.epipoles, {"F": F}, extra={"F": [np.zeros((3, 3)), np.diag([1.0, 0.0, 0.0])]}),
    Case(st.epipolar_lines, {"F": F, "x1": X1[:3]}, extra={"F": [np.zeros((3, 3))]}),
    Case(st.epipolar_distance, {"F": F, "x1": X1[:3], "x2": X2[:3]}, extra={"x2": [X2[:2]], "F": [np.zeros((3, 3))]}),
    Case(
        st.cameras_from_fundamental,
        {"F": F, "v": (0.0, 0.0, 0.0), "lam": 1.0},
        strict=True,
        extra={"F": [np.eye(3), np.zeros((3, 3))], "lam": [0.0]},
    ),
    # ----------------------------------------------------------------- the head
    Case(
        st.StereoRig,
        _rig_fields(RIG),
        kinds={"K": [RIG]},
        extra={
            "K": [ZERO_FOCAL, np.zeros((3, 3))],
            "R1": [NOT_ROTATION, REFLECTION],
            "C2": [RIG.C1],
            "image_size": [(64.5, 48), (0, 48), (64, 48, 3)],
        },
    ),
    Case(
        st.stereo_head,
        {
            "baseline": 0.2,
            "focal_px": 50.0,
            "image_size": (64, 48),
            "principal_point": (31.5, 23.5),
            "position": (0.0, 0.0, 1.2),
            "yaw": 0.0,
            "tilt": 0.35,
        },
        strict=True,
        allow={"principal_point": ["None"]},
        extra={"baseline": [0.0, -0.1], "focal_px": [0.0], "image_size": [(64.5, 48), (0, 48)]},
    ),
    Case(st.random_rig, lambda: {**_rng(), "target": (2.5, 0.0, 0.5)}),
    Case(st.load_rig, {"path": data_path("stereo_rig.json")}, extra={"path": [NOT_A_RIG, BAD_RIG, JSON_LIST, 3]}),
    Case(st.rotation_matrix, {"axis": (0.0, 0.0, 1.0), "angle": 0.3}, strict=True, extra={"axis": [(0.0, 0.0, 0.0)]}),
    Case(
        st.look_at_rotation,
        {"center": (0.0, 0.0, 1.0), "target": (2.0, 0.0, 0.5), "up": (0.0, 0.0, 1.0)},
        extra={"target": [(0.0, 0.0, 1.0)], "up": [(0.0, 0.0, 0.0), (4.0, 0.0, -1.0)]},
    ),
    Case(
        st.observe,
        lambda: {"rig": RIG, "X": X[:3], "noise_px": 0.5, **_rng()},
        kinds={"rig": NOT_RIGS},
        extra={"X": [BEHIND], "noise_px": [-0.5]},
    ),
    # ----------------------------------------------------------------- the scene and its entities (4.1)
    Case(
        st.StereoScene,
        _scene_fields(SCENE),
        kinds={"points": [RIG]},
        extra={
            "circle_normal": [(0.0, 0.0, 0.0)],
            "circle_radius": [-0.1, 0.0],
            "board_size": [(0.0, 0.3)],
            "board_up": [SCENE.board_normal],
            "sphere_radius": [0.0],
        },
    ),
    Case(st.load_scene, {"path": data_path("stereo_scene.json")}, extra={"path": [NOT_A_SCENE, JSON_LIST, 3]}),
    Case(
        st.random_scene,
        lambda: {**_rng(), "rig": RIG, "depth": (1.0, 3.0)},
        kinds={"rig": NOT_RIGS},
        extra={"depth": [(-3.0, -1.0), (3.0, 1.0)]},
    ),
    Case(
        st.sample_scene,
        lambda: {"scene": SCENE, "rig": SCENE_RIG, **_rng(), "n_circle": 4, "n_board": 4, "n_sphere": 4},
        strict=True,
        kinds={"scene": NOT_SCENES, "rig": NOT_RIGS},
        extra={"rig": [AROUND_BALL]},
    ),
    Case(
        st.reconstruct_entities,
        {"rig": SCENE_RIG, "views": VIEWS, "method": "midpoint"},
        kinds={"rig": NOT_RIGS},
        extra={
            "views": [
                {k: v for k, v in VIEWS.items() if k != "segment"},
                {**VIEWS, "points": (VIEWS["points"][0], VIEWS["points"][1][:2])},
                {**VIEWS, "circle_key": (VIEWS["plane_key"][0], VIEWS["plane_key"][0])},
                {**VIEWS, "segment": (np.zeros((2, 2)), np.zeros((2, 2)))},
            ]
        },
    ),
    Case(st.circle_center_via_plane, lambda: {"Z": CIRCLE}, kinds={"Z": [LINE, PAIR, SPHERE, PLANE]}),
    Case(
        st.entity_errors,
        lambda: {"truth": SCENE.truth(), "est": st.reconstruct_entities(SCENE_RIG, VIEWS)},
        extra={"est": [{"line": {"direction": 1.0}}, {"plane": cga.fit_sphere(SAMPLES["sphere"])}]},
    ),
    Case(st.line_polyline, lambda: {"L": LINE, "PP": PAIR}, kinds={"L": [CIRCLE, PAIR, PLANE], "PP": [LINE, CIRCLE]}),
    Case(
        st.circle_polyline,
        {"center": (0.0, 0.0, 1.0), "normal": (0.0, 0.0, 1.0), "radius": 0.5, "n": 8, "phase": 0.0},
        strict=True,
        extra={"normal": [(0.0, 0.0, 0.0)], "radius": [-0.5], "n": [0]},
    ),
    Case(
        st.square_polyline,
        {"center": (0.0, 0.0, 1.0), "normal": (0.0, 0.0, 1.0), "half_diagonal": 0.5},
        strict=True,
        extra={"normal": [(0.0, 0.0, 0.0)], "half_diagonal": [-0.5]},
    ),
    Case(
        st.render_views,
        {"rig": RIG, "scene": SCENE, "samples": None},
        kinds={"rig": NOT_RIGS, "scene": NOT_SCENES},
        extra={"rig": [BACKWARD]},
    ),
    Case(
        st.render_views,
        {"rig": SCENE_RIG, "scene": SCENE, "samples": SAMPLES},
        name="render_views (samples)",
        extra={"samples": [{"circle_key": SAMPLES["circle_key"]}]},
    ),
    # ----------------------------------------------------------------- experiments
    Case(
        st.random_points_in_view,
        lambda: {"rig": RIG, "n": 4, **_rng(), "depth": (1.0, 3.0)},
        strict=True,
        kinds={"rig": NOT_RIGS},
        extra={"depth": [(-3.0, -1.0), (3.0, 1.0), (0.0, 0.0), (1e-3, 1e-3)], "n": [0]},
    ),
    Case(
        st.fundamental_comparison,
        lambda: {"rig": RIG, **_rng(), "n_points": 8, "noise_px": 0.5, "trials": 1, "n_test": 4},
        strict=True,
        kinds={"rig": NOT_RIGS},
        extra={"n_points": [7]},
    ),
    Case(
        st.triangulation_error_curve,
        lambda: {"rig": RIG, **_rng(), "noise_levels": [0.0, 1.0], "n_points": 4, "depth": (1.0, 3.0)},
        strict=True,
        kinds={"rig": NOT_RIGS},
        extra={"depth": [(-3.0, -1.0)]},
    ),
    Case(
        st.entity_error_table,
        lambda: {"rig": SCENE_RIG, "scene": SCENE, **_rng(), "noise_px": 0.5, "trials": 1},
        strict=True,
        kinds={"rig": NOT_RIGS, "scene": NOT_SCENES},
    ),
    Case(
        st.format_table,
        {"rows": [{"a": "x", "b": 1.5, "c": float("nan")}], "columns": ["a", "b", "c"], "formats": {"b": ".2f"}},
        extra={"columns": [["a", "zzz"]], "formats": [{"b": "no-such-format"}], "rows": [[{"a": 1}], [3]]},
    ),
    Case(
        st.format_table,
        {"rows": [st.EntityErrorRow("plane", "fit", 1.5)], "columns": ["entity", "radius_mm"], "formats": None},
        name="format_table (records)",
        allow={"formats": ["None"]},
        extra={"columns": [["entity", "zzz"]], "rows": [[st.EntityErrorRow], [st.FundamentalRow, 3]]},
    ),
    Case(
        st.FundamentalRow,
        {"normalize": True, "rank2": False, "epipolar_px": 0.3, "F_error": 0.01, "s3_over_s2": 1e-3, "cond_Z": 2.0},
        strict=True,
        extra={"epipolar_px": [-1.0], "cond_Z": [float("nan")]},
    ),
    Case(
        st.EntityErrorRow,
        {"entity": "circle", "estimator": "conformal LS", "position_mm": 1.5, "radius_mm": 0.4, "angle_deg": 2.0},
        strict=True,
        allow={"position_mm": ["nan"], "radius_mm": ["nan"], "angle_deg": ["nan"]},
        nonfinite_ok="documented: NaN marks a quantity that does not apply",
        extra={"entity": [""], "position_mm": [float("inf")]},
    ),
    # ----------------------------------------------------------------- the real pair
    Case(st.load_motorcycle, {}),
    Case(
        st.motorcycle_cameras,
        {"calib": MOTO},
        allow={"calib": ["None"]},
        extra={
            "calib": [
                {**MOTO, "focal_px": 0.0},
                {**MOTO, "baseline_m": 0.0},
                {"focal_px": 1.0},
                {**MOTO, "cx": float("nan")},
                {**MOTO, "cy": "1"},
            ]
        },
    ),
    Case(
        st.disparity_to_points,
        {"disp": DISP, "calib": MOTO, "step": 1, "max_depth": 100.0},
        strict=True,
        allow={"calib": ["None"]},
        extra={"step": [0], "max_depth": [0.0, -1.0], "calib": [{**MOTO, "doffs": "x"}], "disp": [np.zeros((2, 2, 2))]},
    ),
    Case(
        st.label_image,
        {"shape": (3, 4), "pixels": [[0, 0], [3, 2]], "labels": [1, 2], "step": 1},
        strict=True,
        extra={"labels": [[1, 2, 3]], "shape": [(0, 4), (3,)], "step": [0], "pixels": [[[0.5, 0.0], [1.0, 1.0]]]},
    ),
    # ----------------------------------------------------------------- detection
    Case(
        st.detect_entities,
        lambda: {"X": CLOUD, **_rng(), "config": DETECT, "noise": 0.01},
        extra={"X": [np.zeros((25, 3)), CLOUD[:4]], "noise": [0.0, np.zeros((25, 3, 3))]},
    ),
    Case(
        st.triangulation_covariance,
        {"P1": P1, "P2": P2, "x1": X1[:3], "x2": X2[:3], "sigma_px": 1.0, "method": "midpoint"},
        strict=True,
        extra={"x2": [X2[:2]], "P2": [P1], "sigma_px": [0.0]},
    ),
    Case(st.scene_rig, {"cfg": TINY_SCENE}, kinds={"cfg": [DETECT]}),
    Case(
        st.stereo_scene,
        lambda: {**_rng(), "cfg": TINY_SCENE, "rig": None},
        allow={"rig": ["None"]},
        kinds={"cfg": [DETECT], "rig": [P1, SCENE]},
    ),
    Case(
        st.evaluate,
        {"scene": DETECT_SCENE, "detections": DETECTIONS, "position_tol": 0.05},
        strict=True,
        allow={"position_tol": ["None"]},
        kinds={"scene": [SCENE, RIG]},
        extra={"position_tol": [-1.0], "detections": [[1.0], [SCENE]]},
    ),
    # the typed results, as the package builds them
    *[
        Case(type(record), (lambda name=name: _fields(st.reconstruct_entities(SCENE_RIG, VIEWS)[name])), strict=True)
        for name, record in st.reconstruct_entities(SCENE_RIG, VIEWS).items()
    ],
    *[
        Case(type(error), _fields(error), strict=True)
        for error in st.entity_errors(SCENE.truth(), st.reconstruct_entities(SCENE_RIG, VIEWS)).values()
    ],
    # the detector's typed results
    Case(
        st.PatchParameters,
        {"normal": [0.0, 0.0, 1.0], "distance": 1.0, "center": [0.1, 0.2, 1.0], "sides": (0.3, 0.4)},
        strict=True,
        extra={"sides": [(0.3, -0.4)]},
    ),
    Case(
        st.DetectedEntity,
        lambda: _fields(DETECTIONS[0]),
        strict=True,
        allow={"blade": ["None"]},
        extra={"params": [{"normal": [0.0, 0.0, 1.0], "distance": 0.0}], "covariance": [np.eye(2)]},
        kinds={"params": [cga.SphereParameters(center=[0.0, 0.0, 0.0], radius=1.0)]},
    ),
    Case(
        st.SelectionEvidence,
        {"support": {"plane": 40, "sphere": 38}, "lr": 1.5},
        strict=True,
        allow={"lr": ["None"]},
        extra={"support": [{"cube": 3}, {"plane": -1}]},
    ),
    Case(
        st.TruthEntity,
        lambda: _fields(DETECT_SCENE.truth[0]),
        strict=True,
        extra={"indices": [[-1, 2]]},
        kinds={"params": [cga.LineParameters(direction=[1.0, 0.0, 0.0], point=[0.0, 0.0, 0.0])]},
    ),
    Case(
        st.DetectionError,
        {"center": 0.01, "angle": 1.0, "offset": 0.002, "radius": None},
        strict=True,
        allow={"angle": ["None"], "offset": ["None"], "radius": ["None"]},
    ),
    Case(st.DetectionMatch, lambda: _fields(_score().matches[0]), strict=True),
    Case(st.KindScore, lambda: _fields(_score().all), strict=True, extra={"precision": [1.5]}),
    Case(st.DetectionScore, lambda: _fields(_score()), strict=True, extra={"kinds": [{"cube": None}]}),
    Case(
        st.TriangulationCurve,
        lambda: _fields(st.triangulation_error_curve(RIG, np.random.default_rng(0), [0.0, 1.0], n_points=4)),
        strict=True,
        extra={"dlt": [[1.0]]},
    ),
]


def _score():
    """The score of the scene's own truth, detected perfectly: one match per true entity."""
    found = [
        st.DetectedEntity(t.kind, t.params, None, t.indices, np.zeros((0, 0)), (), 0.001, 1.0)
        for t in DETECT_SCENE.truth
    ]
    return st.evaluate(DETECT_SCENE, found)


EXEMPT: dict = {}
