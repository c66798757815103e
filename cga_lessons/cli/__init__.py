"""The ``cga-lessons`` command line: its commands, file checks and the static site export.

Layer 6 of the package: imports any layer only (``tests/test_layers.py`` checks it).  This facade exports the names
in ``__all__``; its modules:

* :mod:`~cga_lessons.cli.commands`: The ``cga-lessons`` command line
* :mod:`~cga_lessons.cli.export`: ``cga-lessons export-html``: the stored, executed notebooks as a static site that
  loads nothing from the network
* :mod:`~cga_lessons.cli.io`: File checks and atomic writes of the command line (:mod:`cga_lessons.cli`)
* :mod:`~cga_lessons.cli.segments_csv`: The segments CSV of the command line: the map files ``map2d`` writes and
  ``relocalize`` reads
* :mod:`~cga_lessons.cli.site_math`: Formulas of the exported site (``cga-lessons export-html``) typeset offline: a
  copy of MathJax 2.7 beside the pages
"""

from .commands import build_parser, main
from .io import CLIError
from .segments_csv import SEGMENT_COLUMNS, read_segments_csv, write_segments_csv

__all__ = ["main", "build_parser", "CLIError", "SEGMENT_COLUMNS", "read_segments_csv", "write_segments_csv"]
