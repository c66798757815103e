"""The fuzz of bad inputs: each public callable, called with one argument spoiled at a time.

A :class:`Case` is one valid call of a public function (or a class, or a method): the function and the keyword
arguments that make it work.  :func:`bad_values` derives the spoiled variants of every argument from the type of
its valid value (a float becomes NaN, inf, 1e300, None, a string, a list; an array gets a NaN, an inf, a column too
few or too many, no rows, huge magnitudes; a multivector becomes None, a string, or a multivector with NaN or inf
coefficients; a path becomes a missing file, a folder, an empty file, garbage, a truncated gzip ...), and a case may
add values of its own (``extra``) and entities of the wrong kind that must be refused (``kinds``).

:func:`outcome` sorts what each call did:

- ``clear``: a ``ValueError`` subclass of the package (:class:`~cga_lessons.algebra.GeometryError`) whose message
  names the function and the argument;
- ``accepted``: the call returned, and nothing in its result is NaN or inf (a bad-looking value the function can
  honestly use: ``None`` for an optional argument, a huge but representable scale, ...);
- ``unclear``: any other exception, or a ``ValueError`` that does not say which function and which argument;
- ``silent``: the call returned NaN or inf somewhere in its result;
- ``wrongly accepted``: an entity of a kind the function cannot read (a circle given to a line's reader), or in a
  strict case a value of the wrong type, was accepted;
- ``hung``: the call ran past :data:`TIME_LIMIT` seconds.

The test (``tests/test_fuzz.py``) requires no ``unclear``, ``silent``, ``wrongly accepted`` or ``hung``
outcome; ``python tests/fuzz/report.py`` lists every input tried and what it did.
"""

from __future__ import annotations

import atexit
import copy
import dataclasses
import gzip
import inspect
import itertools
import math
import numbers
import shutil
import signal
import tempfile
import warnings
from collections import Counter
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from cga_lessons.algebra import GeometryError, Multivector

TIME_LIMIT = 20.0  # seconds; a bad input must be refused or finished well within this
FAILURES = ("unclear", "silent", "wrongly accepted", "hung")
TALLY: Counter = Counter()  # outcome -> count, over the cases run in this process (the test's summary line)
CALLS: Counter = Counter()  # "cases" and "inputs" run


@dataclass
class Case:
    """One valid call, and how to spoil it.

    ``func``: the callable (a function, a class, or an unbound method with ``self`` among ``args``).
    ``args``: keyword arguments of a valid call, or a function returning them (for values that a call changes).
    ``label``: the name the error message must contain (default: the function's or class's ``__name__``).
    ``positional``: names passed positionally, in this order (for positional-only parameters, ``self``, ``*args``).
    ``skip``: argument -> why the values its type suggests are not tried (its ``extra`` and ``kinds`` still are;
    ``self`` is never spoiled).
    ``extra``: argument -> more bad values to try.
    ``kinds``: argument -> values of a wrong kind that must be refused (accepting one is a failure).
    ``nonfinite_ok``: why a NaN/inf in the result is the documented answer (``None``: it is not).
    ``name``: the case's id (default: the label).
    ``strict``: a value of the wrong type (None for a number, a string, a list for a scalar, a bool, a complex
    number, NaN, a fraction for a whole number) must be refused, not merely survived; ``allow``: argument -> the
    descriptions of such values that are fine after all (``"None"`` for an optional setting).
    """

    func: Callable
    args: dict | Callable[[], dict] = field(default_factory=dict)
    label: str | None = None
    positional: tuple = ()
    skip: dict = field(default_factory=dict)
    extra: dict = field(default_factory=dict)
    kinds: dict = field(default_factory=dict)
    nonfinite_ok: str | None = None
    name: str | None = None
    strict: bool = False
    allow: dict = field(default_factory=dict)

    @property
    def the_label(self) -> str:
        return self.label or getattr(self.func, "__name__", repr(self.func))

    @property
    def id(self) -> str:
        return self.name or self.the_label

    def fresh_args(self) -> dict:
        return self.args() if callable(self.args) else copy.deepcopy(self.args)


class Hung(Exception):
    pass


