"""The record of a derivation: its :class:`Check` steps, the :class:`Derivation` that holds them, and the
decorator :func:`derivation` that computes each derivation once per process.

A derivation function of :mod:`cga_lessons.symbolic` builds the thesis's objects with SymPy coefficients and
records each printed step as a :class:`Check` (both sides kept for display) in a :class:`Derivation`.  The
comparisons themselves (:func:`~cga_lessons.symbolic.core.same`, exact and modulo relations) are in
:mod:`cga_lessons.symbolic.core`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

from cga_lessons import checks
from cga_lessons.algebra import InvalidInputError

from .core import display, ring_or_none, same, side

__all__ = ["Check", "Derivation", "CheckNameError", "derivation"]


class CheckNameError(InvalidInputError, KeyError):
    """A derivation has no check of this name (also a ``KeyError``, as a missing key of a mapping)."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


def derivation(fn):
    """Decorator of a derivation function: computed once per process, each call returns a copy of the result.

    The checks are exact, so the result never changes; the copy (:meth:`Derivation.copy`) has its own list of
    checks and dict of values, so that adding to one does not change the next call's.
    """
    done: dict = {}

    @functools.wraps(fn)
    def wrapper(*args):
        d = done.get(args)
        if d is None:
            d = done[args] = fn(*args)
        return d.copy()

    return wrapper


@dataclass(frozen=True)
class Check:
    """One step of a derivation: ``lhs == rhs`` and whether it holds.

    Attributes
    ----------
    name : str
        Short key, e.g. ``"2.56 e0 E = e0 (printed)"``.
    label : str
        The thesis's equation number, e.g. ``"2.56"`` (``"table 2.2"`` for a table).
    raw_lhs, raw_rhs
        The two sides as computed (SymPy expressions, multivectors, or ring
        elements of a :class:`Ring`); the properties ``lhs`` and ``rhs``
        give them with SymPy coefficients, for display.
    holds : bool
        Whether ``lhs == rhs`` identically.
    expected : bool
        ``True`` for a correct statement, ``False`` for a printed erratum
        (which must then fail).
    note : str
        What the step says, in words.
    """

    name: str
    label: str
    raw_lhs: object
    raw_rhs: object
    holds: bool
    expected: bool = True
    note: str = ""

    def __post_init__(self):
        for name in ("name", "label"):
            checks.text(getattr(self, name), "Check", name)
        side(self.raw_lhs, "Check", "raw_lhs")
        side(self.raw_rhs, "Check", "raw_rhs")
        checks.flag(self.holds, "Check", "holds")
        checks.flag(self.expected, "Check", "expected")
        checks.text(self.note, "Check", "note", empty=True)

    @property
    def lhs(self):
        """Left side, with SymPy coefficients (converted from ring elements on access)."""
        return display(self.raw_lhs)

    @property
    def rhs(self):
        """Right side, with SymPy coefficients."""
        return display(self.raw_rhs)

    @property
    def ok(self) -> bool:
        """True when the check came out as expected (identity holds, erratum fails)."""
        return self.holds == self.expected


@dataclass
class Derivation:
    """Result of a derivation: the checks of its steps and its named values.

    ``holds`` is true when every correct identity holds and every printed
    erratum fails.  Index by check name: ``d["2.45"].holds``.
    """

    title: str
    labels: tuple
    checks: list = field(default_factory=list)
    values: dict = field(default_factory=dict)

    def __post_init__(self):
        checks.text(self.title, "Derivation", "title")
        if not isinstance(self.labels, (tuple, list)) or not all(isinstance(v, str) and v for v in self.labels):
            raise checks.fail("Derivation", "labels", f"expected a tuple of equation labels, got {self.labels!r:.40}")
        if not isinstance(self.checks, list) or not all(isinstance(c, Check) for c in self.checks):
            raise checks.fail("Derivation", "checks", f"expected a list of Check, got {self.checks!r:.40}")
        if not isinstance(self.values, dict):
            raise checks.fail("Derivation", "values", f"expected a dict of named values, got {self.values!r:.40}")

    def _new_name(self, name, func: str):
        checks.text(name, func, "name")
        if any(c.name == name for c in self.checks):
            raise checks.fail(func, "name", f"check {name!r} recorded twice")

    def add(self, name, label, lhs, rhs, expected=True, note="", rel=None) -> Check:
        """Compare ``lhs`` with ``rhs`` and record the result as a :class:`Check`."""
        func = "Derivation.add"
        self._new_name(name, func)
        checks.text(label, func, "label")
        side(lhs, func, "lhs", allow_none=False)
        side(rhs, func, "rhs", allow_none=False)
        chk = Check(
            name,
            label,
            lhs,
            rhs,
            same(lhs, rhs, ring_or_none(rel, func)),
            checks.flag(expected, func, "expected"),
            checks.text(note, func, "note", empty=True),
        )
        self.checks.append(chk)
        return chk

    def add_bool(self, name, label, value: bool, expected=True, note="", lhs=None, rhs=None) -> Check:
        """Record a check decided elsewhere (proportionality, a set of solutions): ``value`` True or False."""
        func = "Derivation.add_bool"
        self._new_name(name, func)
        checks.text(label, func, "label")
        chk = Check(
            name,
            label,
            side(lhs, func, "lhs"),
            side(rhs, func, "rhs"),
            checks.flag(value, func, "value"),
            checks.flag(expected, func, "expected"),
            checks.text(note, func, "note", empty=True),
        )
        self.checks.append(chk)
        return chk

    def copy(self) -> Derivation:
        """A new Derivation with the same checks and values (its own list and dict)."""
        return Derivation(self.title, self.labels, list(self.checks), dict(self.values))

    @property
    def holds(self) -> bool:
        return all(c.ok for c in self.checks)

    def __getitem__(self, name: str) -> Check:
        for c in self.checks:
            if c.name == name:
                return c
        raise CheckNameError(f"Derivation[]: name: {self.title}: no check named {name!r}; have {self.names()}")

    def names(self) -> list:
        return [c.name for c in self.checks]

    def for_label(self, label: str) -> list:
        """The checks of one equation; a label of none of them, nor of the derivation, is refused."""
        out = [c for c in self.checks if c.label == label]
        if not out and label not in self.labels:
            known = sorted({c.label for c in self.checks} | set(self.labels))
            raise checks.fail(
                "Derivation.for_label", "label", f"{label!r} is not an equation of {self.title!r}: {known}"
            )
        return out

    def errata(self) -> list:
        """The checks of printed forms that are wrong (expected to fail)."""
        return [c for c in self.checks if not c.expected]

    def failures(self) -> list:
        """Checks that did not come out as expected (empty when ``holds``)."""
        return [c for c in self.checks if not c.ok]

    def table(self) -> str:
        """The checks as a Markdown table (for notebooks)."""
        rows = [f"**{self.title}** (Eqs. {', '.join(self.labels)})", "", "| eq. | step | result |", "|---|---|---|"]
        for c in self.checks:
            if c.expected:
                res = "holds" if c.holds else "**FAILS**"
            else:
                res = "printed form fails (erratum)" if not c.holds else "**printed form holds?**"
            name = c.name.replace("|", "\\|")  # a literal | would split the Markdown cell
            rows.append(f"| {c.label} | {name} | {res} |")
        return "\n".join(rows)

    def _repr_markdown_(self) -> str:
        return self.table()

    def __repr__(self) -> str:
        n_err = len(self.errata())
        status = "holds" if self.holds else f"{len(self.failures())} unexpected result(s)"
        return f"<Derivation {self.title!r}: {len(self.checks)} checks, {n_err} errata, {status}>"
