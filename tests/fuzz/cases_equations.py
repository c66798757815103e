"""Fuzz cases of the equation registry and the course table (cga_lessons.equations).

An equation number, a part or a document that the registry does not have is refused, naming the argument; the
README functions are given a README of their own (a temporary copy with the markers), never the checkout's.
"""

from __future__ import annotations

from pathlib import Path

from cga_lessons import equations as eq
from cga_lessons.paths import PROJECT_ROOT
from fuzz.harness import Case, temporary_folder

_DIR = temporary_folder("cga-fuzz-equations-")


def _readme() -> Path:
    """A fresh README with the markers and a stale table between them."""
    path = _DIR / "README.md"
    path.write_text(f"intro\n{eq.README_START}\nstale\n{eq.README_END}\noutro\n", encoding="utf-8")
    return path


NO_MARKERS = _DIR / "no_markers.md"
NO_MARKERS.write_text("a README without the table's markers\n", encoding="utf-8")

CASES = [
    Case(eq.Entry, {"label": "2.1", "title": "the Clifford product", "status": "symbolic",
                    "implementation": "cga_lessons.algebra.Multivector", "test": "tests/test_algebra.py",
                    "printed": "a b", "correct": "a b", "note": "a note", "document": "thesis", "extra": {}},
         strict=True, allow={k: ["None"] for k in ("implementation", "printed", "correct", "note")},
         extra={"label": ["2.999", "9.1"], "document": ["no-such-document"]}),
    Case(eq.coverage_summary),
    Case(eq.Coverage, {"symbolic": 1, "numeric": 2, "definition": 3, "erratum": 4, "todo": 0}, strict=True),
    Case(eq.coverage, {"prefix": "2."}, strict=True, allow={"prefix": ["None"]}, extra={"prefix": ["9.", "x"]}),
    Case(eq.check_registry, {"root": PROJECT_ROOT}, allow={"root": ["None"]}),
    Case(eq.table, {"document": "exploration"}, strict=True, allow={"document": ["None"]}),
    Case(eq.ordered_entries, {"part": "3"}, strict=True, allow={"part": ["None"]}, extra={"part": ["9", "3."]}),
    Case(eq.readme_section, {"root": PROJECT_ROOT}, allow={"root": ["None"]}),
    Case(eq.text_table, {"todo_only": True}, strict=True),
    Case(eq.write_readme, lambda: {"path": _readme()}, extra={"path": [NO_MARKERS]}),
    Case(eq.readme_is_current, lambda: {"path": _readme()}, extra={"path": [NO_MARKERS]}),
    Case(eq.main, {"argv": ["--format", "text", "--todo"]},
         extra={"argv": [["--no-such-option"], ["--format", "html"], ["--readme", str(NO_MARKERS), "--check-readme"],
                         [1.0]]}),
    Case(eq.arrows),
    Case(eq.dependency_table),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
