"""Fuzz cases of :mod:`cga_lessons.exploration`: the nodes around an obstacle, the document's cases, the detour.

Each valid call is small (a grid of a few nodes, a handful of points); see :mod:`fuzz.harness`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import exploration as ex
from fuzz.harness import Case

_GRID = ex.make_grid((0.0, 60.0), (0.0, 60.0), (0.0, 30.0), 30.0)  # 3 x 3 x 2 nodes
_VIEW = ex.CameraView((-10.0, 30.0, 20.0), 0.0, np.radians(150.0))
_OBSTACLE = ex.SphereObstacle((45.0, 30.0, 15.0), 7.5)
_POINTS = np.array([[40.0, 25.0, 10.0], [50.0, 35.0, 20.0], [45.0, 30.0, 7.5], [45.0, 37.5, 15.0], [2.0, 3.0, 4.0]])
_SPHERE_PTS = ex.sphere_points((1.0, 2.0, 3.0), 2.0, 4)
_SMALL = ex.Scenario(x_range=(-60.0, 0.0), y_range=(-30.0, 30.0), z_range=(0.0, 30.0), sphere_samples=6)
_RESULT = ex.run_scenario(_SMALL)

_SPHERE, _PLANE = cga.sphere([0.0, 0.0, 0.0], 1.0), cga.plane([0.0, 0.0, 1.0], 1.0)
_WRONG_VIEW = [_OBSTACLE, _GRID, _SPHERE]  # a camera view's reader given an obstacle, a grid, a conformal sphere
_WRONG_OBSTACLE = [_VIEW, _GRID, _SPHERE]  # an obstacle's reader given a camera view, a grid, a conformal sphere
_WRONG_GRID = [_VIEW, _OBSTACLE, _PLANE]
_COINCIDENT = [np.ones((5, 3))]
_SQUARE = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])
_COPLANAR = [_SQUARE, np.array([[0.0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3]])]  # a square; collinear points


def _rng():
    return np.random.default_rng(1)


CASES = [
    Case(ex.Grid, {"origin": (0.0, 0.0, 0.0), "spacing": 30.0, "shape": (3, 3, 2)}, strict=True,
         extra={"shape": [(0, 3, 2), (3, 3), (10**9, 10**9, 10**9)], "spacing": [0.0, -1.0]}),
    Case(ex.make_grid, {"x_range": (0.0, 60.0), "y_range": (0.0, 60.0), "z_range": (0.0, 30.0), "spacing": 30.0},
         strict=True, extra={"x_range": [(1.0, 0.0), (-1e300, 1e300)], "spacing": [0.0, -30.0, 1e-300]}),
    Case(ex.CameraView, {"position": (0.0, 0.0, 20.0), "heading": np.pi, "fov": 2.6, "max_range": np.inf},
         strict=True, extra={"fov": [0.0, 2 * np.pi, -1.0], "max_range": [0.0, -5.0, 100.0]}),
    Case(ex.SphereObstacle, {"center": (45.0, 30.0, 15.0), "radius": 7.5}, strict=True, extra={"radius": [0.0, -1.0]}),
    Case(ex.Projections, {"edges": (-1.3, 1.3), "tangents": (-0.2, 0.2), "tangent_in_view": (True, True),
                          "centre_bearing": 0.0, "centre_distance": 50.0, "case": "whole"}, strict=True,
         allow={"tangents": ["None"], "centre_bearing": ["None"], "centre_distance": ["None"]},
         extra={"tangent_in_view": [(1, 0), ("yes", "no")], "centre_distance": [-1.0]}),
    Case(ex.Projections, {"edges": (-1.3, 1.3), "tangents": None, "tangent_in_view": (False, False),
                          "centre_bearing": None, "centre_distance": None, "case": "free"},
         strict=True, name="Projections(free)", allow={"tangents": ["None"], "centre_bearing": ["None"],
                                                       "centre_distance": ["None"]}),
    Case(ex.projections, {"view": _VIEW, "obstacle": _OBSTACLE},
         kinds={"view": _WRONG_VIEW, "obstacle": _WRONG_OBSTACLE},
         extra={"obstacle": [ex.SphereObstacle((-10.0, 31.0, 20.0), 5.0)]}),
    Case(ex.fit_sphere, {"points": _SPHERE_PTS}, extra={"points": _COINCIDENT + _COPLANAR + [np.eye(3)]}),
    Case(ex.enclosing_sphere, {"points": _SPHERE_PTS}, extra={"points": _COINCIDENT}),
    Case(ex.sphere_points, {"center": (1.0, 2.0, 3.0), "radius": 2.0, "n": 4}, strict=True,
         extra={"radius": [0.0, -2.0], "n": [2, 10**9]}),
    Case(ex.box_surface_points, lambda: {"rng": _rng(), "center": (1.0, 2.0, 3.0), "size": (2.0, 1.0, 1.0), "n": 6},
         strict=True, extra={"size": [(-1.0, 1.0, 1.0)], "n": [10**12]}),
    Case(ex.seen_nodes, {"nodes": _GRID.nodes, "view": _VIEW, "obstacle": _OBSTACLE},
         kinds={"view": _WRONG_VIEW, "obstacle": _WRONG_OBSTACLE}),
    Case(ex.ray_cast_seen, {"nodes": _GRID.nodes, "view": _VIEW, "obstacle": _OBSTACLE},
         kinds={"view": _WRONG_VIEW, "obstacle": _WRONG_OBSTACLE}),
    Case(ex.l1_distances, {"nodes": _GRID.nodes, "point": (10.0, -5.0, 2.0)}),
    Case(ex.occupied_nodes_loop, {"grid": _GRID, "points": _POINTS}, kinds={"grid": _WRONG_GRID}),
    Case(ex.occupied_nodes, {"grid": _GRID, "points": _POINTS}, kinds={"grid": _WRONG_GRID}),
    Case(ex.cells_touched_by_sphere, {"grid": _GRID, "obstacle": _OBSTACLE},
         kinds={"grid": _WRONG_GRID, "obstacle": _WRONG_OBSTACLE}),
    Case(ex.NodeLabels, {"seen": np.array([True, False, True]), "occupied": np.array([False, False, True]),
                         "analysed": np.array([False, True, False])},
         kinds={"seen": [np.array([1, 0, 1]), np.array([0.0, 1.0, 1.0])], "occupied": [[0, 0, 2]]},
         extra={"analysed": [np.array([True, False])]}),
    Case(ex.label_nodes, {"grid": _GRID, "view": _VIEW, "obstacle": _OBSTACLE, "points": _POINTS},
         kinds={"grid": _WRONG_GRID, "view": _WRONG_VIEW, "obstacle": _WRONG_OBSTACLE}),
    Case(ex.run_scenario, {"scenario": _SMALL, "heading": 3.0}, kinds={"scenario": [_VIEW, _GRID]},
         extra={"not_a_field": [1.0], "fov": [0.0, 7.0]}),
    Case(ex.Scenario, {"x_range": (-120.0, 120.0), "y_range": (-120.0, 120.0), "z_range": (0.0, 30.0),
                       "spacing": 30.0, "robot": (0.0, 0.0, 20.0), "heading": np.pi, "fov": 2.6,
                       "max_range": np.inf, "sphere_center": (-63.0, 6.0, 24.0), "sphere_diameter": 15.0,
                       "sphere_samples": 20}, strict=True, allow={"sphere_center": ["None"]},
         extra={"spacing": [0.0], "fov": [0.0, 7.0], "sphere_diameter": [0.0], "sphere_samples": [2, 10**9],
                "x_range": [(1.0, 0.0)]}),
    Case(ex.detour, {"start": (0.0, 0.0), "goal": (100.0, 0.0), "center": (50.0, 1.0), "radius": 10.0,
                     "clearance": 1.0, "direction": 1, "n_arc": 8, "method": "conformal"},
         strict=True, allow={"direction": ["None"]},
         extra={"goal": [(0.0, 0.0)], "start": [(49.0, 1.0)], "radius": [0.0, -1.0], "direction": [0, 2],
                "n_arc": [1, 10**9], "clearance": [-1.0]}),
    Case(ex.detour, {"start": (0.0, 0.0), "goal": (100.0, 0.0), "center": (50.0, 1.0), "radius": 10.0,
                     "method": "document"}, strict=True, name="detour(document)"),
    Case(ex.line_circle_intersections, {"start": (0.0, 0.0), "goal": (10.0, 1.0), "center": (5.0, 0.0), "radius": 2.0},
         extra={"goal": [(0.0, 0.0)], "radius": [0.0]}),
    Case(ex.line_circle_intersections_conformal,
         {"start": (0.0, 0.0), "goal": (10.0, 1.0), "center": (5.0, 0.0), "radius": 2.0},
         extra={"goal": [(0.0, 0.0)], "radius": [0.0]}),
    Case(ex.occupied_counts_random_centres,
         lambda: {"rng": _rng(), "n": 2, "diameters": (15.0, 25.0), "scenario": _SMALL},
         strict=True, allow={"scenario": ["None"]}, kinds={"scenario": [_VIEW, _RESULT]},
         extra={"n": [10**12], "diameters": [(0.0,), (-1.0,), (500.0,)]}),
    Case(ex.ray_cast_disagreements, {"result": _RESULT}, kinds={"result": [_SMALL, _VIEW]}),
    Case(ex.summary, {"result": _RESULT}, kinds={"result": [_SMALL, _GRID]}),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
