"""``cga-lessons lab``: the course opened in JupyterLab, local only (127.0.0.1) and safe to start as root."""

from __future__ import annotations

import importlib.util
import os
import shlex
import subprocess
import sys
from pathlib import Path

from cga_lessons.paths import PROJECT_ROOT

from .errors import CLIError

__all__ = ["add_parser", "run"]


def add_parser(sub) -> None:
    """The ``lab`` command's arguments."""
    p = sub.add_parser("lab", help="open the course in JupyterLab", description="Open the notebooks in JupyterLab.")
    p.add_argument("--notebook-dir", help="the notebooks folder (default: the checkout's notebooks/)")
    p.add_argument("--port", type=int, help="port to listen on (default: JupyterLab's choice)")
    p.add_argument("--no-browser", action="store_true", help="do not open a browser")
    p.add_argument("--dry-run", action="store_true", help="print the command instead of running it")
    p.set_defaults(func=run)


def run(args) -> int:
    """Run ``lab`` with the parsed arguments ``args``: JupyterLab replaces this process (on POSIX); returns its
    exit status elsewhere, 0 after a dry run."""
    nbdir = Path(args.notebook_dir) if args.notebook_dir else PROJECT_ROOT / "notebooks"
    if not nbdir.is_dir():
        raise CLIError(f"no notebooks folder at {nbdir} (run from a checkout of the course, or pass --notebook-dir)")
    # The lab's root is the checkout (README.md, data/ and notebooks/ side by side), the notebooks' folder opened.
    root = nbdir.parent if nbdir.name == "notebooks" else nbdir
    cmd = [sys.executable, "-m", "jupyterlab", f"--ServerApp.root_dir={root}", "--ServerApp.ip=127.0.0.1"]
    if args.port:
        cmd.append(f"--ServerApp.port={args.port}")
    if args.no_browser:
        cmd.append("--no-browser")
    if (nbdir / "00_start_here.ipynb").is_file():
        cmd.append(f"--LabApp.default_url=/lab/tree/{(nbdir / '00_start_here.ipynb').relative_to(root).as_posix()}")
    if getattr(os, "geteuid", lambda: 1)() == 0:
        cmd.append("--allow-root")  # JupyterLab refuses to start as root without it
    if args.dry_run:
        print(shlex.join(cmd))
        return 0
    if importlib.util.find_spec("jupyterlab") is None:
        raise CLIError("JupyterLab is not installed: pip install -e . installs it with the course")
    if os.name == "posix":  # become JupyterLab: signals (Ctrl-C, a kill) reach the server, no orphan is left
        os.execv(cmd[0], cmd)
    try:
        return subprocess.call(cmd)
    except KeyboardInterrupt:
        return 130
