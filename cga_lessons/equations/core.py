"""The equation registry: every numbered equation of the thesis -> code and test.

Each chapter's entries live in ``cga_lessons/equations/registry/<part>.py`` as a list
``ENTRIES`` of :class:`Entry` (one file per part, so chapters are registered
independently).  This module merges them into :data:`REGISTRY`, fills every
label nobody registered with status ``"todo"``, and reports coverage.

Statuses:

``symbolic``    proved as an identity with SymPy by the named test;
``numeric``     implemented by the named function and checked numerically;
``definition``  a definition or notation with nothing to compute, checked
                where it is used (the test named still exercises it);
``erratum``     the printed formula is wrong: ``printed`` and ``correct``
                hold both forms and ``test`` decides between them;
``todo``        not yet registered.

The README's equation table is generated from the registry by
:func:`~cga_lessons.equations.readme.readme_section` (in :mod:`cga_lessons.equations.readme`) and written between
the markers
``<!-- equations:start -->`` and ``<!-- equations:end -->`` by
``python -m cga_lessons.equations --write-readme`` (or ``cga-lessons equations
--write-readme``); ``tests/test_equation_table.py`` fails when the copy is stale.
"""

from __future__ import annotations

import ast
import functools
import importlib
import pkgutil
import re
from dataclasses import dataclass, field
from pathlib import Path

from cga_lessons import checks
from cga_lessons.paths import PROJECT_ROOT

__all__ = [
    "Entry",
    "Coverage",
    "REGISTRY",
    "THESIS_LABELS",
    "STATUSES",
    "DOCUMENTS",
    "coverage_summary",
    "coverage",
    "check_registry",
    "table",
]

STATUSES = ("symbolic", "numeric", "definition", "erratum", "todo")
#: The documents whose equations are registered: the thesis and the second document (exploration).
DOCUMENTS = ("thesis", "exploration")

#: The 196 numbered equations of the thesis, in order.
THESIS_LABELS: tuple[str, ...] = tuple(
    [f"2.{i}" for i in range(1, 146)]
    + [f"3.{i}" for i in range(1, 22)]
    + [f"4.{i}" for i in range(1, 11)]
    + [f"5.{i}" for i in range(1, 7)]
    + [f"A.{i}" for i in range(1, 15)]
)


@dataclass(frozen=True)
class Entry:
    """One numbered equation: where it is implemented and which test verifies it.

    ``implementation`` is a dotted name (``"cga_lessons.conformal.up"``) and
    ``test`` a pytest node id (``"tests/test_conformal.py::test_up_down"``).
    ``document`` is ``"thesis"`` or ``"exploration"`` (the second document,
    whose equation numbers collide with the thesis's chapter 3).
    """

    label: str
    title: str
    status: str
    implementation: str | None = None
    test: str | None = None
    printed: str | None = None
    correct: str | None = None
    note: str | None = None
    document: str = "thesis"
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    def __post_init__(self):
        checks.text(self.label, "Entry", "label")
        checks.choice(self.document, "Entry", "document", DOCUMENTS)
        if self.document == "thesis" and self.label not in THESIS_LABELS:
            raise checks.fail(
                "Entry", "label", f"{self.label!r} is not a numbered equation of the thesis (2.1 to A.14)"
            )
        if self.document != "thesis" and not re.fullmatch(r"[0-9A-Z]+\.[0-9]+", self.label):
            raise checks.fail("Entry", "label", f"{self.label!r} is not an equation number like '3.1'")
        checks.text(self.title, "Entry", "title", empty=True)
        checks.choice(self.status, "Entry", "status", STATUSES)
        for name in ("implementation", "test", "printed", "correct", "note"):
            if getattr(self, name) is not None:
                checks.text(getattr(self, name), "Entry", name, empty=True)
        checks.instance(self.extra, "Entry", "extra", dict, "a dict")
        if self.status == "erratum" and not (self.printed and self.correct):
            raise checks.fail(
                "Entry", "printed, correct", f"{self.label}: an erratum needs both the printed and the correct form"
            )
        if self.status != "todo" and not self.test:
            raise checks.fail("Entry", "test", f"{self.label}: status {self.status!r} needs the test that verifies it")

    @property
    def key(self) -> str:
        return self.label if self.document == "thesis" else f"{self.document} ({self.label})"


def _load() -> dict[str, Entry]:
    from . import registry as registry_package

    entries: dict[str, Entry] = {}
    for info in sorted(pkgutil.iter_modules(registry_package.__path__), key=lambda m: m.name):
        module = importlib.import_module(f"{registry_package.__name__}.{info.name}")
        for entry in getattr(module, "ENTRIES", []):
            if entry.key in entries:
                raise ValueError(f"equation {entry.key} registered twice (in {info.name})")
            entries[entry.key] = entry
    for label in THESIS_LABELS:
        entries.setdefault(label, Entry(label=label, title="", status="todo"))
    return entries


