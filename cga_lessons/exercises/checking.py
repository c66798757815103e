"""Exercises that check themselves: ``check("ch2.4", answer)`` says right or wrong, and why.

Each chapter notebook ends with a few exercises.  The student writes an answer
into a cell and calls :func:`check`, which prints one line: *right*, or *not
right yet* with what is off (the sign, the grade, the magnitude, the shape, the
type of the answer, or a known mistake such as degrees for radians), and
never the solution.  The truth each answer is compared with is computed
independently of the function a student would call: a closed form, a
4x4 homogeneous matrix, a NumPy construction.

The exercises live in the modules ``cga_lessons/exercises/<part>.py`` (one per
chapter or document), each registering its checkers with :func:`exercise`;
this module finds them all on first use, so a new chapter adds a module and
nothing else.  A checker receives the student's answer and either returns
(right; it may return a short remark to print) or raises :class:`Wrong` (or
:class:`Malformed` when the answer cannot be read at all).  The helpers
:func:`compare_number`, :func:`compare_vector`, :func:`compare_multivector`,
:func:`compare_expression` and :func:`compare_matrix` (in
:mod:`cga_lessons.exercises.compare`, exported by the package) do the diagnosis for
the common kinds of answer.

A later chapter adds ``ch3.py`` with, for instance::

    from .checking import compare_number, exercise

    @exercise("ch3.1", title="...", notebook="05_laser_line_maps", kind="compute", expects="a float")
    def _ch3_1(answer):
        compare_number(answer, truth_from_a_closed_form)

    >>> from cga_lessons import exercises
    >>> r = exercises.check("ch2.4", None)
    ch2.4: not answered yet. Replace None with a float.
    >>> r = exercises.check("ch2.4", 12.5)
    ch2.4: not right yet: the sign is wrong. The inner product of two conformal points is never positive.
    >>> bool(r), r.verdict
    (False, 'wrong')
"""

from __future__ import annotations

import difflib
import importlib
import pkgutil
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError

from .answers import Malformed, Wrong

__all__ = [
    "Exercise",
    "CheckResult",
    "UnknownExerciseError",
    "exercise",
    "check",
    "evaluate",
    "get",
    "given",
    "list_exercises",
]

VERDICTS = ("right", "wrong", "unanswered", "malformed")
KINDS = ("derive", "compute", "break")


