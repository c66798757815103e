"""The comparisons behind :func:`cga_lessons.exercises.check`: read an answer, compare it, say what is off.

Each ``compare_*`` raises :class:`Wrong` (or :class:`Malformed`) with a message naming what is off (the sign,
the grade, the magnitude, the shape, the type, a known mistake passed as a hint) and returns None when the
answer is right.  The messages never print the truth.  A truth, tolerance or hint that is not what the helper
needs (NaN, the wrong shape, the wrong type: the exercise's author's input) is refused by the checks layer.
The reading of answers and the two exceptions live in :mod:`cga_lessons.exercises.answers`.  This module
registers no exercise.
"""

from __future__ import annotations

import math

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import Multivector

from .answers import (
    Malformed,
    Wrong,
    as_array,
    as_expression,
    as_float,
    hint_pairs,
    names_the_answer,
    settings,
    symbol_table,
)

__all__ = [
    "compare_number",
    "compare_vector",
    "compare_matrix",
    "compare_multivector",
    "compare_expression",
]


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


@names_the_answer("value", "truth")
def compare_number(value, truth: float, *, rtol: float = 1e-6, atol: float = 1e-9, hints=(), what="the answer"):
    """Raise :class:`Wrong` unless ``value`` is ``truth`` to float noise; diagnose sign, factor, square, units.

    ``hints`` is a sequence of ``(wrong_value, message)``: known mistakes with their own explanation.
    """
    func = "compare_number"
    rtol, atol = settings(func, rtol=rtol, atol=atol, what=what)
    truth = checks.real(truth, func, "truth")
    hints = hint_pairs(hints, func, lambda c: checks.real(c, func, "hints"))
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


@names_the_answer("value", "truth")
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
    func = "compare_vector"
    rtol, atol = settings(func, rtol=rtol, atol=atol, what=what, up_to_scale=up_to_scale, up_to_sign=up_to_sign)
    truth = checks.array(truth, func, "truth", (None,), at_least=1)
    hints = hint_pairs(hints, func, lambda c: checks.array(c, func, "hints", truth.shape))
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
        if _close(v, cand, **tol):
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


@names_the_answer("value", "truth")
def compare_matrix(
    value, truth, *, rtol: float = 1e-6, atol: float = 1e-9, up_to_scale=False, hints=(), what="the answer"
):
    """Raise :class:`Wrong` unless the 2-D ``value`` equals ``truth``; diagnoses shape, transpose, sign, scale."""
    func = "compare_matrix"
    rtol, atol = settings(func, rtol=rtol, atol=atol, what=what, up_to_scale=up_to_scale)
    truth = checks.array(truth, func, "truth", (None, None), at_least=1)
    if truth.shape[1] == 0:
        raise checks.fail(func, "truth", f"expected a matrix with at least one column, got shape {truth.shape}")
    hints = hint_pairs(hints, func, lambda c: checks.array(c, func, "hints", truth.shape))
    if checks.is_symbolic(value):
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
        if _close(v, cand, rtol, atol * scale):
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
        if checks.is_symbolic(c):
            if getattr(c, "free_symbols", None):
                raise Malformed(f"the {name} coefficient still contains symbols {sorted(map(str, c.free_symbols))}")
            c = float(c)
        try:
            out[i] = float(c)
        except (TypeError, ValueError):
            raise Malformed(f"the {name} coefficient is not a real number ({c!r:.40})") from None
    if not np.all(np.isfinite(out)):
        raise Wrong(f"{what} has NaN or infinite coefficients.")
    truth_arr = np.array([float(truth[n]) for n in names])
    return out, truth_arr, names


def _truth_multivector(truth, func: str):
    """``truth`` if it is one multivector with finite real coefficients, else the error."""
    checks.instance(truth, func, "truth", Multivector, "a Multivector")
    if truth.shape:
        raise checks.fail(func, "truth", f"expected one multivector, got a batch of shape {truth.shape}")
    for name, c in truth.items():
        if checks.is_symbolic(c) or not np.isfinite(c):
            raise checks.fail(func, "truth", f"the {name} coefficient is not a finite number ({c!r:.40})")
    return truth


