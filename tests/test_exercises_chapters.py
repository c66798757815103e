"""Tests of the exercises of chapters 3-5 (cga_lessons.exercises.ch3, _ch4, _ch5).

Right answers are computed here the way a student would, with the library's functions (the map builder's
corrections, point pairs, the motor chains, the Hough steps of chapter 5); the checkers use closed forms and
plain matrices. The truths themselves are cross-checked against the simulator and the library (the symmetric
room's two scans are equal; the printed (4.3) misses by the closed form). Wrong answers are the mistakes each
exercise anticipates, and the messages must name what is off without printing the solution.
"""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from cga_lessons import conformal as cga
from cga_lessons import exercises, mapping2d
from cga_lessons import map3d as rb
from cga_lessons.map3d.tour import homogeneous_chains
from cga_lessons.mapping2d import laser, lines
from cga_lessons.relocalization import hough as hough
from cga_lessons.relocalization import thesis as thesis

ROOT = Path(__file__).resolve().parents[1]
PARTS = ("ch3", "ch4", "ch5")

# --------------------------------------------------------------------------- right answers, the student's way


def _rho_from_origin_change():
    delta, theta, px, py, s = sp.symbols("delta theta px py s", real=True)
    n = sp.Matrix([sp.cos(theta), sp.sin(theta)])
    q = 2 * n + s * sp.Matrix([-sp.sin(theta), sp.cos(theta)])  # a point of the line, 2 m along n
    p = sp.Matrix([px, py])
    R = sp.Matrix([[sp.cos(delta), -sp.sin(delta)], [sp.sin(delta), sp.cos(delta)]])
    q_turned = p + R * (q - p)  # the scan turned by delta about the robot
    return sp.simplify((R * n).dot(q_turned) - n.dot(q))


def _corridor_left_over():
    rho_g, rho_l, theta_l = exercises.given("ch3.3")
    error = np.array([0.30, -0.10])  # stated in the exercise
    return error - mapping2d.translation_correction(rho_g, rho_l, theta_l)


def _closest_point():
    seg = mapping2d.Segment([2.0, 1.0], [0.0, 3.0])
    return mapping2d.point_pair_structure(mapping2d.segment_point_pair(seg)).closest_point


def _sphere_wedge_square():
    d, r1, r2 = sp.symbols("d r1 r2", positive=True)
    s1, s2 = cga.sphere([0, 0, 0], r1), cga.sphere([d, 0, 0], r2)
    return sp.simplify(((s1 ^ s2) * (s1 ^ s2)).scalar())


def _camera_matrix():
    return cga.motor_to_matrix(rb.chain_motors(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2).M_eu)


def _printed_4_3_distance():
    x, y, phi = sp.symbols("x y phi", real=True)
    t = sp.Matrix([x, y])
    R_phi = sp.Matrix([[sp.cos(phi), -sp.sin(phi)], [sp.sin(phi), sp.cos(phi)]])
    return sp.sqrt(((R_phi - sp.eye(2)) * t).dot((R_phi - sp.eye(2)) * t))


def _swapped_view():
    R = cga.rotor([0, 0, 1], 0.3) * cga.rotor([0, 1, 0], 0.5) * cga.rotor([0, 0, 1], 1.2)
    return cga.euclidean(R * cga.e1 * ~R)


def _translation_from_pairs():
    rotation, scan, mapped = exercises.given("ch5.2")
    turned = np.column_stack([scan[:, 0], scan[:, 1] + rotation])
    return thesis.translation_from_lines(mapped, turned, np.array([0, 1]))


def _printed_shift_error():
    _, scan, mapped = exercises.given("ch5.2")
    psi = hough.shifted_set(scan, hough.hough_differences(mapped[0], scan[:1]))  # (5.4) as printed
    return float(psi[0, 1, 0] - mapped[1, 0])


