"""The one checking layer: every public function checks its arguments here.

Each check takes the value, the name of the public function being called
(``func``) and the name of its argument (``name``), and either returns the
value in the form the caller computes with (a float, an int, a float array
of a known shape, a :class:`pathlib.Path`) or raises
:class:`~cga_lessons.errors.InvalidInputError` with the message
``"func: name: problem"``.  Every error is a ``ValueError``, so a user's
``except ValueError`` catches all of them; the message tells which call,
which argument and what is wrong with it.

Layer 0: this module imports only NumPy and :mod:`cga_lessons.errors`.
Checks that need a higher layer (the kind of a conformal entity, a map or a
camera) are written in that layer on top of :func:`fail` and
:func:`instance`, so that the wording stays the same everywhere.
"""

from __future__ import annotations

import math
import numbers
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from cga_lessons.errors import DegenerateGeometryError, GeometryError, InvalidInputError

__all__ = ["fail", "degenerate", "is_symbolic", "real", "integer", "flag", "choice", "text", "array", "batch", "rows",
           "same_length", "instance", "finite_result", "magnitude", "MAX_MAGNITUDE", "generator", "seed", "relabel",
           "existing_path", "new_path", "record", "vector3", "length", "measure", "short"]  # fmt: skip

#: The largest coordinate a geometric computation accepts by default: a float's range ends near 1.8e308, so the
#: square of a number beyond about 1.3e154 overflows, and sums of a few such squares (a squared distance, the
#: e+ and e- coefficients of a conformal point) need a little room below that.
MAX_MAGNITUDE = 1e150


def fail(func: str, name: str, problem: str) -> InvalidInputError:
    """The error for a bad argument, ready to raise: ``"func: name: problem"``.

    >>> str(fail("up", "x", "contains NaN or inf"))
    'up: x: contains NaN or inf'
    """
    return InvalidInputError(f"{func}: {name}: {problem}")


def degenerate(func: str, name: str, problem: str) -> DegenerateGeometryError:
    """The error for well-formed input that describes degenerate geometry (coincident points, ...)."""
    return DegenerateGeometryError(f"{func}: {name}: {problem}")


def is_symbolic(value) -> bool:
    """Whether ``value`` is a SymPy object (checked without importing SymPy)."""
    return type(value).__module__.split(".")[0] == "sympy"


def short(value) -> str:
    """``repr(value)``, cut to 40 characters: how an error message quotes a bad value.

    >>> short("x" * 50)
    "'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx..."
    """
    r = repr(value)
    return r if len(r) <= 40 else r[:37] + "..."


def _is_bool(value) -> bool:
    return isinstance(value, (bool, np.bool_))


def real(
    value,
    func: str,
    name: str,
    *,
    low: float | None = None,
    high: float | None = None,
    strict_low: bool = False,
    strict_high: bool = False,
    symbolic: bool = False,
):
    """``value`` as a finite float within ``[low, high]`` (open ends if ``strict_*``).

    Refuses bools, strings, None, complex numbers, arrays, NaN and inf.  With
    ``symbolic=True`` a SymPy expression is returned unchanged (range not checked).

    >>> real(2, "f", "x", low=0)
    2.0
    >>> real(-1, "f", "x", low=0)
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: x: must be >= 0, got -1
    """
    if symbolic and is_symbolic(value):
        return value
    if _is_bool(value):
        raise fail(func, name, f"must be a real number, got the bool {value!r}")
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (complex, np.complexfloating)) or not isinstance(value, numbers.Real):
        raise fail(func, name, f"must be a real number, got {type(value).__name__} {short(value)}")
    try:
        x = float(value)
    except OverflowError:
        x = math.inf
    if not math.isfinite(x):
        raise fail(func, name, f"is NaN or inf ({short(value)})")
    if low is not None and (x < low or (strict_low and x == low)):
        raise fail(func, name, f"must be {'>' if strict_low else '>='} {low}, got {short(value)}")
    if high is not None and (x > high or (strict_high and x == high)):
        raise fail(func, name, f"must be {'<' if strict_high else '<='} {high}, got {short(value)}")
    return x


