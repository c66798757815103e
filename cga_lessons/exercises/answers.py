"""Reading a student's answer (a number, an array, a SymPy expression), the exceptions a checker raises, and the
checks of the comparisons' own settings (tolerances, hints, symbols).

:class:`Wrong` (and :class:`Malformed`, an answer that cannot be read at all) is what a checker raises for an
answer that is not right.  Both are ``ValueError`` subclasses of the package
(:class:`~cga_lessons.algebra.InvalidInputError`): raised by one of the helpers, the text names it and its
argument, ``"compare_number: value: the sign is wrong."``; :attr:`Wrong.reason` is what is off alone, which is
what :func:`~cga_lessons.exercises.check` prints.  A bad truth or setting given to a helper (by the author of an
exercise) is refused by the checks layer as everywhere else.  This module registers no exercise.
"""

from __future__ import annotations

import functools
import math
import numbers

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError, Multivector

__all__ = ["Wrong", "Malformed", "as_float", "as_array", "as_expression"]


class Wrong(InvalidInputError):
    """Raised by a checker: the answer is readable but not right; :attr:`reason` says what is off.

    Raised by a comparison helper, its text also names the helper and its arguments (``func``, ``name``): the
    answer and the truth it disagrees with, ``"compare_number: value, truth: the sign is wrong."``.
    """

    def __init__(self, reason, func: str | None = None, name: str | None = None):
        super().__init__(reason)
        self.reason, self.func, self.name = str(reason), func, name

    def __str__(self):
        return f"{self.func}: {self.name}: {self.reason}" if self.func else self.reason


class Malformed(Wrong):
    """Raised by a checker: the answer cannot be read as the kind of value the exercise asks for."""


def names_the_answer(name: str, against: str | None = None):
    """Decorator of a helper: a :class:`Wrong` raised inside it names the helper and its argument ``name``.

    A disagreement (a :class:`Wrong` that is not :class:`Malformed`) also names ``against``, the argument the
    answer was compared with.  The outermost helper names it (``compare_vector`` calling ``as_array`` gives
    ``"compare_vector: value, truth: ..."``).
    """

    def wrap(fn):
        @functools.wraps(fn)
        def inner(*args, **kwargs):
            try:
                return fn(*args, **kwargs)
            except Wrong as exc:
                both = against is not None and not isinstance(exc, Malformed)
                exc.func, exc.name = fn.__name__, f"{name}, {against}" if both else name
                raise

        return inner

    return wrap


# --------------------------------------------------------------------------- the helpers' settings


def _sympy():
    import sympy

    return sympy


def shape_text(shape) -> str:
    return "(" + ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"


def settings(func: str, *, rtol, atol, what, **flags) -> tuple[float, float]:
    """The tolerances (finite, >= 0), the text ``what`` and the True/False ``flags`` of a comparison, checked."""
    for name, value in flags.items():
        checks.flag(value, func, name)
    checks.text(what, func, "what")
    return checks.real(rtol, func, "rtol", low=0), checks.real(atol, func, "atol", low=0)


def hint_pairs(hints, func: str, read) -> list:
    """``hints`` as ``[(candidate read by read(), message)]``: known mistakes and what to say about them."""
    if isinstance(hints, (str, bytes, dict)) or not hasattr(hints, "__iter__"):
        raise checks.fail(func, "hints", f"expected a sequence of (wrong value, message) pairs, got {hints!r:.40}")
    out = []
    for pair in hints:
        if isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise checks.fail(func, "hints", f"each hint is a (wrong value, message) pair, got {pair!r:.40}")
        try:
            cand = read(pair[0])
        except (Wrong, InvalidInputError) as exc:
            raise checks.fail(func, "hints", f"the hint value {pair[0]!r:.40} cannot be read: {exc}") from None
        out.append((cand, checks.text(pair[1], func, "hints")))
    return out


def symbol_table(symbols, func: str) -> dict:
    """``symbols`` as ``{name: sympy.Symbol}``, the exercise's symbols."""
    sp = _sympy()
    if not isinstance(symbols, dict) or not symbols:
        raise checks.fail(func, "symbols", f"expected {{name: sympy.Symbol}}, got {symbols!r:.40}")
    for k, v in symbols.items():
        if not isinstance(k, str) or not isinstance(v, sp.Symbol):
            raise checks.fail(func, "symbols", f"expected {{name: sympy.Symbol}}, got the entry {k!r}: {v!r:.40}")
    return symbols


# --------------------------------------------------------------------------- reading answers