RIGHT = {
    "ch3.1": lambda: lines.diff_theta(0.02, 6.25),
    "ch3.2": _rho_from_origin_change,
    "ch3.3": _corridor_left_over,
    "ch3.4": _closest_point,
    "ch3.5": _sphere_wedge_square,
    "ch3.6": lambda: np.array([[3.0, 1.0], [4.0, 1.0]]),
    "ch4.1": _camera_matrix,
    "ch4.2": _printed_4_3_distance,
    "ch4.3": _swapped_view,
    "ch5.1": lambda: np.array([5.0, 1.5, -0.7 + math.pi]),
    "ch5.2": _translation_from_pairs,
    "ch5.3": _printed_shift_error,
}


def _mine():
    return [e for e in exercises.list_exercises() if e.id.split(".")[0] in PARTS]


def test_every_chapter_exercise_has_a_right_answer_here():
    assert sorted(RIGHT) == sorted(e.id for e in _mine())


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_right_answers_are_right(exercise_id):
    result = exercises.evaluate(exercise_id, RIGHT[exercise_id]())
    assert result.verdict == "right" and bool(result), result.message
    assert result.message.startswith(f"{exercise_id}: right.")


# --------------------------------------------------------------------------- the truths against the library


def test_symmetric_room_scans_are_identical_from_the_two_poses():
    room = laser.load_scene("room")
    a = laser.simulate_scan(room, np.array([1.0, 2.5, -0.7]), None, range_noise=0.0)
    b = laser.simulate_scan(room, RIGHT["ch5.1"](), None, range_noise=0.0)
    assert np.array_equal(np.isfinite(a[0]), np.isfinite(b[0]))
    assert np.allclose(a[0][np.isfinite(a[0])], b[0][np.isfinite(b[0])], atol=1e-9)
    mirror = laser.simulate_scan(room, np.array([5.0, 2.5, math.pi + 0.7]), None, range_noise=0.0)
    assert np.allclose(mirror[0][::-1], a[0], atol=1e-9)  # the mirror pose sees the scan reversed
    assert not np.allclose(mirror[0], a[0], atol=1e-3)


def test_printed_laser_chain_misses_by_the_closed_form():
    rng = np.random.default_rng(4)
    for _ in range(5):
        x, y, theta = rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-np.pi, np.pi)
        phi = rng.uniform(0.1, 3.0)
        g = rb.RobotGeometry(laser_mount=(0.3, 0.1, 0.35, phi))
        m = rb.chain_motors(g, x=x, y=y, theta=theta)
        printed = cga.motor_to_matrix(rb.laser_chain_as_printed(m.M_cl, m.M_pos))[:3, 3]
        correct = homogeneous_chains(g, x=x, y=y, theta=theta).laser[:3, 3]
        expected = 2 * math.hypot(x, y) * math.sin(phi / 2)
        assert np.linalg.norm(printed - correct) == pytest.approx(expected, rel=1e-9)
        got = exercises.evaluate(
            "ch4.2", 2 * sp.sqrt(sp.Symbol("x") ** 2 + sp.Symbol("y") ** 2) * sp.sin(sp.Symbol("phi") / 2)
        )
        assert got.verdict == "right"


def test_camera_truth_is_the_library_homogeneous_chain():
    H = homogeneous_chains(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2).camera_left
    assert exercises.evaluate("ch4.1", H).verdict == "right"


def test_corridor_lines_leave_the_along_wall_direction_open():
    rho_g, rho_l, theta_l = exercises.given("ch3.3")
    n = np.column_stack([np.cos(theta_l), np.sin(theta_l)])
    assert np.linalg.matrix_rank(n.T @ n, tol=1e-9) == 1
    left = _corridor_left_over()
    assert abs(left @ n[0]) < 1e-12 and np.linalg.norm(left) > 0.1  # only the along-wall part is left


def test_hough_match_sphere_reject_example_is_case_5_of_the_library():
    g, local = ([0.0, 1.0], [2.0, 1.0]), RIGHT["ch3.6"]()
    assert mapping2d.sphere_case(*map(np.array, g), *local) == 5
    s_g, s_l = mapping2d.Segment(*g), mapping2d.Segment(*local)
    assert math.hypot(lines.diff_theta(s_g.theta, s_l.theta), s_g.rho - s_l.rho) < 1e-12


