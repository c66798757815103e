"""The exported site typesets its formulas offline: ``export-html`` copies MathJax 2.7 (from the PyPI package
jupyter-server-mathjax) into the site and points the pages at it with a relative URL.

Independent truths: the files on disk, the page's own ``<script src>``, and what headless Chromium makes of the page
opened from disk with the network unused: MathJax's rendered elements and the MathML they carry, the files MathJax
reported as failed, the state of the page's web fonts, and a screenshot.
"""

import json
import os
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import nbformat
import numpy as np
import pytest
from headless import require_chromium, run_chromium

from cga_lessons import cli
from cga_lessons.cli import export as cli_export
from cga_lessons.cli import site_math

FORMULA = r"$\mathbf{e}_+$"


def run(argv, capsys):
    rc = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def math_notebook(path):
    nb = nbformat.v4.new_notebook()
    text = (
        "# Null vectors\n\n"
        rf"The basis vector {FORMULA} squares to one and $\mathbf{{e}}_-$ to minus one:"
        "\n\n"
        r"$$\mathbf{e}_+^2 = 1, \qquad \mathbf{e}_-^2 = -1, \qquad e_0 = \tfrac12 (\mathbf{e}_- - \mathbf{e}_+).$$"
    )
    cell = nbformat.v4.new_code_cell("x**2", execution_count=1)
    cell.outputs = [
        nbformat.v4.new_output(
            "execute_result", {"text/latex": r"$\displaystyle x^{2}$", "text/plain": "x**2"}, execution_count=1
        )
    ]
    nb.cells = [nbformat.v4.new_markdown_cell(text), cell]
    nbformat.write(nb, path)


@pytest.fixture
def nbdir(tmp_path):
    folder = tmp_path / "nb"
    folder.mkdir()
    math_notebook(folder / "01_null.ipynb")
    return folder


def snapshot(root):
    return sorted(str(p.relative_to(root)) for p in Path(root).rglob("*"))


def script_sources(page):
    return re.findall(r"""<script\b[^>]*\bsrc\s*=\s*["']([^"']+)""", page)


# --------------------------------------------------------------------------- the copy and the relative URL
def test_site_bundles_mathjax_and_pages_load_it_relatively(nbdir, tmp_path, capsys):
    source = site_math.mathjax_source()
    assert source is not None, "jupyter-server-mathjax is a dependency of the course"
    site = tmp_path / "site"
    rc, out, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 0, err
    copy = site / "mathjax"
    files = sorted(p.relative_to(copy).as_posix() for p in copy.rglob("*") if p.is_file())
    assert files == site_math.mathjax_files(source)
    for name in files:
        assert (copy / name).read_bytes() == (source / name).read_bytes()
    assert {"MathJax.js", "config/TeX-AMS-MML_HTMLorMML-full.js", "LICENSE"} <= set(files)
    assert "jax/output/HTML-CSS/fonts/STIX-Web/fontdata.js" in files
    assert sum(name.startswith("fonts/HTML-CSS/STIX-Web/woff/") for name in files) > 20
    assert not any(name.startswith(("jax/output/SVG/", "localization/de/")) for name in files)  # only what is used
    assert sum((copy / name).stat().st_size for name in files) < 3_000_000
    assert "mathjax/ (MathJax 2.7 for the formulas" in out and "open " in out and "index.html" in out

    page = (site / "01_null.html").read_text()
    sources = script_sources(page)
    assert sources == [site_math.PAGE_URL]  # the one script the page loads: the copy, relatively
    for src in sources:
        assert not re.match(r"^([a-z]+:|/)", src, flags=re.I)
        assert (site / src.split("?")[0]).is_file()
    assert 'webFont: "STIX-Web"' in page and FORMULA in page  # the copy's settings; the formula, for MathJax
    assert not re.search(r"""(?:src|href)\s*=\s*["'](?:https?:)?//""", page)  # nothing from the network
    assert "LaTeX source" not in (site / "index.html").read_text()


def test_mathjax_url_overrides_the_copy(nbdir, tmp_path, capsys):
    site = tmp_path / "site"
    url = "../shared/mathjax/MathJax.js?config=TeX-AMS_CHTML"
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, "--mathjax-url", url], capsys)
    assert rc == 0, err
    assert sorted(p.name for p in site.iterdir()) == ["01_null.html", "index.html"]  # nothing copied
    page = (site / "01_null.html").read_text()
    assert script_sources(page) == [url] and "STIX-Web" not in page


