"""Chapter 2 registry: products and involutions (2.11-2.37).

Circle and line (2.78-2.81), rigid motions (2.94-2.110) and the section 2.4 properties (2.111-2.130) are in
``ch2_circles_and_motions``; the derivations (2.1-2.10, 2.38-2.77, 2.82-2.93, 2.131-2.145) in ``ch2_derivations`` and
``ch2_derivations_entities``.
"""

from cga_lessons.equations.core import Entry

ALGEBRA = "cga_lessons.algebra"
TEST_ALGEBRA = "tests/test_algebra.py"


def equation(label, title, status, impl, test, **kw):
    """One :class:`Entry` from its fields in order (label, title, status, implementation, test)."""
    return Entry(label=label, title=title, status=status, implementation=impl, test=test, **kw)


ENTRIES = [
    equation(
        "2.11",
        "ab = a.b + a^b",
        "numeric",
        f"{ALGEBRA}.Multivector.__mul__",
        f"{TEST_ALGEBRA}::test_inner_outer_of_vectors_eq_2_13_2_14",
    ),
    equation(
        "2.12",
        "ba = a.b - a^b",
        "numeric",
        f"{ALGEBRA}.Multivector.__mul__",
        f"{TEST_ALGEBRA}::test_inner_outer_of_vectors_eq_2_13_2_14",
    ),
    equation(
        "2.13",
        "a.b = (ab + ba)/2",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_outer_of_vectors_eq_2_13_2_14",
    ),
    equation(
        "2.14",
        "a^b = (ab - ba)/2",
        "numeric",
        f"{ALGEBRA}.Multivector.__xor__",
        f"{TEST_ALGEBRA}::test_inner_outer_of_vectors_eq_2_13_2_14",
    ),
    equation(
        "2.15",
        "G_n as the sum of its grades",
        "definition",
        f"{ALGEBRA}.Multivector.grade",
        f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35",
    ),
    equation(
        "2.16", "even part", "numeric", f"{ALGEBRA}.Multivector.even", f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35"
    ),
    equation(
        "2.17", "odd part", "numeric", f"{ALGEBRA}.Multivector.odd", f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35"
    ),
    equation(
        "2.18",
        "M = sum of grade parts",
        "numeric",
        f"{ALGEBRA}.Multivector.grade",
        f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35",
    ),
    equation(
        "2.19",
        "inverse of a vector a/a^2",
        "numeric",
        f"{ALGEBRA}.Multivector.inv",
        f"{TEST_ALGEBRA}::test_inverse_of_vector_eq_2_19_and_general",
    ),
    equation(
        "2.20",
        "outer product with a scalar",
        "numeric",
        f"{ALGEBRA}.Multivector.__xor__",
        f"{TEST_ALGEBRA}::test_outer_with_scalar_eq_2_20",
    ),
    equation(
        "2.21",
        "inner product of blades (recursive)",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.22",
        "blade . vector expansion",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.23",
        "vector . blade expansion",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.24",
        "a . (b^c) = (a.b)c - (a.c)b",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_vector_bivector_eq_2_24",
    ),
    equation(
        "2.25",
        "x . B_s expansion",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.26",
        "(a1^a2) . B = a1 . (a2 . B)",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.27",
        "nested inner products",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_expansions_eq_2_21_to_2_27",
    ),
    equation(
        "2.28",
        "scalar . M = 0",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_inner_product_with_scalar_is_zero_eq_2_28",
    ),
    equation(
        "2.29",
        "A . B = <AB>_|r-s|",
        "numeric",
        f"{ALGEBRA}.Multivector.__or__",
        f"{TEST_ALGEBRA}::test_grade_selection_eq_2_29_2_30",
    ),
    equation(
        "2.30",
        "A ^ B = <AB>_r+s",
        "numeric",
        f"{ALGEBRA}.Multivector.__xor__",
        f"{TEST_ALGEBRA}::test_grade_selection_eq_2_29_2_30",
    ),
    equation(
        "2.31",
        "dual M* = M I^-1",
        "numeric",
        f"{ALGEBRA}.Multivector.dual",
        f"{TEST_ALGEBRA}::test_dual_and_pseudoscalar_eq_2_31",
    ),
    equation(
        "2.32",
        "reverse of a blade",
        "numeric",
        f"{ALGEBRA}.Multivector.__invert__",
        f"{TEST_ALGEBRA}::test_reverse_of_blade_eq_2_32",
    ),
    equation(
        "2.33",
        "reverse by grade",
        "numeric",
        f"{ALGEBRA}.Multivector.__invert__",
        f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35",
    ),
    equation(
        "2.34",
        "reverse of a product",
        "numeric",
        f"{ALGEBRA}.Multivector.__invert__",
        f"{TEST_ALGEBRA}::test_reverse_of_product_eq_2_34",
    ),
    equation(
        "2.35",
        "grade involution",
        "numeric",
        f"{ALGEBRA}.Multivector.involute",
        f"{TEST_ALGEBRA}::test_involutions_eq_2_33_2_35",
    ),
    equation(
        "2.36", "commutator product", "numeric", f"{ALGEBRA}.commutator", f"{TEST_ALGEBRA}::test_commutator_eq_2_36"
    ),
    equation(
        "2.37",
        "exponential (closed form for bivectors)",
        "numeric",
        f"{ALGEBRA}.exp",
        f"{TEST_ALGEBRA}::test_exp_closed_form_matches_series_eq_2_37",
    ),
]
