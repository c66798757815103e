"""File checks and atomic writes of the command line (:mod:`cga_lessons.cli`).

The rules every command that writes files follows:

* every output path is checked *before* any work (:func:`check_output_dir`,
  :func:`check_output_files`): the output folder must be a folder or
  creatable; a file inside must not exist unless overwriting was asked for;
  a folder (or another non-regular file) where a file goes is an error even
  then; a symbolic link where a file goes is refused unless overwriting was
  asked for, and then the link itself is replaced, never its target;
* a file is written to a temporary file in its own folder and renamed onto
  its path in one step (:func:`atomic_write`), and a command's set of files
  is written into a hidden temporary folder and moved into place only when
  every one of them is complete (:class:`StagedOutputs`): a failure or an
  interruption leaves no partial file and never touches an existing one.

Input text files are read through :func:`read_csv_rows`, which turns a
missing, binary or UTF-16 file, an over-long line or field into one
:class:`InputFileError` naming the file and line.  The map files of
``map2d`` and ``relocalize`` are read and written by
:mod:`cga_lessons.cli.segments_csv`.

The errors are :class:`~cga_lessons.cli.CLIError` subclasses, so the command line prints them as one-line
errors, and so :class:`~cga_lessons.algebra.InvalidInputError` subclasses (``ValueError``), as everywhere in the
package.  ``CLIError`` is defined here (so that these checks can raise it) and imported from
:mod:`cga_lessons.cli`, its public home.
"""

from __future__ import annotations

import codecs
import contextlib
import csv
import os
import shutil
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

# cga_lessons.errors holds the error without importing NumPy, so that the command line starts quickly.
from cga_lessons.errors import InvalidInputError

__all__ = [
    "CLIError",
    "OutputPathError",
    "OutputExistsError",
    "InputFileError",
    "check_output_dir",
    "check_output_files",
    "commit_file",
    "atomic_write",
    "StagedOutputs",
    "read_csv_rows",
]

MAX_LINE_BYTES = 1 << 20  # a line of a CSV input longer than this (1 MiB) is refused


class CLIError(InvalidInputError):
    """A problem the user can fix (a missing file, an output that exists); printed without a traceback.

    An :class:`~cga_lessons.algebra.InvalidInputError` (so a ``ValueError``), as every error the package raises
    for bad input.
    """


CLIError.__module__ = "cga_lessons.cli"  # its public home (defined here so that the file checks can raise it)


class OutputPathError(CLIError):
    """An output path that cannot be written as asked: a folder or a symbolic link where a file goes, a file
    where a folder goes, a folder without write permission.

    A :class:`~cga_lessons.cli.CLIError`, so an :class:`~cga_lessons.algebra.InvalidInputError`.
    """


class OutputExistsError(OutputPathError, FileExistsError):
    """An output file exists and overwriting was not asked for (nothing is written).

    Both an :class:`OutputPathError` (a ``ValueError``) and a ``FileExistsError``.
    """


class InputFileError(CLIError):
    """An input file that cannot be read: missing, a folder, binary, UTF-16, unreadable, or malformed.

    A :class:`~cga_lessons.cli.CLIError`, so an :class:`~cga_lessons.algebra.InvalidInputError`.
    """


def _q(path) -> str:
    return repr(str(path))


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _nearest_existing(path: Path) -> Path:
    for p in (path, *path.parents):
        if os.path.lexists(p):
            return p
    return Path(".")  # not reached: a relative path ends in "." and an absolute one in "/"


def check_output_dir(path, *, what: str = "output folder") -> Path:
    """Check that ``path`` is a folder one can write in, or can be made one; returns it as a :class:`Path`.

    Nothing is created.  A symbolic link to a folder is a folder.

    Raises
    ------
    OutputPathError
        ``path`` (or a folder on the way to it) is a file or a dangling link, or the folder in which it would
        be made is not writable.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> check_output_dir(folder / "new" / "site") == folder / "new" / "site"
    True
    >>> _ = (folder / "notes.txt").write_text("mine")
    >>> check_output_dir(folder / "notes.txt" / "site")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.io.OutputPathError: cannot make the output folder '.../notes.txt/site': '.../notes.txt' is a file
    """
    path = Path(path)
    base = _nearest_existing(path)
    if base.is_dir():
        if not os.access(base, os.W_OK | os.X_OK):
            doing = "write in" if base == path else f"make the {what} {_q(path)}: cannot write in"
            raise OutputPathError(f"cannot {doing} {_q(base)} (permission denied)")
        return path
    kind = "a dangling symbolic link" if base.is_symlink() and not base.exists() else "a file"
    if base == path:
        raise OutputPathError(f"the {what} {_q(path)} is {kind}, not a folder")
    raise OutputPathError(f"cannot make the {what} {_q(path)}: {_q(base)} is {kind}")