def test_without_jupyter_server_mathjax_the_site_still_exports(nbdir, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(site_math, "mathjax_source", lambda: None)
    site = tmp_path / "site"
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 0 and "jupyter-server-mathjax is not installed" in err and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in site.iterdir()) == ["01_null.html", "index.html"]
    assert script_sources((site / "01_null.html").read_text()) == []
    assert "LaTeX source" in (site / "index.html").read_text()


def test_existing_copy_is_replaced_only_with_force(nbdir, tmp_path, capsys):
    site = tmp_path / "site"
    (site / "mathjax").mkdir(parents=True)
    (site / "mathjax" / "notes.txt").write_text("mine")
    before = snapshot(tmp_path)
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 1 and "will not overwrite" in err and "mathjax" in err and "--force" in err
    assert len(err.strip().splitlines()) == 1 and snapshot(tmp_path) == before
    (site / "mathjax" / "MathJax.js").write_text("an old copy")
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, "--force"], capsys)
    assert rc == 0, err
    assert (site / "mathjax" / "MathJax.js").read_bytes() == (site_math.mathjax_source() / "MathJax.js").read_bytes()
    assert (site / "mathjax" / "notes.txt").read_text() == "mine"  # the user's own file stays
    assert not [p for p in site.iterdir() if p.name.startswith(".")]  # no temporary folder left
    # an existing site folder without a copy: the files move in one by one, their folders made first
    other = tmp_path / "other"
    other.mkdir()
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", other], capsys)
    assert rc == 0, err
    assert (other / "mathjax" / "jax" / "output" / "HTML-CSS" / "fonts" / "STIX-Web" / "fontdata.js").is_file()
    assert sorted(p.name for p in other.iterdir()) == ["01_null.html", "index.html", "mathjax"]


@pytest.mark.parametrize("kind", ["file", "symlink"])
def test_something_else_where_the_copy_goes_is_a_one_line_error(nbdir, tmp_path, capsys, kind):
    site, elsewhere = tmp_path / "site", tmp_path / "elsewhere"
    site.mkdir()
    elsewhere.mkdir()
    if kind == "file":
        (site / "mathjax").write_text("not a folder")
    else:
        (site / "mathjax").symlink_to(elsewhere, target_is_directory=True)
    before = snapshot(tmp_path)
    for force in ([], ["--force"]):
        rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site, *force], capsys)
        assert rc == 1 and err.startswith("cga-lessons export-html: error: ") and len(err.strip().splitlines()) == 1
        assert "mathjax" in err and ("not a folder" if kind == "file" else "symbolic link") in err
        assert snapshot(tmp_path) == before  # nothing written, the link's target untouched


def test_a_failed_copy_leaves_no_page(nbdir, tmp_path, capsys, monkeypatch):
    real, calls = shutil.copyfile, []

    def flaky(src, dst, *args, **kwargs):
        calls.append(src)
        if len(calls) == 50:
            raise PermissionError(13, "Permission denied", str(src))
        return real(src, dst, *args, **kwargs)

    monkeypatch.setattr(cli_export.shutil, "copyfile", flaky)
    before = snapshot(tmp_path)
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", tmp_path / "site"], capsys)
    assert rc == 1 and "cannot copy MathJax" in err and "Permission denied" in err and "no page" in err
    assert len(err.strip().splitlines()) == 1 and snapshot(tmp_path) == before


# --------------------------------------------------------------------------- typeset in headless Chromium
# Put before the page's own MathJax settings (MathJax 2 reads a ``window.MathJax`` object as settings): records the
# files MathJax could not load, and, once the page is typeset, the state of every web font and the loaded files.
PROBE = """<script>
window.MathJax = {AuthorInit: function () {
    var failed = [];
    MathJax.Hub.Register.MessageHook("file load error", function (m) { failed.push(String(m[1])); });
    function report() {
        var ajax = MathJax.Ajax, fonts = [], loaded = Object.keys(ajax.loaded);
        loaded.forEach(function (f) { if (ajax.loaded[f] !== ajax.STATUS.OK) { failed.push(f); } });
        document.fonts.forEach(function (f) { fonts.push([f.family.replace(/["']/g, ""), f.status]); });
        var result = {failed: failed, pending: Object.keys(ajax.loading), fonts: fonts, loaded: loaded};
        document.body.setAttribute("data-cga-probe", JSON.stringify(result));
    }
    // after the typesetting, and after what MathJax loads later (the menu) or gives up on (15 s): virtual time
    MathJax.Hub.Register.StartupHook("End", function () {
        MathJax.Hub.Queue(function () { setTimeout(report, 20000); });
    });
}};
</script>
"""


