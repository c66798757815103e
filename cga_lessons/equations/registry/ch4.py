"""Chapter 4 registry, section 4.2: the robot geometer's sensors as motor chains (4.1-4.10)."""

from cga_lessons.equations.core import Entry

CHAINS = "cga_lessons.map3d.chains"
TEST_ROBOT = "tests/test_robot.py"
TEST_MAP3D = "tests/test_map3d.py"

ENTRIES = [
    Entry(
        label="4.1",
        title="M_cl = R_pos M_lsr ~R_pos (the laser mount turned with the robot)",
        status="numeric",
        implementation=f"{CHAINS}.turned_laser_mount, {CHAINS}.laser_mount_motor, cga_lessons.map3d.robot.Robot",
        test=f"{TEST_ROBOT}::test_laser_chain_4_1_to_4_3_equals_homogeneous_matrices",
    ),
    Entry(
        label="4.2",
        title="M_pos: the robot's motion",
        status="erratum",
        implementation=f"{CHAINS}.base_motor, {CHAINS}.base_motor_as_printed",
        printed="M_pos = T_pos R_lsr",
        correct="M_pos = T_pos R_pos",
        note="R_lsr, the laser's mounting rotor (1 for the forward-looking laser), leaves the robot's heading out "
        "of the chain; (3.17), its 2D model, uses the robot's rotor",
        test=f"{TEST_ROBOT}::test_eq_4_2_erratum_printed_form_ignores_the_heading",
    ),
    Entry(
        label="4.3",
        title="M_lu: laser frame to unified frame",
        status="erratum",
        implementation=f"{CHAINS}.laser_chain, {CHAINS}.laser_chain_as_printed, cga_lessons.map3d.geometer.geometer_chains",
        printed="M_lu = M_cl M_pos",
        correct="M_lu = T_pos M_cl R_pos (= M_pos M_lsr)",
        note="the printed order is right only for a laser not turned on the robot (M_cl is then a translation and "
        "commutes with T_pos), as in (3.17); with a mount yaw phi it translates by R_pos t_lsr + R_phi t_pos",
        test=f"{TEST_ROBOT}::test_eq_4_3_erratum_printed_order_needs_a_straight_laser, "
        f"{TEST_ROBOT}::test_laser_chain_4_1_to_4_3_equals_homogeneous_matrices, tests/test_kinematics.py::test_geometer_chains_equal_todays_robot_code",
    ),
    Entry(
        label="4.4",
        title="x' = M_lu x ~M_lu (laser entities to the unified frame)",
        status="numeric",
        implementation=f"{CHAINS}.to_unified, cga_lessons.map3d.robot.Robot.laser_to_unified, cga_lessons.map3d.fuse.build_fused_map",
        test=f"{TEST_ROBOT}::test_eq_4_4_moves_laser_entities_like_the_matrix, "
        f"{TEST_MAP3D}::test_scan_segments_land_at_laser_height_on_the_walls",
    ),
    Entry(
        label="4.5",
        title="T_ep = R_pos T_eje ~R_pos (to the point nearest the pan-tilt axes)",
        status="numeric",
        implementation=f"{CHAINS}.head_translator, {CHAINS}.axes_nearest_point",
        test=f"{TEST_ROBOT}::test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices, {TEST_ROBOT}::test_axes_nearest_point",
    ),
    Entry(
        label="4.6",
        title="R_pt = R_pos R_pan R_tilt",
        status="numeric",
        implementation=f"{CHAINS}.head_rotor, {CHAINS}.stereo_chain_about_lines",
        note="the footnote's variant, rotations about the axis lines L_pan, L_tilt by (2.109), is "
        "stereo_chain_about_lines; it stays exact when calibrated axes miss each other",
        test=f"{TEST_ROBOT}::test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices, "
        f"{TEST_ROBOT}::test_chain_about_lines_2_109_is_exact_for_axes_that_miss",
    ),
    Entry(
        label="4.7",
        title="T_opt = R_pt T_ojo ~R_pt (on to the left camera)",
        status="numeric",
        implementation=f"{CHAINS}.eye_translator",
        test=f"{TEST_ROBOT}::test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices",
    ),
    Entry(
        label="4.8",
        title="M_mpt = T_pos R_pt",
        status="numeric",
        implementation=f"{CHAINS}.head_motor",
        test=f"{TEST_ROBOT}::test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices",
    ),
    Entry(
        label="4.9",
        title="M_eu: stereo frame to unified frame",
        status="erratum",
        implementation=f"{CHAINS}.stereo_chain, {CHAINS}.stereo_chain_as_printed, cga_lessons.map3d.geometer.geometer_chains",
        printed="M_eu = T_opt T_ep R_mpt",
        correct="M_eu = T_opt T_ep M_mpt",
        note="R_mpt is not defined; (4.8) defines the motor M_mpt for this place; its rotor alone (R_pt) drops "
        "the robot's position T_pos",
        test=f"{TEST_ROBOT}::test_eq_4_9_erratum_rotor_alone_loses_the_position, "
        f"{TEST_ROBOT}::test_stereo_chain_4_5_to_4_9_equals_homogeneous_matrices, tests/test_kinematics.py::test_geometer_chains_equal_todays_robot_code",
    ),
    Entry(
        label="4.10",
        title="x' = M_eu x ~M_eu (stereo entities to the unified frame)",
        status="numeric",
        implementation=f"{CHAINS}.to_unified, cga_lessons.map3d.robot.Robot.stereo_to_unified, cga_lessons.map3d.fuse.build_fused_map",
        test=f"{TEST_ROBOT}::test_eq_4_10_moves_stereo_entities_like_the_matrix, "
        f"{TEST_MAP3D}::test_noise_free_tour_recovers_the_truth, {TEST_MAP3D}::test_view_entities_are_the_fits_of_the_moved_points",
    ),
]