def test_map_lines_of_ch5_are_the_scan_lines_moved_by_the_pose():
    rotation, scan, mapped = exercises.given("ch5.2")
    t = RIGHT["ch5.2"]()
    assert np.allclose(hough.shifted_set_corrected(scan, rotation, t), mapped, atol=1e-12)


# --------------------------------------------------------------------------- equivalent forms

delta, theta, px, py = sp.symbols("delta theta px py")
EQUIVALENT = [
    ("ch3.1", 0.02 - 6.25 + 2 * math.pi),
    ("ch3.1", np.float32(0.02 - 6.25 + 2 * math.pi).astype(np.float64)),
    ("ch3.2", (sp.cos(theta + delta) - sp.cos(theta)) * px + (sp.sin(theta + delta) - sp.sin(theta)) * py),
    ("ch3.2", "-2*sin(delta/2)*(px*sin(theta + delta/2) - py*cos(theta + delta/2))"),
    ("ch3.4", [1.5, 1.5, 0.0]),
    ("ch3.5", "((r1 - r2)**2 - d**2)*((r1 + r2)**2 - d**2)/4"),
    ("ch3.6", [[10.0, 1.0], [9.0, 1.0]]),  # the other way round, far off: the same line
    ("ch3.6", [[-3.0, 1.02], [-1.5, 1.02]]),
    ("ch4.3", _swapped_view().tolist()),
    ("ch5.1", [5.0, 1.5, -0.7 - math.pi]),
    ("ch5.1", [5.0, 1.5, 2.44]),  # rounded to two decimals: right, and said to be rounded
]