def integer(value, func: str, name: str, *, low: int | None = None, high: int | None = None) -> int:
    """``value`` as an int within ``[low, high]``; a float is accepted only if it is integral.

    >>> integer(3.0, "f", "n")
    3
    >>> integer(2.5, "f", "n")
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: n: must be a whole number, got 2.5
    """
    if _is_bool(value):
        raise fail(func, name, f"must be a whole number, got the bool {value!r}")
    if isinstance(value, numbers.Integral):
        n = int(value)
    else:
        x = real(value, func, name)
        if x != int(x):
            raise fail(func, name, f"must be a whole number, got {short(value)}")
        n = int(x)
    if low is not None and n < low:
        raise fail(func, name, f"must be >= {low}, got {n}")
    if high is not None and n > high:
        raise fail(func, name, f"must be <= {high}, got {n}")
    return n


def flag(value, func: str, name: str) -> bool:
    """``value`` as a bool; only True/False (or NumPy's bools) are accepted."""
    if not _is_bool(value):
        raise fail(func, name, f"must be True or False, got {short(value)}")
    return bool(value)


def choice(value, func: str, name: str, options) -> str:
    """``value`` if it is one of ``options`` (strings), else an error listing them."""
    options = tuple(options)
    if not isinstance(value, str) or value not in options:
        raise fail(func, name, f"must be one of {', '.join(map(repr, options))}; got {short(value)}")
    return value


def text(value, func: str, name: str, *, empty: bool = False) -> str:
    """``value`` as a string (non-empty unless ``empty``)."""
    if not isinstance(value, str):
        raise fail(func, name, f"must be a string, got {type(value).__name__} {short(value)}")
    if not empty and not value.strip():
        raise fail(func, name, "must not be empty")
    return value


def _as_float_array(value, func: str, name: str) -> np.ndarray:
    if value is None or isinstance(value, (str, bytes)):
        raise fail(func, name, f"must be numbers, got {short(value)}")
    try:
        raw = np.asarray(value)
        if raw.dtype.kind == "c":
            raise fail(func, name, "must be real numbers, got complex ones")
        a = np.asarray(raw, dtype=float)
    except OverflowError:
        raise fail(func, name, "contains NaN or inf (a number too large for a float)") from None
    except (TypeError, ValueError) as exc:
        if isinstance(exc, InvalidInputError):
            raise
        what = "rows of different lengths" if "inhomogeneous" in str(exc) else short(value)
        raise fail(func, name, f"must be an array of numbers, got {what}") from None
    return a


def _shape_text(shape) -> str:
    parts = ["N" if s is None else str(s) for s in shape]
    return "(" + ", ".join(parts) + ("," if len(parts) == 1 else "") + ")"


def _values(a: np.ndarray, func: str, name: str, limit, why: str) -> None:
    """Refuse NaN or inf in ``a`` and, with a ``limit``, magnitudes beyond it (:func:`magnitude`'s words).

    One pass for what a call costs: a few values are read as Python floats; a large array by its maximum and minimum
    (NaN makes both comparisons false, inf the strict ones), with no array of flags made.
    """
    if a.size == 0:
        return
    if a.size <= 16:
        vals = a.ravel().tolist()
        if not all(map(math.isfinite, vals)):
            raise fail(func, name, "contains NaN or inf")
        big = max(map(abs, vals))
    else:
        hi, lo = float(a.max()), float(a.min())
        if not (hi < math.inf and lo > -math.inf):
            raise fail(func, name, "contains NaN or inf")
        big = max(hi, -lo)
    if limit is not None and big > limit:
        raise fail(func, name, f"magnitudes up to {big:.3g}, beyond {limit:.3g}: {why}")


