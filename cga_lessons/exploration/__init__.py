"""The second document: seen, unseen and occupied nodes around an obstacle, and the path around it.

Layer 3 of the package: imports layers 0-2 (errors, algebra, conformal) only (``tests/test_layers.py`` checks it).
Nothing here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in
``__all__``; its modules:

* :mod:`~cga_lessons.exploration.cases`: The test cases of the exploration document's section 3.1.4, and the check
  against ray casting
* :mod:`~cga_lessons.exploration.grid`: The workspace grid, the robot's cameras and the obstacle of the exploration
  document (section 3.1), and the checks of their inputs
* :mod:`~cga_lessons.exploration.nodes`: Seen, unseen and occupied nodes around an obstacle: the exploration
  document, section 3.1
* :mod:`~cga_lessons.exploration.path`: The path around an obstacle: the exploration document, section 3.2,
  equations (3.2)-(3.3)
* :mod:`~cga_lessons.exploration.spheres`: The sphere that encloses an obstacle (exploration document, section
  3.1.2) and points on spheres and boxes
"""

from .cases import (
    DISAGREEMENTS,
    DOCUMENT_CASES,
    Scenario,
    occupied_counts_random_centres,
    ray_cast_disagreements,
    run_scenario,
    summary,
)
from .grid import CameraView, Grid, SphereObstacle, make_grid
from .nodes import (
    ANALYSED,
    LABEL_NAMES,
    NOT_SEEN,
    OCCUPIED,
    SEEN,
    NodeLabels,
    Projections,
    cells_touched_by_sphere,
    l1_distances,
    label_nodes,
    occupied_nodes,
    occupied_nodes_loop,
    projections,
    ray_cast_seen,
    seen_nodes,
)
from .path import detour, line_circle_intersections, line_circle_intersections_conformal
from .spheres import box_surface_points, enclosing_sphere, fit_sphere, sphere_points

__all__ = [
    "NOT_SEEN",
    "SEEN",
    "ANALYSED",
    "OCCUPIED",
    "LABEL_NAMES",
    "Grid",
    "make_grid",
    "CameraView",
    "SphereObstacle",
    "Projections",
    "projections",
    "fit_sphere",
    "enclosing_sphere",
    "sphere_points",
    "box_surface_points",
    "seen_nodes",
    "ray_cast_seen",
    "l1_distances",
    "occupied_nodes_loop",
    "occupied_nodes",
    "cells_touched_by_sphere",
    "NodeLabels",
    "label_nodes",
    "run_scenario",
    "DISAGREEMENTS",
    "DOCUMENT_CASES",
    "Scenario",
    "detour",
    "line_circle_intersections",
    "line_circle_intersections_conformal",
    "occupied_counts_random_centres",
    "ray_cast_disagreements",
    "summary",
]