@contextmanager
def time_limit(seconds: float):
    """Raise :class:`Hung` in the main thread after ``seconds`` (SIGALRM; no limit where there is none)."""
    if not hasattr(signal, "SIGALRM"):  # pragma: no cover (Windows)
        yield
        return

    def on_alarm(signum, frame):
        raise Hung()

    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


# ------------------------------------------------------------------ bad values by the type of the valid one
def temporary_folder(prefix: str) -> Path:
    """A new folder for the files the cases write and read, removed when the test process ends."""
    folder = Path(tempfile.mkdtemp(prefix=prefix))
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    return folder


_FILES = temporary_folder("cga-fuzz-")
_MISSING = itertools.count()


def fresh_path(name: str) -> Path:
    """A path ``name`` that does not exist yet, in a new folder of its own (for the cases of writers)."""
    return Path(tempfile.mkdtemp(dir=_FILES)) / name


def _bad_files() -> list:
    """A missing file, a folder, an empty file, binary garbage, text garbage, a truncated gzip."""
    empty = _FILES / "empty.log"
    empty.write_bytes(b"")
    garbage = _FILES / "garbage.log"
    garbage.write_bytes(bytes(range(256)) * 4)
    text = _FILES / "text.log"
    text.write_text("FLASER 3 not numbers here\nODOM x y\n\x00\n", encoding="utf-8")
    trunc = _FILES / "truncated.gz"
    trunc.write_bytes(gzip.compress(b"FLASER 180 " + b"1.0 " * 400)[:40])
    missing = _FILES / f"no-such-file-{next(_MISSING)}.log"  # a new name each time: a writer may create it
    return [
        ("a missing file", missing),
        ("a folder", _FILES),
        ("an empty file", empty),
        ("binary garbage", garbage),
        ("text garbage", text),
        ("a truncated gzip", trunc),
    ]


