"""Fuzz cases of the self-checking exercises (cga_lessons.exercises): the registry, the checks and the comparisons.

A student's answer may be anything: :func:`check` and :func:`evaluate` turn a wrong or unreadable answer into a
verdict (a returned :class:`CheckResult`), never an exception.  The comparison helpers raise :class:`Wrong` (a
``ValueError`` naming the helper and its ``value``) for a wrong answer, and refuse a bad ``truth`` or setting.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from cga_lessons import exercises as ex
from cga_lessons.algebra import Algebra
from fuzz.harness import Case

G3 = Algebra(3)
MV = G3.vector([1.0, 2.0, 3.0]) + G3.blade("e12", 0.5)
RHO = sp.Symbol("rho", positive=True)
SYMBOLS = {"rho": RHO}
TRUTH_EXPR = RHO**2 / 2


def _checker(answer):
    ex.compare_number(answer, 1.0)


CASES = [
    # ---------------------------------------------------------------- the registry
    Case(ex.Exercise, {"id": "ch9.1", "title": "a test", "notebook": "01_geometric_algebra", "kind": "compute",
                       "expects": "a float", "checker": _checker, "equations": ("2.1",), "given": None},
         strict=True, allow={"given": ["None"]}),
    Case(ex.CheckResult, {"exercise_id": "ch2.4", "verdict": "right", "message": "ch2.4: right."}, strict=True),
    Case(ex.exercise, {"id": "ch9.2", "title": "a test", "notebook": "01_geometric_algebra", "kind": "compute",
                       "expects": "a float", "equations": ("2.1",), "given": None},
         positional=("id",), strict=True, allow={"given": ["None"]}),
    Case(ex.check, {"exercise_id": "ch2.4", "answer": -10.0}, extra={"exercise_id": ["ch2.99", "ch2"]}),
    Case(ex.evaluate, {"exercise_id": "ch2.4", "answer": -10.0}, extra={"exercise_id": ["ch2.99", " "]}),
    Case(ex.evaluate, {"exercise_id": "ch2.11", "answer": np.array([1.0, 2.0, 3.0])}, name="evaluate (array)"),
    Case(ex.evaluate, {"exercise_id": "ch2.2", "answer": MV}, name="evaluate (multivector)"),
    Case(ex.get, {"exercise_id": "ch2.4"}, extra={"exercise_id": ["ch2.99"]}),
    Case(ex.given, {"exercise_id": "ch5.2"}, extra={"exercise_id": ["ch2.4", "ch2.99"]}),
    Case(ex.list_exercises, {"part": "ch2"}, extra={"part": ["ch99", "chx"]}, allow={"part": ["None"]}, strict=True),
    # ---------------------------------------------------------------- reading answers
    Case(ex.as_float, {"answer": 1.5, "what": "the answer"}),
    Case(ex.as_array, {"answer": [1.0, 2.0, 3.0], "shape": (3,), "what": "the answer"},
         extra={"shape": [(-1,), ("3",), (None, None, None, None, None)]}),
    Case(ex.as_expression, {"value": "rho**2/2", "symbols": SYMBOLS, "what": "the answer"},
         extra={"value": ["rho +", "x + 1"], "symbols": [{"rho": 1.0}, {}]}),
    # ---------------------------------------------------------------- comparing
    Case(ex.compare_number, {"value": 2.0, "truth": 2.0, "rtol": 1e-6, "atol": 1e-9, "hints": (), "what": "the answer"},
         strict=True, extra={"value": [-2.0, 4.0, 0.0], "hints": [((1.0, "one"),), ((None, "bad"),), (("x",),)]}),
    Case(ex.compare_vector, {"value": [1.0, 2.0, 3.0], "truth": np.array([1.0, 2.0, 3.0]), "rtol": 1e-6,
                             "atol": 1e-9, "up_to_scale": False, "up_to_sign": False, "what": "the answer"},
         strict=True, extra={"value": [[-1.0, -2.0, -3.0], [3.0, 2.0, 1.0], [0.0, 0.0, 0.0], [2.0, 4.0, 6.0]],
                             "truth": [np.zeros(3)]}),
    Case(ex.compare_matrix, {"value": np.eye(2), "truth": np.eye(2), "rtol": 1e-6, "atol": 1e-9,
                             "up_to_scale": False, "what": "the answer"},
         strict=True, extra={"value": [-np.eye(2), np.array([[1.0, 2.0], [0.0, 1.0]])], "truth": [np.zeros((2, 2))]}),
    Case(ex.compare_multivector, {"value": MV, "truth": MV, "rtol": 1e-6, "atol": 1e-9, "up_to_scale": False,
                                  "up_to_sign": False, "what": "the answer"},
         strict=True, extra={"value": [-MV, 2.0 * MV, G3.vector([1.0, 2.0, 3.0]), Algebra(4).scalar(1.0), 1.0],
                             "truth": [G3.scalar(0.0)]}),
    Case(ex.compare_expression, {"value": "rho**2/2", "truth": TRUTH_EXPR, "symbols": SYMBOLS, "domain": (0.3, 2.0),
                                 "seed": 0, "what": "the answer"},
         strict=True, extra={"value": ["-rho**2/2", "rho**2", "1/(rho - rho)", "q"], "domain": [(2.0, 0.3), (1.0,)],
                             "truth": [RHO / 0]}),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
