"""The registry rendered: the README's equation table, the plain-text table of the terminal, and the command
``python -m cga_lessons.equations`` (:func:`main`).

The table is written between the markers ``<!-- equations:start -->`` and ``<!-- equations:end -->`` of the
README by :func:`write_readme`; :func:`readme_is_current` says whether the copy there is stale.
"""

from __future__ import annotations

import argparse
import inspect
import sys
from pathlib import Path

from cga_lessons import checks
from cga_lessons.files import atomic_write
from cga_lessons.paths import PROJECT_ROOT

from .core import REGISTRY, STATUSES, THESIS_LABELS, Coverage, Entry, coverage_summary, def_lines, node_parts, resolve

__all__ = [
    "PARTS",
    "README_START",
    "README_END",
    "ordered_entries",
    "readme_section",
    "text_table",
    "write_readme",
    "readme_is_current",
    "main",
]

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
    if part is not None:
        checks.choice(part, "ordered_entries", "part", PARTS)
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


def _source_location(dotted: str, root: Path) -> tuple[str, int | None] | None:
    """(path relative to ``root``, line of the def) of a dotted name's definition, or None outside the project."""
    try:
        obj = resolve(dotted)
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
    line = def_lines(str(Path(path).resolve())).get(qualname) if qualname else None
    return rel.as_posix(), line


def _test_location(node_id: str, root: Path) -> tuple[str, int | None]:
    path, file, name = node_parts(node_id, root)
    if name is None or not file.is_file() or file.suffix != ".py":
        return path, None
    return path, def_lines(str(file.resolve())).get(name)


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


def _part_counts(part: str) -> Coverage:
    """How many of one part's equations have each status."""
    counts = dict.fromkeys(STATUSES, 0)
    for entry in ordered_entries(part):
        counts[entry.status] += 1
    return Coverage(**counts)


def readme_section(root: Path | None = None) -> str:
    """The README's equation table (Markdown): coverage by part, the errata, and one row per equation.

    Every equation links to its implementation (file and line) and its test; the rows of each part sit in a
    collapsed ``<details>`` block so the README stays readable.
    """
    root = (_ROOT if root is None else checks.existing_path(root, "readme_section", "root", kind="folder")).resolve()
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
        lines.append(f"| {name}: {what} | {c.total} | " + " | ".join(str(getattr(c, s)) for s in STATUSES) + " |")
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
        done = c.total - c.todo
        todo = f", <b>{c.todo} todo</b>" if c.todo else ""
        lines += [
            "",
            "<details>",
            f"<summary><b>{name}</b>: {what} ({done} of {c.total} equations registered{todo})</summary>",
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
    todo_only = checks.flag(todo_only, "text_table", "todo_only")
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


def _read_readme(path, func: str) -> tuple[Path, str, tuple[str, str, str]]:
    """``(path, its text, (head, table, tail))`` of a README with the table's markers, or the error naming ``func``."""
    path = _ROOT / "README.md" if path is None else checks.existing_path(path, func, "path")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise checks.fail(func, "path", f"cannot read {path} as UTF-8 text ({exc})") from None
    start, end = text.find(README_START), text.find(README_END)
    if start < 0 or end < 0 or end < start:
        raise checks.fail(
            func,
            "path",
            f"{path}: the equation table needs the marker lines {README_START!r} and {README_END!r} (in that order)",
        )
    head = text[: start + len(README_START)]
    return path, text, (head, text[len(head) : end], text[end:])


def readme_is_current(path=None) -> bool:
    """True when the README's table (between the markers) is what :func:`readme_section` renders now."""
    _, _, (_, body, _) = _read_readme(path, "readme_is_current")
    return body == "\n" + readme_section()


def write_readme(path=None) -> bool:
    """Write the table between the README's markers; returns True if the file changed.

    Only the text between ``<!-- equations:start -->`` and ``<!-- equations:end -->`` is replaced.
    """
    path, text, (head, _, tail) = _read_readme(path, "write_readme")
    new = head + "\n" + readme_section() + tail
    if new == text:
        return False
    atomic_write(path, new, "write_readme", overwrite=True)  # whole or not at all
    return True


class _Stop(Exception):
    """argparse finished (``--help``) or refused the arguments: main returns this status."""

    def __init__(self, status: int):
        super().__init__(status)
        self.status = status


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser that makes :func:`main` return its exit status instead of raising SystemExit."""

    def exit(self, status=0, message=None):
        if message:
            print(message, end="", file=sys.stderr)
        raise _Stop(status)


def main(argv=None) -> int:
    """``python -m cga_lessons.equations [--write-readme | --check-readme] [--format markdown|text] [--todo]``.

    ``argv``: the arguments (a list of strings; default the command line's).  Returns the exit status: 0, 1 for a
    stale or unreadable README, 2 (after argparse's usage message) for arguments it does not know.
    """
    if argv is not None and (
        isinstance(argv, (str, bytes))
        or not isinstance(argv, (list, tuple))
        or not all(isinstance(a, str) for a in argv)
    ):
        raise checks.fail("main", "argv", f"expected a list of strings (command-line arguments), got {argv!r:.60}")
    ap = _Parser(prog="python -m cga_lessons.equations", description="The thesis's equation registry.")
    ap.add_argument("--write-readme", action="store_true", help="write the table between the README's markers")
    ap.add_argument("--check-readme", action="store_true", help="exit with status 1 if the README's table is stale")
    ap.add_argument("--readme", default=None, help="the README to write or check (default: the checkout's README.md)")
    ap.add_argument("--format", choices=("markdown", "text"), default="text", help="how to print the table")
    ap.add_argument("--todo", action="store_true", help="list only the equations still todo")
    try:
        args = ap.parse_args(argv)
    except _Stop as stop:
        return stop.status
    return _run(args)


def _run(args) -> int:
    """The command :func:`main` parsed."""
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
