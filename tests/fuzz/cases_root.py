"""The package root's own public function, ``data_path``, and the layer-0 file writer (:mod:`cga_lessons.files`).

The writer is called as a public function calls it (``func="save"``, the name its errors must give); its paths are
fresh ones in a folder of their own, so that a valid call writes a new file.
"""

import tempfile
from pathlib import Path

from cga_lessons import data_path, files
from fuzz.harness import Case, temporary_folder

_DIR = temporary_folder("cga-fuzz-root-")


def _fresh(name: str) -> Path:
    """A path that does not exist yet (a new one for every call)."""
    return Path(tempfile.mkdtemp(dir=_DIR)) / name


CASES = [
    Case(
        data_path,
        {"*args": ("carmen", "intel-corrected.log.gz")},
        skip={"*args": "spoiled by the whole tuples below: the parts are names, not numbers"},
        label="data_path",
        extra={"*args": [("no-such-folder", "x.log"), ("..", "README.md"), ("/etc", "passwd"), (None,), ("", "x")]},
    ),
    Case(
        files.atomic_write,
        lambda: {"path": _fresh("out.txt"), "content": "text", "func": "save", "overwrite": False},
        label="save",
        skip={"func": "the caller's own name, a str the package writes, not a user's input"},
        extra={"path": [_DIR / "no-such-folder" / "x.txt", _DIR, ""]},
        kinds={"content": [None, 3.0, ["text"]]},
        strict=True,
    ),
]
EXEMPT = {}
