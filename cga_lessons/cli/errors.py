"""The errors of the command line: problems the user can fix, printed as one line without a traceback.

Every one is a :class:`CLIError`, so an :class:`~cga_lessons.algebra.InvalidInputError` (a ``ValueError``), as
everywhere in the package.  ``CLIError`` is exported by :mod:`cga_lessons.cli`, its public home.
"""

from __future__ import annotations

# cga_lessons.errors holds the error without importing NumPy, so that the command line starts quickly.
from cga_lessons.errors import InvalidInputError

__all__ = ["CLIError", "OutputPathError", "OutputExistsError", "InputFileError"]


class CLIError(InvalidInputError):
    """A problem the user can fix (a missing file, an output that exists); printed without a traceback.

    An :class:`~cga_lessons.algebra.InvalidInputError` (so a ``ValueError``), as every error the package raises
    for bad input.
    """


CLIError.__module__ = "cga_lessons.cli"  # its public home


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
