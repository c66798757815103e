"""Files written whole or not at all: the package's one writer of output files (layer 0).

Every function of the package that writes a file (``write_tum``, meshcat's ``export_html``, the command line's map
files and staged outputs) writes it here, by these rules:

* nothing is written over an existing file unless it is asked for (``overwrite=True``); a symbolic link where the
  file goes counts as an existing file, and with ``overwrite`` the link itself is replaced, never its target;
* no partial file: the content goes to a hidden temporary file in the same folder, which is flushed to disk and
  renamed onto the path in one step; on any failure, an error raised by the caller's own code that produces the
  content included, the temporary file is removed and an existing file is left as it was;
* a bad path (not a path, a folder, in a folder that does not exist or cannot be written in, an existing file)
  raises the checks' ``ValueError`` naming the function and its argument (:func:`cga_lessons.checks.new_path`);
  a failure of the file system itself (a full disk) raises its ``OSError``, and leaves nothing behind either.

Layer 0: imports :mod:`cga_lessons.errors`, and :mod:`cga_lessons.checks` when a file is written (not on import:
NumPy, which the checks use, stays out of the command line's start).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from cga_lessons.errors import InvalidInputError

__all__ = ["ExistingFileError", "atomic_open", "atomic_write", "atomic_move", "umask"]


class ExistingFileError(InvalidInputError, FileExistsError):
    """A file to write exists (or a symbolic link lies where it goes) and overwriting was not asked for: nothing
    was written.

    Both an :class:`~cga_lessons.algebra.InvalidInputError` (a ``ValueError``) and a ``FileExistsError``.
    """


def _exists(func: str, name: str, path: Path) -> ExistingFileError:
    return ExistingFileError(f"{func}: {name}: {path} exists (pass overwrite=True to replace it)")


def umask() -> int:
    """The process's file-creation mask: a new file gets the permissions ``0o666 & ~umask()``."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def atomic_move(src, dst, func: str, name: str = "path", *, overwrite: bool = False) -> Path:
    """Move the finished file ``src`` onto ``dst`` (in the same file system) in one step; returns ``dst``.

    With ``overwrite`` an existing ``dst`` is replaced (a symbolic link itself, never its target).  Without it an
    existing ``dst`` raises :class:`ExistingFileError` (``"func: name: ... exists ..."``) and ``src`` is left where
    it is: a hard link makes the check and the move one step, so a file that appears meanwhile is not overwritten
    either.  Another failure of the file system raises its ``OSError``.
    """
    src, dst = Path(src), Path(dst)
    if overwrite:
        os.replace(src, dst)
        return dst
    try:
        os.link(src, dst)
    except FileExistsError:
        raise _exists(func, name, dst) from None
    except OSError:  # no hard links on this file system: check, then rename
        if os.path.lexists(dst):
            raise _exists(func, name, dst) from None
        os.replace(src, dst)
    else:
        os.unlink(src)
    return dst


@contextlib.contextmanager
def atomic_open(
    path,
    func: str,
    name: str = "path",
    *,
    overwrite: bool = False,
    binary: bool = False,
    encoding: str = "utf-8",
    newline: str | None = None,
) -> Iterator[IO]:
    """Open ``path`` to be written whole or not at all: the block writes a hidden temporary file in the same
    folder, which becomes ``path`` when the block ends without an error and is removed when it raises.

    ``path`` is checked on entering, before the block runs: a str or a Path, not a folder, in an existing folder,
    not an existing file (nor a symbolic link) unless ``overwrite``.  The file is text (``encoding``, ``newline`` as
    for :func:`open`) or, with ``binary``, bytes; it gets the permissions of a new file.  ``func`` and ``name`` are
    the public function writing and its argument holding the path, named in the errors.

    Raises
    ------
    ExistingFileError
        ``path`` exists and ``overwrite`` is false (checked on entering and again when the file is moved in).
    InvalidInputError
        ``path`` is not a path, is a folder, or its folder is missing or cannot be written in.
    OSError
        The file system fails while the file is written or moved in (a full disk): nothing is left behind.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_open(target, "save") as f:
    ...     _ = f.write("complete")
    >>> with atomic_open(target, "save", overwrite=True) as f:
    ...     _ = f.write("half")
    ...     raise RuntimeError("interrupted")
    Traceback (most recent call last):
    ...
    RuntimeError: interrupted
    >>> target.read_text(), sorted(p.name for p in target.parent.iterdir())
    ('complete', ['out.txt'])
    """
    from cga_lessons import checks  # on the first write, not on import (see the module's note)

    overwrite = checks.flag(overwrite, func, "overwrite")
    path = checks.new_path(path, func, name, overwrite=True)  # a path, not a folder, its folder there
    if not overwrite and os.path.lexists(path):
        raise _exists(func, name, path)
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    except OSError as exc:
        raise checks.fail(func, name, f"cannot write in {path.parent}: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "wb") if binary else os.fdopen(fd, "w", encoding=encoding, newline=newline) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o666 & ~umask())  # mkstemp makes the file private; an output file is an ordinary one
        atomic_move(tmp, path, func, name, overwrite=overwrite)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)


def atomic_write(
    path, content: str | bytes, func: str, name: str = "path", *, overwrite: bool = False, encoding: str = "utf-8"
) -> Path:
    """Write ``content`` (a str, or bytes) to ``path`` whole or not at all, by :func:`atomic_open`'s rules;
    returns the path as a :class:`Path`.  Its errors name ``func``, the public function writing.

    >>> import pathlib, tempfile
    >>> target = atomic_write(pathlib.Path(tempfile.mkdtemp()) / "a.txt", "mine", "save")
    >>> atomic_write(target, "theirs", "save")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.files.ExistingFileError: save: path: .../a.txt exists (pass overwrite=True to replace it)
    >>> target.read_text()
    'mine'
    """
    if not isinstance(content, (str, bytes, bytearray)):
        raise InvalidInputError(f"{func}: content: expected a str or bytes, got {type(content).__name__}")
    binary = not isinstance(content, str)
    with atomic_open(path, func, name, overwrite=overwrite, binary=binary, encoding=encoding) as f:
        f.write(content)
    return Path(path)
