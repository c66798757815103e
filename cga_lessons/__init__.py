"""cga-lessons: conformal geometric algebra for robot mapping, as a runnable course."""

from pathlib import Path

__version__ = "0.1.0"

_ROOT = Path(__file__).resolve().parent.parent


def data_path(*parts: str) -> Path:
    """Path of a file in the project's ``data/`` folder."""
    return _ROOT.joinpath("data", *parts)
