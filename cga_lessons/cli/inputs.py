"""The input files of the command line, read with the file and line named in every error.

Text files are read through :func:`read_csv_rows`, which turns a missing, binary or UTF-16 file, an over-long
line or field into one :class:`~cga_lessons.cli.errors.InputFileError` naming the file and line; a CARMEN log
through :func:`read_log`.  The map files of ``map2d`` and ``relocalize`` are read and written by
:mod:`cga_lessons.cli.segments_csv`.
"""

from __future__ import annotations

import codecs
import csv
from collections.abc import Iterator
from pathlib import Path

from cga_lessons.errors import InvalidInputError

from .errors import CLIError, InputFileError

__all__ = ["MAX_LINE_BYTES", "read_csv_rows", "read_log"]

MAX_LINE_BYTES = 1 << 20  # a line of a CSV input longer than this (1 MiB) is refused


def _q(path) -> str:
    return repr(str(path))


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
    cga_lessons.cli.errors.InputFileError: the map file '.../m.csv' is UTF-16 text, not UTF-8 (save it as UTF-8)
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


def read_log(path):
    """The CARMEN log at ``path`` (:func:`cga_lessons.mapping2d.read_carmen_log`); a missing, unreadable or
    malformed log raises a :class:`~cga_lessons.cli.CLIError` whose message names the file."""
    from cga_lessons.mapping2d import read_carmen_log  # NumPy and the mapping code, loaded by the commands that read

    try:
        return read_carmen_log(path)
    except InvalidInputError as exc:
        raise CLIError(str(exc).removeprefix("read_carmen_log: path: ")) from None
