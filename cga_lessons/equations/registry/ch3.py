"""Chapter 3 registry: 2D laser line maps, plain (3.1-3.12) and with point pairs (3.13-3.21)."""

from cga_lessons.equations.core import Entry

LINES = "cga_lessons.mapping2d.lines"
MAPPING2D = "cga_lessons.mapping2d"
GEOMETRY = "cga_lessons.mapping2d.geometry"
CORRECTIONS = "cga_lessons.mapping2d.corrections"
CONFORMAL_MAP = "cga_lessons.mapping2d.conformal"
CONFORMAL_GEOMETRY = "cga_lessons.mapping2d.conformal_geometry"
TEST_LINES = "tests/test_lines.py"
TEST_MAPPING2D = "tests/test_mapping2d.py"
ESTIMATION = "cga_lessons.mapping2d.estimation"
TEST_ESTIMATION = "tests/test_mapping2d_estimation.py"

ENTRIES = [
    Entry(
        label="3.1",
        title="line a x + b y + c = 0 through the first and last point",
        status="numeric",
        implementation=f"cga_lessons.mapping2d.segment.line_through, {LINES}.split_points",
        test=f"{TEST_LINES}::test_line_through_and_point_distance_3_1_3_2, {TEST_LINES}::test_split_points_at_a_corner_and_not_on_a_line",
    ),
    Entry(
        label="3.2",
        title="distance of a point to a line",
        status="numeric",
        implementation=f"cga_lessons.mapping2d.segment.point_line_distance, {LINES}.split_points",
        test=f"{TEST_LINES}::test_line_through_and_point_distance_3_1_3_2, {TEST_LINES}::test_split_points_at_a_corner_and_not_on_a_line",
    ),
    Entry(
        label="3.3",
        title="Hough normal form x cos(theta) + y sin(theta) = rho; the segment structure",
        status="numeric",
        implementation="cga_lessons.mapping2d.segment.Segment",
        test=f"{TEST_LINES}::test_segment_members_3_3",
    ),
    Entry(
        label="3.4",
        title="v' = R(theta_o) v + T_o",
        status="numeric",
        implementation=(
            f"cga_lessons.mapping2d.poses.compose, cga_lessons.mapping2d.segment.Segment.transformed, {GEOMETRY}.PlainGeometry.transform, "
            f"{GEOMETRY}.PlainGeometry.to_global_rows"
        ),
        test=(
            f"{TEST_MAPPING2D}::test_transform_is_the_rigid_motion_3_4, "
            f"{TEST_LINES}::test_segment_transformed_is_the_motion_of_its_points_3_4, "
            f"{TEST_MAPPING2D}::test_refit_moves_the_map_with_the_poses"
        ),
    ),
    Entry(
        label="3.5",
        title="diffTheta",
        status="erratum",
        implementation=f"{LINES}.diff_theta",
        printed="case 1: theta_a > theta_b, theta_a + theta_xi >= 2 pi, theta_b + theta_xi <= 0 (case 2 alike)",
        correct="case 1: theta_a > theta_b, theta_a + theta_xi >= 2 pi, theta_b - theta_xi <= 0 (case 2 alike)",
        note="as printed the cases never apply for angles in [0, 2 pi); the thesis's own example needs the minus",
        test=f"{TEST_LINES}::test_diff_theta_thesis_example, {TEST_LINES}::test_diff_theta_erratum_printed_form_fails_its_own_example",
    ),
    Entry(
        label="3.6",
        title="theta = theta_o + theta_corr",
        status="numeric",
        implementation=(
            f"{MAPPING2D}.build_map, cga_lessons.mapping2d.builder.MapBuilder.correct, "
            "cga_lessons.mapping2d.correction.ScanCorrector.register"
        ),
        test=(
            f"{TEST_MAPPING2D}::test_build_map_noise_free_recovers_truth_and_walls, {TEST_MAPPING2D}::test_build_map_office_meets_the_targets, "
            f"{TEST_MAPPING2D}::test_correct_recovers_a_known_pose_and_gates_a_wrong_pair"
        ),
    ),
    Entry(
        label="3.7",
        title="T = T_o + T_corr",
        status="numeric",
        implementation=(
            f"{MAPPING2D}.build_map, cga_lessons.mapping2d.builder.MapBuilder.correct, "
            "cga_lessons.mapping2d.correction.ScanCorrector.register"
        ),
        test=(
            f"{TEST_MAPPING2D}::test_build_map_noise_free_recovers_truth_and_walls, {TEST_MAPPING2D}::test_build_map_office_meets_the_targets, "
            f"{TEST_MAPPING2D}::test_correct_recovers_a_known_pose_and_gates_a_wrong_pair"
        ),
    ),
    Entry(
        label="3.8",
        title="theta_corr = mean of diffTheta over the correspondences",
        status="numeric",
        implementation=f"{CORRECTIONS}.theta_correction, {CORRECTIONS}.pose_correction, {ESTIMATION}.Measurements.from_pairs, {ESTIMATION}.estimate_correction",
        test=(
            f"{TEST_MAPPING2D}::test_theta_correction_3_8_is_the_mean, {TEST_MAPPING2D}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TEST_ESTIMATION}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.9",
        title="T_corr from one correspondence (closest points)",
        status="numeric",
        implementation=f"{CORRECTIONS}.translation_correction",
        test=f"{TEST_MAPPING2D}::test_translation_correction_3_9_to_3_12",
    ),
    Entry(
        label="3.10",
        title="l_G = l_L' + t_x cos(theta) + t_y sin(theta)",
        status="numeric",
        implementation=f"{CORRECTIONS}.translation_correction",
        test=f"{TEST_MAPPING2D}::test_translation_correction_3_9_to_3_12",
    ),
    Entry(
        label="3.11",
        title="rho_G - ((p_L'c + t) . n) = 0",
        status="numeric",
        implementation=f"{CORRECTIONS}.translation_correction, {CORRECTIONS}.pose_correction, {ESTIMATION}.Measurements.from_pairs, {ESTIMATION}.estimate_correction",
        test=(
            f"{TEST_MAPPING2D}::test_translation_correction_3_9_to_3_12, {TEST_MAPPING2D}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TEST_ESTIMATION}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.12",
        title="least squares sum (rho_G - rho_T)^2",
        status="numeric",
        implementation=f"{CORRECTIONS}.translation_correction, {CORRECTIONS}.pose_correction, {ESTIMATION}.Measurements.from_pairs, {ESTIMATION}.estimate_correction",
        test=(
            f"{TEST_MAPPING2D}::test_translation_correction_3_9_to_3_12, {TEST_MAPPING2D}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TEST_ESTIMATION}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.13",
        title="E2C(x, y)",
        status="numeric",
        implementation=f"{CONFORMAL_MAP}.e2c, {CONFORMAL_MAP}.c2e",
        test=f"{TEST_MAPPING2D}::test_e2c_3_13",
    ),
    Entry(
        label="3.14",
        title="Hesse distance rho^2 = ((L* . e0) / (L* . e0 . e))^2",
        status="numeric",
        implementation=f"{CONFORMAL_MAP}.point_pair_structure, {CONFORMAL_GEOMETRY}.ConformalGeometry.hough",
        test=f"{TEST_MAPPING2D}::test_point_pair_structure_3_14_3_15, {TEST_MAPPING2D}::test_conformal_geometry_equals_plain_geometry",
    ),
    Entry(
        label="3.15",
        title="closest point to the origin",
        status="erratum",
        implementation=f"{CONFORMAL_MAP}.point_pair_structure, cga_lessons.conformal.lines_circles.line_closest_point",
        printed="p = -(L* . E) . ((e+ . L) I_E)",
        correct="p = (L* . E) . ((e+ . L) I_E), L* normalised by (2.126) (the sign of the moment 2.128)",
        test=f"{TEST_MAPPING2D}::test_eq_3_15_erratum_printed_sign_gives_the_antipode, {TEST_MAPPING2D}::test_point_pair_structure_3_14_3_15",
    ),
    Entry(
        label="3.16",
        title="M_laser-robot = T_laser-robot R_laser-robot",
        status="numeric",
        implementation=f"{CONFORMAL_MAP}.robot_motor, {CONFORMAL_MAP}.laser_motor",
        test=f"{TEST_MAPPING2D}::test_laser_motor_3_16_3_18",
    ),
    Entry(
        label="3.17",
        title="M_laser = M_l-r M_robot",
        status="erratum",
        implementation=f"{CONFORMAL_MAP}.laser_motor",
        printed="M_l-r = R_robot M_laser-robot ~R_robot",
        correct="M_l-r = M_robot M_laser-robot ~M_robot, i.e. M_laser = M_robot M_laser-robot",
        note="the printed form is right only for a laser not turned on the robot",
        test=f"{TEST_MAPPING2D}::test_laser_motor_erratum_3_17",
    ),
    Entry(
        label="3.18",
        title="x' = M_laser x ~M_laser",
        status="numeric",
        implementation=f"{CONFORMAL_GEOMETRY}.ConformalGeometry.to_global, {CONFORMAL_GEOMETRY}.ConformalGeometry.to_global_rows",
        test=f"{TEST_MAPPING2D}::test_laser_motor_3_16_3_18, {TEST_MAPPING2D}::test_conformal_geometry_equals_plain_geometry",
    ),
    Entry(
        label="3.19",
        title="correspondence matrix M_c from the sphere cases 1-5",
        status="numeric",
        implementation=(
            f"{CONFORMAL_GEOMETRY}.sphere_case, {CONFORMAL_GEOMETRY}.ConformalGeometry.overlap, {CONFORMAL_GEOMETRY}.ConformalGeometry.overlap_rows, {GEOMETRY}.correspondences"
        ),
        test=f"{TEST_MAPPING2D}::test_sphere_cases_3_19, {TEST_MAPPING2D}::test_plain_and_conformal_build_the_same_map",
    ),
    Entry(
        label="3.20",
        title="p_e1 = p_1 (same sense) or p_2 (opposite)",
        status="numeric",
        implementation=(
            f"{CONFORMAL_GEOMETRY}.ConformalGeometry.fuse_ends, {GEOMETRY}.PlainGeometry.fuse_ends, "
            "cga_lessons.mapping2d.fusion.fuse_segment"
        ),
        test=f"{TEST_MAPPING2D}::test_fuse_ends_3_20_3_21",
    ),
    Entry(
        label="3.21",
        title="p_e2 = p_2 (same sense) or p_1 (opposite)",
        status="numeric",
        implementation=(
            f"{CONFORMAL_GEOMETRY}.ConformalGeometry.fuse_ends, {GEOMETRY}.PlainGeometry.fuse_ends, "
            "cga_lessons.mapping2d.fusion.fuse_segment"
        ),
        test=f"{TEST_MAPPING2D}::test_fuse_ends_3_20_3_21",
    ),
]
