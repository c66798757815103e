"""Tests of the self-checking exercises (cga_lessons.exercises and the exercises_* modules).

Right answers are computed here the way a student would, with the library's functions (the checkers use
closed forms and matrices instead); wrong answers are the mistakes each exercise anticipates, and the
messages must name what is off without printing the solution.
"""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from cga_lessons import conformal as cga
from cga_lessons import exercises
from cga_lessons.algebra import Algebra, InvalidInputError, exp
from cga_lessons.exercises.checking import KINDS
from cga_lessons.exploration import path as ep
from cga_lessons.stereo import camera, epipolar

ROOT = Path(__file__).resolve().parents[1]
G3, G4 = Algebra(3), Algebra(4)


# --------------------------------------------------------------------------- right answers, the student's way


def _bivector_square():
    x, y, z = sp.symbols("x y z", real=True)
    B = G3.blade("e12", x) + G3.blade("e23", y) + G3.blade("e31", z)
    return (B * B).scalar()


def _imaginary_sphere():
    c1, c2, c3, rho = sp.symbols("c1 c2 c3 rho", real=True)
    s = cga.up([c1, c2, c3]) + cga.einf * (rho**2 / 2)
    return sp.simplify((s * s).scalar())


def _printed_263():
    x = np.array([1.0, 2.0, 2.0])
    return cga.down(cga.vector(x) + (cga.em - cga.ep) * (x @ x / 2) + (cga.em + cga.ep) * 0.5)


def _motor_about_line():
    T = cga.translator([1.0, 1.0, 0.0])
    return T * cga.rotor([0, 0, 1], math.pi / 2) * ~T


def _weighted_points():
    alpha, beta, d = sp.symbols("alpha beta d", positive=True)
    return sp.simplify(-2 * ((cga.up([0, 0, 0]) * alpha) | (cga.up([d, 0, 0]) * beta)).scalar())


def _plane_null_space():
    x1, x2 = exercises.given("chA.3")
    Z = epipolar.eight_point_matrix(x1, x2)
    s = np.linalg.svd(Z, compute_uv=False)
    return int(np.sum(s < 1e-10 * s[0])) + Z.shape[1] - len(s)


def _tangent_bearings():
    beta, half = math.atan2(6.0, -63.0), math.asin(7.5 / math.hypot(63.0, 6.0))
    return np.array([beta - half, beta + half])


RIGHT = {
    "ch2.1": _bivector_square,
    "ch2.2": lambda: G3.vector([1.0, 2.0, 3.0]).dual(),
    "ch2.3": lambda: exp(G4.blade("e12") + G4.blade("e34")),
    "ch2.4": lambda: float(cga.up([1.0, 2.0, 2.0]) | cga.up([4.0, 6.0, 2.0])),
    "ch2.5": _imaginary_sphere,
    "ch2.6": _printed_263,
    "ch2.7": _motor_about_line,
    "ch2.8": lambda: -2 * sp.Symbol("phi"),
    "ch2.9": lambda: cga.down(
        cga.apply(cga.rotor([0, 0, 1], math.pi / 2) * cga.translator([1, 0, 0]), cga.up([0, 0, 0]))
    ),
    "ch2.10": lambda: cga.rotor_angle_axis(cga.G41.scalar(0.6) + cga.G41.blade("e12", -0.8)),
    "ch2.11": lambda: cga.decompose_motor(exercises.given("ch2.11"))[1],
    "ch2.12": _weighted_points,
    "chA.1": lambda: camera.camera_center(exercises.given("chA.1")),
    "chA.2": lambda: epipolar.epipoles(exercises.given("chA.2"))[1],
    "chA.3": _plane_null_space,
    "expl.1": _tangent_bearings,
    "expl.2": lambda: ep.line_circle_intersections([0, 0], [100, 20], [50, 5], 12),
    "expl.3": lambda: np.array([20.0, 20.0, 5.0]),
}


