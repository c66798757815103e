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
:func:`readme_section` and written between the markers
``<!-- equations:start -->`` and ``<!-- equations:end -->`` by
``python -m cga_lessons.equations --write-readme`` (or ``cga-lessons equations
--write-readme``); ``tests/test_equation_table.py`` fails when the copy is stale.
"""

from __future__ import annotations

import argparse
import ast
import functools
import importlib
import inspect
import pkgutil
import sys
from dataclasses import dataclass, field
from pathlib import Path

from cga_lessons.paths import PROJECT_ROOT

__all__ = [
    "Entry",
    "REGISTRY",
    "THESIS_LABELS",
    "coverage_summary",
    "coverage",
    "check_registry",
    "table",
    "ordered_entries",
    "readme_section",
    "text_table",
    "write_readme",
    "readme_is_current",
    "README_START",
    "README_END",
]

STATUSES = ("symbolic", "numeric", "definition", "erratum", "todo")

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
        if self.status not in STATUSES:
            raise ValueError(f"Entry {self.label}: status {self.status!r} is not one of {STATUSES}")
        if self.status == "erratum" and not (self.printed and self.correct):
            raise ValueError(f"Entry {self.label}: an erratum needs both the printed and the correct form")
        if self.status != "todo" and not self.test:
            raise ValueError(f"Entry {self.label}: status {self.status!r} needs the test that verifies it")

    @property
    def key(self) -> str:
        return self.label if self.document == "thesis" else f"{self.document} ({self.label})"


def _load() -> dict[str, Entry]:
    from . import registry as pkg

    reg: dict[str, Entry] = {}
    for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda m: m.name):
        mod = importlib.import_module(f"{pkg.__name__}.{info.name}")
        for entry in getattr(mod, "ENTRIES", []):
            if entry.key in reg:
                raise ValueError(f"equation {entry.key} registered twice (in {info.name})")
            reg[entry.key] = entry
    for label in THESIS_LABELS:
        reg.setdefault(label, Entry(label=label, title="", status="todo"))
    return reg


#: label -> :class:`Entry`; thesis labels are ``"2.131"``, ``"A.14"``; the
#: second document's are ``"exploration (3.1)"``.
REGISTRY: dict[str, Entry] = _load()


def coverage(prefix: str | None = None) -> dict[str, int]:
    """Counts per status over the thesis's 196 equations (or those starting with ``prefix``)."""
    counts = dict.fromkeys(STATUSES, 0)
    for label in THESIS_LABELS:
        if prefix is None or label.startswith(prefix):
            counts[REGISTRY[label].status] += 1
    return counts


def coverage_summary() -> str:
    """One line: how many of the 196 numbered equations are verified, by status."""
    c = coverage()
    done = len(THESIS_LABELS) - c["todo"]
    parts = ", ".join(f"{k} {c[k]}" for k in STATUSES if k != "todo")
    extra = sum(1 for e in REGISTRY.values() if e.document != "thesis")
    return (
        f"{done} of {len(THESIS_LABELS)} thesis equations registered ({parts}; todo {c['todo']}); "
        f"{extra} from the exploration document"
    )


def _resolve(dotted: str):
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


def _test_exists(node_id: str, root: Path) -> bool:
    path, _, rest = node_id.partition("::")
    file = root / path
    if not file.is_file():
        return False
    if not rest:
        return True
    names = rest.split("::")
    tree = ast.parse(file.read_text())
    body = tree.body
    for name in names:
        name = name.split("[")[0]
        found = None
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.name == name:
                found = node
                break
        if found is None:
            return False
        body = getattr(found, "body", [])
    return True


def check_registry(root: Path | None = None) -> list[str]:
    """Problems in the registry: implementations that do not import, tests that do not exist."""
    root = root or PROJECT_ROOT
    problems = []
    for key, e in REGISTRY.items():
        if e.status == "todo":
            continue
        if e.implementation:
            for dotted in e.implementation.split(","):
                try:
                    _resolve(dotted.strip())
                except Exception as exc:  # noqa: BLE001 - report every failure
                    problems.append(f"{key}: implementation {dotted.strip()!r} does not resolve ({exc})")
        elif e.status in ("numeric", "symbolic"):
            problems.append(f"{key}: status {e.status} but no implementation named")
        for node in e.test.split(","):
            if not _test_exists(node.strip(), root):
                problems.append(f"{key}: test {node.strip()!r} does not exist")
    return problems