class UnknownExerciseError(InvalidInputError, KeyError):
    """No exercise has this id."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


@dataclass(frozen=True)
class Exercise:
    """One exercise: its id, where it is set, what it asks for and its checker.

    Attributes
    ----------
    id : str
        ``"ch2.4"``, ``"chA.1"``, ``"expl.2"``: part and number.
    title : str
        One line saying what is asked.
    notebook : str
        The notebook that sets it (``"02_conformal_model"``).
    kind : {"derive", "compute", "break"}
        Derive a formula, compute a value, or break a method and explain why.
    expects : str
        What kind of answer, e.g. ``"a float"``, ``"a Multivector of G(4,1)"``.
    equations : tuple of str
        The thesis equations it exercises.
    checker : callable
        ``checker(answer) -> str | None``; raises :class:`Wrong`.
    given : callable, optional
        Makes the exercise's input (a motor, a camera matrix) for :func:`given`,
        when the notebook should not show how it was built.
    """

    id: str
    title: str
    notebook: str
    kind: str
    expects: str
    checker: Callable[[Any], Any] = field(repr=False)
    equations: tuple = ()
    given: Callable[[], Any] | None = field(default=None, repr=False)

    def __post_init__(self):
        _check_fields("Exercise", **{f: getattr(self, f) for f in self.__dataclass_fields__})


def _check_fields(func, *, id, title, notebook, kind, expects, checker, equations, given):
    """The fields of an exercise, checked (for :class:`Exercise` and :func:`exercise`)."""
    checks.text(id, func, "id")
    if not re.fullmatch(r"[a-zA-Z]+[0-9A-Z]*\.[0-9]+", id):
        raise checks.fail(func, "id", f"{id!r}: an id is a part and a number, like 'ch2.4'")
    for name, value in (("title", title), ("notebook", notebook), ("expects", expects)):
        checks.text(value, func, name)
    checks.choice(kind, func, "kind", KINDS)
    if not callable(checker):
        raise checks.fail(func, "checker", f"expected a function of the answer, got {checker!r:.40}")
    if isinstance(equations, (str, bytes)) or not isinstance(equations, (tuple, list)):
        raise checks.fail(func, "equations", f"expected a tuple of equation labels, got {equations!r:.40}")
    for label in equations:
        checks.text(label, func, "equations")
    if given is not None and not callable(given):
        raise checks.fail(func, "given", f"expected None or a function making the input, got {given!r:.40}")


@dataclass(frozen=True)
class CheckResult:
    """The verdict on one answer; ``bool(result)`` is True only when it is right."""

    exercise_id: str
    verdict: str
    message: str

    def __post_init__(self):
        checks.text(self.exercise_id, "CheckResult", "exercise_id")
        checks.choice(self.verdict, "CheckResult", "verdict", VERDICTS)
        checks.text(self.message, "CheckResult", "message")

    def __bool__(self):
        return self.verdict == "right"

    def __str__(self):
        return self.message

    def __repr__(self):
        return f"CheckResult({self.exercise_id!r}: {self.verdict})"

    def _ipython_display_(self):
        # check() has printed the message already; showing it again as Out[] would repeat it.
        pass


_REGISTRY: dict[str, Exercise] = {}
_LOADED = False


def exercise(id: str, *, title: str, notebook: str, kind: str, expects: str, equations=(), given=None):
    """Decorator registering ``checker(answer)`` as exercise ``id`` (used by the chapters' modules of this package)."""

    fields = dict(id=id, title=title, notebook=notebook, kind=kind, expects=expects, equations=equations, given=given)
    _check_fields("exercise", checker=print, **fields)  # the checker itself comes with the decoration

    def register(checker):
        ex = Exercise(id, title, notebook, kind, expects, checker, tuple(equations), given)
        if id in _REGISTRY and _REGISTRY[id].checker.__qualname__ != checker.__qualname__:
            raise checks.fail("exercise", "id", f"{id!r} registered twice ({_REGISTRY[id].checker.__module__})")
        _REGISTRY[id] = ex
        return checker

    return register


def _load():
    global _LOADED
    if _LOADED:
        return
    here = Path(__file__).resolve().parent  # every module of this package but the machinery holds exercises
    for info in sorted(pkgutil.iter_modules([str(here)]), key=lambda m: m.name):
        if info.name not in ("answers", "checking", "compare"):
            importlib.import_module(f"{__package__}.{info.name}")
    _LOADED = True


def _sort_key(ex_id: str):
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", ex_id)]


def list_exercises(part: str | None = None) -> list[Exercise]:
    """Every registered exercise (or those whose id starts with ``part``, e.g. ``"ch2"``), in order.

    A ``part`` no exercise belongs to is refused (the message lists the parts).
    """
    _load()
    ids = sorted(_REGISTRY, key=_sort_key)
    if part is not None:
        checks.text(part, "list_exercises", "part")
        ids = [i for i in ids if i.split(".")[0] == part or i.startswith(part)]
        if not ids:
            parts = sorted({i.split(".")[0] for i in _REGISTRY}, key=_sort_key)
            raise checks.fail("list_exercises", "part", f"no exercise belongs to {part!r}; the parts are {parts}")
    return [_REGISTRY[i] for i in ids]


def get(exercise_id: str) -> Exercise:
    """The exercise with this id; raises :class:`UnknownExerciseError` naming the close ones."""
    return _get(exercise_id, "get")


def _get(exercise_id: str, func: str) -> Exercise:
    """:func:`get` for the public function ``func`` (the name its errors carry)."""
    _load()
    if not isinstance(exercise_id, str):
        raise UnknownExerciseError(
            f"{func}: exercise_id: the exercise id must be a string like 'ch2.4', got {exercise_id!r}"
        )
    key = exercise_id.strip()
    if key in _REGISTRY:
        return _REGISTRY[key]
    close = difflib.get_close_matches(key, list(_REGISTRY), n=3, cutoff=0.5)
    hint = f" Did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    raise UnknownExerciseError(
        f"{func}: exercise_id: there is no exercise {exercise_id!r}.{hint} "
        f"exercises.list_exercises() lists all {len(_REGISTRY)} of them."
    )


def given(exercise_id: str):
    """The input of an exercise whose construction the notebook does not show (a motor, a camera matrix)."""
    ex = _get(exercise_id, "given")
    if ex.given is None:
        raise checks.fail(
            "given", "exercise_id", f"exercise {ex.id} has no hidden input; everything it needs is in its text"
        )
    return ex.given()


def evaluate(exercise_id: str, answer) -> CheckResult:
    """Judge ``answer`` without printing: a :class:`CheckResult`."""
    return _evaluate(_get(exercise_id, "evaluate"), answer)


def _evaluate(ex: Exercise, answer) -> CheckResult:
    if answer is None or answer is Ellipsis:
        return CheckResult(ex.id, "unanswered", f"{ex.id}: not answered yet. Replace None with {ex.expects}.")
    try:
        remark = ex.checker(answer)
    except Malformed as exc:
        return CheckResult(
            ex.id, "malformed", f"{ex.id}: cannot read this answer: {exc.reason} (expected {ex.expects})."
        )
    except Wrong as exc:
        return CheckResult(ex.id, "wrong", f"{ex.id}: not right yet: {exc.reason}")
    except Exception as exc:  # noqa: BLE001 - whatever the answer makes a checker trip on, say so
        return CheckResult(
            ex.id,
            "malformed",
            f"{ex.id}: cannot check this answer ({type(exc).__name__}: {exc}); expected {ex.expects}.",
        )
    text = f"{ex.id}: right." + (f" {remark}" if remark else "")
    return CheckResult(ex.id, "right", text)


def check(exercise_id: str, answer) -> CheckResult:
    """Check an answer and print the verdict: right, or what is off, without the solution.

    Parameters
    ----------
    exercise_id : str
        As given in the notebook, e.g. ``"ch2.4"``.
    answer
        The value the exercise asks for; ``None`` means not answered yet.

    Returns
    -------
    CheckResult
        ``bool(result)`` is True when the answer is right.

    Raises
    ------
    UnknownExerciseError
        If no exercise has this id (the message names the close ones).
    """
    result = _evaluate(_get(exercise_id, "check"), answer)
    print(result.message)
    return result
