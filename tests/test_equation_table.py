"""The README's equation table: generated from the registry, complete, with links that land on the code.

The staleness test compares the README's copy with a fresh rendering; when the registry or the code it
links to changes, regenerate with ``python -m cga_lessons.equations --write-readme``.
"""

import re
from pathlib import Path

import pytest

from cga_lessons import equations, symbolic
from cga_lessons.equations import readme
from cga_lessons.equations.core import resolve

ROOT = Path(__file__).resolve().parents[1]


def split_row(row: str) -> list[str]:
    """The cells of a Markdown table row, splitting only on unescaped pipes."""
    cells = re.split(r"(?<!\\)\|", row.strip())
    return [c.strip() for c in cells[1:-1]]


def unescape(cell: str) -> str:
    return re.sub(r"\\(.)", r"\1", cell)


@pytest.fixture(scope="module")
def rendered():
    return equations.readme_section()


def table_rows(text: str, header_start: str) -> list[list[str]]:
    """Rows of every table whose header starts with ``header_start``."""
    rows, inside = [], False
    for line in text.splitlines():
        if line.startswith(header_start):
            inside = True
            continue
        if inside and line.startswith("|---"):
            continue
        if inside and line.startswith("|"):
            rows.append(split_row(line))
        else:
            inside = False
    return rows


def test_readme_table_is_current(rendered):
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert text.count(equations.README_START) == 1 and text.count(equations.README_END) == 1, (
        f"README.md needs one {equations.README_START!r} and one {equations.README_END!r} line"
    )
    body = text.split(equations.README_START)[1].split(equations.README_END)[0]
    assert body == "\n" + rendered, (
        "README.md's equation table is stale (the registry or the code it links to changed): "
        f"regenerate it with `{readme.REGENERATE}` and commit README.md"
    )


def test_every_equation_has_exactly_one_row(rendered):
    rows = table_rows(rendered, "| eq. | what |")
    keys = [unescape(r[0]) for r in rows]
    assert all(len(r) == 5 for r in rows)  # no title or code cell broke a row
    assert sorted(keys) == sorted(equations.REGISTRY) and len(keys) == len(set(keys))
    thesis = [k for k in keys if k in equations.THESIS_LABELS]
    assert thesis == list(equations.THESIS_LABELS)  # in the thesis's order
    for r in rows:
        e = equations.REGISTRY[unescape(r[0])]
        assert unescape(r[1]) == e.title and r[2].strip("*") == e.status


def test_summary_counts_match_the_registry(rendered):
    rows = table_rows(rendered, "| part | equations |")
    prefixes = {"Chapter 2": "2.", "Chapter 3": "3.", "Chapter 4": "4.", "Chapter 5": "5.", "Appendix A": "A."}
    seen = 0
    for r in rows:
        name = r[0].split(":")[0]
        if name not in prefixes:
            continue
        counts = equations.coverage(prefixes[name])
        assert [int(c) for c in r[2:]] == [getattr(counts, s) for s in equations.STATUSES]
        assert int(r[1]) == counts.total == sum(getattr(counts, s) for s in equations.STATUSES)
        seen += int(r[1])
    assert seen == len(equations.THESIS_LABELS) == 196
    assert equations.coverage_summary() in rendered


def test_errata_show_the_printed_and_the_correct_form(rendered):
    rows = table_rows(rendered, "| eq. | printed |")
    errata = [(e.key, e.printed, e.correct) for e in equations.ordered_entries() if e.status == "erratum"]
    errata += [(e.label, e.printed, e.correct) for e in symbolic.ERRATA if e.label.startswith("table")]  # the tables
    assert len(rows) == len(errata) > 0
    for r, e in zip(rows, errata):
        printed, correct = (unescape(c).strip("`").strip() for c in r[1:3])
        assert (unescape(r[0]), printed, correct) == e


def _links(rendered):
    return re.findall(r"\[`([^`]+)`\]\(([^)#]+)(?:#L(\d+))?\)", rendered)


def _defined_name(label: str) -> str:
    """The name in the ``def`` a link's label lands on: the function's own name when the label is a method that a
    class takes from a plain function (``Multivector.__invert__`` is ``involutions.reverse``), else the label's last
    part (a test, a class, a function)."""
    if label.startswith(("tests/", "test_")):
        return label.split(".")[-1]
    try:
        obj = resolve("cga_lessons." + label)
    except (ImportError, AttributeError):
        return label.split(".")[-1]
    return getattr(obj, "__name__", label.split(".")[-1])


