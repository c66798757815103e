"""The ``cga-lessons`` command line.

Subcommands::

    cga-lessons lab                       open the course in JupyterLab (root-safe, on 127.0.0.1)
    cga-lessons map2d LOG                 line map of a CARMEN laser log: a PNG, the segments as CSV, the
                                          trajectory as a TUM file, and its error against the log's poses
    cga-lessons relocalize MAP_CSV LOG --scan-index K [K ...]
                                          where is the robot of scan K on a saved map (chapter 5)
    cga-lessons equations                 the equation registry as a table (--todo, --write-readme)
    cga-lessons export-html               the stored, executed notebooks as a static site, offline

Every subcommand that writes files checks every output path before any work
and refuses to overwrite a file, or to write through a symbolic link, unless
``--force`` is given (which replaces the link itself, never its target; a
folder where a file goes is refused even then); it writes its files in a
hidden temporary folder and moves them into place only when all of them are
complete (:mod:`cga_lessons.cli.outputs`).  Missing or malformed inputs give a
one-line error and exit status 1 (2 for a wrong command line).
``python -m cga_lessons`` runs the same program.

Each command is a module of its own with its arguments (``add_parser``) and its run (``run``):
:mod:`~cga_lessons.cli.lab`, :mod:`~cga_lessons.cli.map2d`, :mod:`~cga_lessons.cli.relocalize`; ``equations`` runs
:func:`cga_lessons.equations.main` and ``export-html`` :func:`cga_lessons.cli.export.export_html`, whose
arguments are here.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from cga_lessons.errors import InvalidInputError

from . import lab, map2d, relocalize
from .errors import CLIError

__all__ = [
    "main",
    "build_parser",
]


def build_parser() -> argparse.ArgumentParser:
    """The parser of the whole command line: one subparser a command."""
    ap = argparse.ArgumentParser(
        prog="cga-lessons",
        description="Conformal geometric algebra for robot mapping: the course's command line.",
    )
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")
    lab.add_parser(sub)
    map2d.add_parser(sub)
    relocalize.add_parser(sub)
    _add_equations_parser(sub)
    _add_export_html_parser(sub)
    return ap


def _add_equations_parser(sub) -> None:
    """The ``equations`` command's arguments."""
    p = sub.add_parser("equations", help="the equation registry as a table", description="The coverage table.")
    p.add_argument("--format", choices=("markdown", "text"), default="text", help="output format (default text)")
    p.add_argument("--todo", action="store_true", help="list only the equations still todo")
    p.add_argument("--write-readme", action="store_true", help="regenerate the table between the README's markers")
    p.add_argument("--check-readme", action="store_true", help="exit with status 1 when the README's table is stale")
    p.add_argument("--readme", help="README to write or check (default: the checkout's README.md)")
    p.set_defaults(func=_cmd_equations)


def _add_export_html_parser(sub) -> None:
    """The ``export-html`` command's arguments."""
    p = sub.add_parser(
        "export-html",
        help="the executed notebooks as a static site",
        description="Convert the stored, executed notebooks to HTML pages with an index, without executing them and "
        "without any script or style loaded from the network.",
    )
    p.add_argument("--out-dir", default="site", help="folder for the pages (default: site)")
    p.add_argument("--notebook-dir", help="the notebooks folder (default: the checkout's notebooks/)")
    p.add_argument("--include-solutions", action="store_true", help="also export teacher_solutions.ipynb")
    p.add_argument(
        "--mathjax-url",
        default="",
        help="MathJax 2.7 script to typeset formulas (default: the copy bundled into the site's mathjax/)",
    )
    p.add_argument("--force", action="store_true", help="overwrite existing pages")
    p.set_defaults(func=_cmd_export_html)


def _cmd_equations(args) -> int:
    from cga_lessons.equations import main as equations_main

    argv = ["--format", args.format] + (["--todo"] if args.todo else [])
    if args.write_readme:
        argv.append("--write-readme")
    if args.check_readme:
        argv.append("--check-readme")
    if args.readme:
        if not Path(args.readme).is_file():
            raise CLIError(f"no such README {args.readme!r}")
        argv += ["--readme", args.readme]
    return equations_main(argv)


def _cmd_export_html(args) -> int:
    from .export import export_html  # nbconvert and its template, loaded for this command only

    return export_html(args)


def main(argv=None) -> int:
    """Run the command line with the arguments ``argv`` (a list of strings; None: the process's own, ``sys.argv``);
    returns the exit status: 0 done, 1 an error the user can fix (printed on one line), 2 a wrong command line
    (argparse's usage message), 130 interrupted.

    Raises
    ------
    InvalidInputError
        ``argv`` is not a list (or tuple) of strings (or paths).
    """
    parser = build_parser()
    try:
        args = parser.parse_args(_argv(argv))
    except SystemExit as exc:  # argparse has printed the usage and the error (status 2), or the help (status 0)
        return exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except CLIError as exc:
        message = " ".join(str(exc).split("\n"))  # one line, whatever the message holds
        print(f"cga-lessons {args.command}: error: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"cga-lessons {args.command}: interrupted", file=sys.stderr)
        return 130


def _argv(argv):
    """The command-line arguments as a list of strings (None: the process's own)."""
    if argv is None:
        return None
    if not isinstance(argv, (list, tuple)):
        raise InvalidInputError(f"main: argv: expected a list of strings, got {type(argv).__name__} {argv!r:.40}")
    bad = [a for a in argv if not isinstance(a, (str, os.PathLike))]
    if bad:
        raise InvalidInputError(f"main: argv: expected strings, got {bad[0]!r:.40} ({type(bad[0]).__name__})")
    return [os.fspath(a) for a in argv]


if __name__ == "__main__":
    sys.exit(main())
