"""Fuzz cases of :mod:`cga_lessons.map3d`: the robot geometer's chains, its tour and the fused 3D map.

Each valid call is small: a tour of 3 poses with one stereo view, its fused map built once; see
:mod:`fuzz.harness`.  Arguments holding multivectors are made fresh by a function, not deep-copied (a deep copy of
a multivector is no longer one of G(4,1): its copied algebra is another object).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import kinematics as kin
from cga_lessons import map3d
from cga_lessons.mapping2d import OdometryModel
from fuzz.harness import Case

_GEOMETRY = map3d.RobotGeometry()
_STATE = map3d.RobotState(1.0, 2.0, 0.3, -0.2, 0.1)


def _tour():
    return map3d.simulate_tour(np.random.default_rng(0), waypoints=((1.5, 1.5), (2.5, 1.5)), step=0.5, stops=(1,),
                               pans=(0.6,), tilts=(0.3,))  # fmt: skip


_TOUR = _tour()
_FUSED = map3d.build_fused_map(_TOUR)
_VIEW = _FUSED.views[0]
_MOTORS = map3d.chain_motors(_GEOMETRY, x=1.0, y=2.0, theta=0.3, pan=-0.2, tilt=0.1)
_BATCH = map3d.chain_motors(_GEOMETRY, x=np.array([1.0, 2.0]), y=0.5, theta=np.array([0.3, -0.1]))

_SPHERE = cga.sphere([0.0, 0.0, 1.0], 0.5)
_PLANE = cga.plane([0.0, 0.0, 1.0], 1.0)
_CIRCLE = cga.circle_from_points([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
_LINE = cga.line_from_points([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
_POINT = cga.up([1.0, 2.0, 3.0])
_ENTITIES = {"sphere": _SPHERE, "plane": _PLANE, "circle": _CIRCLE, "line": _LINE}
_NOT_MOTORS = [_SPHERE, _POINT, _LINE, _PLANE]  # a motor argument given entities
_NOT_GEOMETRY = [_STATE, _TOUR, {"baseline": 0.12}]
_NOT_FUSED = [_TOUR, _VIEW, _GEOMETRY]


def _(args: dict):
    """Fresh valid arguments for each call (not deep-copied)."""
    return lambda: dict(args)


def _robot_args(**more):
    return lambda: {"self": map3d.Robot(state=_STATE), **more}


def _entity_case(kind: str) -> Case:
    wrong = [X for k, X in _ENTITIES.items() if k != kind] + [_POINT, _MOTORS.M_lu]
    return Case(map3d.entity_parameters, _({"kind": kind, "blade": _ENTITIES[kind]}), name=f"entity_parameters({kind})",
                kinds={"blade": wrong}, extra={"blade": [_BATCH.M_lu]})  # fmt: skip


def _fields(result) -> dict:
    """A typed result's fields by name (the values themselves: multivectors are not deep-copied)."""
    return {f.name: getattr(result, f.name) for f in dataclasses.fields(result)}


_OBJECTS = {o.kind: o for o in _FUSED.objects.values()}
_TRUTHS = {type(o).__name__: o.truth() for o in _TOUR.world.objects}
_FRAMES = map3d.Robot(state=_STATE).frames()
_H = map3d.homogeneous_chains(_GEOMETRY, x=np.array([1.0, 2.0]), y=0.5, theta=0.3)
_SQUARE = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]])  # on the plane z = 1
_PARAMETERS = (cga.SphereParameters, cga.PlaneParameters, cga.CircleParameters, cga.LineParameters)


def _result_cases() -> list:
    """The typed results: each made from the fields of one the package returned."""
    out = [Case(cls, _(_fields(map3d.entity_parameters(cls.kind, _ENTITIES[cls.kind]))), strict=True)
           for cls in _PARAMETERS]  # fmt: skip
    out += [Case(type(_TRUTHS[k]), _(_fields(_TRUTHS[k])), strict=True) for k in ("Board", "Post", "Pedestal")]
    line = _OBJECTS["line"]
    out += [
        Case(map3d.ChainMotors, _(_fields(_MOTORS)), strict=True, extra={"M_eu": [_BATCH.M_eu]},
             kinds={"M_lu": [_SPHERE]}),
        Case(map3d.ChainMotors, _(_fields(_BATCH)), name="ChainMotors(batch)", skip={"pan_axis": "as the single case"},
             extra={"M_eu": [cga.translator(np.ones((3, 3)))]}),
        Case(map3d.RobotFrames, _(_fields(_FRAMES)), strict=True),
        Case(map3d.HomogeneousChains, _(_fields(_H)), strict=True, extra={"laser": [np.eye(3), np.zeros((2, 4, 3))]}),
        Case(map3d.PostGroup, _({"center": np.array([2.6, 2.3, 0.35]), "n": 4, "spread": 0.01}), strict=True,
             extra={"n": [-1], "spread": [-0.1]}),
        Case(map3d.FusedObject, _(_fields(line)), name="FusedObject(line)", strict=True,
             kinds={"params": [map3d.entity_parameters("sphere", _SPHERE)], "blade": [_SPHERE]},
             extra={"kind": ["plane"], "ends": [np.zeros((3, 3))], "corners": [np.zeros((4, 3))]}),
        Case(map3d.FusedObject, _({"kind": "plane", "blade": _PLANE, "params": map3d.entity_parameters("plane", _PLANE),
                                   "n_views": 1, "points": _SQUARE[:3], "rms": 0.0, "ends": None, "corners": _SQUARE}),
             name="FusedObject(plane)", strict=True,
             allow={"ends": ["None"]}, extra={"corners": [np.zeros((3, 3))], "ends": [np.zeros((2, 3))]}),
    ]  # fmt: skip
    return out


