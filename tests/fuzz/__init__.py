"""The fuzz of bad inputs over every public callable (see :mod:`fuzz.harness`); cases by package in ``cases_*``."""
