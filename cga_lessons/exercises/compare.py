"""The comparisons behind :func:`cga_lessons.exercises.check`: read an answer, compare it, say what is off.

Each ``compare_*`` raises :class:`Wrong` (or :class:`Malformed`) with a message naming what is off (the sign,
the grade, the magnitude, the shape, the type, a known mistake passed as a hint) and returns None when the
answer is right.  The messages never print the truth.  This module registers no exercise.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons.algebra import Multivector

__all__ = [
    "Wrong",
    "Malformed",
    "as_float",
    "as_array",
    "as_expression",
    "compare_number",
    "compare_vector",
    "compare_matrix",
    "compare_multivector",
    "compare_expression",
]


class Wrong(Exception):
    """Raised by a checker: the answer is readable but not right; the message says what is off."""


class Malformed(Wrong):
    """Raised by a checker: the answer cannot be read as the kind of value the exercise asks for."""


# --------------------------------------------------------------------------- reading answers


def _sympy():
    import sympy

    return sympy


def _is_sympy(x) -> bool:
    return type(x).__module__.startswith("sympy")


def as_float(answer, what: str = "the answer") -> float:
    """A real number from an int, float, NumPy scalar or 0-d/1-element array, SymPy number or scalar Multivector."""
    if isinstance(answer, bool):
        raise Malformed(f"{what} is a bool ({answer}), not a number")
    if isinstance(answer, Multivector):
        extra = [b for b in answer.blades() if b != "1"]
        if extra:
            raise Wrong(f"the grade is wrong: {what} should be a scalar, but your multivector has blades {extra}")
        answer = answer.scalar()
    if _is_sympy(answer):
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
    value = float(answer)
    if not math.isfinite(value):
        raise Wrong(f"{what} is {value}, not a finite number")
    return value


def as_array(answer, shape: tuple, what: str = "the answer") -> np.ndarray:
    """A finite float array of the given shape (``None`` entries in ``shape`` match any length)."""
    if isinstance(answer, Multivector):
        raise Malformed(f"{what} should be a NumPy array of shape {_shape_text(shape)}, not a Multivector")
    if isinstance(answer, (str, bytes, dict, set)):
        raise Malformed(f"{what} should be an array of shape {_shape_text(shape)}, not a {type(answer).__name__}")
    try:
        arr = np.asarray(answer, dtype=float)
    except (TypeError, ValueError) as exc:
        raise Malformed(f"{what} cannot be read as an array of numbers ({exc})") from None
    if arr.ndim != len(shape) or any(s is not None and s != a for s, a in zip(shape, arr.shape)):
        raise Wrong(f"the shape is wrong: {what} should have shape {_shape_text(shape)}, yours has {arr.shape}.")
    if not np.all(np.isfinite(arr)):
        raise Wrong(f"{what} contains NaN or infinite values.")
    return arr


def _shape_text(shape) -> str:
    return "(" + ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"


# --------------------------------------------------------------------------- comparing


def _close(a, b, rtol, atol) -> bool:
    return bool(np.allclose(a, b, rtol=rtol, atol=atol))


_NICE_FACTORS = {
    2.0: "twice too large",
    0.5: "half of what it should be",
    4.0: "four times too large",
    0.25: "a quarter of what it should be",
    math.pi: "pi times too large",
    1 / math.pi: "pi times too small",
}


def _factor_text(ratio: float) -> str | None:
    for f, text in _NICE_FACTORS.items():
        if abs(ratio - f) <= 1e-6 * f:
            return text
    if abs(ratio - 180 / math.pi) < 1e-6 * 57:
        return "it looks like degrees; give radians"
    if abs(ratio - math.pi / 180) < 1e-9:
        return "it looks like radians where degrees are asked"
    return None


def _magnitude_text(value: float, truth: float) -> str:
    ratio = abs(value) / abs(truth)
    if ratio > 10:
        return "far too large (more than ten times)"
    if ratio < 0.1:
        return "far too small (less than a tenth)"
    return "too large" if ratio > 1 else "too small"


def compare_number(value, truth: float, *, rtol: float = 1e-6, atol: float = 1e-9, hints=(), what="the answer"):
    """Raise :class:`Wrong` unless ``value`` is ``truth`` to float noise; diagnose sign, factor, square, units.

    ``hints`` is a sequence of ``(wrong_value, message)``: known mistakes with their own explanation.
    """
    v = as_float(value, what)
    if _close(v, truth, rtol, atol):
        return
    for cand, msg in hints:
        if _close(v, cand, rtol, atol):
            raise Wrong(msg)
    if truth != 0 and _close(v, -truth, rtol, atol):
        raise Wrong("the sign is wrong.")
    if truth == 0:
        raise Wrong(f"the magnitude is off: {what} should be zero.")
    if v == 0:
        raise Wrong(f"{what} is zero, and it should not be.")
    if abs(truth) != 1 and _close(v, truth * truth, rtol, atol):
        raise Wrong("that looks like the square of the right value.")
    if truth > 0 and _close(v * v, truth, rtol, atol):
        raise Wrong("that looks like the square root of the right value (is a square missing?).")
    ratio = v / truth
    text = _factor_text(abs(ratio))
    sign = "" if ratio > 0 else "the sign is wrong, and "
    if text:
        raise Wrong(f"{sign}the magnitude is off: {text}.")
    raise Wrong(f"{sign}the magnitude is off: {_magnitude_text(v, truth)}.")


def _angle_between(a, b) -> float:
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    c = float(np.clip(a @ b / (na * nb), -1.0, 1.0))
    return math.degrees(math.acos(c))


def compare_vector(
    value,
    truth,
    *,
    rtol: float = 1e-6,
    atol: float = 1e-9,
    up_to_scale: bool = False,
    up_to_sign: bool = False,
    hints=(),
    what="the answer",
):
    """Raise :class:`Wrong` unless ``value`` equals the 1-D ``truth`` (or a multiple of it, if ``up_to_scale``).

    Diagnoses shape, overall sign, length (parallel but scaled), order of the components and direction.
    """
    truth = np.asarray(truth, float)
    v = as_array(value, truth.shape, what)
    scale = max(float(np.abs(truth).max()), 1e-300)
    tol = dict(rtol=rtol, atol=atol * max(scale, 1.0))
    if _close(v, truth, **tol) or (up_to_sign and _close(v, -truth, **tol)):
        return
    if up_to_scale and np.linalg.norm(v) > 0:
        s = (v @ truth) / (truth @ truth)
        if s != 0 and _close(v, s * truth, rtol=rtol, atol=atol * scale * abs(s)):
            return
    for cand, msg in hints:
        if _close(v, np.asarray(cand, float), **tol):
            raise Wrong(msg)
    if _close(v, -truth, **tol):
        raise Wrong("the sign is wrong: your vector points the opposite way.")
    if np.linalg.norm(v) == 0:
        raise Wrong(f"{what} is the zero vector.")
    if truth.ndim == 1 and np.linalg.norm(truth) > 0:
        s = (v @ truth) / (truth @ truth)
        if _close(v, s * truth, rtol=rtol, atol=atol * scale * max(abs(s), 1.0)):
            if s < 0:
                raise Wrong("your vector lies along the right line but points the opposite way, and its length is off.")
            text = _factor_text(s)
            raise Wrong(f"the direction is right but the length is off{': ' + text if text else ''}.")
        if len(v) > 1 and _close(np.sort(v), np.sort(truth), **tol):
            raise Wrong("the right numbers, in the wrong order.")
        angle = _angle_between(v, truth)
        if angle < 90:
            raise Wrong(f"the direction is off by {angle:.0f} degrees.")
        raise Wrong(f"the direction is off by {angle:.0f} degrees (more than a right angle: check the sign).")
    raise Wrong("the values are off.")


def compare_matrix(
    value, truth, *, rtol: float = 1e-6, atol: float = 1e-9, up_to_scale=False, hints=(), what="the answer"
):
    """Raise :class:`Wrong` unless the 2-D ``value`` equals ``truth``; diagnoses shape, transpose, sign, scale."""
    truth = np.asarray(truth, float)
    if _is_sympy(value):
        try:
            value = np.array(value.tolist(), dtype=float)
        except (TypeError, ValueError) as exc:
            raise Malformed(f"{what} has entries that are not numbers ({exc})") from None
    v = as_array(value, truth.shape, what)
    scale = max(float(np.abs(truth).max()), 1e-300)
    if _close(v, truth, rtol, atol * scale):
        return
    if up_to_scale and np.abs(v).max() > 0:
        s = np.sum(v * truth) / np.sum(truth * truth)
        if s != 0 and _close(v, s * truth, rtol, atol * scale * abs(s)):
            return
    for cand, msg in hints:
        if _close(v, np.asarray(cand, float), rtol, atol * scale):
            raise Wrong(msg)
    if _close(v, -truth, rtol, atol * scale):
        raise Wrong("the sign is wrong (the whole matrix is negated).")
    if truth.shape[0] == truth.shape[1] and _close(v, truth.T, rtol, atol * scale):
        raise Wrong("that is the transpose of the right matrix.")
    if np.abs(v).max() > 0:
        s = np.sum(v * truth) / np.sum(truth * truth)
        if s != 0 and _close(v, s * truth, rtol, atol * scale * abs(s)):
            raise Wrong("proportional to the right matrix, but the scale is off.")
    wrong = int(np.sum(~np.isclose(v, truth, rtol=rtol, atol=atol * scale)))
    raise Wrong(f"{wrong} of the {truth.size} entries are off.")


def _mv_arrays(value: Multivector, truth: Multivector, what: str):
    """Coefficient arrays of two multivectors of the same signature, matched by blade name."""
    if not isinstance(value, Multivector):
        raise Malformed(f"{what} should be a Multivector, not a {type(value).__name__}")
    A, B = value.algebra, truth.algebra
    if A is not B and (A.signature != B.signature or A.labels != B.labels):
        raise Wrong(
            f"your multivector lives in G{A.signature} with basis {A.labels}; "
            f"the exercise is in G{B.signature} with basis {B.labels}."
        )
    if value.shape:
        raise Wrong(f"the shape is wrong: {what} should be one multivector, yours is a batch of shape {value.shape}.")
    names = [B.blade_names[b] for b in B.blade_order]
    out = np.zeros(len(names))
    for i, name in enumerate(names):
        c = value[name]
        if _is_sympy(c):
            if getattr(c, "free_symbols", None):
                raise Malformed(f"the {name} coefficient still contains symbols {sorted(map(str, c.free_symbols))}")
            c = float(c)
        out[i] = float(c)
    truth_arr = np.array([float(truth[n]) for n in names])
    return out, truth_arr, names


def compare_multivector(
    value,
    truth: Multivector,
    *,
    rtol: float = 1e-6,
    atol: float = 1e-9,
    up_to_scale: bool = False,
    up_to_sign: bool = False,
    hints=(),
    what="the answer",
):
    """Raise :class:`Wrong` unless ``value`` is the multivector ``truth`` (up to a nonzero factor or a sign, if asked).

    Diagnoses the algebra, the grades present, an overall sign, a scale factor and which blades are off.
    """
    v, t, names = _mv_arrays(value, truth, what)
    scale = max(float(np.abs(t).max()), 1e-300)
    tol = dict(rtol=rtol, atol=atol * max(scale, 1.0))
    if _close(v, t, **tol) or (up_to_sign and _close(v, -t, **tol)):
        return
    s = (v @ t) / (t @ t) if t @ t > 0 else 0.0
    parallel = s != 0 and _close(v, s * t, rtol=rtol, atol=atol * scale * max(abs(s), 1.0))
    if up_to_scale and parallel:
        return
    for cand, msg in hints:
        c, _, _ = _mv_arrays(cand, truth, "hint")
        if _close(v, c, **tol):
            raise Wrong(msg)
    if not np.any(np.abs(v) > atol * scale):
        raise Wrong(f"{what} is zero.")
    grades = truth.algebra.grades
    order = truth.algebra.blade_order
    noise = 1e-9 * max(scale, float(np.abs(v).max()))
    g_v = sorted({grades[order[i]] for i in np.flatnonzero(np.abs(v) > noise)})
    g_t = sorted({grades[order[i]] for i in np.flatnonzero(np.abs(t) > noise)})
    if g_v != g_t:
        raise Wrong(f"the grade is wrong: your multivector has grade(s) {g_v}, the answer has grade(s) {g_t}.")
    if _close(v, -t, **tol):
        raise Wrong("the sign is wrong: you have minus the right multivector.")
    if parallel:
        text = _factor_text(abs(s))
        sign = "the sign is wrong, and " if s < 0 else ""
        raise Wrong(
            f"{sign}it is proportional to the right multivector, but the scale is off{': ' + text if text else ''}."
        )
    off = [names[i] for i in range(len(names)) if not np.isclose(v[i], t[i], rtol=rtol, atol=tol["atol"])]
    shown = ", ".join(off[:4]) + (f" and {len(off) - 4} more" if len(off) > 4 else "")
    raise Wrong(f"the grades are right but coefficients are off (blades {shown}).")


def as_expression(value, symbols: dict, what: str):
    sp = _sympy()
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
    if isinstance(value, bool) or not (_is_sympy(value) or isinstance(value, numbers.Number)):
        raise Malformed(f"{what} should be a SymPy expression, not a {type(value).__name__}")
    expr = sp.sympify(value)
    if not isinstance(expr, sp.Expr):
        raise Malformed(f"{what} should be a SymPy expression, not a {type(expr).__name__}")
    # match symbols by name: a student's sp.Symbol("rho") is the exercise's rho whatever its assumptions
    unknown = sorted(str(s) for s in expr.free_symbols if str(s) not in symbols)
    if unknown:
        raise Wrong(f"{what} uses {', '.join(unknown)}, which the exercise does not have (use {', '.join(symbols)}).")
    return expr.subs({s: symbols[str(s)] for s in expr.free_symbols})


def compare_expression(value, truth, symbols: dict, *, domain=(0.3, 2.0), hints=(), seed: int = 0, what="the answer"):
    """Raise :class:`Wrong` unless the SymPy expression (or string) ``value`` equals ``truth`` as a function.

    ``symbols`` maps names to the exercise's SymPy symbols.  Equality is decided by evaluating both at random
    points of ``domain`` (equivalent forms pass however they are written) and confirmed by ``simplify`` where
    it can; a constant ratio, an overall sign or a missing symbol is named.
    """
    sp = _sympy()
    expr = as_expression(value, symbols, what)
    syms = list(symbols.values())
    rng = np.random.default_rng(seed)
    pts = rng.uniform(*domain, size=(7, len(syms)))

    def values(e):
        f = sp.lambdify(syms, e, modules="numpy")
        out = np.array([complex(f(*p)) for p in pts])
        return out

    try:
        a, b = values(expr), values(truth)
    except (ZeroDivisionError, TypeError, ValueError, OverflowError) as exc:
        raise Wrong(f"{what} cannot be evaluated on the exercise's values ({type(exc).__name__}).") from None
    if not np.all(np.isfinite(a)):
        raise Wrong(f"{what} is not finite for some values of {', '.join(symbols)} where the answer is.")
    scale = max(float(np.abs(b).max()), 1e-300)
    if np.allclose(a, b, rtol=1e-9, atol=1e-12 * scale):
        return
    for cand, msg in hints:
        if np.allclose(a, values(cand), rtol=1e-9, atol=1e-12 * scale):
            raise Wrong(msg)
    if np.allclose(a, -b, rtol=1e-9, atol=1e-12 * scale):
        raise Wrong("the sign is wrong.")
    missing = sorted(str(s) for s in truth.free_symbols if s not in expr.free_symbols)
    if np.all(np.abs(b) > 1e-12 * scale):
        ratio = a / b
        if np.allclose(ratio, ratio[0], rtol=1e-9) and abs(ratio[0]) > 0:
            text = _factor_text(abs(ratio[0].real))
            sign = "the sign is wrong, and " if ratio[0].real < 0 else ""
            raise Wrong(f"{sign}it is off by a constant factor{': ' + text if text else ''}.")
    if missing:
        raise Wrong(f"the answer depends on {', '.join(missing)}, and your expression does not.")
    raise Wrong("it is a different function of " + ", ".join(symbols) + ".")
