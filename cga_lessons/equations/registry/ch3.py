"""Chapter 3 registry: 2D laser line maps, plain (3.1-3.12) and with point pairs (3.13-3.21)."""

from cga_lessons.equations.core import Entry

L = "cga_lessons.mapping2d.lines"
M = "cga_lessons.mapping2d"
G = "cga_lessons.mapping2d.geometry"
K = "cga_lessons.mapping2d.corrections"
C = "cga_lessons.mapping2d.conformal"
TL = "tests/test_lines.py"
TM = "tests/test_mapping2d.py"
E = "cga_lessons.mapping2d.estimation"
TE = "tests/test_mapping2d_estimation.py"

ENTRIES = [
    Entry(
        label="3.1",
        title="line a x + b y + c = 0 through the first and last point",
        status="numeric",
        implementation=f"cga_lessons.mapping2d.segment.line_through, {L}.split_points",
        test=f"{TL}::test_line_through_and_point_distance_3_1_3_2, {TL}::test_split_points_at_a_corner_and_not_on_a_line",
    ),
    Entry(
        label="3.2",
        title="distance of a point to a line",
        status="numeric",
        implementation=f"cga_lessons.mapping2d.segment.point_line_distance, {L}.split_points",
        test=f"{TL}::test_line_through_and_point_distance_3_1_3_2, {TL}::test_split_points_at_a_corner_and_not_on_a_line",
    ),
    Entry(
        label="3.3",
        title="Hough normal form x cos(theta) + y sin(theta) = rho; the segment structure",
        status="numeric",
        implementation="cga_lessons.mapping2d.segment.Segment",
        test=f"{TL}::test_segment_members_3_3",
    ),
    Entry(
        label="3.4",
        title="v' = R(theta_o) v + T_o",
        status="numeric",
        implementation=(
            f"cga_lessons.mapping2d.poses.compose, cga_lessons.mapping2d.segment.Segment.transformed, {G}.PlainGeometry.transform, "
            f"{G}.PlainGeometry.to_global_rows"
        ),
        test=(
            f"{TM}::test_transform_is_the_rigid_motion_3_4, "
            f"{TL}::test_segment_transformed_is_the_motion_of_its_points_3_4, "
            f"{TM}::test_refit_moves_the_map_with_the_poses"
        ),
    ),
    Entry(
        label="3.5",
        title="diffTheta",
        status="erratum",
        implementation=f"{L}.diff_theta",
        printed="case 1: theta_a > theta_b, theta_a + theta_xi >= 2 pi, theta_b + theta_xi <= 0 (case 2 alike)",
        correct="case 1: theta_a > theta_b, theta_a + theta_xi >= 2 pi, theta_b - theta_xi <= 0 (case 2 alike)",
        note="as printed the cases never apply for angles in [0, 2 pi); the thesis's own example needs the minus",
        test=f"{TL}::test_diff_theta_thesis_example, {TL}::test_diff_theta_erratum_printed_form_fails_its_own_example",
    ),
    Entry(
        label="3.6",
        title="theta = theta_o + theta_corr",
        status="numeric",
        implementation=(
            f"{M}.build_map, cga_lessons.mapping2d.builder.MapBuilder.correct, "
            "cga_lessons.mapping2d.correction.ScanCorrector.register"
        ),
        test=(
            f"{TM}::test_build_map_noise_free_recovers_truth_and_walls, {TM}::test_build_map_office_meets_the_targets, "
            f"{TM}::test_correct_recovers_a_known_pose_and_gates_a_wrong_pair"
        ),
    ),
    Entry(
        label="3.7",
        title="T = T_o + T_corr",
        status="numeric",
        implementation=(
            f"{M}.build_map, cga_lessons.mapping2d.builder.MapBuilder.correct, "
            "cga_lessons.mapping2d.correction.ScanCorrector.register"
        ),
        test=(
            f"{TM}::test_build_map_noise_free_recovers_truth_and_walls, {TM}::test_build_map_office_meets_the_targets, "
            f"{TM}::test_correct_recovers_a_known_pose_and_gates_a_wrong_pair"
        ),
    ),
    Entry(
        label="3.8",
        title="theta_corr = mean of diffTheta over the correspondences",
        status="numeric",
        implementation=f"{K}.theta_correction, {K}.pose_correction, {E}.Measurements.from_pairs, {E}.estimate_correction",
        test=(
            f"{TM}::test_theta_correction_3_8_is_the_mean, {TM}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TE}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.9",
        title="T_corr from one correspondence (closest points)",
        status="numeric",
        implementation=f"{K}.translation_correction",
        test=f"{TM}::test_translation_correction_3_9_to_3_12",
    ),
    Entry(
        label="3.10",
        title="l_G = l_L' + t_x cos(theta) + t_y sin(theta)",
        status="numeric",
        implementation=f"{K}.translation_correction",
        test=f"{TM}::test_translation_correction_3_9_to_3_12",
    ),
    Entry(
        label="3.11",
        title="rho_G - ((p_L'c + t) . n) = 0",
        status="numeric",
        implementation=f"{K}.translation_correction, {K}.pose_correction, {E}.Measurements.from_pairs, {E}.estimate_correction",
        test=(
            f"{TM}::test_translation_correction_3_9_to_3_12, {TM}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TE}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.12",
        title="least squares sum (rho_G - rho_T)^2",
        status="numeric",
        implementation=f"{K}.translation_correction, {K}.pose_correction, {E}.Measurements.from_pairs, {E}.estimate_correction",
        test=(
            f"{TM}::test_translation_correction_3_9_to_3_12, {TM}::test_pose_correction_is_3_8_and_3_12_solved_together, "
            f"{TE}::test_estimate_correction_recovers_a_known_offset_and_its_test_obeys_the_chi_square_law"
        ),
    ),
    Entry(
        label="3.13",
        title="E2C(x, y)",
        status="numeric",
        implementation=f"{C}.e2c, {C}.c2e",
        test=f"{TM}::test_e2c_3_13",
    ),
    Entry(
        label="3.14",
        title="Hesse distance rho^2 = ((L* . e0) / (L* . e0 . e))^2",
        status="numeric",
        implementation=f"{C}.point_pair_structure, {C}.ConformalGeometry.hough",
        test=f"{TM}::test_point_pair_structure_3_14_3_15, {TM}::test_conformal_geometry_equals_plain_geometry",
    ),
    Entry(
        label="3.15",
        title="closest point to the origin",
        status="erratum",
        implementation=f"{C}.point_pair_structure, cga_lessons.conformal.lines_circles.line_closest_point",
        printed="p = -(L* . E) . ((e+ . L) I_E)",
        correct="p = (L* . E) . ((e+ . L) I_E), L* normalised by (2.126) (the sign of the moment 2.128)",
        test=f"{TM}::test_eq_3_15_erratum_printed_sign_gives_the_antipode, {TM}::test_point_pair_structure_3_14_3_15",
    ),
    Entry(
        label="3.16",
        title="M_laser-robot = T_laser-robot R_laser-robot",
        status="numeric",
        implementation=f"{C}.robot_motor, {C}.laser_motor",
        test=f"{TM}::test_laser_motor_3_16_3_18",
    ),
    Entry(
        label="3.17",
        title="M_laser = M_l-r M_robot",
        status="erratum",
        implementation=f"{C}.laser_motor",
        printed="M_l-r = R_robot M_laser-robot ~R_robot",
        correct="M_l-r = M_robot M_laser-robot ~M_robot, i.e. M_laser = M_robot M_laser-robot",
        note="the printed form is right only for a laser not turned on the robot",
        test=f"{TM}::test_laser_motor_erratum_3_17",
    ),
    Entry(
        label="3.18",
        title="x' = M_laser x ~M_laser",
        status="numeric",
        implementation=f"{C}.ConformalGeometry.to_global, {C}.ConformalGeometry.to_global_rows",
        test=f"{TM}::test_laser_motor_3_16_3_18, {TM}::test_conformal_geometry_equals_plain_geometry",
    ),
    Entry(
        label="3.19",
        title="correspondence matrix M_c from the sphere cases 1-5",
        status="numeric",
        implementation=(
            f"{C}.sphere_case, {C}.ConformalGeometry.overlap, {C}.ConformalGeometry.overlap_rows, {G}.correspondences"
        ),
        test=f"{TM}::test_sphere_cases_3_19, {TM}::test_plain_and_conformal_build_the_same_map",
    ),
    Entry(
        label="3.20",
        title="p_e1 = p_1 (same sense) or p_2 (opposite)",
        status="numeric",
        implementation=f"{C}.ConformalGeometry.fuse_ends, {G}.PlainGeometry.fuse_ends",
        test=f"{TM}::test_fuse_ends_3_20_3_21",
    ),
    Entry(
        label="3.21",
        title="p_e2 = p_2 (same sense) or p_1 (opposite)",
        status="numeric",
        implementation=f"{C}.ConformalGeometry.fuse_ends, {G}.PlainGeometry.fuse_ends",
        test=f"{TM}::test_fuse_ends_3_20_3_21",
    ),
]