def array(
    value,
    func: str,
    name: str,
    shape: tuple,
    *,
    finite: bool = True,
    at_least: int = 0,
    limit: float | None = None,
    why: str = "squares overflow a float",
) -> np.ndarray:
    """``value`` as a float array of ``shape`` (``None`` matches any length), finite by default.

    ``at_least`` is the least length of the first axis; ``limit`` (with its reason ``why``) the largest magnitude
    accepted, as :func:`magnitude` says it.

    >>> array([[1, 2]], "f", "uv", (None, 2)).shape
    (1, 2)
    >>> array([1, 2], "f", "uv", (None, 2))
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: uv: expected shape (N, 2), got (2,)
    """
    a = _as_float_array(value, func, name)
    if a.ndim != len(shape) or any(s is not None and s != d for s, d in zip(shape, a.shape)):
        raise fail(func, name, f"expected shape {_shape_text(shape)}, got {a.shape}")
    if finite:
        _values(a, func, name, limit, why)
    if a.ndim and len(a) < at_least:
        raise fail(func, name, f"expected at least {at_least} rows, got {len(a)}")
    return a


def batch(
    value,
    func: str,
    name: str,
    tail: tuple,
    *,
    finite: bool = True,
    at_least: int = 0,
    limit: float | None = None,
    why: str = "squares overflow a float",
):
    """``value`` of shape ``tail`` (one item) or ``(N,) + tail`` (a batch), as ``(array (N,)+tail, single)``;
    finite, and within ``limit`` when one is given (as :func:`array`).

    >>> a, single = batch([1, 2, 3], "f", "x", (3,))
    >>> a.shape, single
    ((1, 3), True)
    """
    a = _as_float_array(value, func, name)
    single = a.shape == tuple(tail)
    if single:
        a = a[None]
    if a.ndim != len(tail) + 1 or a.shape[1:] != tuple(tail):
        one, many = _shape_text(tail), _shape_text((None, *tail))
        raise fail(func, name, f"expected shape {one} or {many}, got {a.shape}")
    if finite:
        _values(a, func, name, limit, why)
    if len(a) < at_least:
        raise fail(func, name, f"expected at least {at_least} items, got {len(a)}")
    return a, single


def rows(value, func: str, name: str, width: int, *, at_least: int = 0) -> np.ndarray:
    """``value`` as a finite float array of shape (N, width) with at least ``at_least`` rows."""
    return array(value, func, name, (None, width), at_least=at_least)


def same_length(func: str, **named) -> int:
    """The common length of the named arrays, or an error naming the ones that differ.

    >>> same_length("f", uv=np.zeros((3, 2)), xyz=np.zeros((4, 3)))
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: uv, xyz: must have the same length, got 3 and 4
    """
    lengths = {k: len(v) for k, v in named.items()}
    if len(set(lengths.values())) > 1:
        got = " and ".join(map(str, lengths.values()))
        raise fail(func, ", ".join(lengths), f"must have the same length, got {got}")
    return next(iter(lengths.values()), 0)


def instance(value, func: str, name: str, types, what: str):
    """``value`` if it is an instance of ``types``; else an error saying ``what`` was expected."""
    if not isinstance(value, types):
        raise fail(func, name, f"expected {what}, got {type(value).__name__} {short(value)}")
    return value


def record(obj, **checkers) -> None:
    """Check and normalise fields of the frozen dataclass ``obj`` from its ``__post_init__``: for each
    ``name=check``, the field becomes ``check(value, func, name)``, ``func`` the class's name; a field whose default
    is None is left alone while it is None (an optional field)."""
    func = type(obj).__name__
    fields = getattr(type(obj), "__dataclass_fields__", {})
    for name, check in checkers.items():
        value = getattr(obj, name)
        if value is None and name in fields and fields[name].default is None:
            continue
        object.__setattr__(obj, name, check(value, func, name))


def vector3(value, func: str, name: str) -> np.ndarray:
    """A finite 3-vector as a float array (3,)."""
    return array(value, func, name, (3,))


def length(value, func: str, name: str) -> float:
    """A finite length (or radius, or count of units), at least 0."""
    return real(value, func, name, low=0.0)


def measure(value, func: str, name: str) -> float:
    """A finite real, or NaN: the marker of a table entry that does not apply (a radius error for a plane)."""
    if isinstance(value, float | np.floating) and math.isnan(value):
        return math.nan
    return real(value, func, name)