#: label -> :class:`Entry`; thesis labels are ``"2.131"``, ``"A.14"``; the
#: second document's are ``"exploration (3.1)"``.
REGISTRY: dict[str, Entry] = _load()


@dataclass(frozen=True)
class Coverage:
    """How many numbered equations have each status (:data:`STATUSES`): ``symbolic``, ``numeric``, ``definition``,
    ``erratum`` (verified) and ``todo`` (not yet registered); ``total`` is their sum."""

    symbolic: int
    numeric: int
    definition: int
    erratum: int
    todo: int

    def __post_init__(self):
        for name in STATUSES:
            checks.integer(getattr(self, name), "Coverage", name, low=0)

    @property
    def total(self) -> int:
        """The number of equations counted."""
        return sum(getattr(self, name) for name in STATUSES)


def coverage(prefix: str | None = None) -> Coverage:
    """Counts per status over the thesis's 196 equations (or those starting with ``prefix``, e.g. ``"2."``).

    A ``prefix`` no equation number starts with is refused.

    >>> from cga_lessons import equations
    >>> equations.coverage("2.").total
    145
    """
    if prefix is not None:
        checks.text(prefix, "coverage", "prefix")
        if not any(label.startswith(prefix) for label in THESIS_LABELS):
            raise checks.fail("coverage", "prefix", f"no equation number of the thesis starts with {prefix!r}")
    counts = dict.fromkeys(STATUSES, 0)
    for label in THESIS_LABELS:
        if prefix is None or label.startswith(prefix):
            counts[REGISTRY[label].status] += 1
    return Coverage(**counts)


def coverage_summary() -> str:
    """One line: how many of the 196 numbered equations are verified, by status."""
    c = coverage()
    done = len(THESIS_LABELS) - c.todo
    parts = ", ".join(f"{k} {getattr(c, k)}" for k in STATUSES if k != "todo")
    extra = sum(1 for entry in REGISTRY.values() if entry.document != "thesis")
    return (
        f"{done} of {len(THESIS_LABELS)} thesis equations registered ({parts}; todo {c.todo}); "
        f"{extra} from the exploration document"
    )


def resolve(dotted: str):
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(dotted)


@functools.cache
def def_lines(path: str) -> dict[str, int]:
    """``{qualified name: line of its def/class}`` for every function and class of a Python file (parsed once)."""
    out: dict[str, int] = {}

    def walk(body, prefix):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                name = prefix + node.name
                out.setdefault(name, node.lineno)
                walk(node.body, name + ".")

    walk(ast.parse(Path(path).read_text(encoding="utf-8")).body, "")
    return out


def node_parts(node_id: str, root: Path) -> tuple[str, Path, str | None]:
    """A test's node id (``tests/test_x.py::Class::test_y[case]``) as its path as written, that file under ``root``
    and the qualified name of its def (``Class.test_y``; None for a whole file)."""
    path, _, rest = node_id.partition("::")
    name = ".".join(part.split("[")[0] for part in rest.split("::")) if rest else None
    return path, root / path, name


def _test_exists(node_id: str, root: Path) -> bool:
    _, file, name = node_parts(node_id, root)
    if not file.is_file():
        return False
    if name is None:
        return True
    return name in def_lines(str(file.resolve()))  # each test file is parsed once


def check_registry(root: Path | None = None) -> list[str]:
    """Problems in the registry: implementations that do not import, tests that do not exist (under ``root``)."""
    root = PROJECT_ROOT if root is None else checks.existing_path(root, "check_registry", "root", kind="folder")
    problems = []
    for key, entry in REGISTRY.items():
        if entry.status == "todo":
            continue
        if entry.implementation:
            for dotted in entry.implementation.split(","):
                try:
                    resolve(dotted.strip())
                except Exception as exc:  # noqa: BLE001 - report every failure
                    problems.append(f"{key}: implementation {dotted.strip()!r} does not resolve ({exc})")
        elif entry.status in ("numeric", "symbolic"):
            problems.append(f"{key}: status {entry.status} but no implementation named")
        for node in entry.test.split(","):
            if not _test_exists(node.strip(), root):
                problems.append(f"{key}: test {node.strip()!r} does not exist")
    return problems


def table(document: str | None = None) -> str:
    """The registry as a Markdown table (label, title, status, code, test); optionally one ``document``."""
    if document is not None:
        checks.choice(document, "table", "document", sorted({entry.document for entry in REGISTRY.values()}))
    rows = ["| eq. | what | status | code | test |", "|---|---|---|---|---|"]
    for key, entry in REGISTRY.items():
        if document and entry.document != document:
            continue
        impl = f"`{entry.implementation}`" if entry.implementation else ""
        test = f"`{entry.test}`" if entry.test else ""
        status = entry.status
        if entry.status == "erratum":
            status = f"erratum: printed `{entry.printed}`, correct `{entry.correct}`"
        rows.append(f"| {key} | {entry.title} | {status} | {impl} | {test} |")
    return "\n".join(rows)