def test_code_and_test_links_land_on_their_definitions(rendered):
    links = _links(rendered)
    assert len(links) > 300
    checked = 0
    for label, path, line in links:
        file = ROOT / path
        assert file.is_file(), path
        if not line:
            continue
        text = file.read_text(encoding="utf-8").splitlines()[int(line) - 1]
        name = _defined_name(label)
        assert re.match(rf"\s*(async\s+)?(def|class)\s+{re.escape(name)}\b", text), (label, path, line, text)
        checked += 1
    assert checked > 0.9 * len(links)


def test_every_registered_implementation_and_test_is_linked(rendered):
    linked = {label for label, _, _ in _links(rendered)}
    for e in equations.REGISTRY.values():
        for dotted in filter(None, (d.strip() for d in (e.implementation or "").split(","))):
            assert dotted.removeprefix("cga_lessons.") in linked, dotted
        for node in filter(None, (t.strip() for t in (e.test or "").split(","))):
            assert node.split("::")[-1] in linked, node


def test_markdown_escaping_keeps_cells_and_code_intact():
    assert split_row("| " + readme._md("a | b * c_d <x>") + " | 2 |") == [r"a \| b \* c\_d \<x\>", "2"]
    assert split_row("| " + readme._code("A | B") + " |") == [r"`A \| B`"]
    assert readme._code("a`b") == "`` a`b ``"


def test_text_table_lists_todo_only_when_asked():
    full = equations.text_table()
    todo = equations.text_table(todo_only=True)
    n_todo = equations.coverage().todo
    assert len(re.findall(r"^  \S+\s+todo\b", todo, flags=re.M)) == n_todo
    assert len(re.findall(r"^  \S+ ", full, flags=re.M)) == len(equations.REGISTRY)


def test_write_readme_replaces_only_the_marked_region(tmp_path):
    readme = tmp_path / "README.md"
    start, end = equations.README_START, equations.README_END
    readme.write_text(f"intro\n{start}\nstale\n{end}\noutro\n", encoding="utf-8")
    assert not equations.readme_is_current(readme)
    assert equations.write_readme(readme) is True
    assert equations.readme_is_current(readme) and equations.write_readme(readme) is False
    text = readme.read_text(encoding="utf-8")
    assert text.startswith(f"intro\n{start}\n<!-- generated") and text.endswith(f"{end}\noutro\n")
    readme.write_text(f"{end}\n{start}\n")
    with pytest.raises(ValueError, match="marker"):
        equations.write_readme(readme)


def test_python_dash_m_sees_the_same_registry():
    """``python -m cga_lessons.equations`` must not build a second, half-loaded registry of its own."""
    import os
    import subprocess
    import sys

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    done = subprocess.run(
        [sys.executable, "-m", "cga_lessons.equations", "--todo"], capture_output=True, text=True, env=env, cwd=ROOT
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == equations.coverage_summary()


def test_text_table_keeps_names_tests_and_the_errata_forms_whole():
    text = equations.text_table()
    for e in equations.ordered_entries():
        assert e.title in text
        for t in (e.test or "").split(","):
            assert t.strip() in text
        if e.status == "erratum":
            assert f"printed: {e.printed}" in text and f"correct: {e.correct}" in text


def test_a_wrong_equation_number_part_or_argument_is_refused_clearly(tmp_path, capsys):
    with pytest.raises(ValueError, match="coverage: prefix: no equation number of the thesis starts with '9.'"):
        equations.coverage("9.")
    with pytest.raises(ValueError, match="ordered_entries: part: must be one of"):
        equations.ordered_entries("9")
    with pytest.raises(ValueError, match="Entry: label: '2.999' is not a numbered equation of the thesis"):
        equations.Entry("2.999", "a title", "todo")
    with pytest.raises(ValueError, match="readme_is_current: path: no such file"):
        equations.readme_is_current(tmp_path / "missing.md")
    assert equations.main(["--no-such-option"]) == 2  # argparse's usage on stderr, no SystemExit
    assert "unrecognized arguments" in capsys.readouterr().err
    with pytest.raises(ValueError, match="main: argv: expected a list of strings"):
        equations.main("--todo")
