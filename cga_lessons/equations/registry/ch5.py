"""Chapter 5 registry: relocalization by voting in Hough space (5.1-5.6)."""

from cga_lessons.equations.core import Entry

HOUGH = "cga_lessons.relocalization.hough"
TEST_RELOCALIZATION = "tests/test_relocalization.py"

ENTRIES = [
    Entry(
        label="5.1",
        title="Delta theta_j = diffTheta(m_i theta, l_j theta)",
        status="numeric",
        implementation=f"{HOUGH}.hough_differences",
        test=f"{TEST_RELOCALIZATION}::test_hough_differences_5_1_to_5_3",
        note="uses diffTheta (3.5) in its corrected form",
    ),
    Entry(
        label="5.2",
        title="Delta rho_j = m_i rho - l_j rho",
        status="numeric",
        implementation=f"{HOUGH}.hough_differences",
        test=f"{TEST_RELOCALIZATION}::test_hough_differences_5_1_to_5_3",
        note=(
            "computed as printed; the two rho are measured from different origins (map, laser), "
            "which is why the shift (5.4) fails under a translation"
        ),
    ),
    Entry(
        label="5.3",
        title="phi_{m_i l} = m_i - L_h, the set of differences of one map line",
        status="numeric",
        implementation=f"{HOUGH}.hough_differences",
        test=f"{TEST_RELOCALIZATION}::test_hough_differences_5_1_to_5_3",
    ),
    Entry(
        label="5.4",
        title="psi_{h_i} = L_h + phi_{m_i l}, the local set shifted by each difference",
        status="erratum",
        implementation=f"{HOUGH}.shifted_set, {HOUGH}.shifted_set_corrected",
        printed="psi = L_h + phi: every local line moved by the same (Delta rho_j, Delta theta_j)",
        correct=(
            "under the motion x -> R(Theta) x + t a line (rho, theta) goes to (rho + t . (cos(theta + Theta), "
            "sin(theta + Theta)), theta + Theta): the rho shift depends on each line's direction, so t must come "
            "from two non-parallel correspondences (3.11-3.12); the printed shift holds for a rotation about the "
            "laser only (t = 0, section 5.1)"
        ),
        note="measured: read literally the method locates almost no pose that includes a translation (notebook 09)",
        test=f"{TEST_RELOCALIZATION}::test_shifted_set_as_printed_fails_under_a_translation_erratum_5_4",
    ),
    Entry(
        label="5.5",
        title="xi_{h_i} = M_h - psi_{h_i}, every shifted line against every map line",
        status="numeric",
        implementation=f"{HOUGH}.hough_comparison",
        test=f"{TEST_RELOCALIZATION}::test_shifted_set_and_comparison_5_4_5_5",
    ),
    Entry(
        label="5.6",
        title="vote matrix V (|M| x |L|): +1 where xi is below xi_theta and xi_rho",
        status="numeric",
        implementation=f"{HOUGH}.vote_matrix, {HOUGH}.vote_matrix_indexed",
        test=f"{TEST_RELOCALIZATION}::test_vote_matrix_hand_built_5_6, {TEST_RELOCALIZATION}::test_vote_matrix_indexed_equals_the_literal_loop",
        note=(
            "V[i, j] counts the pairs (k, m) with l_k + (m_i - l_j) within the thresholds of m (the support of "
            "m_i <-> l_j); steps 6-10 in cga_lessons.relocalization.thesis; the angle votes alone propose the "
            "rotations of cga_lessons.relocalization.relocalize"
        ),
    ),
]