def _array_variants(a: np.ndarray) -> list:
    out = []
    shape = f"{a.shape}"
    if a.size:
        nan = a.copy()
        nan.flat[a.size // 2] = np.nan
        inf = a.copy()
        inf.flat[0] = np.inf
        out += [(f"{shape} with a NaN", nan), (f"{shape} with an inf", inf)]
        out.append((f"{shape} times 1e300", a * 1e300 + 1e300))
    if a.ndim >= 1 and a.shape[-1] > 1:
        out.append((f"{a[..., :-1].shape}: a column short", a[..., :-1]))
    if a.ndim >= 1:
        more = np.concatenate([a, a[..., :1]], axis=-1) if a.shape[-1] else np.zeros(a.shape[:-1] + (1,))
        out.append((f"{more.shape}: a column more", more))
        out.append((f"{(0,) + a.shape[1:]}: empty", np.zeros((0,) + a.shape[1:])))
    out += [("None", None), ("'text'", "text"), (f"{shape} complex", a.astype(complex) + 1j)]
    if a.ndim == 2 and len(a) >= 2:
        out.append(("ragged rows", [list(a[0]), list(a[1][:-1])]))
    return out


def _multivector_variants(X: Multivector) -> list:
    coeffs = dict(X._c) if X._c else {0: 1.0}
    blade = next(iter(coeffs))

    def with_value(v):
        c = dict(coeffs)
        c[blade] = c[blade] * 0 + v if isinstance(c[blade], np.ndarray) else v
        return Multivector(X.algebra, c)

    return [
        ("None", None),
        ("'text'", "text"),
        ("an array (32,)", np.zeros(32)),
        ("a multivector with NaN", with_value(np.nan)),
        ("a multivector with inf", with_value(np.inf)),
    ]


def _plain(values) -> list:
    return [(_describe(v), v) for v in values]


def bad_values(valid) -> list:
    """``(description, value)`` of the spoiled variants of one valid argument value, chosen by its type."""
    if isinstance(valid, (bool, np.bool_)):
        return _plain([None, "yes", 2, math.nan])
    if isinstance(valid, numbers.Integral):
        return _plain([None, "3", 2.5, math.nan, math.inf, -1, True])
    if isinstance(valid, numbers.Real):
        return _plain([math.nan, math.inf, -math.inf, None, "1.0", 1j, [1.0, 2.0], 1e300, -1e300, True])
    if isinstance(valid, str):
        return _plain([None, 3, "no-such-option", ""])
    if isinstance(valid, Path):
        return _bad_files()
    if isinstance(valid, Multivector):
        return _multivector_variants(valid)
    if isinstance(valid, np.ndarray) and valid.dtype.kind in "biuf":
        return _array_variants(valid.astype(float))
    if isinstance(valid, (list, tuple)) and valid:
        try:
            a = np.asarray(valid)
        except ValueError:  # ragged: not one array
            a = None
        if a is not None and a.dtype.kind in "biuf":
            return _array_variants(a.astype(float))
    return _plain([None, "text", 1.0])


# ------------------------------------------------------------------ what a call did
def nonfinite_paths(value, depth: int = 0, at: str = "") -> set[str]:
    """Where NaN or inf is in a result: short paths such as ``.delta``, ``[2]``, ``blade 8`` (``""``: the value)."""
    if depth > 4 or value is None or isinstance(value, (str, bytes, bool, type)):
        return set()
    if isinstance(value, numbers.Number) and not isinstance(value, numbers.Integral):
        try:
            return set() if math.isfinite(abs(complex(value))) else {at}
        except (TypeError, ValueError):
            return set()
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc" and not np.all(np.isfinite(value)):
            return {at}
        if value.dtype.kind == "O" and value.size <= 1000:
            return set().union(*(nonfinite_paths(v, depth + 1, at + "[]") for v in value.flat))
        return set()
    if isinstance(value, Multivector):
        out = set()
        for k, v in value._c.items():
            if not hasattr(v, "free_symbols"):
                out |= nonfinite_paths(v, depth + 1, f"{at} blade {k}")
        return out
    if isinstance(value, dict):
        items = list(value.items())[:200]
        return set().union(set(), *(nonfinite_paths(v, depth + 1, f"{at}[{k!r}]") for k, v in items))
    if isinstance(value, (list, tuple)):
        items = list(enumerate(value[:200]))
        return set().union(set(), *(nonfinite_paths(v, depth + 1, f"{at}[{i}]") for i, v in items))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = dataclasses.fields(value)
        return set().union(
            set(), *(nonfinite_paths(getattr(value, f.name, None), depth + 1, f"{at}.{f.name}") for f in fields)
        )
    return set()


def call(case: Case, kwargs: dict):
    """Call the case's function with ``kwargs`` (its positional names passed by position)."""
    pos = [kwargs.pop(n) for n in case.positional if n in kwargs]
    star = kwargs.pop("*args", ())
    return case.func(*pos, *star, **kwargs)


def _close_figures():
    import sys

    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:
        plt.close("all")


def attempt(case: Case, arg: str | None, bad):
    """Call the case with ``arg`` set to ``bad`` (``arg`` None: the valid call): ``("returned", result)`` or
    ``("raised", exception)`` or ``("hung", None)``."""
    kwargs = case.fresh_args()
    if arg is not None:
        kwargs[arg] = bad
    try:
        with warnings.catch_warnings(), time_limit(TIME_LIMIT):
            warnings.simplefilter("ignore")
            return "returned", call(case, kwargs)
    except Hung:
        return "hung", None
    except Exception as exc:  # noqa: BLE001 (sorting every kind of failure is the point)
        return "raised", exc
    finally:
        _close_figures()


def outcome(case: Case, arg: str, bad, *, must_refuse: bool = False, expected=frozenset()) -> tuple[str, str]:
    """``(status, detail)`` of the case called with ``arg`` set to ``bad``.

    ``expected``: where the valid call's own result is NaN or inf (a documented ``inf`` default, say); a spoiled
    call's NaN or inf elsewhere is silent.
    """
    how, what = attempt(case, arg, bad)
    if how == "hung":
        return "hung", f"ran past {TIME_LIMIT:g} s"
    if how == "raised":
        msg = str(what)
        if not isinstance(what, GeometryError):
            return "unclear", f"{type(what).__name__}: {msg[:160]}"
        label, named = case.the_label, shown_name(case.func, arg) in msg
        if label in msg and named:
            return "clear", msg
        missing = " and ".join(w for w, ok in ((repr(label), label in msg), (repr(arg), named)) if not ok)
        return "unclear", f"{type(what).__name__} does not name {missing}: {msg}"
    where = nonfinite_paths(what) - set(expected)
    if where and case.nonfinite_ok is None:
        return "silent", f"NaN or inf in the result at {', '.join(sorted(where)[:3]) or 'the value'}"
    if must_refuse:
        return "wrongly accepted", f"accepted {_describe(bad)}"
    return "accepted", f"returned {type(what).__name__}"


def shown_name(func, arg: str) -> str:
    """The name a message gives an argument: ``"*args"`` is the function's own name for its ``*parameter``."""
    if arg != "*args":
        return arg
    try:
        params = inspect.signature(func).parameters.values()
    except (TypeError, ValueError):
        return arg
    return next((p.name for p in params if p.kind is inspect.Parameter.VAR_POSITIONAL), arg)


def _describe(value) -> str:
    if isinstance(value, Multivector):
        try:
            from cga_lessons import conformal as cga

            return f"a {cga.classify(value).kind}" if hasattr(cga, "classify") else "a multivector"
        except Exception:  # noqa: BLE001
            return "a multivector"
    if isinstance(value, np.ndarray):
        return f"array{value.shape}"
    r = repr(value)
    return r if len(r) < 40 else r[:37] + "..."


def wrong_type(valid, bad) -> bool:
    """Whether ``bad`` is plainly of the wrong type for an argument whose valid value is ``valid``."""
    if isinstance(bad, float) and math.isnan(bad):
        return True
    if bad is None:
        return valid is not None
    if isinstance(valid, (bool, np.bool_)):
        return not isinstance(bad, (bool, np.bool_))
    if isinstance(bad, (bool, np.bool_, str, complex, list)):
        return not isinstance(valid, type(bad))
    if isinstance(valid, numbers.Integral) and isinstance(bad, float):
        return not bad.is_integer()
    return False


def tries(case: Case):
    """Every ``(arg, description, bad value, must_refuse)`` the fuzz tries on a case."""
    valid = case.fresh_args()
    for arg, value in valid.items():
        if arg == "self":
            continue
        allowed = case.allow.get(arg, ())
        generated = [] if arg in case.skip else bad_values(value)
        for desc, bad in generated + _plain(case.extra.get(arg, ())):
            yield arg, desc, bad, case.strict and desc not in allowed and wrong_type(value, bad)
        for bad in case.kinds.get(arg, ()):
            yield arg, _describe(bad), bad, True
    for arg, values in case.extra.items():
        if arg not in valid:
            for bad in values:
                yield arg, _describe(bad), bad, False


def run_case(case: Case) -> list[tuple[str, str, str, str]]:
    """``(arg, bad value, status, detail)`` of the valid call (arg ``""``) and of every spoiled one."""
    how, what = attempt(case, None, None)
    if how == "returned":
        expected, valid = nonfinite_paths(what), ("valid", f"returned {type(what).__name__}")
    else:
        expected, valid = set(), (how, f"{type(what).__name__}: {str(what)[:160]}")
    rows = [("", "(valid call)", *valid)]
    for arg, desc, bad, must_refuse in tries(case):
        status, detail = outcome(case, arg, bad, must_refuse=must_refuse, expected=expected)
        rows.append((arg, desc, status, detail))
    CALLS["cases"] += 1
    CALLS["inputs"] += len(rows) - 1
    TALLY.update(r[2] for r in rows[1:])
    return rows


def problems_of(rows) -> list[str]:
    """The rows that fail the fuzz, as readable lines (the valid call must work)."""
    out = []
    for arg, bad, status, detail in rows:
        if arg == "" and status != "valid":
            out.append(f"the valid call: {status}: {detail}")
        elif status in FAILURES:
            out.append(f"{arg} = {bad}: {status}: {detail}")
    return out


def public_callables(module) -> dict[str, Any]:
    """``name -> object`` of the functions and classes in a module's ``__all__``."""
    out = {}
    for name in getattr(module, "__all__", ()):
        obj = getattr(module, name)
        if inspect.isfunction(obj) or inspect.isclass(obj) or inspect.isbuiltin(obj):
            out[name] = obj
    return out