def table(document: str | None = None) -> str:
    """The registry as a Markdown table (label, title, status, code, test)."""
    rows = ["| eq. | what | status | code | test |", "|---|---|---|---|---|"]
    for key, e in REGISTRY.items():
        if document and e.document != document:
            continue
        impl = f"`{e.implementation}`" if e.implementation else ""
        test = f"`{e.test}`" if e.test else ""
        status = e.status
        if e.status == "erratum":
            status = f"erratum: printed `{e.printed}`, correct `{e.correct}`"
        rows.append(f"| {key} | {e.title} | {status} | {impl} | {test} |")
    return "\n".join(rows)


# --------------------------------------------------------------------------- rendering for the README and the CLI

README_START = "<!-- equations:start -->"
README_END = "<!-- equations:end -->"
REGENERATE = "python -m cga_lessons.equations --write-readme"
_ROOT = PROJECT_ROOT

#: The parts of the thesis (label prefix -> heading), and the second document.
PARTS = {
    "2": ("Chapter 2", "geometric algebra and the conformal model"),
    "3": ("Chapter 3", "2D laser line maps"),
    "4": ("Chapter 4", "3D maps from stereo and laser"),
    "5": ("Chapter 5", "relocalization"),
    "A": ("Appendix A", "cameras and two views"),
    "exploration": ("Exploration document", "seen, unseen and occupied nodes, the path around an obstacle"),
}


def _part(e: Entry) -> str:
    return e.document if e.document != "thesis" else e.label.split(".")[0]


def ordered_entries(part: str | None = None) -> list[Entry]:
    """Entries in the thesis's order (2.1 ... A.14), then the second document's; optionally one part (``"3"``)."""
    index = {label: i for i, label in enumerate(THESIS_LABELS)}

    def key(e: Entry):
        if e.document == "thesis" and e.label in index:
            return (0, index[e.label], "")
        return (1, 0, f"{e.document} {e.label}")

    out = sorted(REGISTRY.values(), key=key)
    return [e for e in out if part is None or _part(e) == part]


def _md(text: str | None) -> str:
    """Plain text made safe for a Markdown table cell (no emphasis, links, HTML or cell breaks)."""
    out = []
    for ch in text or "":
        out.append("\\" + ch if ch in "\\`*_[]<>|~#" else ch)
    return "".join(out)


def _code(text: str) -> str:
    """An inline code span for a table cell (pipes escaped, backticks fenced)."""
    text = text.replace("|", "\\|")
    return f"`` {text} ``" if "`" in text else f"`{text}`"


@functools.cache
def _def_lines(path: str) -> dict[str, int]:
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


def _source_location(dotted: str, root: Path) -> tuple[str, int | None] | None:
    """(path relative to ``root``, line of the def) of a dotted name's definition, or None outside the project."""
    try:
        obj = _resolve(dotted)
    except Exception:  # noqa: BLE001 - a name that does not resolve gets no link (check_registry reports it)
        return None
    if isinstance(obj, property):
        obj = obj.fget
    if callable(obj):
        obj = inspect.unwrap(obj)
    if inspect.ismodule(obj):
        path, qualname = getattr(obj, "__file__", None), None
    else:
        module = sys.modules.get(getattr(obj, "__module__", "") or "")
        path, qualname = getattr(module, "__file__", None), getattr(obj, "__qualname__", None)
        if path is None:  # a constant: link the module that holds it
            path = getattr(sys.modules.get(dotted.rsplit(".", 1)[0]), "__file__", None)
    if path is None:
        return None
    try:
        rel = Path(path).resolve().relative_to(root)
    except ValueError:
        return None
    line = _def_lines(str(Path(path).resolve())).get(qualname) if qualname else None
    return rel.as_posix(), line