def test_every_exercise_has_a_right_answer_here():
    # chapters 3-5 have theirs in tests/test_exercises_chapters.py
    ids = [e.id for e in exercises.list_exercises() if e.id.split(".")[0] in ("ch2", "chA", "expl")]
    assert sorted(RIGHT) == sorted(ids)


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_right_answers_are_right(exercise_id):
    result = exercises.evaluate(exercise_id, RIGHT[exercise_id]())
    assert result.verdict == "right" and bool(result), result.message
    assert result.message.startswith(f"{exercise_id}: right.")


# --------------------------------------------------------------------------- equivalent forms and float noise

x, y, z, phi = sp.symbols("x y z phi")  # no assumptions: matched to the exercise's symbols by name
EQUIVALENT = [
    ("ch2.1", "-(x**2 + y**2 + z**2)"),
    ("ch2.1", -x * x - (y + z) ** 2 + 2 * y * z),
    ("ch2.1", cga.G41.scalar(-(x**2) - y**2 - z**2)),  # a scalar multivector
    ("ch2.2", (lambda A: A.vector([1.0, 2.0, 3.0]) * A.pseudoscalar().inv())(Algebra(3))),  # another G(3)
    ("ch2.4", -12.5 + 1e-12),
    ("ch2.4", np.float32(-12.5)),
    ("ch2.4", sp.Rational(-25, 2)),
    ("ch2.6", [1 / 9, 2 / 9, 2 / 9]),
    ("ch2.7", -_motor_about_line()),  # M and -M are the same motion
    ("ch2.8", 2 * sp.pi - 2 * phi),  # modulo a full turn
    ("ch2.8", sp.atan2(-sp.sin(2 * phi), sp.cos(2 * phi))),
    ("ch2.10", (2 * math.pi - 2 * math.acos(0.6), np.array([0.0, 0.0, -1.0]))),  # the same rotation
    ("ch2.10", [2 * math.acos(0.6), [0, 0, 1]]),
    ("chA.1", np.append(camera.camera_center(exercises.given("chA.1")), 1.0) * -3.0),  # homogeneous, any scale
    ("chA.2", -7 * epipolar.epipoles(exercises.given("chA.2"))[1]),
    ("chA.3", 3.0),
    ("expl.1", _tangent_bearings()[::-1] + 2 * math.pi),
    ("expl.2", ep.line_circle_intersections([0, 0], [100, 20], [50, 5], 12)[::-1]),
    ("expl.3", [-91.0, 50.0, 27.0]),
]