def check_output_files(paths, *, overwrite: bool = False, force_hint: str = "overwrite=True") -> list[Path]:
    """Check that each of ``paths`` can be written as a regular file; returns them as :class:`Path` objects.

    Only the paths themselves are looked at (see :func:`check_output_dir` for their folder).  An existing
    regular file, or a symbolic link (dangling or not), is an error unless ``overwrite``; a folder or another
    non-regular file (a FIFO, a device) is an error even then.  ``force_hint`` names the way to overwrite in
    the messages (``--force`` on the command line).

    Raises
    ------
    OutputPathError
        A folder, a non-regular file or (without ``overwrite``) a symbolic link where a file goes.
    OutputExistsError
        Without ``overwrite``, some of the files exist (all of them are named).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.csv").write_text("mine")
    >>> (folder / "b.csv").symlink_to(folder / "nowhere.csv")
    >>> [p.name for p in check_output_files([folder / "c.csv"])]
    ['c.csv']
    >>> check_output_files([folder / "a.csv"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.io.OutputExistsError: will not overwrite .../a.csv (pass overwrite=True to replace)
    >>> check_output_files([folder / "b.csv"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.io.OutputPathError: will not write through the symbolic link .../b.csv (pass ...)
    >>> check_output_files([folder], overwrite=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.io.OutputPathError: ... is a folder: an output file goes there
    """
    paths = [Path(p) for p in paths]
    existing = []
    for p in paths:
        try:
            st = p.lstat()
        except (FileNotFoundError, NotADirectoryError):  # free (a file on the way: check_output_dir names it)
            continue
        except OSError as exc:
            raise OutputPathError(f"cannot check the output file {_q(p)}: {exc.strerror or exc}") from None
        if stat.S_ISLNK(st.st_mode):
            if not overwrite:
                raise OutputPathError(
                    f"will not write through the symbolic link {p} (pass {force_hint} to replace the link itself, "
                    "never its target)"
                )
        elif stat.S_ISDIR(st.st_mode):
            raise OutputPathError(f"{_q(p)} is a folder: an output file goes there")
        elif not stat.S_ISREG(st.st_mode):
            raise OutputPathError(f"{_q(p)} is not a regular file: an output file goes there")
        else:
            existing.append(str(p))
    if existing and not overwrite:
        raise OutputExistsError(f"will not overwrite {', '.join(existing)} (pass {force_hint} to replace)")
    return paths


