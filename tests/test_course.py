"""The chapter table is the one source of the README's dependency sentence and of notebook 00's table and diagram."""

from pathlib import Path

import nbformat

from cga_lessons.equations import course

ROOT = Path(__file__).resolve().parents[1]


def test_every_chapter_notebook_is_in_the_table_and_needs_only_earlier_ones():
    on_disk = sorted(p.stem for p in (ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb") if not p.stem.startswith("00"))
    assert [c.notebook for c in course.CHAPTERS] == on_disk
    numbers = [c.number for c in course.CHAPTERS]
    for c in course.CHAPTERS:
        assert all(n in numbers and n < c.number for n in c.needs), c.notebook


def test_the_readme_says_what_the_table_says():
    readme = (ROOT / "README.md").read_text()
    assert course.dependency_sentence() in readme


def test_notebook_00_draws_table_and_diagram_from_the_table():
    nb = nbformat.read(ROOT / "notebooks" / "00_start_here.ipynb", as_version=4)
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    assert "equations.dependency_table()" in code and "equations.arrows()" in code
    prose = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    assert "| needs |" not in prose  # no hand-kept copy of the table
