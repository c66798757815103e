"""Where the project's files are: the checkout's root and the bundled data (layer 0: imports nothing of the package).

The data (``data/`` of the checkout: the CARMEN logs, the scenes, the stereo head) travel with the package:
``cga_lessons/data`` is a link to the checkout's ``data/`` folder, and a wheel carries a copy of it as package data,
so :func:`data_path` finds the files from a checkout, an editable install and an installed wheel alike.
"""

from __future__ import annotations

from pathlib import Path, PurePosixPath

from cga_lessons.errors import InvalidInputError

__all__ = ["PROJECT_ROOT", "DATA_DIR", "data_path"]

_PACKAGE = Path(__file__).resolve().parent

#: The folder that holds ``cga_lessons/``, ``data/``, ``notebooks/`` and ``README.md`` in a checkout (in an installed
#: wheel it holds the package alone: the notebooks and the README are the checkout's).
PROJECT_ROOT = _PACKAGE.parent

#: The bundled data: the package's own copy (a wheel) or link (a checkout), else the checkout's ``data/`` folder
#: (a checkout where the link could not be made).
DATA_DIR = _PACKAGE / "data" if (_PACKAGE / "data").is_dir() else PROJECT_ROOT / "data"


def data_path(*parts: str) -> Path:
    """Path of a bundled data file or folder, e.g. ``data_path("carmen", "intel-corrected.log.gz")``.

    Each part is a name inside the bundled data (no absolute path, no ``..``); a path that names nothing bundled
    raises :class:`~cga_lessons.algebra.InvalidInputError` listing what the folder holds.
    """
    for part in parts:
        if not isinstance(part, str) or not part:
            raise InvalidInputError(f"data_path: parts: expected names (non-empty strings), got {part!r:.40}")
        if PurePosixPath(part).is_absolute() or ".." in PurePosixPath(part.replace("\\", "/")).parts:
            raise InvalidInputError(f"data_path: parts: {part!r} leaves the bundled data folder")
    path = DATA_DIR.joinpath(*parts)
    if not path.exists():
        parent = path.parent if path.parent.is_dir() else DATA_DIR
        held = ", ".join(sorted(q.name for q in parent.iterdir() if not q.name.startswith(("_", ".")))[:20])
        raise InvalidInputError(f"data_path: parts: no bundled {'/'.join(parts)!r}; {parent.name}/ holds {held}")
    return path