def commit_file(src, dst, *, overwrite: bool = False) -> Path:
    """Move the finished file ``src`` onto ``dst`` (in the same file system) in one step; returns ``dst``.

    With ``overwrite`` an existing ``dst`` is replaced (a symbolic link itself, never its target); without it
    an existing ``dst`` raises :class:`OutputExistsError` and ``src`` is left where it is (a hard link makes the
    check and the move one step, so a file that appears meanwhile is not overwritten either).
    """
    src, dst = Path(src), Path(dst)
    try:
        if overwrite:
            os.replace(src, dst)
            return dst
        try:
            os.link(src, dst)
        except FileExistsError:
            raise OutputExistsError(f"will not overwrite {dst} (it appeared meanwhile)") from None
        except OSError:  # no hard links on this file system: check, then rename
            if os.path.lexists(dst):
                raise OutputExistsError(f"will not overwrite {dst} (it appeared meanwhile)") from None
            os.replace(src, dst)
        else:
            os.unlink(src)
    except OutputPathError:
        raise
    except OSError as exc:
        raise OutputPathError(f"cannot write {_q(dst)}: {exc.strerror or exc}") from None
    return dst


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", *, overwrite: bool = False, **open_kwargs):
    """Write ``path`` in one step: the block writes a temporary file in the same folder, which is flushed to disk
    and renamed onto ``path`` when the block ends without an error, and removed when it raises.

    ``path`` is checked first with :func:`check_output_files`; ``mode`` is ``"w"`` or ``"wb"``; the other keyword
    arguments go to :func:`open` (``encoding``, ``newline``).  The file gets the permissions of a new file.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "out.txt"
    >>> with atomic_write(target, encoding="utf-8") as f:
    ...     _ = f.write("complete")
    >>> target.read_text()
    'complete'
    >>> with atomic_write(target, overwrite=True) as f:
    ...     _ = f.write("half")
    ...     raise ValueError("interrupted")
    Traceback (most recent call last):
    ...
    ValueError: interrupted
    >>> target.read_text(), sorted(p.name for p in target.parent.iterdir())
    ('complete', ['out.txt'])
    """
    if mode not in ("w", "wb"):
        raise InvalidInputError(f"atomic_write: mode must be 'w' or 'wb', got {mode!r}")
    path = Path(path)
    check_output_files([path], overwrite=overwrite)
    if not path.parent.is_dir():
        raise OutputPathError(f"cannot write {_q(path)}: no such folder {_q(path.parent)}")
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, mode, **open_kwargs) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes the file private; an output file is an ordinary one
        commit_file(tmp, path, overwrite=overwrite)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)


class StagedOutputs:
    """A command's output files, written into a hidden temporary folder and moved into ``out_dir`` together.

    Entering checks ``out_dir`` and the files (:func:`check_output_dir`, :func:`check_output_files`) and makes
    the temporary folder: inside ``out_dir`` when it exists, else beside it (in its nearest existing folder),
    so that a new ``out_dir`` appears in one rename, complete.  The block writes each file at
    :meth:`path` and calls :meth:`commit`; leaving the block without committing (an error, an interruption)
    removes the temporary folder, so nothing is left behind and no existing file is touched.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> site = pathlib.Path(tempfile.mkdtemp()) / "site"
    >>> with StagedOutputs(site, ["a.html", "index.html"]) as stage:
    ...     for name in stage.names:
    ...         _ = stage.path(name).write_text(name)
    ...     _ = stage.commit()
    >>> sorted(p.name for p in site.iterdir())
    ['a.html', 'index.html']
    >>> with StagedOutputs(site, ["b.html"]) as stage:
    ...     _ = stage.path("b.html").write_text("half")
    ...     raise ValueError("a page failed")
    Traceback (most recent call last):
    ...
    ValueError: a page failed
    >>> sorted(p.name for p in site.iterdir())
    ['a.html', 'index.html']
    """

    def __init__(self, out_dir, names, *, overwrite: bool = False, force_hint: str = "overwrite=True"):
        self.out_dir, self.names, self.overwrite = Path(out_dir), list(names), overwrite
        self.force_hint = force_hint
        self.targets = [self.out_dir / name for name in self.names]
        self._stage: Path | None = None
        self._fresh = False

    def __enter__(self) -> StagedOutputs:
        check_output_dir(self.out_dir, what="output folder")
        check_output_files(self.targets, overwrite=self.overwrite, force_hint=self.force_hint)
        self._fresh = not self.out_dir.is_dir()
        base = _nearest_existing(self.out_dir) if self._fresh else self.out_dir
        try:
            self._stage = Path(tempfile.mkdtemp(dir=base, prefix=".cga-lessons-", suffix=".tmp"))
        except OSError as exc:
            raise OutputPathError(f"cannot write in {_q(base)}: {exc.strerror or exc}") from None
        return self

    def path(self, name: str) -> Path:
        """Where to write the output file ``name`` (one of :attr:`names`) inside the temporary folder."""
        if self._stage is None or name not in self.names:
            raise InvalidInputError(f"StagedOutputs.path: {name!r} is not a staged output of {self.out_dir}")
        return self._stage / name

    def commit(self) -> list[Path]:
        """Move every file into ``out_dir`` (a new ``out_dir`` in one rename); returns the final paths."""
        stage = self._stage
        missing = [n for n in self.names if stage is None or not (stage / n).is_file()]
        if missing:
            raise InvalidInputError(f"StagedOutputs.commit: {', '.join(missing)} not written")
        if self._fresh and not os.path.lexists(self.out_dir):
            try:
                self.out_dir.parent.mkdir(parents=True, exist_ok=True)
                os.chmod(stage, 0o777 & ~_umask())  # mkdtemp makes the folder private; an output folder is not
                os.rename(stage, self.out_dir)
                self._stage = None
                return list(self.targets)
            except OSError:  # the folder appeared meanwhile: move the files one by one, as into an existing one
                pass
        try:
            self.out_dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise OutputPathError(f"cannot make the output folder {_q(self.out_dir)}: {exc.strerror or exc}") from None
        for name, target in zip(self.names, self.targets):
            commit_file(stage / name, target, overwrite=self.overwrite)
        return list(self.targets)

    def __exit__(self, *exc_info):
        if self._stage is not None:
            shutil.rmtree(self._stage, ignore_errors=True)
            self._stage = None
        return False