@pytest.mark.parametrize("exercise_id, answer", EQUIVALENT)
def test_equivalent_forms_are_right(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "right", result.message


def test_a_rounded_answer_is_right_and_told_the_exact_value():
    message = exercises.evaluate("ch5.1", [5.0, 1.5, 2.44]).message
    assert "To the rounding you gave: exactly (5, 1.5, 2.441593)" in message
    assert "rounding" not in exercises.evaluate("ch5.1", [5.0, 1.5, -0.7 + math.pi]).message


# --------------------------------------------------------------------------- wrong answers say what is off


def _wrong_camera(**change):
    state = dict(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2)
    state.update(change)
    return cga.motor_to_matrix(rb.chain_motors(**state).M_eu)


def _printed_camera():
    m = rb.chain_motors(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2)
    return cga.motor_to_matrix(rb.stereo_chain_as_printed(m.T_opt, m.T_ep, m.R_pt))


def _right_order_view():
    R = cga.rotor([0, 0, 1], 0.3) * cga.rotor([0, 0, 1], 1.2) * cga.rotor([0, 1, 0], 0.5)
    return cga.euclidean(R * cga.e1 * ~R)


rotation5, scan5, map5 = exercises.given("ch5.2")
x, y, phi, d, r1, r2 = sp.symbols("x y phi d r1 r2")
WRONG = [
    ("ch3.1", 0.02 - 6.25, "long way"),
    ("ch3.1", lines.diff_theta_as_printed(0.02, 6.25), "as printed"),
    ("ch3.1", -(0.02 - 6.25 + 2 * math.pi), "sign"),
    ("ch3.1", math.degrees(0.02 - 6.25 + 2 * math.pi), "degrees"),
    ("ch3.2", delta * (-px * sp.sin(theta) + py * sp.cos(theta)), "first-order"),
    ("ch3.2", 0, "from the robot"),
    ("ch3.2", px * (sp.cos(theta - delta) - sp.cos(theta)) + py * (sp.sin(theta - delta) - sp.sin(theta)), "wrong way"),
    ("ch3.2", px * sp.sin(delta), "depends on"),
    ("ch3.2", px * sp.sin(delta) + py * theta * 0.1, "different function"),
    ("ch3.3", mapping2d.translation_correction(*exercises.given("ch3.3")), "correction itself"),
    ("ch3.3", [0.30, -0.10], "whole error"),
    ("ch3.3", [0.0, 0.0], "rank"),
    ("ch3.3", -_corridor_left_over(), "opposite"),
    ("ch3.3", [0.3, 0.1, 0.0], "shape"),
    ("ch3.4", [-1.5, -1.5], "antipode"),
    ("ch3.4", [1.0, 2.0], "middle of the segment"),
    ("ch3.4", [1.5, 1.5, 0.2], "z = 0"),
    ("ch3.5", ((r1**2 + r2**2 - d**2) / 2) ** 2, "one more term"),
    ("ch3.5", ((r1**2 + r2**2 - d**2) / 2) ** 2 + r1**2 * r2**2, "sign of the s1^2 s2^2"),
    ("ch3.5", (r1**2 + r2**2 + d**2) ** 2 / 4 - r1**2 * r2**2, "sign of d^2"),
    ("ch3.5", -(((r1**2 + r2**2 - d**2) / 2) ** 2 - r1**2 * r2**2), "sign"),
    ("ch3.6", [[0.5, 1.0], [1.5, 1.0]], "inside the other"),
    ("ch3.6", [[1.5, 1.0], [3.0, 1.0]], "intersect"),
    ("ch3.6", [[3.0, 1.5], [4.0, 1.5]], "Hough space"),
    ("ch4.1", _printed_camera(), "position is missing"),
    ("ch4.1", np.linalg.inv(_camera_matrix()), "inverse"),
    ("ch4.1", _wrong_camera(pan=0.2, tilt=0.3), "rotation is off"),
    ("ch4.1", 2 * _camera_matrix(), "last row"),
    ("ch4.1", np.diag([2.0, 1.0, 1.0, 1.0]), "not a rotation"),
    ("ch4.1", _camera_matrix()[:3], "shape"),
    ("ch4.1", cga.motor_to_matrix(rb.chain_motors(x=1.5, y=-0.5, theta=2.0, pan=0.3, tilt=0.2).M_lu), "off"),
    ("ch4.2", 0, "straight ahead"),
    ("ch4.2", sp.sqrt(x**2 + y**2) * phi, "arc length"),
    ("ch4.2", sp.sqrt(x**2 + y**2) * sp.sin(phi / 2), "constant factor"),
    ("ch4.2", 2 * sp.sqrt(x**2 + y**2) * sp.sin(sp.Symbol("psi") / 2), "psi"),
    ("ch4.3", _right_order_view(), "thesis's order"),
    ("ch4.3", [1.0, 0.0, 0.0], "direction is off"),
    ("ch5.1", [1.0, 2.5, -0.7], "pose itself"),
    ("ch5.1", [5.0, 1.5, -0.7], "heading"),
    ("ch5.1", [5.0, 1.5, math.degrees(-0.7 + math.pi)], "degrees"),
    ("ch5.1", [1.0, 2.5, -0.7 + math.pi], "on the spot"),
    ("ch5.1", [5.0, 2.5, math.pi + 0.7], "mirror"),
    ("ch5.1", [1.0, 1.5, 0.7], "mirror"),
    ("ch5.1", [9.0, 2.5, 0.4], "outside"),
    ("ch5.1", [3.0, 2.0, 0.4], "looks different"),
    (
        "ch5.2",
        np.linalg.solve(np.column_stack([np.cos(scan5[:, 1]), np.sin(scan5[:, 1])]), map5[:, 0] - scan5[:, 0]),
        "turn them",
    ),
    ("ch5.2", -_translation_from_pairs(), "sign"),
    ("ch5.3", 0.0, "exact"),
    ("ch5.3", -_printed_shift_error(), "sign"),
]


@pytest.mark.parametrize("exercise_id, answer, keyword", WRONG)
def test_wrong_answers_name_what_is_off(exercise_id, answer, keyword):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "wrong" and not result, result.message
    assert keyword in result.message, result.message


def _leaks(value) -> list:
    """Ways a message could print a number of the solution."""
    return [f"{v:.3f}" for v in np.ravel(value)] + [f"{v:.2f}" for v in np.ravel(value) if abs(v) > 0.05]


def test_messages_never_print_the_solution():
    truths = {k: RIGHT[k]() for k in ("ch3.1", "ch3.3", "ch3.4", "ch4.1", "ch4.3", "ch5.1", "ch5.2", "ch5.3")}
    for exercise_id, answer, _ in WRONG:
        message = exercises.evaluate(exercise_id, answer).message.split(":", 1)[1]
        if exercise_id in truths:
            for leak in _leaks(truths[exercise_id]):
                assert leak not in message, (exercise_id, leak, message)
    assert "sin(phi" not in exercises.evaluate("ch4.2", 0).message
    assert "r1 - r2" not in exercises.evaluate("ch3.5", d**2).message


# --------------------------------------------------------------------------- placeholders, malformed, registry


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_placeholder_is_not_answered_yet(exercise_id, capsys):
    result = exercises.check(exercise_id, None)
    assert result.verdict == "unanswered"
    assert capsys.readouterr().out == (
        f"{exercise_id}: not answered yet. Replace None with {exercises.get(exercise_id).expects}.\n"
    )


@pytest.mark.parametrize(
    "exercise_id, answer",
    [
        ("ch3.1", "a little"),
        ("ch3.2", "delta +* px"),
        ("ch3.6", [[1.0, 1.0], [1.0, 1.0]]),
        ("ch4.1", cga.translator([1.0, 0.0, 0.0])),
        ("ch4.2", {"x": 1}),
        ("ch5.2", "east"),
    ],
)
def test_malformed_answers_say_what_was_expected(exercise_id, answer):
    result = exercises.evaluate(exercise_id, answer)
    assert result.verdict == "malformed" and not result, result.message
    assert exercises.get(exercise_id).expects in result.message


def test_each_chapter_notebook_sets_two_or_three_exercises_of_two_kinds_at_least():
    by_notebook = {}
    for e in _mine():
        by_notebook.setdefault(e.notebook, []).append(e)
    assert set(by_notebook) == {"05_laser_line_maps", "06_conformal_line_maps", "08_fused_3d_map", "09_relocalization"}
    for nb, exs in by_notebook.items():
        assert 2 <= len(exs) <= 3, nb
        assert len({e.kind for e in exs}) >= 2, nb
        assert all(e.equations for e in exs), nb


def _code_sources(path):
    nb = json.loads(Path(path).read_text())
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]


