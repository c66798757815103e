"""Registry entries, one module per part of the thesis (see :mod:`cga_lessons.equations`)."""