def _test_location(node_id: str, root: Path) -> tuple[str, int | None]:
    path, _, rest = node_id.partition("::")
    file = root / path
    if not rest or not file.is_file() or file.suffix != ".py":
        return path, None
    name = ".".join(part.split("[")[0] for part in rest.split("::"))
    return path, _def_lines(str(file.resolve())).get(name)


def _link(label: str, location: tuple[str, int | None] | None) -> str:
    if location is None:
        return label
    path, line = location
    return f"[{label}]({path}{f'#L{line}' if line else ''})"


def _code_cell(e: Entry, root: Path) -> str:
    if not e.implementation:
        return ""
    links = []
    for dotted in (d.strip() for d in e.implementation.split(",")):
        short = dotted.removeprefix("cga_lessons.")
        links.append(_link(_code(short), _source_location(dotted, root)))
    return "<br>".join(links)


def _test_cell(e: Entry, root: Path) -> str:
    if not e.test:
        return ""
    links = []
    for node in (t.strip() for t in e.test.split(",")):
        short = node.split("::")[-1] if "::" in node else node
        links.append(_link(_code(short), _test_location(node, root)))
    return "<br>".join(links)


def _part_counts(part: str) -> dict[str, int]:
    counts = dict.fromkeys(STATUSES, 0)
    for e in ordered_entries(part):
        counts[e.status] += 1
    return counts


def readme_section(root: Path | None = None) -> str:
    """The README's equation table (Markdown): coverage by part, the errata, and one row per equation.

    Every equation links to its implementation (file and line) and its test; the rows of each part sit in a
    collapsed ``<details>`` block so the README stays readable.
    """
    root = Path(root or _ROOT).resolve()
    lines = [
        f"<!-- generated from the registry by `{REGENERATE}`; edit the registry, not this table -->",
        "",
        coverage_summary() + ".",
        "",
        "| part | equations | " + " | ".join(STATUSES) + " |",
        "|---|" + "---:|" * (len(STATUSES) + 1),
    ]
    parts = [p for p in PARTS if ordered_entries(p)]
    for p in parts:
        c = _part_counts(p)
        name, what = PARTS[p]
        lines.append(f"| {name}: {what} | {sum(c.values())} | " + " | ".join(str(c[s]) for s in STATUSES) + " |")
    errata = [e for e in ordered_entries() if e.status == "erratum"]
    if errata:
        lines += [
            "",
            "**Errata.** Where the printed thesis is wrong, the code implements the correct form and the test decides "
            "between the two:",
            "",
            "| eq. | printed | correct | why | test |",
            "|---|---|---|---|---|",
        ]
        for e in errata:
            lines.append(
                f"| {_md(e.key)} | {_code(e.printed)} | {_code(e.correct)} | {_md(e.note)} | {_test_cell(e, root)} |"
            )
        from cga_lessons.symbolic import ERRATA  # the tables' rows have no equation number, so no registry entry

        node = "tests/test_symbolic.py::test_errata"
        for err in ERRATA:
            if err.label.startswith("table"):
                test = _link(_code("test_errata"), _test_location(node, root))
                lines.append(
                    f"| {_md(err.label)} | {_code(err.printed)} | {_code(err.correct)} | {_md(err.note)} | {test} |"
                )
    for p in parts:
        entries = ordered_entries(p)
        c = _part_counts(p)
        name, what = PARTS[p]
        done = sum(c.values()) - c["todo"]
        todo = f", <b>{c['todo']} todo</b>" if c["todo"] else ""
        lines += [
            "",
            "<details>",
            f"<summary><b>{name}</b>: {what} ({done} of {sum(c.values())} equations registered{todo})</summary>",
            "",
            "| eq. | what | status | code | test |",
            "|---|---|---|---|---|",
        ]
        for e in entries:
            status = "**todo**" if e.status == "todo" else e.status
            cells = [_md(e.key), _md(e.title), status, _code_cell(e, root), _test_cell(e, root)]
            lines.append("| " + " | ".join(cells) + " |")
        lines += ["", "</details>"]
    return "\n".join(lines) + "\n"


