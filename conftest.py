"""pytest configuration shared by the unit tests, the doctests and the notebooks.

The notebooks run in Jupyter kernels (nbval), which are separate processes: put
this checkout first on their ``PYTHONPATH`` so a kernel imports the package next
to the notebook under test, whatever copy of ``cga_lessons`` is installed.
"""

import os
from pathlib import Path

_ROOT = str(Path(__file__).resolve().parent)
_paths = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and p != _ROOT]
os.environ["PYTHONPATH"] = os.pathsep.join([_ROOT, *_paths])


import pytest  # noqa: E402

# The bundled data's scripts (cga_lessons/data links to data/) are not the package's modules.
collect_ignore = ["cga_lessons/data"]


@pytest.fixture(autouse=True)
def _close_figures():
    """Close the matplotlib figures a test or doctest opened (the explorers keep theirs open to redraw them)."""
    yield
    import sys

    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")


@pytest.fixture(autouse=True)
def _doctest_temporary_files(request, tmp_path_factory, monkeypatch):
    """The folders a doctest makes with ``tempfile`` go in pytest's own temporary tree, which pytest prunes."""
    if isinstance(request.node, pytest.DoctestItem):
        import tempfile

        monkeypatch.setattr(tempfile, "tempdir", str(tmp_path_factory.mktemp("doctest")))
    yield
