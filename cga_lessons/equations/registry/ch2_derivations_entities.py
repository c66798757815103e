"""Registry entries of chapter 2 proved by the symbolic derivations (:mod:`cga_lessons.symbolic`), second part.

Labels 2.82-2.93 (conformal transformations: reflections and inversions in planes and spheres) and 2.131-2.145
(the points of a point pair, rotors and motors taken apart); 2.1-2.10 and 2.38-2.77 are in ``ch2_derivations``.  "symbolic": the named test proves the identity with SymPy; "definition": a
definition or notation, exercised by the named test; "erratum": the printed form is wrong, and the test shows it
fails while the correct form holds (see ``cga_lessons.symbolic.ERRATA``).
"""

from cga_lessons.equations.core import Entry

ENTRIES = [
    Entry(
        label="2.82",
        title="conformal transformation G x G^^-1 keeps the null cone",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.apply, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.83",
        title="even versor with V ~V = |V|^2 (rotor)",
        status="definition",
        implementation="cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.84",
        title="reflection -s x s^-1 = x - 2 (s . x) s^-1",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.invert_in_sphere, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.85",
        title="inversion in the unit sphere: sigma = x^2, image x^-1",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.invert_in_sphere, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.86",
        title="s . x = -((x - p)^2 - rho^2)/2",
        status="symbolic",
        implementation="cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.87",
        title="inversion in a sphere: sigma x' = ((x - p)/rho)^2 up(g(x))",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.invert_in_sphere, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.88",
        title="g(x) = rho^2 / (x - p) + p",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.invert_in_sphere, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.89",
        title="plane P = n + delta e",
        status="definition",
        implementation="cga_lessons.conformal.entities.plane, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.90",
        title="reflection g(x) = n x n^ + 2 delta n",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.reflect_in_plane, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
        note="the text's 's . x = n . x' holds only for delta = 0 (s . x = n . x - delta); table 2.2 prints 2 x delta for 2 delta n",
    ),
    Entry(
        label="2.91",
        title="plane through c: n + (n . c) e",
        status="symbolic",
        implementation="cga_lessons.conformal.versors.reflect_in_plane, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.92",
        title="translator as two reflections",
        status="erratum",
        implementation="cga_lessons.conformal.versors_build.translator, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations, tests/test_symbolic.py::test_errata",
        printed="T = (n + delta e)(n + 0 e) = 1 + t e / 2",
        correct="T = (n + delta e) n = 1 + e t / 2 (= 1 - t e / 2), t = 2 delta n",
        note="1 + e t/2 moves by +t (2.100); the printed 1 + t e/2 moves by -t, as table 2.2 pairs it with x - t",
    ),
    Entry(
        label="2.93",
        title="rotation about c as two reflections",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_build.translator, cga_lessons.symbolic.conformal_transformations",
        test="tests/test_symbolic.py::test_conformal_transformations",
    ),
    Entry(
        label="2.131",
        title="points of a point pair (B +- sqrt(B B)) / (B . e)",
        status="erratum",
        implementation="cga_lessons.conformal.entities.point_pair_endpoints, cga_lessons.symbolic.point_pair_extraction",
        test="tests/test_conformal.py::test_point_pair_endpoints_order_eq_2_131_erratum, "
        "tests/test_symbolic.py::test_point_pair_extraction",
        printed="p_1,2 = (PP* +- sqrt(PP* PP*)) / (PP* . e)",
        correct="p_1,2 = (PP* -+ sqrt(PP* PP*)) (PP* . e)^-1",
        note="Division is right multiplication by (PP* . e)^-1; p1 = a of PP* = a ^ b comes from the numerator "
        "PP* - sqrt(PP* PP*) of (2.132), as the text says, so the printed +- gives b first (left division swaps "
        "them back). The text after (2.133) calls PP* . e the plane 'tangent' to the line: it is the plane through "
        "the midpoint perpendicular to the line.",
    ),
    Entry(
        label="2.132",
        title="B - sqrt(B B) = p1 p2",
        status="symbolic",
        implementation="cga_lessons.symbolic.point_pair_extraction",
        test="tests/test_symbolic.py::test_point_pair_extraction",
    ),
    Entry(
        label="2.133",
        title="B + sqrt(B B) = -p2 p1",
        status="symbolic",
        implementation="cga_lessons.symbolic.point_pair_extraction",
        test="tests/test_symbolic.py::test_point_pair_extraction",
    ),
    Entry(
        label="2.134",
        title="sphere through a point pair PP* / (PP* ^ e)",
        status="symbolic",
        implementation="cga_lessons.conformal.entities.point_pair_sphere, cga_lessons.symbolic.point_pair_extraction",
        test="tests/test_symbolic.py::test_point_pair_extraction",
        note="equal to the midpoint sphere up to scale (the factor is -1 for normalised points)",
    ),
    Entry(
        label="2.135",
        title="cos(theta/2) = (R + ~R)/2",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.rotor_angle_axis, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.136",
        title="theta = 2 acos(c)",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.rotor_angle_axis, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
        note="theta up to sign, as the text says (sin(theta'/2)^2 = sin(theta/2)^2)",
    ),
    Entry(
        label="2.137",
        title="axis L = R - c = (R - ~R)/2",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.rotor_angle_axis, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
        note="L* . E = -sin(theta/2) n: the unit axis is -sign(sin(theta/2)) n, paired with the angle's sign",
    ),
    Entry(
        label="2.138",
        title="rotor at the origin R = (R_L ^ E) E",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.rotor_angle_axis, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.139",
        title="R_L ~R_L = 1",
        status="erratum",
        implementation="cga_lessons.conformal.versors_build.rotor_about_line, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_conformal.py::test_unit_norm_of_a_general_rotation_eq_2_139_erratum, "
        "tests/test_symbolic.py::test_rotors_and_motors",
        printed="R_L ~R_L = T R ~T ~T ~R  (first line)",
        correct="R_L ~R_L = T R ~T T ~R ~T = 1",
        note="The reverse of T R ~T is T ~R ~T; the printed first line is not 1 for a translation t != 0. The "
        "following lines and the result, 1, are right.",
    ),
    Entry(
        label="2.140",
        title="M = T R = R + e t R / 2",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_build.motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.141",
        title="R = (M ^ E) E",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.decompose_motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.142",
        title="R' = (e- . M) I_E, v1 . v2 = 0",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.decompose_motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.143",
        title="M = R + e R' I_E",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.decompose_motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.144",
        title="t = 2 R' I_E ~R",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_rigid.decompose_motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
    Entry(
        label="2.145",
        title="M ~M = 1",
        status="symbolic",
        implementation="cga_lessons.conformal.versors_build.motor, cga_lessons.symbolic.rotors_and_motors",
        test="tests/test_symbolic.py::test_rotors_and_motors",
    ),
]