def text_table(todo_only: bool = False) -> str:
    """The registry as plain text for a terminal, grouped by part, nothing cut short.

    One line per equation (label, status, title), then indented lines with
    the code that implements it, the test that verifies it and, for an
    erratum, the printed and the correct form::

      2.105              erratum    rotation about a line applied to a point
          code: versors.rotor_about_line
          test: tests/test_conformal.py::test_rotation_about_a_line_applied_to_a_point_eq_2_105_erratum
          printed: x' = T R ~T x ~R ~T
          correct: x' = T R ~T x T ~R ~T
    """
    out = []
    for p in PARTS:
        entries = [e for e in ordered_entries(p) if not todo_only or e.status == "todo"]
        if not entries:
            continue
        name, what = PARTS[p]
        out.append(f"{name}: {what}")
        for e in entries:
            out.append(f"  {e.key:<18} {e.status:<10} {e.title or '-'}".rstrip())
            code = ", ".join(c.strip().removeprefix("cga_lessons.") for c in (e.implementation or "").split(",") if c)
            if code:
                out.append(f"      code: {code}")
            if e.test:
                out.append(f"      test: {', '.join(t.strip() for t in e.test.split(','))}")
            if e.status == "erratum":
                out.append(f"      printed: {e.printed}")
                out.append(f"      correct: {e.correct}")
        out.append("")
    out.append(coverage_summary())
    return "\n".join(out)


def _split_readme(text: str, path) -> tuple[str, str, str]:
    start, end = text.find(README_START), text.find(README_END)
    if start < 0 or end < 0 or end < start:
        raise ValueError(
            f"{path}: the equation table needs the marker lines {README_START!r} and {README_END!r} (in that order)"
        )
    head = text[: start + len(README_START)]
    return head, text[len(head) : end], text[end:]


def readme_is_current(path=None) -> bool:
    """True when the README's table (between the markers) is what :func:`readme_section` renders now."""
    path = Path(path or _ROOT / "README.md")
    _, body, _ = _split_readme(path.read_text(encoding="utf-8"), path)
    return body == "\n" + readme_section()


def write_readme(path=None) -> bool:
    """Write the table between the README's markers; returns True if the file changed.

    Only the text between ``<!-- equations:start -->`` and ``<!-- equations:end -->`` is replaced.
    """
    path = Path(path or _ROOT / "README.md")
    text = path.read_text(encoding="utf-8")
    head, body, tail = _split_readme(text, path)
    new = head + "\n" + readme_section() + tail
    if new == text:
        return False
    path.write_text(new, encoding="utf-8")
    return True


def main(argv=None) -> int:
    """``python -m cga_lessons.equations [--write-readme | --check-readme] [--format markdown|text] [--todo]``."""
    ap = argparse.ArgumentParser(prog="python -m cga_lessons.equations", description="The thesis's equation registry.")
    ap.add_argument("--write-readme", action="store_true", help="write the table between the README's markers")
    ap.add_argument("--check-readme", action="store_true", help="exit with status 1 if the README's table is stale")
    ap.add_argument("--readme", default=None, help="the README to write or check (default: the checkout's README.md)")
    ap.add_argument("--format", choices=("markdown", "text"), default="text", help="how to print the table")
    ap.add_argument("--todo", action="store_true", help="list only the equations still todo")
    args = ap.parse_args(argv)
    readme = Path(args.readme) if args.readme else _ROOT / "README.md"
    try:
        if args.write_readme:
            changed = write_readme(readme)
            print(f"{readme}: equation table {'updated' if changed else 'already current'}")
            return 0
        if args.check_readme:
            if readme_is_current(readme):
                print(f"{readme}: equation table is current")
                return 0
            print(f"{readme}: equation table is stale; run `{REGENERATE}`", file=sys.stderr)
            return 1
    except (OSError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    if args.format == "markdown":
        if args.todo:
            rows = ["| eq. | status |", "|---|---|"] + [
                f"| {_md(e.key)} | todo |" for e in ordered_entries() if e.status == "todo"
            ]
            print("\n".join(rows))
        else:
            print(readme_section(), end="")
    else:
        print(text_table(todo_only=args.todo))
    return 0
