"""Where the project's files are: the checkout's root and the bundled data (layer 0: imports nothing of the package).

The data (``data/`` of the checkout: the CARMEN logs, the scenes, the stereo head) travel with the package:
``cga_lessons/data`` is a link to the checkout's ``data/`` folder, and a wheel carries a copy of it as package data,
so :func:`data_path` finds the files from a checkout, an editable install and an installed wheel alike.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["PROJECT_ROOT", "DATA_DIR", "data_path"]

_PACKAGE = Path(__file__).resolve().parent

#: The folder that holds ``cga_lessons/``, ``data/``, ``notebooks/`` and ``README.md`` in a checkout (in an installed
#: wheel it holds the package alone: the notebooks and the README are the checkout's).
PROJECT_ROOT = _PACKAGE.parent

#: The bundled data: the package's own copy (a wheel) or link (a checkout), else the checkout's ``data/`` folder
#: (a checkout where the link could not be made).
DATA_DIR = _PACKAGE / "data" if (_PACKAGE / "data").is_dir() else PROJECT_ROOT / "data"


def data_path(*parts: str) -> Path:
    """Path of a bundled data file, e.g. ``data_path("carmen", "intel-corrected.log.gz")``."""
    return DATA_DIR.joinpath(*parts)