@names_the_answer("value", "truth")
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
    func = "compare_multivector"
    rtol, atol = settings(func, rtol=rtol, atol=atol, what=what, up_to_scale=up_to_scale, up_to_sign=up_to_sign)
    _truth_multivector(truth, func)
    hints = hint_pairs(hints, func, lambda c: _mv_arrays(c, truth, "the hint")[0])
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
        if _close(v, cand, **tol):
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


def _sample_points(symbols, domain, seed, func: str) -> np.ndarray:
    """The 7 random points of ``domain`` (low, high) at which the two expressions are compared."""
    if isinstance(domain, (str, bytes)) or not hasattr(domain, "__len__") or len(domain) != 2:
        raise checks.fail(func, "domain", f"expected (low, high), got {domain!r:.40}")
    low, high = (checks.real(v, func, "domain") for v in domain)
    if not low < high:
        raise checks.fail(func, "domain", f"expected low < high, got {domain!r:.40}")
    seed = checks.integer(seed, func, "seed", low=0)
    return np.random.default_rng(seed).uniform(low, high, size=(7, len(symbols)))


def _truth_expression(truth, symbols: dict, func: str):
    """``truth`` as a finite SymPy expression in the exercise's ``symbols``."""
    import sympy as sp

    if isinstance(truth, bool) or not (checks.is_symbolic(truth) or isinstance(truth, (int, float))):
        raise checks.fail(func, "truth", f"expected a SymPy expression, got {type(truth).__name__} {truth!r:.40}")
    truth = sp.sympify(truth)
    if not isinstance(truth, sp.Expr) or truth.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        raise checks.fail(func, "truth", f"expected a finite SymPy expression, got {truth!r:.40}")
    unknown = truth.free_symbols - set(symbols.values())
    if unknown:
        raise checks.fail(func, "truth", f"uses {sorted(map(str, unknown))}, which are not among symbols")
    return truth


@names_the_answer("value", "truth")
def compare_expression(value, truth, symbols: dict, *, domain=(0.3, 2.0), hints=(), seed: int = 0, what="the answer"):
    """Raise :class:`Wrong` unless the SymPy expression (or string) ``value`` equals ``truth`` as a function.

    ``symbols`` maps names to the exercise's SymPy symbols.  Equality is decided by evaluating both at random
    points of ``domain`` (equivalent forms pass however they are written) and confirmed by ``simplify`` where
    it can; a constant ratio, an overall sign or a missing symbol is named.
    """
    import sympy as sp

    func = "compare_expression"
    symbols = symbol_table(symbols, func)
    checks.text(what, func, "what")
    truth = _truth_expression(truth, symbols, func)
    pts = _sample_points(symbols, domain, seed, func)
    syms = list(symbols.values())

    def values(e):
        f = sp.lambdify(syms, e, modules="numpy")
        with np.errstate(all="ignore"):
            return np.array([complex(f(*p)) for p in pts])

    try:
        b = values(truth)
    except (ArithmeticError, TypeError, ValueError, KeyError, NameError) as exc:
        raise checks.fail(func, "truth", f"cannot be evaluated on domain ({type(exc).__name__}: {exc})") from None
    if not np.all(np.isfinite(b)):
        raise checks.fail(func, "truth", f"is not finite at some points of domain {tuple(domain)}")
    hints = hint_pairs(hints, func, lambda c: values(as_expression(c, symbols, "the hint")))
    expr = as_expression(value, symbols, what)
    try:
        a = values(expr)
    except (ArithmeticError, TypeError, ValueError, KeyError, NameError) as exc:
        raise Wrong(f"{what} cannot be evaluated on the exercise's values ({type(exc).__name__}).") from None
    if not np.all(np.isfinite(a)):
        raise Wrong(f"{what} is not finite for some values of {', '.join(symbols)} where the answer is.")
    scale = max(float(np.abs(b).max()), 1e-300)
    if np.allclose(a, b, rtol=1e-9, atol=1e-12 * scale):
        return
    for cand, msg in hints:
        if np.allclose(a, cand, rtol=1e-9, atol=1e-12 * scale):
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