_DOFS = {"x": 1.0, "y": 2.0, "theta": 0.3, "pan": -0.2, "tilt": 0.1}
_DOF_ARRAYS = {"x": np.array([1.0, 2.0]), "y": 0.5, "theta": np.array([0.3, -0.1]), "pan": 0.0, "tilt": 0.2}

CASES = [
    Case(map3d.StereoEntity, _({"name": _VIEW.name, "kind": _VIEW.kind, "view": 0, "scan": 1, "state": _STATE,
                                "blade_stereo": _VIEW.blade_stereo, "blade_world": _VIEW.blade_world,
                                "params": _VIEW.params, "points_world": _VIEW.points_world[:5]}),
         strict=True, kinds={"state": [_GEOMETRY], "params": [[1.0, 2.0], _TRUTHS["Pedestal"], {"radius": 0.1}]}),
    Case(map3d.FusedMap, _({"tour": _TOUR, "laser": _FUSED.laser, "laser_height": _FUSED.laser_height,
                            "scan_segments": [], "virtual_walls": list(_FUSED.virtual_walls),
                            "laser_post_detections": np.array([[2.6, 2.3, 0.35], [2.61, 2.31, 0.35]]),
                            "laser_post_groups": list(_FUSED.laser_post_groups), "views": list(_FUSED.views),
                            "objects": dict(_FUSED.objects), "wall_height": 1.0, "post_radius": 0.05,
                            "robot": None}),
         kinds={"tour": [_FUSED, _GEOMETRY], "laser": [_TOUR], "robot": [_GEOMETRY]},
         extra={"scan_segments": [[np.zeros((2, 2, 2))]], "wall_height": [0.0]}),
    Case(map3d.build_fused_map, _({"tour": _TOUR, "method": "plain", "virtual_wall_height": 1.0, "post_radius": 0.05,
                                   "min_post_detections": 3, "poses_from": "laser", "max_depth_sigma": 0.05,
                                   "laser": _FUSED.laser}),
         strict=True, allow={"laser": ["None"]}, kinds={"tour": [_FUSED, _VIEW], "laser": [_FUSED, _TOUR]},
         extra={"post_radius": [0.0, 1e6], "virtual_wall_height": [0.0]}),
    Case(map3d.stereo_depth_limit, {"geometry": _GEOMETRY, "noise_px": 0.5, "max_depth_sigma": 0.05}, strict=True,
         kinds={"geometry": _NOT_GEOMETRY}, extra={"noise_px": [1e-300], "max_depth_sigma": [0.0]}),
    *(_entity_case(kind) for kind in _ENTITIES),
    *_result_cases(),
    Case(map3d.GeometerChains, _({"camera": kin.ur5(), "laser": kin.panda()}),
         kinds={"camera": [kin.UR5_DH, _MOTORS.M_eu], "laser": [[kin.revolute([0, 0, 1.0])]]}),
    Case(map3d.geometer_chains, {"geometry": _GEOMETRY}, kinds={"geometry": _NOT_GEOMETRY}),
    Case(map3d.Robot, {"geometry": _GEOMETRY, "state": _STATE}, allow={"geometry": ["None"], "state": ["None"]},
         kinds={"geometry": _NOT_GEOMETRY, "state": [_GEOMETRY, _DOFS]},
         extra={"state": [map3d.RobotState(tilt=2.0)]}),
    Case(map3d.Robot.update, _robot_args(pan=0.3, x=1.5), label="Robot.update", positional=("self",), strict=True,
         extra={"tilt": [2.0, np.nan], "roll": [0.1]}),
    Case(map3d.Robot.set_state, _robot_args(state=map3d.RobotState(pan=0.4)), label="Robot.set_state",
         positional=("self",), kinds={"state": [_GEOMETRY, _DOFS]}, extra={"state": [map3d.RobotState(tilt=2.0)]}),
    Case(map3d.Robot.laser_to_unified, _robot_args(X=_LINE), label="Robot.laser_to_unified", positional=("self",)),
    Case(map3d.Robot.stereo_to_unified, _robot_args(X=_SPHERE, about_lines=True), label="Robot.stereo_to_unified",
         positional=("self",), strict=True),
    Case(map3d.base_motor_as_printed, _({"T_pos": _MOTORS.T_pos, "R_lsr": cga.rotor([0.0, 0.0, 1.0], 0.2)}),
         kinds={"T_pos": _NOT_MOTORS, "R_lsr": _NOT_MOTORS}, extra={"R_lsr": [_BATCH.R_pos]}),
    Case(map3d.laser_chain_as_printed, _({"M_cl": _BATCH.M_cl, "M_pos": _BATCH.M_pos}),
         kinds={"M_cl": _NOT_MOTORS, "M_pos": _NOT_MOTORS}, extra={"M_pos": [cga.translator(np.ones((3, 3)))]}),
    Case(map3d.stereo_chain_as_printed, _({k: getattr(_MOTORS, k) for k in ("T_opt", "T_ep", "R_pt")}),
         kinds={"T_opt": _NOT_MOTORS, "T_ep": _NOT_MOTORS, "R_pt": _NOT_MOTORS}),
    Case(map3d.base_rotor, {"theta": 0.3}),
    Case(map3d.base_rotor, {"theta": np.array([0.3, -1.0, 2.0])}, name="base_rotor(batch)"),
    Case(map3d.base_translator, {"x": 1.0, "y": np.array([0.5, -0.5])}, extra={"x": [np.zeros(3)]}),
    Case(map3d.chain_motors, {"geometry": _GEOMETRY, **_DOFS}, allow={"geometry": ["None"]},
         kinds={"geometry": _NOT_GEOMETRY}),
    Case(map3d.chain_motors, {"geometry": None, **_DOF_ARRAYS}, name="chain_motors(batch)",
         extra={"pan": [np.zeros(3)]}),
    Case(map3d.homogeneous_chains, {"geometry": _GEOMETRY, **_DOFS}, allow={"geometry": ["None"]},
         kinds={"geometry": _NOT_GEOMETRY}),
    Case(map3d.homogeneous_chains, {"geometry": None, **_DOF_ARRAYS}, name="homogeneous_chains(batch)",
         extra={"tilt": [np.zeros(3)]}),
    Case(map3d.residual_table, _({"fused": _FUSED}), kinds={"fused": _NOT_FUSED}),
    Case(map3d.view_errors, _({"fused": _FUSED}), kinds={"fused": _NOT_FUSED}),
    Case(map3d.ViewErrorRow, {"view": 0, "object": "ball", "entity": "sphere", "distance_m": 1.2, "points": 40,
                              "stereo_pos_cm": 0.8, "stereo_angle_deg": 1.5, "stereo_radius_cm": 0.3},
         strict=True, nonfinite_ok="documented: NaN marks an entry that does not apply",
         allow={k: ["nan"] for k in ("stereo_pos_cm", "stereo_angle_deg", "stereo_radius_cm")},
         extra={"view": [-1], "distance_m": [-0.5], "object": [""]}),
    Case(map3d.ResidualRow, {"object": "board", "entity": "plane", "seen_by": "stereo + laser", "views": 3,
                             "laser_n": 120, "stereo_pos_cm": 1.0, "stereo_angle_deg": 0.5,
                             "stereo_radius_cm": 2.0, "laser_pos_cm": 0.4, "laser_stereo_cm": 0.9,
                             "laser_stereo_deg": 0.7},
         strict=True, nonfinite_ok="documented: NaN marks an entry that does not apply",
         allow={k: ["nan"] for k in map3d.COLUMNS[5:]}, extra={"laser_n": [-1], "views": [1.5]}),
    Case(map3d.simulate_tour, lambda: {"rng": np.random.default_rng(0), "world": None, "geometry": _GEOMETRY,
                                       "waypoints": ((1.5, 1.5), (2.5, 1.5)), "step": 0.5, "stops": (1,),
                                       "pans": (0.6,), "tilts": (0.3,), "noise_px": 0.5, "range_noise": 0.01,
                                       "min_points": 12, "odometry_model": OdometryModel()},
         strict=True, allow={"world": ["None"], "geometry": ["None"], "odometry_model": ["None"]},
         kinds={"world": [_TOUR, _GEOMETRY], "geometry": _NOT_GEOMETRY, "odometry_model": [_GEOMETRY]},
         extra={"waypoints": [((1.5, 1.5), (1.5, 1.5)), ((0.0, 0.0), (1e9, 0.0))], "step": [1e-9],
                "stops": [(-1,), (99,)], "pans": [(4.0,)], "tilts": [(2.0,)]}),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