class _Lines:
    """The lines of a UTF-8 file open in binary mode, decoded one by one and counted, so that a message names
    the line at fault: at most ``max_bytes`` bytes each, no NUL byte, a byte-order mark skipped."""

    def __init__(self, path: Path, what: str, max_bytes: int):
        self.path, self.what, self.max_bytes, self.count = path, what, max_bytes, 0

    def read(self, f) -> Iterator[str]:
        while line := f.readline(self.max_bytes + 1):
            self.count += 1
            where = f"the {self.what} {_q(self.path)}, line {self.count}"
            if len(line) > self.max_bytes:
                raise InputFileError(f"{where}: a line longer than {self.max_bytes} bytes")
            if b"\0" in line:
                raise InputFileError(f"{where}: a NUL byte (a binary file, not text)")
            if self.count == 1:
                line = line.removeprefix(codecs.BOM_UTF8)
            try:
                yield line.decode("utf-8")
            except UnicodeDecodeError as exc:
                raise InputFileError(f"{where}: not UTF-8 text ({exc.reason})") from None


def read_csv_rows(path, *, what: str = "file", max_line: int = MAX_LINE_BYTES) -> Iterator[tuple[int, list[str]]]:
    """The rows of a UTF-8 CSV file (a byte-order mark is skipped), each as ``(line number, fields)``.

    Raises :class:`InputFileError` naming the file (and the line) when it is missing, a folder, unreadable,
    binary (it holds NUL bytes), UTF-16 or UTF-32 text, not UTF-8, or has a line longer than ``max_line``
    bytes or a field longer than :func:`csv.field_size_limit`.  ``what`` names the file in the messages.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "m.csv"
    >>> _ = p.write_bytes(b"\\xef\\xbb\\xbfa,b\\n1,2\\n")
    >>> list(read_csv_rows(p))
    [(1, ['a', 'b']), (2, ['1', '2'])]
    >>> _ = p.write_text("a,b", encoding="utf-16")
    >>> list(read_csv_rows(p, what="map file"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.io.InputFileError: the map file '.../m.csv' is UTF-16 text, not UTF-8 (save it as UTF-8)
    """
    path = Path(path)
    if not path.exists():
        raise InputFileError(f"no such {what} {_q(path)}")
    if not path.is_file():
        raise InputFileError(f"the {what} {_q(path)} is {'a folder' if path.is_dir() else 'not a regular file'}")
    lines = _Lines(path, what, max_line)
    try:
        with open(path, "rb") as f:
            head = f.read(4)
            boms = {
                "UTF-32": (codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE),
                "UTF-16": (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE),
            }
            for name, marks in boms.items():  # UTF-32 first: its little-endian mark starts with UTF-16's
                if head.startswith(marks):
                    raise InputFileError(f"the {what} {_q(path)} is {name} text, not UTF-8 (save it as UTF-8)")
            f.seek(0)
            rows = csv.reader(lines.read(f))
            for row in rows:
                yield rows.line_num, row
    except csv.Error as exc:
        text = str(exc)
        if "field larger than field limit" in text:
            text = f"a field longer than {csv.field_size_limit()} characters"
        raise InputFileError(f"the {what} {_q(path)}, line {lines.count}: {text}") from None
    except OSError as exc:
        raise InputFileError(f"cannot read the {what} {_q(path)}: {exc.strerror or exc}") from None


# --------------------------------------------------------------------------- segments as CSV