@pytest.mark.parametrize("exercise_id, answer", EQUIVALENT)
def test_equivalent_forms_are_right(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "right", result.message


# --------------------------------------------------------------------------- wrong answers say what is off

a, b, d, rho = sp.symbols("alpha beta d rho")
WRONG = [
    ("ch2.1", "x**2 + y**2 + z**2", "sign"),
    ("ch2.1", "-(x**2 + y**2)", "depends on z"),
    ("ch2.1", "-3*(x**2 + y**2 + z**2)", "constant factor"),
    ("ch2.1", "-(x**2 + q**2)", "uses q"),
    ("ch2.2", G3.vector([1.0, 2.0, 3.0]) * G3.pseudoscalar(), "sign"),
    ("ch2.2", G3.vector([1.0, 2.0, 3.0]), "grade"),
    ("ch2.2", G3.vector([1.0, 2.0, 3.0]).dual() * 2.0, "scale"),
    ("ch2.2", G3.blade("e23", -1.0) + G3.blade("e31", -3.0) + G3.blade("e12", -2.0), "coefficients are off"),
    ("ch2.2", cga.vector([1.0, 2.0, 3.0]).dual(), "G(4, 1, 0)"),
    ("ch2.3", (G4.blade("e12") + G4.blade("e34")) * (math.sin(2**0.5) / 2**0.5) + math.cos(2**0.5), "one-plane"),
    ("ch2.4", 12.5, "sign"),
    ("ch2.4", -25.0, "factor 1/2"),
    ("ch2.4", -5.0, "distance"),
    ("ch2.4", -3.1, "too small"),
    ("ch2.4", -1250.0, "far too large"),
    ("ch2.4", np.array([-12.5, 0.0]), "shape"),
    ("ch2.4", float("nan"), "finite"),
    ("ch2.5", rho**2, "real sphere"),
    ("ch2.5", -2 * rho**2, "constant factor"),
    ("ch2.6", [1.0, 2.0, 2.0], "corrected"),
    ("ch2.6", [-1 / 9, -2 / 9, -2 / 9], "sign"),
    ("ch2.6", [2 / 9, 1 / 9, 2 / 9], "wrong order"),
    ("ch2.7", cga.rotor([0, 0, 1], math.pi / 2), "through the origin"),
    ("ch2.7", cga.translator([1, 1, 0]) * cga.rotor([0, 0, 1], -math.pi / 2) * ~cga.translator([1, 1, 0]), "wrong way"),
    ("ch2.7", ~cga.translator([1, 1, 0]) * cga.rotor([0, 0, 1], math.pi / 2) * cga.translator([1, 1, 0]), "-c"),
    ("ch2.7", _motor_about_line() * 3.0, "normalise"),
    ("ch2.7", cga.up([1.0, 1.0, 0.0]), "grade"),
    ("ch2.7", cga.translator([0.0, 0.0, 1.0]), "c should stay"),
    ("ch2.8", 2 * phi, "sign"),
    ("ch2.8", -phi, "half the angle"),
    ("ch2.8", sp.sin(phi), "different function"),
    ("ch2.9", [1.0, 0.0, 0.0], "T R"),
    ("ch2.9", [0.0, -1.0, 0.0], "wrong way"),
    ("ch2.10", (math.degrees(2 * math.acos(0.6)), [0, 0, 1]), "degrees"),
    ("ch2.10", (math.acos(0.6), [0, 0, 1]), "half the angle"),
    ("ch2.10", (2 * math.acos(0.6), [0, 0, -1]), "other way"),
    ("ch2.10", (2 * math.acos(0.6), [0, 0, 2]), "unit vector"),
    ("ch2.10", (2 * math.acos(0.6), [1, 0, 0]), "axis is off by 90 degrees"),
    ("ch2.11", np.array([0.35, -0.65, 0.2]), "factor 2"),
    ("ch2.11", -np.array([0.7, -1.3, 0.4]), "sign"),
    ("ch2.12", d**2, "normalised points"),
    ("ch2.12", -a * b * d**2, "sign"),
    ("ch2.12", a * d**2, "depends on beta"),
    ("chA.1", -np.asarray(exercises.given("chA.1"))[:, :3].T @ np.zeros(3) + [0.0, 0.0, 0.0], "zero vector"),
    ("chA.1", np.array([0.0, 0.0, 0.0, 0.0]) + [1.0, 2.0, 3.0, 0.0], "infinity"),
    ("chA.2", epipolar.epipoles(exercises.given("chA.2"))[0], "first image"),
    ("chA.3", 1, "general position"),
    ("chA.3", 2, "9th"),
    ("chA.3", 6, "rank"),
    ("chA.3", 2.5, "whole number"),
    ("expl.1", np.degrees(_tangent_bearings()), "degrees"),
    ("expl.1", [math.atan2(6, -63)] * 2, "bearing of the centre"),
    ("expl.2", ep.line_circle_intersections([0, 0], [100, 20], [50, 5], 12)[:, ::-1], "swapped"),
    ("expl.2", ep.line_circle_intersections([0, 0], [100, 20], [50, 5], 12)[0], "shape"),
    ("expl.3", [5.0, 5.0, 5.0], "cell's own node"),
    ("expl.3", [15.0, 15.0, 15.0], "equally near"),
    ("expl.3", [500.0, 0.0, 0.0], "outside"),
]


@pytest.mark.parametrize("exercise_id, answer, keyword", WRONG)
def test_wrong_answers_name_what_is_off(exercise_id, answer, keyword):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "wrong" and not result, result.message
    assert keyword in result.message, result.message


TRUTHS = {  # exercise -> text that would give the solution away
    "ch2.4": ["12.5"],
    "ch2.6": ["0.111", "1/9"],
    "ch2.9": ["[0", "(0"],
    "ch2.11": ["0.7", "1.3"],
    "chA.3": ["3"],
    "ch2.1": ["x**2 + y**2"],
    "ch2.12": ["alpha*beta"],
}


def test_messages_never_print_the_solution():
    for exercise_id, answer, _ in WRONG:
        message = exercises.evaluate(exercise_id, answer).message
        for leak in TRUTHS.get(exercise_id, []):
            assert leak not in message.split(":", 1)[1], (exercise_id, message)


# --------------------------------------------------------------------------- placeholders, malformed, unknown


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_placeholder_is_not_answered_yet(exercise_id, capsys):
    result = exercises.check(exercise_id, None)
    out = capsys.readouterr().out
    assert result.verdict == "unanswered" and not result
    assert out == f"{exercise_id}: not answered yet. Replace None with {exercises.get(exercise_id).expects}.\n"


@pytest.mark.parametrize(
    "exercise_id, answer",
    [
        ("ch2.4", "minus twelve"),
        ("ch2.4", {"value": 1}),
        ("ch2.2", [0.0, 1.0, 2.0]),
        ("ch2.1", "x +* y"),
        ("ch2.7", "a motor"),
        ("ch2.10", 1.85),
        ("ch2.4", True),
        ("ch2.1", object()),
    ],
)
def test_malformed_answers_say_what_was_expected(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "malformed" and not result
    assert "expected" in result.message and exercises.get(exercise_id).expects in result.message


def test_unknown_ids_raise_with_suggestions():
    with pytest.raises(
        exercises.UnknownExerciseError, match=r"check: exercise_id: there is no exercise 'ch2\.13'.*Did you mean"
    ) as err:
        exercises.check("ch2.13", 1.0)
    assert isinstance(err.value, ValueError) and isinstance(err.value, InvalidInputError)
    with pytest.raises(exercises.UnknownExerciseError, match="evaluate: exercise_id: the exercise id must be a string"):
        exercises.evaluate(2.4, 1.0)
    with pytest.raises(InvalidInputError, match="given: exercise_id: exercise ch2.4 has no hidden input"):
        exercises.given("ch2.4")
    with pytest.raises(InvalidInputError, match="list_exercises: part: no exercise belongs to 'ch99'"):
        exercises.list_exercises("ch99")


def test_a_wrong_answer_names_the_helper_and_prints_only_the_reason():
    """Wrong is a ValueError of the package naming the helper and its arguments; check() prints the reason alone."""
    with pytest.raises(exercises.Wrong, match="compare_number: value, truth: the sign is wrong") as err:
        exercises.compare_number(-2.0, 2.0)
    assert isinstance(err.value, InvalidInputError) and err.value.reason == "the sign is wrong."
    with pytest.raises(exercises.Malformed, match="compare_vector: value: the answer should be an array"):
        exercises.compare_vector("text", [1.0, 2.0, 3.0])
    with pytest.raises(InvalidInputError, match="compare_number: truth: is NaN or inf"):
        exercises.compare_number(1.0, math.nan)
    with pytest.raises(InvalidInputError, match="compare_vector: rtol: must be >= 0"):
        exercises.compare_vector([1.0], [1.0], rtol=-1.0)
    result = exercises.evaluate("ch2.4", 12.5)
    assert (
        result.message.startswith("ch2.4: not right yet: the sign is wrong.") and "compare_number" not in result.message
    )
    with pytest.raises(exercises.Wrong, match="as_array: answer: .* is complex"):
        exercises.as_array(np.array([1.0 + 1j, 2.0]), (2,))


def test_check_prints_one_line_and_returns_the_verdict(capsys):
    result = exercises.check("ch2.4", -12.5)
    assert capsys.readouterr().out.count("\n") == 1
    assert bool(result) and result.verdict == "right" and str(result) == result.message
    assert repr(result) == "CheckResult('ch2.4': right)"


# --------------------------------------------------------------------------- the registry


def test_list_is_in_natural_order_and_filters_by_part():
    ids = [e.id for e in exercises.list_exercises()]
    assert ids.index("ch2.2") < ids.index("ch2.10") < ids.index("chA.1")
    assert [e.id for e in exercises.list_exercises("ch2")] == [f"ch2.{i}" for i in range(1, 13)]
    assert all(e.kind in KINDS for e in exercises.list_exercises())
    kinds = {e.notebook: set() for e in exercises.list_exercises()}
    for e in exercises.list_exercises():
        kinds[e.notebook].add(e.kind)
    assert all(len(v) >= 2 for v in kinds.values())  # each notebook mixes derive/compute/break


def test_duplicate_ids_and_bad_ids_are_refused():
    with pytest.raises(InvalidInputError, match="registered twice"):
        exercises.exercise("ch2.4", title="t", notebook="n", kind="compute", expects="e")(lambda a: None)
    with pytest.raises(InvalidInputError, match="kind"):
        exercises.Exercise("zz.1", "t", "n", "guess", "e", lambda a: None)
    with pytest.raises(InvalidInputError, match="part and a number"):
        exercises.Exercise("ch 2", "t", "n", "compute", "e", lambda a: None)


def _code_sources(path):
    nb = json.loads(Path(path).read_text())
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]


def test_every_exercise_is_set_in_its_notebook_and_solved_for_the_teacher():
    solutions = "\n".join(_code_sources(ROOT / "notebooks" / "teacher_solutions.ipynb"))
    for e in exercises.list_exercises():
        nb = ROOT / "notebooks" / f"{e.notebook}.ipynb"
        assert nb.is_file(), e.notebook
        cells = [c for c in _code_sources(nb) if f'check("{e.id}"' in c]
        assert len(cells) == 1, (e.id, e.notebook)
        assert re.search(r"^answer = None\b", cells[0], flags=re.M), cells[0]  # the stored placeholder
        assert f'check("{e.id}"' in solutions, e.id


def test_helpers_diagnose_generic_mistakes():
    W = exercises.Wrong
    with pytest.raises(W, match="degrees"):
        exercises.compare_number(math.degrees(0.7), 0.7)
    with pytest.raises(W, match="square root"):
        exercises.compare_number(3.0, 9.0)
    with pytest.raises(W, match="square of"):
        exercises.compare_number(81.0, 9.0)
    exercises.compare_vector([2.0, 4.0, 6.0], [1.0, 2.0, 3.0], up_to_scale=True)
    with pytest.raises(W, match="length is off: twice"):
        exercises.compare_vector([2.0, 4.0, 6.0], [1.0, 2.0, 3.0])
    with pytest.raises(W, match="transpose"):
        exercises.compare_matrix(np.arange(9.0).reshape(3, 3).T, np.arange(9.0).reshape(3, 3))
    exercises.compare_matrix(sp.Matrix([[2, 0], [0, 2]]), np.eye(2), up_to_scale=True)
    M = G3.vector([1.0, 0.0, 0.0]) ^ G3.vector([0.0, 1.0, 1.0])
    exercises.compare_multivector(M * -4.0, M, up_to_scale=True)
    with pytest.raises(W, match="sign is wrong, and it is proportional"):
        exercises.compare_multivector(M * -4.0, M)
    with pytest.raises(W, match="batch"):
        exercises.compare_multivector(cga.up(np.zeros((2, 3))), cga.up([0.0, 0.0, 0.0]))
