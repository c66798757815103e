"""Appendix A: the pinhole camera, two-view geometry and triangulation (A.1-A.14)."""

from cga_lessons.equations.core import Entry

TEST_CAMERA = "tests/test_camera.py::"

ENTRIES = [
    Entry(
        label="A.1",
        title="pinhole projection matrix P = K R [I | -C]",
        status="numeric",
        implementation="cga_lessons.stereo.camera.projection_matrix",
        test=TEST_CAMERA
        + "test_projection_matrix_A1_equals_A3_and_pinhole_formula, "
        + TEST_CAMERA
        + "test_project_A5_matches_opencv",
    ),
    Entry(
        label="A.2",
        title="calibration matrix K (focal lengths, skew, principal point)",
        status="numeric",
        implementation="cga_lessons.stereo.camera.calibration_matrix",
        test=TEST_CAMERA
        + "test_calibration_matrix_A2, "
        + TEST_CAMERA
        + "test_decompose_projection_inverts_A1_like_opencv",
    ),
    Entry(
        label="A.3",
        title="P = K [R | t] with t = -R C",
        status="numeric",
        implementation="cga_lessons.stereo.camera.projection_matrix_rt",
        test=TEST_CAMERA + "test_projection_matrix_A1_equals_A3_and_pinhole_formula",
    ),
    Entry(
        label="A.4",
        title="homogeneous 3D point [X, Y, Z, W]",
        status="definition",
        implementation="cga_lessons.stereo.camera.to_homogeneous, cga_lessons.stereo.camera.from_homogeneous",
        test=TEST_CAMERA + "test_homogeneous_A4_roundtrip_and_point_at_infinity",
    ),
    Entry(
        label="A.5",
        title="projection lambda x = P X; the rows of P are the optical planes",
        status="numeric",
        implementation="cga_lessons.stereo.camera.project, cga_lessons.stereo.camera.optical_planes",
        test=TEST_CAMERA
        + "test_project_A5_matches_opencv, "
        + TEST_CAMERA
        + "test_camera_center_and_optical_planes_fig_A2",
    ),
    Entry(
        label="A.6",
        title="epipolar constraint x'^T F x = 0",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.fundamental_8point, cga_lessons.stereo.epipolar.epipolar_distance",
        test=TEST_CAMERA + "test_fundamental_8point_noise_free_reproduces_truth",
    ),
    Entry(
        label="A.7",
        title="epipolar constraint written out in the entries of F",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.eight_point_matrix",
        test=TEST_CAMERA + "test_eight_point_matrix_A7_A9_is_the_bilinear_form",
    ),
    Entry(
        label="A.8",
        title="one row [x'x, x'y, x', y'x, y'y, y', x, y, 1] f = 0",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.eight_point_matrix",
        test=TEST_CAMERA + "test_eight_point_matrix_A7_A9_is_the_bilinear_form",
    ),
    Entry(
        label="A.9",
        title="8-point system Z f = 0, f the null vector of Z",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.fundamental_8point",
        test=TEST_CAMERA
        + "test_fundamental_8point_noise_free_reproduces_truth, "
        + TEST_CAMERA
        + "test_fundamental_8point_is_opencvs_estimator_with_noise, "
        + TEST_CAMERA
        + "test_fundamental_degenerate_input",
        note="The thesis takes the null vector of Z in pixel coordinates and states that F has rank 2 without "
        "enforcing it; the implementation adds Hartley's normalisation and the rank-2 projection (both optional, "
        "compared in notebook 07).",
    ),  # fmt: skip
    Entry(
        label="A.10",
        title="first camera from F: P = [I | 0]",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.cameras_from_fundamental",
        test=TEST_CAMERA + "test_cameras_from_fundamental_A10_A13",
    ),
    Entry(
        label="A.11",
        title="second camera from F: P' = [[e']x F | e'], F^T e' = 0",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.cameras_from_fundamental, cga_lessons.stereo.epipolar.epipoles",
        test=TEST_CAMERA
        + "test_cameras_from_fundamental_A10_A13, "
        + TEST_CAMERA
        + "test_rank2_step_and_epipoles_are_the_other_centre",
    ),
    Entry(
        label="A.12",
        title="cross-product matrix [e']x",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.skew",
        test=TEST_CAMERA + "test_skew_A12_is_the_cross_product",
    ),
    Entry(
        label="A.13",
        title="general second camera P' = [[e']x F + e' v^T | lambda e']",
        status="numeric",
        implementation="cga_lessons.stereo.epipolar.cameras_from_fundamental",
        test=TEST_CAMERA + "test_cameras_from_fundamental_A10_A13",
    ),
    Entry(
        label="A.14",
        title="back-projected ray X(lambda) = P+ x + lambda C; midpoint triangulation (fig. A.4)",
        status="numeric",
        implementation="cga_lessons.stereo.camera.back_project, cga_lessons.stereo.camera.pseudo_inverse, "
        "cga_lessons.stereo.triangulation.triangulate",
        test=TEST_CAMERA
        + "test_back_projected_rays_A14_pass_through_the_points, "
        + TEST_CAMERA
        + "test_midpoint_is_the_middle_of_the_common_perpendicular_fig_A4, "
        + TEST_CAMERA
        + "test_triangulate_noise_free_reproduces_truth, "
        + TEST_CAMERA
        + "test_pseudo_inverse_footnote_A14",
    ),  # fmt: skip
]
