"""Formulas of the exported site (``cga-lessons export-html``) typeset offline: a copy of MathJax 2.7 beside the pages.

The copy comes from the PyPI package ``jupyter-server-mathjax`` (MathJax 2.7.x: TeX input, HTML-CSS output with the
STIX-Web web fonts, the SVG output).  Only what the pages use is copied into the site's ``mathjax/`` folder
(:func:`mathjax_files`: 193 files, 2.0 MB from version 0.2.6): the loader, the combined TeX + HTML-CSS
configuration, the TeX extensions that ``\\require`` or a macro loads on demand, the HTML-CSS output and its
STIX-Web fonts (WOFF), the English messages and the licence.  Left out: the SVG output, the accessibility
explorer (``a11y``), the translations.  The pages point at the copy with a relative URL (:data:`PAGE_URL`), so the
site can be moved, served from anywhere, or opened from disk.
"""

from __future__ import annotations

import html
import importlib.util
from pathlib import Path

__all__ = ["MATHJAX_DIR", "PAGE_URL", "mathjax_source", "mathjax_files", "head_html"]

MATHJAX_DIR = "mathjax"  # the copy's folder, inside the site
_CONFIG = "TeX-AMS-MML_HTMLorMML-full,Safe"  # the combined configuration the package ships, and the Safe extension
PAGE_URL = f"{MATHJAX_DIR}/MathJax.js?config={_CONFIG}"  # relative to a page of the site

# What the pages need, as glob patterns relative to the package's static/ folder.
_NEEDED = (
    "LICENSE",
    "MathJax.js",
    "config/TeX-AMS-MML_HTMLorMML-full.js",
    "config/Safe.js",
    "extensions/*.js",  # tex2jax, MathMenu, MathZoom, Safe, ... (the combined configuration holds a11y's menu)
    "extensions/TeX/**/*.js",  # \require{...}, autoloaded macros (cancel, color, mhchem, ...)
    "extensions/HTML-CSS/*.js",
    "jax/input/TeX/*.js",
    "jax/element/mml/**/*.js",  # the MathML element jax and its operator tables
    "jax/output/HTML-CSS/**/*.js",  # the output, its autoloaded parts and the STIX-Web font data
    "fonts/HTML-CSS/STIX-Web/woff/*.woff",
    "localization/en/*.js",
)

# MathJax's settings for the copy: the HTML-CSS output with the STIX-Web web fonts (the only fonts in the package;
# no local font is looked for, so every reader sees the same glyphs), and the delimiters of Jupyter's Markdown.
_PAGE_CONFIG = """MathJax.Hub.Config({
    TeX: {equationNumbers: {autoNumber: "AMS", useLabelIds: true}},
    tex2jax: {
        inlineMath: [["$", "$"], ["\\\\(", "\\\\)"]],
        displayMath: [["$$", "$$"], ["\\\\[", "\\\\]"]],
        processEscapes: true,
        processEnvironments: true
    },
    MMLorHTML: {prefer: "HTML"},
    "HTML-CSS": {
        availableFonts: [],
        preferredFont: null,
        webFont: "STIX-Web",
        imageFont: null,
        linebreaks: {automatic: true}
    },
    displayAlign: "center",
    messageStyle: "none",
    showMathMenu: true
});"""


def mathjax_source() -> Path | None:
    """The ``static`` folder of the installed ``jupyter-server-mathjax`` (MathJax 2.7), or None without it.

    The package is located without being imported (importing it would import Jupyter Server).
    """
    try:
        spec = importlib.util.find_spec("jupyter_server_mathjax")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        static = Path(location) / "static"
        if (static / "MathJax.js").is_file() and (static / "config" / "TeX-AMS-MML_HTMLorMML-full.js").is_file():
            return static
    return None


def mathjax_files(source: Path) -> list[str]:
    """The files of the copy, as POSIX paths relative to ``source`` (sorted, each once)."""
    found = set()
    for pattern in _NEEDED:
        for path in source.glob(pattern):
            if path.is_file():
                found.add(path.relative_to(source).as_posix())
    return sorted(found)


def head_html(url: str = PAGE_URL) -> str:
    """The ``<head>`` elements that load MathJax from ``url`` with the settings of the bundled copy."""
    return (
        '<script type="text/x-mathjax-config">\n'
        f"{_PAGE_CONFIG}\n"
        "</script>\n"
        f'<script src="{html.escape(url, quote=True)}"></script>\n'
    )
