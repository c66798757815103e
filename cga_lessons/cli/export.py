"""``cga-lessons export-html``: the stored, executed notebooks as a static site that loads nothing from the network.

The pages are built in a hidden temporary folder and moved into ``--out-dir`` only when every notebook has
been exported (:class:`cga_lessons.cli.outputs.StagedOutputs`): a notebook that cannot be read or converted is
named in a one-line error and leaves no page behind, so the next run starts from where the site was.

Formulas are typeset offline by a copy of MathJax 2.7 in the site's ``mathjax/`` folder
(:mod:`cga_lessons.cli.site_math`), staged and moved in with the pages; ``--mathjax-url`` points the pages at another
MathJax instead (nothing is copied).
"""

from __future__ import annotations

import html
import os
import shutil
import sys
from pathlib import Path
from typing import NamedTuple

from cga_lessons.paths import PROJECT_ROOT

from . import site_math
from .errors import CLIError, OutputExistsError, OutputPathError
from .outputs import StagedOutputs, check_output_dir, check_output_files

__all__ = ["export_html"]

_OFFLINE_TEMPLATE = """{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{% block jupyter_widgets %}{% endblock jupyter_widgets %}
{%- block html_head_js_mathjax -%}
{%- if resources.cga_mathjax_head -%}{{ resources.cga_mathjax_head }}
{%- elif resources.mathjax_url -%}{{ mathjax(resources.mathjax_url) }}{%- endif -%}
{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
"""


def _notebook_title(nb, fallback: str) -> str:
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return fallback


def _first_line(exc: BaseException) -> str:
    text = next((line.strip() for line in str(exc).splitlines() if line.strip()), "")
    text = text if len(text) <= 200 else text[:197] + "..."
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


class _StagedSite(StagedOutputs):
    """:class:`StagedOutputs` whose files may lie in subfolders of the site (the MathJax copy)."""

    def path(self, name: str) -> Path:
        target = super().path(name)
        target.parent.mkdir(parents=True, exist_ok=True)
        return target

    def commit(self) -> list[Path]:
        if self.out_dir.is_dir():  # the files are moved in one by one: make their folders first, before moving any
            for folder in sorted({t.parent for t in self.targets} - {self.out_dir}):
                try:
                    folder.mkdir(parents=True, exist_ok=True)
                except OSError as exc:
                    raise OutputPathError(f"cannot make the folder {str(folder)!r}: {exc.strerror or exc}") from None
        return super().commit()


class _MathJaxCopy(NamedTuple):
    """The bundled MathJax to copy into the site: the folder it comes from and the site's names of its files."""

    source: Path
    names: list[str]


def _mathjax_copy(out: Path, force: bool) -> _MathJaxCopy | None:
    """Where the bundled MathJax comes from and the site's names of its files; None (and a warning) without it.

    Checks the site's ``mathjax/`` folder as :func:`check_output_files` checks a page: a symbolic link or a file
    there is an error; an existing copy is replaced only with ``--force``.
    """
    source = site_math.mathjax_source()
    if source is None:
        print(
            "export-html: warning: jupyter-server-mathjax is not installed, so formulas stay LaTeX source "
            "(pip install jupyter-server-mathjax, or pass --mathjax-url)",
            file=sys.stderr,
        )
        return None
    folder = out / site_math.MATHJAX_DIR
    if folder.is_symlink():
        raise OutputPathError(f"will not write through the symbolic link {folder} (remove it, or pass --mathjax-url)")
    if os.path.lexists(folder) and not folder.is_dir():
        raise OutputPathError(f"{str(folder)!r} is not a folder: the site's MathJax copy goes there")
    if folder.is_dir() and not force:
        raise OutputExistsError(f"will not overwrite {folder} (pass --force to replace)")
    names = [f"{site_math.MATHJAX_DIR}/{name}" for name in site_math.mathjax_files(source)]
    check_output_files([out / name for name in names], overwrite=force, force_hint="--force")
    return _MathJaxCopy(source, names)


