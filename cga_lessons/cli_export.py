"""``cga-lessons export-html``: the stored, executed notebooks as a static site that loads nothing from the network.

The pages are built in a hidden temporary folder and moved into ``--out-dir`` only when every notebook has
been exported (:class:`cga_lessons.cli_io.StagedOutputs`): a notebook that cannot be read or converted is
named in a one-line error and leaves no page behind, so the next run starts from where the site was.
"""

from __future__ import annotations

import html
import sys
from pathlib import Path

from .cli import _ROOT, CLIError
from .cli_io import StagedOutputs, check_output_dir, check_output_files

__all__ = ["export_html"]

_OFFLINE_TEMPLATE = """{%- extends 'index.html.j2' -%}
{%- block html_head_js_requirejs -%}{%- endblock html_head_js_requirejs -%}
{% block jupyter_widgets %}{% endblock jupyter_widgets %}
{%- block html_head_js_mathjax -%}
{%- if resources.mathjax_url -%}{{ mathjax(resources.mathjax_url) }}{%- endif -%}
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


def export_html(args) -> int:
    """Run ``export-html`` with the parsed arguments ``args``; returns the exit status."""
    nbdir = Path(args.notebook_dir) if args.notebook_dir else _ROOT / "notebooks"
    if not nbdir.is_dir():
        raise CLIError(f"no notebooks folder at {nbdir}")
    paths = sorted(p for p in nbdir.glob("*.ipynb") if args.include_solutions or p.stem != "teacher_solutions")
    if not paths:
        raise CLIError(f"no notebooks (*.ipynb) in {nbdir}")
    out = Path(args.out_dir)
    names = [f"{p.stem}.html" for p in paths] + ["index.html"]
    check_output_dir(out)  # before nbconvert's (slow) import and any page
    check_output_files([out / name for name in names], overwrite=args.force, force_hint="--force")

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
    with StagedOutputs(out, names, overwrite=args.force, force_hint="--force") as stage:
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
                body, _ = exporter.from_notebook_node(nb, resources={"metadata": {"name": p.stem}})
                title = _notebook_title(nb, p.stem)
            except Exception as exc:
                raise CLIError(f"{p}: cannot convert the notebook ({_first_line(exc)}); no page was written") from None
            stage.path(name).write_text(body, encoding="utf-8")
            pages.append((name, title))
        stage.path("index.html").write_text(_index_page(pages, bool(args.mathjax_url)), encoding="utf-8")
        written = stage.commit()
    for target in written:
        print(f"  wrote {target}")
    print(f"export-html: {len(pages)} notebooks; open {written[-1]} in a browser (no network needed)")
    return 0


def _index_page(pages, mathjax: bool) -> str:
    items = "\n".join(f'<li><a href="{html.escape(name)}">{html.escape(title)}</a></li>' for name, title in pages)
    math_note = (
        ""
        if mathjax
        else "<p><small>Formulas appear as LaTeX source: no MathJax is bundled. Rebuild with "
        "<code>--mathjax-url</code> pointing at a local MathJax 2.7 copy to typeset them.</small></p>"
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
