"""Tests of the exercises of chapter 6, the future work (cga_lessons.exercises.ch6).

Right answers are computed here the way a student would, with the library (the kinematic chain's product of
motors, its finite-difference Jacobian, the filter's KLD bound); the checkers use closed forms. The truths
are cross-checked against the library and against each other. Wrong answers are the mistakes each exercise
anticipates, and the messages must name what is off without printing the solution.
"""

import math

import numpy as np
import pytest

from cga_lessons import exercises
from cga_lessons import kinematics as kin
from cga_lessons.relocalization.sampling import kld_bound

Q = np.array([math.pi / 3, -math.pi / 2])


def _arm():
    return kin.chain([kin.revolute([0, 0, 1]), kin.revolute([0, 0, 1], point=[0.5, 0, 0])], home=[0.8, 0, 0])


def _tool(q):
    return kin.forward_matrix(_arm(), q)[:3, 3]


def _position_jacobian(q, h=1e-6):
    J = np.zeros((2, 2))
    for i in range(2):
        d = np.zeros(2)
        d[i] = h
        J[:, i] = (_tool(q + d)[:2] - _tool(q - d)[:2]) / (2 * h)
    return J


def _singular_elbow():
    """The elbow angle in (0, 2 pi) where the position Jacobian's determinant changes sign."""
    grid = np.linspace(0.1, 2 * math.pi - 0.1, 200)
    det = np.array([np.linalg.det(_position_jacobian(np.array([0.3, g]))) for g in grid])
    k = int(np.flatnonzero(np.diff(np.sign(det)))[0])
    a, b = grid[k], grid[k + 1]
    for _ in range(60):  # bisection
        m = 0.5 * (a + b)
        if np.sign(np.linalg.det(_position_jacobian(np.array([0.3, m])))) == np.sign(det[k]):
            a = m
        else:
            b = m
    return 0.5 * (a + b)


RIGHT = {
    "ch6.1": lambda: _tool(Q),
    "ch6.2": _singular_elbow,
    "ch6.3": lambda: float(kld_bound(50)),
}


def test_every_chapter_6_exercise_has_a_right_answer_here():
    assert sorted(RIGHT) == sorted(e.id for e in exercises.list_exercises("ch6"))


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_right_answers_are_right(exercise_id):
    result = exercises.evaluate(exercise_id, RIGHT[exercise_id]())
    assert result.verdict == "right" and bool(result), result.message
    assert result.message.startswith(f"{exercise_id}: right.")


def test_the_truths_against_the_library():
    # the product of motors is the closed form of a planar two-link arm
    q1, q2 = Q
    closed = [0.5 * math.cos(q1) + 0.3 * math.cos(q1 + q2), 0.5 * math.sin(q1) + 0.3 * math.sin(q1 + q2), 0.0]
    assert np.allclose(_tool(Q), closed, atol=1e-12)
    # the determinant of the tool position's Jacobian is l1 l2 sin q2; the spatial Jacobian keeps rank 2
    for e in (0.4, 2.0, math.pi):
        assert np.linalg.det(_position_jacobian(np.array([0.3, e]))) == pytest.approx(0.15 * math.sin(e), abs=1e-8)
        assert np.linalg.matrix_rank(kin.spatial_jacobian(_arm(), [0.3, e])) == 2
    assert _singular_elbow() == pytest.approx(math.pi, abs=1e-8)
    # the KLD bound, by the chi-square quantile itself (scipy) against the Wilson-Hilferty form
    from scipy import stats

    exact = stats.chi2.ppf(0.99, 49) / (2 * 0.05)
    assert kld_bound(50) == pytest.approx(exact, rel=2e-3)


EQUIVALENT = [
    ("ch6.1", list(_tool(Q))),
    ("ch6.2", -math.pi),  # the same elbow, turned the other way
    ("ch6.2", 3 * math.pi),
    ("ch6.3", 750),
    ("ch6.3", 749.34),  # before rounding up, to two decimals
]


@pytest.mark.parametrize("exercise_id, answer", EQUIVALENT)
def test_equivalent_forms_are_right(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "right", result.message


WRONG = [
    (
        "ch6.1",
        [0.5 * math.cos(Q[0]) + 0.3 * math.cos(Q[1]), 0.5 * math.sin(Q[0]) + 0.3 * math.sin(Q[1]), 0.0],
        "q1 + q2",
    ),
    ("ch6.1", [0.8, 0.0, 0.0], "home position"),
    ("ch6.1", _tool(-Q), "wrong way"),
    ("ch6.1", _tool(np.degrees(Q)), "degrees"),
    ("ch6.2", 0.0, "stretched"),
    ("ch6.2", 180.0, "degrees"),
    ("ch6.2", math.pi / 2, "largest"),
    ("ch6.2", 1.0, "independent"),
    ("ch6.3", 749, "round up"),
    ("ch6.3", 600.0, "magnitude"),
    ("ch6.1", [0.5, 0.3], "shape"),
    ("ch6.3", [750, 751], "one number"),
]


@pytest.mark.parametrize("exercise_id, answer, keyword", WRONG)
def test_wrong_answers_name_what_is_off(exercise_id, answer, keyword):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "wrong" and not result, result.message
    assert keyword in result.message, result.message


def test_the_motors_in_the_wrong_order_are_named():
    """M2(q2) M1(q1) M0: joint 1 turns the tool first, then joint 2 about its home axis, which has not moved."""
    m1 = kin.chain([kin.revolute([0, 0, 1])], home=[0.8, 0, 0])
    first = kin.forward_matrix(m1, [Q[0]])[:3, 3]
    c, s = math.cos(Q[1]), math.sin(Q[1])
    d = first - np.array([0.5, 0.0, 0.0])
    swapped = np.array([0.5 + c * d[0] - s * d[1], s * d[0] + c * d[1], 0.0])
    result = exercises.evaluate("ch6.1", swapped)
    assert result.verdict == "wrong" and "order" in result.message


def test_messages_never_print_the_solution():
    for exercise_id, answer, _ in WRONG:
        text = exercises.evaluate(exercise_id, answer).message.split(":", 1)[1]
        assert "749" not in text and "750" not in text and "0.509" not in text and "3.14" not in text


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_placeholder_is_not_answered_yet(exercise_id, capsys):
    result = exercises.check(exercise_id, None)
    assert result.verdict == "unanswered"
    assert capsys.readouterr().out.startswith(f"{exercise_id}: not answered yet.")


@pytest.mark.parametrize("exercise_id, answer", [("ch6.1", "the tool"), ("ch6.2", "pi"), ("ch6.3", {"n": 750})])
def test_malformed_answers_say_what_was_expected(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "malformed", result.message
    assert "expected" in result.message
