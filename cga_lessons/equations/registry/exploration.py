"""Equations of the second document (exploration with a mobile robot), sections 3.1-3.2.

Their numbers collide with the thesis's chapter 3, so they carry ``document="exploration"``
and are listed as ``"exploration (3.1)"`` etc.
"""

from cga_lessons.equations.core import Entry

ENTRIES = [
    Entry(
        label="3.1",
        title="L1 distance B from every node to a point of the sphere; nearest-node loop for occupied nodes",
        status="numeric",
        implementation="cga_lessons.exploration.nodes.l1_distances, cga_lessons.exploration.nodes.occupied_nodes_loop",
        test="tests/test_exploration.py::test_l1_distance_equation_3_1, "
        "tests/test_exploration.py::test_loop_matches_indexed_and_brute_force",
        note="The loop skips an analysed node for the current point only; removing it for good can lose "
        "an occupied node (tests/test_exploration.py::test_analysed_nodes_are_skipped_for_one_point_only).",
        document="exploration",
    ),
    Entry(
        label="3.2",
        title="Straight path y - y1 = m (x - x1) from the robot towards the goal",
        status="numeric",
        implementation="cga_lessons.exploration.path.line_circle_intersections",
        test="tests/test_exploration.py::test_crossings_document_vs_conformal",
        note="Solved with x and y swapped when |m| > 1 (a vertical path has no slope).",
        document="exploration",
    ),
    Entry(
        label="3.3",
        title="Obstacle circle (x - a)^2 + (y - b)^2 = r^2; its crossings with (3.2), also as a conformal point pair",
        status="numeric",
        implementation="cga_lessons.exploration.path.line_circle_intersections, "
        "cga_lessons.exploration.path.line_circle_intersections_conformal, cga_lessons.exploration.path.detour",
        test="tests/test_exploration.py::test_crossings_document_vs_conformal, "
        "tests/test_exploration.py::test_detour_is_smooth_stays_outside_and_is_shortest",
        document="exploration",
    ),
]