def export_html(args) -> int:
    """Run ``export-html`` with the parsed arguments ``args``; returns the exit status."""
    nbdir = Path(args.notebook_dir) if args.notebook_dir else PROJECT_ROOT / "notebooks"
    if not nbdir.is_dir():
        raise CLIError(f"no notebooks folder at {nbdir}")
    paths = sorted(p for p in nbdir.glob("*.ipynb") if args.include_solutions or p.stem != "teacher_solutions")
    if not paths:
        raise CLIError(f"no notebooks (*.ipynb) in {nbdir}")
    out = Path(args.out_dir)
    names = [f"{p.stem}.html" for p in paths] + ["index.html"]
    check_output_dir(out)  # before nbconvert's (slow) import and any page
    check_output_files([out / name for name in names], overwrite=args.force, force_hint="--force")
    copy = None if args.mathjax_url else _mathjax_copy(out, args.force)
    copied = copy.names if copy else []
    head = {"cga_mathjax_head": site_math.head_html()} if copy else {}

    import nbformat
    from jinja2 import DictLoader
    from nbconvert import HTMLExporter

    exporter = HTMLExporter(
        template_name="lab",
        extra_loaders=[DictLoader({"cga_offline.html.j2": _OFFLINE_TEMPLATE})],
        template_file="cga_offline.html.j2",
        mathjax_url=args.mathjax_url or "",
    )
    pages = []
    # MathJax first and the index last: moved into an existing site one by one, the pages follow their MathJax
    with _StagedSite(out, copied + names, overwrite=args.force, force_hint="--force") as stage:
        for p, name in zip(paths, names):
            # A notebook is a third party's JSON, read and converted by third-party code: whatever fails in
            # there (bad JSON, a schema error, a cell of the wrong type, a NUL byte) is this notebook's fault.
            try:
                nb = nbformat.read(p, as_version=4)
            except Exception as exc:
                raise CLIError(f"{p}: not a readable notebook ({_first_line(exc)}); no page was written") from None
            try:
                code = [c for c in nb.cells if c.cell_type == "code" and c.source.strip()]
                if code and all(c.get("execution_count") is None and not c.get("outputs") for c in code):
                    print(
                        f"export-html: warning: {p.name} has no stored outputs (it is exported as it is)",
                        file=sys.stderr,
                    )
                body, _ = exporter.from_notebook_node(nb, resources={"metadata": {"name": p.stem}, **head})
                title = _notebook_title(nb, p.stem)
            except Exception as exc:
                raise CLIError(f"{p}: cannot convert the notebook ({_first_line(exc)}); no page was written") from None
            stage.path(name).write_text(body, encoding="utf-8")
            pages.append((name, title))
        stage.path("index.html").write_text(_index_page(pages, bool(copy or args.mathjax_url)), encoding="utf-8")
        if copy:
            source, prefix = copy.source, f"{site_math.MATHJAX_DIR}/"
            for name in copied:
                try:
                    shutil.copyfile(source / name.removeprefix(prefix), stage.path(name))
                except OSError as exc:
                    why = _first_line(exc)
                    raise CLIError(f"cannot copy MathJax from {source} ({why}); no page was written") from None
        written = stage.commit()
    for target in written[len(copied) :]:
        print(f"  wrote {target}")
    if copy:
        print(f"  wrote {out / site_math.MATHJAX_DIR}/ (MathJax 2.7 for the formulas: {len(copied)} files)")
    print(f"export-html: {len(pages)} notebooks; open {written[-1]} in a browser (no network needed)")
    return 0


def _index_page(pages, mathjax: bool) -> str:
    items = "\n".join(f'<li><a href="{html.escape(name)}">{html.escape(title)}</a></li>' for name, title in pages)
    math_note = (
        ""
        if mathjax
        else "<p><small>Formulas appear as LaTeX source: no MathJax was bundled (jupyter-server-mathjax is not "
        "installed). Install it and export again, or rebuild with <code>--mathjax-url</code> pointing at a local "
        "MathJax 2.7 copy, to typeset them.</small></p>"
    )
    return f"""<!DOCTYPE html>
<html lang="en">
<head><meta charset="utf-8"><title>cga-lessons: the course</title>
<style>body {{ font-family: sans-serif; max-width: 48em; margin: 2em auto; line-height: 1.5; }}</style>
</head>
<body>
<h1>cga-lessons</h1>
<p>Conformal geometric algebra for robot mapping, a runnable course after M. Bernal Mar&iacute;n's thesis (2007).
These pages are the notebooks as executed and stored in the repository.</p>
<ol>
{items}
</ol>
{math_note}
</body>
</html>
"""
