"""Chapter 2 registry: products and involutions (2.11-2.37), circle and line (2.78-2.81),
rigid motions (2.94-2.110) and section 2.4 properties (2.111-2.130).

The derivations (2.1-2.10, 2.38-2.77, 2.82-2.93, 2.131-2.145) are in ``ch2_derivations``.
"""

from cga_lessons.equations import Entry

A = "cga_lessons.algebra"
EN = "cga_lessons.entities"
V = "cga_lessons.versors"
M = "cga_lessons.model"
TA = "tests/test_algebra.py"
TC = "tests/test_conformal.py"


def _e(label, title, status, impl, test, **kw):
    return Entry(label=label, title=title, status=status, implementation=impl, test=test, **kw)


ENTRIES = [
    _e("2.11", "ab = a.b + a^b", "numeric", f"{A}.Multivector.__mul__", f"{TA}::test_inner_outer_of_vectors_eq_2_13_2_14"),
    _e("2.12", "ba = a.b - a^b", "numeric", f"{A}.Multivector.__mul__", f"{TA}::test_inner_outer_of_vectors_eq_2_13_2_14"),
    _e("2.13", "a.b = (ab + ba)/2", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_outer_of_vectors_eq_2_13_2_14"),
    _e("2.14", "a^b = (ab - ba)/2", "numeric", f"{A}.Multivector.__xor__", f"{TA}::test_inner_outer_of_vectors_eq_2_13_2_14"),
    _e("2.15", "G_n as the sum of its grades", "definition", f"{A}.Multivector.grade", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.16", "even part", "numeric", f"{A}.Multivector.even", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.17", "odd part", "numeric", f"{A}.Multivector.odd", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.18", "M = sum of grade parts", "numeric", f"{A}.Multivector.grade", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.19", "inverse of a vector a/a^2", "numeric", f"{A}.Multivector.inv", f"{TA}::test_inverse_of_vector_eq_2_19_and_general"),
    _e("2.20", "outer product with a scalar", "numeric", f"{A}.Multivector.__xor__", f"{TA}::test_outer_with_scalar_eq_2_20"),
    _e("2.21", "inner product of blades (recursive)", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.22", "blade . vector expansion", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.23", "vector . blade expansion", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.24", "a . (b^c) = (a.b)c - (a.c)b", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_vector_bivector_eq_2_24"),
    _e("2.25", "x . B_s expansion", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.26", "(a1^a2) . B = a1 . (a2 . B)", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.27", "nested inner products", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_expansions_eq_2_21_to_2_27"),
    _e("2.28", "scalar . M = 0", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_inner_product_with_scalar_is_zero_eq_2_28"),
    _e("2.29", "A . B = <AB>_|r-s|", "numeric", f"{A}.Multivector.__or__", f"{TA}::test_grade_selection_eq_2_29_2_30"),
    _e("2.30", "A ^ B = <AB>_r+s", "numeric", f"{A}.Multivector.__xor__", f"{TA}::test_grade_selection_eq_2_29_2_30"),
    _e("2.31", "dual M* = M I^-1", "numeric", f"{A}.Multivector.dual", f"{TA}::test_dual_and_pseudoscalar_eq_2_31"),
    _e("2.32", "reverse of a blade", "numeric", f"{A}.Multivector.__invert__", f"{TA}::test_reverse_of_blade_eq_2_32"),
    _e("2.33", "reverse by grade", "numeric", f"{A}.Multivector.__invert__", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.34", "reverse of a product", "numeric", f"{A}.Multivector.__invert__", f"{TA}::test_reverse_of_product_eq_2_34"),
    _e("2.35", "grade involution", "numeric", f"{A}.Multivector.involute", f"{TA}::test_involutions_eq_2_33_2_35"),
    _e("2.36", "commutator product", "numeric", f"{A}.commutator", f"{TA}::test_commutator_eq_2_36"),
    _e("2.37", "exponential (closed form for bivectors)", "numeric", f"{A}.exp", f"{TA}::test_exp_closed_form_matches_series_eq_2_37"),
    _e("2.78", "circle: x on both spheres", "definition", f"{EN}.circle_center_radius", f"{TC}::test_circle_as_sphere_intersection_eq_2_78_2_79"),
    _e("2.79", "circle z = s1 ^ s2, x . z = 0", "numeric", f"{EN}.circle_center_radius", f"{TC}::test_circle_as_sphere_intersection_eq_2_78_2_79"),
    _e("2.80", "circle z* = a ^ b ^ c", "numeric", f"{EN}.circle_from_points", f"{TC}::test_circle_center_radius_eq_2_80_2_119_to_2_124"),
    _e("2.81", "line L* = e ^ a ^ b = e M + r E", "numeric", f"{EN}.line_from_points", f"{TC}::test_line_pluecker_form_eq_2_81_2_107_2_108"),
    _e("2.94", "rotor R = exp(-theta/2 l)", "numeric", f"{V}.rotor", f"{TC}::test_translator_and_rotor_conventions_eq_2_94_2_100"),
    _e("2.95", "rotor cos - sin l", "numeric", f"{V}.rotor", f"{TC}::test_translator_and_rotor_conventions_eq_2_94_2_100"),
    _e("2.96", "rotor components on e23 e31 e12", "numeric", f"{V}.rotor", f"{TC}::test_rotor_reverse_eq_2_97"),
    _e("2.97", "reverse of a rotor", "numeric", f"{V}.rotor", f"{TC}::test_rotor_reverse_eq_2_97"),
    _e("2.98", "rotation x' = R x ~R", "numeric", f"{V}.apply", f"{TC}::test_motor_matches_matrix_eq_2_102_2_103"),
    _e("2.99", "composition of rotors", "erratum", f"{V}.apply", f"{TC}::test_rotor_composition_order_eq_2_99_erratum",
       printed="R = R1 R2;  x' = R x ~R = (R2 R1) x (~R1 ~R2)", correct="R = R2 R1 (R1 applied first)",
       note="The text sets R = R1 R2 and then applies R2 R1; only R2 R1 turns by R1 first (the matrix H2 H1)."),
    _e("2.100", "translator T = 1 + e t/2", "numeric", f"{V}.translator, cga_lessons.kinematics.prismatic",
       f"{TC}::test_translator_and_rotor_conventions_eq_2_94_2_100, tests/test_kinematics.py::test_joint_motors_are_exp_of_the_axis_lines_eq_2_100_2_107_to_2_109"),
    _e("2.101", "translation x' = T x ~T", "numeric", f"{V}.apply", f"{TC}::test_translator_and_rotor_conventions_eq_2_94_2_100"),
    _e("2.102", "motor M = T R", "numeric", f"{V}.motor", f"{TC}::test_motor_matches_matrix_eq_2_102_2_103"),
    _e("2.103", "rigid motion x' = M x ~M", "numeric", f"{V}.apply, cga_lessons.kinematics.spatial_jacobian",
       f"{TC}::test_motor_matches_matrix_eq_2_102_2_103, tests/test_kinematics.py::test_jacobian_columns_are_the_axis_lines_moved_by_the_joints_before"),
    _e("2.104", "general rotation T R ~T", "numeric", f"{V}.rotor_about_line", f"{TC}::test_rotor_about_line_and_screw_eq_2_104_2_110"),
    _e("2.105", "rotation about a line applied to a point", "erratum", f"{V}.rotor_about_line",
       f"{TC}::test_rotation_about_a_line_applied_to_a_point_eq_2_105_erratum",
       printed="x' = T R ~T x ~R ~T", correct="x' = T R ~T x T ~R ~T",
       note="One T is missing (the reverse of T R ~T is T ~R ~T); the sentence after it also writes T R ~T = ~R_L "
            "where (2.104) has R_L."),
    _e("2.106", "R_L = exp(-theta/2 (l + e (t.l)))", "numeric", f"{V}.rotor_about_line", f"{TC}::test_rotor_about_line_and_screw_eq_2_104_2_110"),
    _e("2.107", "line L* = e (t ^ r) + r E", "numeric", f"{EN}.normalize_line, cga_lessons.kinematics.revolute",
       f"{TC}::test_line_pluecker_form_eq_2_81_2_107_2_108, tests/test_kinematics.py::test_joint_motors_are_exp_of_the_axis_lines_eq_2_100_2_107_to_2_109"),
    _e("2.108", "standard line L = e (t . l) + l", "numeric", f"{EN}.standard_form", f"{TC}::test_line_pluecker_form_eq_2_81_2_107_2_108"),
    _e("2.109", "R_L = exp(-theta/2 L)", "numeric", f"{V}.rotor_about_line, cga_lessons.kinematics.forward_motor",
       f"{TC}::test_rotor_about_line_and_screw_eq_2_104_2_110, tests/test_kinematics.py::test_joint_motors_are_exp_of_the_axis_lines_eq_2_100_2_107_to_2_109"),
    _e("2.110", "screw motion exp(-theta/2 (l + e m))", "numeric", f"{V}.screw, cga_lessons.kinematics_ik.twist_error",
       f"{TC}::test_rotor_about_line_and_screw_eq_2_104_2_110, tests/test_kinematics.py::test_twist_error_is_the_logarithm_of_motor_log_eq_2_110"),
    _e("2.111", "point normalisation x / (-e . x)", "numeric", f"{M}.normalize_point", f"{TC}::test_up_is_null_and_normalised_eq_2_61_2_62"),
    _e("2.112", "projective point e ^ x", "numeric", f"{M}.normalize_point", f"{TC}::test_affine_representation_eq_2_112_2_113"),
    _e("2.113", "affine point (e ^ x) E = 1 + e x", "numeric", f"{M}.normalize_point", f"{TC}::test_affine_representation_eq_2_112_2_113"),
    _e("2.114", "Euclidean point by rejection from E", "numeric", f"{M}.down", f"{TC}::test_up_down_batch_and_symbolic"),
    _e("2.115", "sphere normalisation", "numeric", f"{EN}.sphere_center_radius", f"{TC}::test_sphere_forms_agree_eq_2_72_2_75"),
    _e("2.116", "sphere centre (s ^ E) E", "numeric", f"{EN}.sphere_center_radius", f"{TC}::test_sphere_forms_agree_eq_2_72_2_75"),
    _e("2.117", "centre point p = s + s^2 e/2", "numeric", f"{EN}.sphere_center_radius", f"{TC}::test_sphere_centre_point_eq_2_117"),
    _e("2.118", "inside / on / outside a sphere", "numeric", f"{EN}.point_sphere_side", f"{TC}::test_sphere_batch_and_side_eq_2_118"),
    _e("2.119", "plane of a circle z* ^ e", "numeric", f"{EN}.circle_plane", f"{TC}::test_circle_center_radius_eq_2_80_2_119_to_2_124"),
    _e("2.120", "axis of a circle z ^ e", "numeric", f"{EN}.circle_center_radius", f"{TC}::test_circle_axis_and_sphere_eq_2_120_2_124"),
    _e("2.121", "axis . plane = e ^ s_e0", "erratum", f"{EN}.circle_plane", f"{TC}::test_circle_centre_sphere_eq_2_121",
       printed="L_z* . P_z* = e ^ s_e0", correct="L_z* . P_z = e ^ s_e0 (P_z = P_z* Ic, the plane in standard form)",
       note="With the dual plane of (2.119) the contraction is zero; with the standard-form plane it is e ^ s for the "
            "sphere centred on the circle's centre through the origin. Found while building the stereo chapter."),
    _e("2.122", "circle radius", "erratum", f"{EN}.circle_center_radius", f"{TC}::test_circle_center_radius_eq_2_80_2_119_to_2_124",
       printed="rho_z = z^2 / (e ^ z)^2", correct="rho_z^2 = -z^2 / (e ^ z)^2",
       note="The printed quotient is minus the squared radius (z standard or dual form alike)."),
    _e("2.123", "sphere of a circle s_z = (e . z) z", "numeric", f"{EN}.circle_center_radius", f"{TC}::test_circle_center_radius_eq_2_80_2_119_to_2_124"),
    _e("2.124", "sphere of a circle by division s_z* = z / P_z*", "numeric", f"{EN}.circle_plane",
       f"{TC}::test_sphere_of_a_circle_by_division_eq_2_124_holds_up_to_scale",
       note="Holds up to scale: z / P_z* (z standard, P_z* dual) is pure grade 4, the dual of the sphere (2.123), with "
            "opposite signs for right and left division. Also z* / P_z* has s_z as its vector part."),
    _e("2.125", "L*^2 = (a - b)^2", "numeric", f"{EN}.normalize_line", f"{TC}::test_line_properties_eq_2_125_to_2_130"),
    _e("2.126", "line normalisation", "numeric", f"{EN}.normalize_line", f"{TC}::test_line_properties_eq_2_125_to_2_130"),
    _e("2.127", "line direction r = L* . E", "numeric", f"{EN}.line_direction", f"{TC}::test_line_properties_eq_2_125_to_2_130"),
    _e("2.128", "line moment", "erratum", f"{EN}.line_moment", f"{TC}::test_line_properties_eq_2_125_to_2_130",
       printed="m = e+ L", correct="m = -e+ . L = e+ . (L* Ic^-1)",
       note="With L = L* Ic (the inverse of 2.31) the printed geometric product has other grades and its vector "
            "part is -(a x r); the Pluecker moment a x r, which makes (2.129) hold, is -e+ . L."),
    _e("2.129", "closest point p = -r . M", "numeric", f"{EN}.line_closest_point", f"{TC}::test_line_properties_eq_2_125_to_2_130"),
    _e("2.130", "point-line distance", "numeric", f"{EN}.point_line_distance", f"{TC}::test_line_properties_eq_2_125_to_2_130"),
]
