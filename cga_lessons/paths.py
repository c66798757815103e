"""Where the project's files are: the checkout's root and its ``data/`` folder (layer 0: imports nothing of the
package)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["PROJECT_ROOT", "data_path"]

#: The folder that holds ``cga_lessons/``, ``data/``, ``notebooks/`` and ``README.md`` in a checkout.
PROJECT_ROOT = Path(__file__).resolve().parent.parent


def data_path(*parts: str) -> Path:
    """Path of a file in the project's ``data/`` folder."""
    return PROJECT_ROOT.joinpath("data", *parts)
