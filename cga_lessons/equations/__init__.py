"""The equation registry (every numbered equation of the thesis -> code and test) and the course's table of chapters.

Layer 5 of the package: imports layers 0-4 only (``tests/test_layers.py`` checks it).  This facade exports the names
in ``__all__``; its modules:

* :mod:`~cga_lessons.equations.core`: The equation registry: every numbered equation of the thesis -> code and test
* :mod:`~cga_lessons.equations.course`: The course's chapters and how they depend on each other: one table for the
  README and notebook 00
* :mod:`~cga_lessons.equations.readme`: The registry rendered: the README's equation table, the terminal's table and
  the command ``python -m cga_lessons.equations``
* :mod:`~cga_lessons.equations.registry`: one module of entries per part of the thesis
"""

from .core import (
    REGISTRY,
    STATUSES,
    THESIS_LABELS,
    Coverage,
    Entry,
    check_registry,
    coverage,
    coverage_summary,
    table,
)
from .course import arrows, dependency_table
from .readme import (
    PARTS,
    README_END,
    README_START,
    main,
    ordered_entries,
    readme_is_current,
    readme_section,
    text_table,
    write_readme,
)

__all__ = [
    "Entry",
    "Coverage",
    "REGISTRY",
    "THESIS_LABELS",
    "coverage_summary",
    "coverage",
    "check_registry",
    "table",
    "ordered_entries",
    "readme_section",
    "text_table",
    "write_readme",
    "readme_is_current",
    "README_START",
    "README_END",
    "PARTS",
    "STATUSES",
    "main",
    "arrows",
    "dependency_table",
]
