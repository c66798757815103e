"""The ``cga-lessons`` command line: its commands, file checks and the static site export.

Layer 6 of the package: imports any layer only (``tests/test_layers.py`` checks it).  This facade exports the names
in ``__all__``; its modules:

* :mod:`~cga_lessons.cli.commands`: The ``cga-lessons`` command line: its parser and ``main``
* :mod:`~cga_lessons.cli.lab`, :mod:`~cga_lessons.cli.map2d`, :mod:`~cga_lessons.cli.relocalize`: one command each
  (its arguments and its run)
* :mod:`~cga_lessons.cli.export`: ``cga-lessons export-html``: the stored, executed notebooks as a static site that
  loads nothing from the network
* :mod:`~cga_lessons.cli.site_math`: Formulas of the exported site (``cga-lessons export-html``) typeset offline: a
  copy of MathJax 2.7 beside the pages
* :mod:`~cga_lessons.cli.arguments`: The argument types of the command line's parsers
* :mod:`~cga_lessons.cli.progress`: The progress bar of the long commands
* :mod:`~cga_lessons.cli.errors`: The errors of the command line (one-line messages, no traceback)
* :mod:`~cga_lessons.cli.inputs`: The input files, read with the file and line named in every error
* :mod:`~cga_lessons.cli.outputs`: The output paths, checked before any work, written whole or not at all
* :mod:`~cga_lessons.cli.segments_csv`: The segments CSV of the command line: the map files ``map2d`` writes and
  ``relocalize`` reads
"""

from .commands import build_parser, main
from .errors import CLIError
from .segments_csv import SEGMENT_COLUMNS, read_segments_csv, write_segments_csv

__all__ = ["main", "build_parser", "CLIError", "SEGMENT_COLUMNS", "read_segments_csv", "write_segments_csv"]