@pytest.mark.parametrize("exercise_id", sorted(RIGHT))
def test_exercise_is_set_in_its_notebook_and_solved_for_the_teacher(exercise_id):
    e = exercises.get(exercise_id)
    cells = [c for c in _code_sources(ROOT / "notebooks" / f"{e.notebook}.ipynb") if f'check("{e.id}"' in c]
    assert len(cells) == 1, (e.id, e.notebook)
    assert re.search(r"^answer = None\b", cells[0], flags=re.M), cells[0]
    solutions = "\n".join(_code_sources(ROOT / "notebooks" / "teacher_solutions.ipynb"))
    assert f'check("{e.id}"' in solutions, e.id


# --------------------------------------------------------------------------- the README's chapter pictures


def _figures_script():
    import importlib.util

    spec = importlib.util.spec_from_file_location("make_chapter_figures", ROOT / "docs" / "make_chapter_figures.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_notebook_has_a_chapter_picture_found_in_its_stored_outputs():
    figures = _figures_script()
    notebooks = sorted(p.stem for p in (ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    assert sorted(figures.PICTURES) == notebooks
    for name, (marker, index, _) in figures.PICTURES.items():
        png = figures.thumbnail(figures.stored_image(name, marker, index))
        assert png.startswith(b"\x89PNG") and len(png) <= figures.MAX_BYTES, name
        checked_in = ROOT / "docs" / "chapters" / f"{name}.png"
        assert checked_in.is_file() and checked_in.stat().st_size <= figures.MAX_BYTES, name
    with pytest.raises(figures.FigureNotFound, match="no code cell contains"):
        figures.stored_image("01_geometric_algebra", "this text is in no cell", 0)