@names_the_answer("answer")
def as_float(answer, what: str = "the answer") -> float:
    """A real number from an int, float, NumPy scalar or 0-d/1-element array, SymPy number or scalar Multivector."""
    checks.text(what, "as_float", "what")
    if isinstance(answer, bool):
        raise Malformed(f"{what} is a bool ({answer}), not a number")
    if isinstance(answer, Multivector):
        extra = [b for b in answer.blades() if b != "1"]
        if extra:
            raise Wrong(f"the grade is wrong: {what} should be a scalar, but your multivector has blades {extra}")
        answer = answer.scalar()
    if checks.is_symbolic(answer):
        if getattr(answer, "free_symbols", None):
            raise Malformed(f"{what} still contains symbols {sorted(map(str, answer.free_symbols))}; give a number")
        try:
            value = complex(answer.evalf())
        except (TypeError, ValueError) as exc:
            raise Malformed(f"{what} is not a number ({exc})") from None
        if abs(value.imag) > 1e-12 * max(1.0, abs(value.real)):
            raise Wrong(f"{what} is complex ({value}); a real number is expected")
        answer = value.real
    if isinstance(answer, np.ndarray):
        if answer.size != 1:
            raise Wrong(f"the shape is wrong: {what} should be one number, you gave an array of shape {answer.shape}.")
        answer = answer.reshape(-1)[0]
    if isinstance(answer, (list, tuple)):
        raise Wrong(
            f"the shape is wrong: {what} should be one number, you gave a {type(answer).__name__} of {len(answer)}."
        )
    if isinstance(answer, complex) or isinstance(answer, np.complexfloating):
        if abs(answer.imag) > 1e-12 * max(1.0, abs(answer.real)):
            raise Wrong(f"{what} is complex ({answer}); a real number is expected")
        answer = answer.real
    if not isinstance(answer, numbers.Real):
        raise Malformed(f"{what} is a {type(answer).__name__}, not a number")
    try:
        value = float(answer)
    except OverflowError:
        value = math.inf
    if not math.isfinite(value):
        raise Wrong(f"{what} is {value}, not a finite number")
    return value


def _shape(shape, func: str) -> tuple:
    if not isinstance(shape, tuple) or any(
        s is not None and (isinstance(s, bool) or not isinstance(s, numbers.Integral) or s < 0) for s in shape
    ):
        raise checks.fail(func, "shape", f"expected a tuple of lengths (ints >= 0, or None for any), got {shape!r:.40}")
    return shape


@names_the_answer("answer")
def as_array(answer, shape: tuple, what: str = "the answer") -> np.ndarray:
    """A finite float array of the given shape (``None`` entries in ``shape`` match any length)."""
    shape = _shape(shape, "as_array")
    checks.text(what, "as_array", "what")
    if isinstance(answer, Multivector):
        raise Malformed(f"{what} should be a NumPy array of shape {shape_text(shape)}, not a Multivector")
    if isinstance(answer, (str, bytes, dict, set)):
        raise Malformed(f"{what} should be an array of shape {shape_text(shape)}, not a {type(answer).__name__}")
    try:
        arr = np.asarray(answer)
        if arr.dtype.kind == "c":  # complex: only with no imaginary part to speak of, never truncated silently
            if np.any(np.abs(arr.imag) > 1e-12 * np.maximum(1.0, np.abs(arr.real))):
                raise Wrong(f"{what} is complex; real numbers are expected")
            arr = arr.real
        arr = np.asarray(arr, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        if isinstance(exc, Wrong):
            raise
        raise Malformed(f"{what} cannot be read as an array of numbers ({exc})") from None
    if arr.ndim != len(shape) or any(s is not None and s != a for s, a in zip(shape, arr.shape)):
        raise Wrong(f"the shape is wrong: {what} should have shape {shape_text(shape)}, yours has {arr.shape}.")
    if not np.all(np.isfinite(arr)):
        raise Wrong(f"{what} contains NaN or infinite values.")
    return arr


@names_the_answer("value")
def as_expression(value, symbols: dict, what: str = "the answer"):
    """A SymPy expression in the exercise's ``symbols`` (``{name: Symbol}``) from an expression, number or string."""
    sp = _sympy()
    symbols = symbol_table(symbols, "as_expression")
    checks.text(what, "as_expression", "what")
    if isinstance(value, Multivector):
        extra = [b for b in value.blades() if b != "1"]
        if extra:
            raise Wrong(
                f"the grade is wrong: {what} should be a scalar expression, your multivector has blades {extra}"
            )
        value = value.scalar()
    if isinstance(value, str):
        try:
            value = sp.sympify(value, locals=dict(symbols))
        except (sp.SympifyError, SyntaxError, TypeError) as exc:
            raise Malformed(f"the string {value!r} is not a formula SymPy can read ({exc})") from None
    if isinstance(value, bool) or not (checks.is_symbolic(value) or isinstance(value, numbers.Number)):
        raise Malformed(f"{what} should be a SymPy expression, not a {type(value).__name__}")
    expr = sp.sympify(value)
    if not isinstance(expr, sp.Expr):
        raise Malformed(f"{what} should be a SymPy expression, not a {type(expr).__name__}")
    if expr.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        raise Wrong(f"{what} is not finite (it is or contains zoo, nan or oo).")
    # match symbols by name: a student's sp.Symbol("rho") is the exercise's rho whatever its assumptions
    unknown = sorted(str(s) for s in expr.free_symbols if str(s) not in symbols)
    if unknown:
        raise Wrong(f"{what} uses {', '.join(unknown)}, which the exercise does not have (use {', '.join(symbols)}).")
    return expr.subs({s: symbols[str(s)] for s in expr.free_symbols})