class VisibleText(HTMLParser):
    """The text a reader sees (not scripts, styles or the hidden copy of the MathML), and each element's attributes."""

    HIDDEN = {"script", "style", "title", "template"}
    VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.text, self.elements = [], [], []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.elements.append((tag, attrs))
        if tag not in self.VOID:
            hidden = tag in self.HIDDEN or "MJX_Assistive_MathML" in (attrs.get("class") or "")
            self.stack.append((tag, hidden or bool(self.stack and self.stack[-1][1])))

    def handle_endtag(self, tag):
        while self.stack:
            if self.stack.pop()[0] == tag:
                break

    def handle_data(self, data):
        if not (self.stack and self.stack[-1][1]):
            self.text.append(data)


def chromium_dom_and_screenshot(url, png, size=(900, 700), timeout=90):
    """The page's final DOM and its picture; MathJax's timers run in virtual time, and no host name resolves."""
    return run_chromium(
        url,
        screenshot=png,
        size=size,
        budget_ms=60000,
        dump_dom=True,
        timeout=timeout,
        extra=("--host-resolver-rules=MAP * ~NOTFOUND",),
    )


def test_formulas_are_typeset_offline_in_headless_chromium(nbdir, tmp_path, capsys):
    from PIL import Image

    require_chromium()
    site = tmp_path / "site"
    rc, _, err = run(["export-html", "--notebook-dir", nbdir, "--out-dir", site], capsys)
    assert rc == 0, err
    page = (site / "01_null.html").read_text()
    anchor = '<script type="text/x-mathjax-config">'
    assert page.count(anchor) == 1
    probe = site / "probe.html"  # beside the page: the same relative URLs
    probe.write_text(page.replace(anchor, PROBE + anchor), encoding="utf-8")
    png = tmp_path / "page.png"
    code, dom, err = chromium_dom_and_screenshot(probe.as_uri(), png)
    assert code == 0 and "</html>" in dom, err[-2000:]
    if os.environ.get("CGA_KEEP_SCREENSHOT"):
        shutil.copy(png, f"{os.environ['CGA_KEEP_SCREENSHOT']}_math.png")

    parsed = VisibleText()
    parsed.feed(dom)
    body = next(attrs for tag, attrs in parsed.elements if tag == "body")
    assert "data-cga-probe" in body, "MathJax did not finish typesetting the page"
    report = json.loads(body["data-cga-probe"])
    assert report["failed"] == [], report["failed"]
    loaded = [url for url in report["loaded"] if "/mathjax/" in url]
    assert loaded and all(url.startswith(site.as_uri() + "/mathjax/") for url in loaded)  # the copy, nothing else
    fonts = dict(report["fonts"])  # (MathJax_Blank fails on purpose: MathJax's font detection loads about:blank)
    assert any(family.startswith("STIXMathJax") and fonts[family] == "loaded" for family in fonts), fonts
    stix = {family: state for family, state in fonts.items() if family.startswith("STIXMathJax")}
    assert "error" not in stix.values(), stix  # every web font the formulas asked for was found in the copy

    # the formulas were replaced by MathJax's rendering: no TeX left in the text a reader sees
    visible = " ".join("".join(parsed.text).split())
    assert FORMULA not in visible and "\\mathbf" not in visible and "$$" not in visible, visible[:500]
    assert "The basis vector" in visible and "squares to one" in visible
    rendered = [attrs for tag, attrs in parsed.elements if "MathJax" in (attrs.get("class") or "").split()]
    assert len(rendered) >= 4  # e+, e-, the display and the output cell's x^2
    mathml = [re.sub(r"\s+", "", attrs.get("data-mathml", "")) for attrs in rendered]
    e_plus = '<msub><mrowclass="MJX-TeXAtom-ORD"><mimathvariant="bold">e</mi></mrow><mo>+</mo></msub>'  # e_+
    assert any(e_plus in m for m in mathml), mathml[:2]
    assert any(tag == "div" and "MathJax_Display" in (attrs.get("class") or "") for tag, attrs in parsed.elements)

    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    assert img.shape == (700, 900, 3) and img.reshape(-1, 3).std(axis=0).max() > 10, "blank screenshot"