def finite_result(value, func: str, what: str = "the result"):
    """``value`` (a number or an array) if finite; else an error: the input overflowed the computation.

    For results whose inputs were all finite but whose computation ran out of
    float range (squares of 1e200, ...): nothing returns NaN or inf silently.
    """
    a = np.asarray(value)
    if a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{func}: {what} overflows a float (the input's magnitudes are too large)")
    return value


def existing_path(value, func: str, name: str, *, kind: str = "file") -> Path:
    """``value`` (str or path) as a :class:`Path` to an existing ``kind`` ("file" or "folder")."""
    if not isinstance(value, (str, Path)) or (isinstance(value, str) and not value):
        raise fail(func, name, f"expected a path, got {short(value)}")
    p = Path(value)
    if kind == "file" and not p.is_file():
        raise fail(func, name, f"no such file: {p}" if not p.exists() else f"is not a file: {p}")
    if kind == "folder" and not p.is_dir():
        raise fail(func, name, f"no such folder: {p}")
    return p


def new_path(value, func: str, name: str, *, overwrite: bool = False) -> Path:
    """``value`` as a :class:`Path` to write; an existing file is refused unless ``overwrite``."""
    if not isinstance(value, (str, Path)) or (isinstance(value, str) and not value):
        raise fail(func, name, f"expected a path, got {short(value)}")
    p = Path(value)
    if p.is_dir():
        raise fail(func, name, f"is a folder: {p}")
    if p.exists() and not overwrite:
        raise fail(func, name, f"{p} exists (pass overwrite=True to replace it)")
    if not p.parent.is_dir():
        raise fail(func, name, f"no such folder: {p.parent}")
    return p


def magnitude(value, func: str, name: str, *, limit: float = MAX_MAGNITUDE, why: str = "squares overflow a float"):
    """``value`` (an array or a number, already finite) if no entry exceeds ``limit`` in size; else an error saying
    ``why`` such magnitudes cannot be computed with.

    >>> magnitude([1e200, 0], "f", "x")
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: f: x: magnitudes up to 1e+200, beyond 1e+150: squares overflow a float
    """
    a = np.abs(np.asarray(value, dtype=float))
    if a.size and float(np.max(a)) > limit:
        raise fail(func, name, f"magnitudes up to {float(np.max(a)):.3g}, beyond {limit:.3g}: {why}")
    return value


def generator(value, func: str, name: str = "rng", *, seeds: bool = False, optional: bool = False):
    """A :class:`numpy.random.Generator`: ``value`` itself; with ``seeds`` an int seed >= 0 makes one
    (``numpy.random.default_rng(seed)``); with ``optional`` None stays None."""
    if value is None and optional:
        return None
    if isinstance(value, np.random.Generator):
        return value
    if seeds and isinstance(value, numbers.Integral) and not _is_bool(value):
        return np.random.default_rng(integer(value, func, name, low=0))
    what = "a numpy.random.Generator (numpy.random.default_rng(seed))"
    what += ", an int seed >= 0" if seeds else ""
    what += " or None" if optional else ""
    raise fail(func, name, f"expected {what}, got {type(value).__name__} {short(value)}")


def seed(value, func: str, name: str = "seed"):
    """A random seed: None or a whole number >= 0."""
    return None if value is None else integer(value, func, name, low=0)


@contextmanager
def relabel(func: str, name: str):
    """Within the block, a package error raised by a call made with argument ``name`` of ``func`` is re-raised as
    ``func``'s: ``"func: name: problem (said by inner)"``, so the user is told which of their calls was at fault.

    >>> with relabel("outer", "point"):
    ...     raise fail("down", "X", "is not null")
    Traceback (most recent call last):
    ...
    cga_lessons.algebra.InvalidInputError: outer: point: is not null (said by down)
    """
    try:
        yield
    except GeometryError as exc:
        parts = str(exc).split(": ", 2)
        said = f" (said by {parts[0]})" if len(parts) == 3 and parts[0] != func else ""
        problem = parts[-1] if len(parts) == 3 else str(exc)
        raise type(exc)(f"{func}: {name}: {problem}{said}") from None
