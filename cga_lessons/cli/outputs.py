"""The output paths of the command line: checked before any work, written whole or not at all.

The rules every command that writes files follows:

* every output path is checked *before* any work (:func:`check_output_dir`,
  :func:`check_output_files`): the output folder must be a folder or
  creatable; a file inside must not exist unless overwriting was asked for;
  a folder (or another non-regular file) where a file goes is an error even
  then; a symbolic link where a file goes is refused unless overwriting was
  asked for, and then the link itself is replaced, never its target;
* a command's set of files is written into a hidden temporary folder and moved into place only when every one of
  them is complete (:class:`StagedOutputs`), each file moved in one step by the package's one file writer
  (:func:`cga_lessons.files.atomic_move`, through :func:`commit_file`): a failure or an interruption leaves no
  partial file and never touches an existing one.

The errors are the :class:`~cga_lessons.cli.errors.OutputPathError` family, so the command line prints them as
one-line errors.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from pathlib import Path

from cga_lessons.errors import InvalidInputError
from cga_lessons.files import ExistingFileError, atomic_move, umask

from .errors import OutputExistsError, OutputPathError

__all__ = ["check_output_dir", "check_output_files", "commit_file", "StagedOutputs"]


def _q(path) -> str:
    return repr(str(path))


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
    cga_lessons.cli.errors.OutputPathError: cannot make the output folder '.../notes.txt/site': '...' is a file
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
    cga_lessons.cli.errors.OutputExistsError: will not overwrite .../a.csv (pass overwrite=True to replace)
    >>> check_output_files([folder / "b.csv"])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.errors.OutputPathError: will not write through the symbolic link .../b.csv (pass ...)
    >>> check_output_files([folder], overwrite=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    cga_lessons.cli.errors.OutputPathError: ... is a folder: an output file goes there
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
    try:
        return atomic_move(src, dst, "commit_file", "dst", overwrite=overwrite)
    except ExistingFileError:
        raise OutputExistsError(f"will not overwrite {dst} (it appeared meanwhile)") from None
    except OSError as exc:
        raise OutputPathError(f"cannot write {_q(dst)}: {exc.strerror or exc}") from None


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
                os.chmod(stage, 0o777 & ~umask())  # mkdtemp makes the folder private; an output folder is not
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
