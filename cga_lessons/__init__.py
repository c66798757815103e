"""cga-lessons: conformal geometric algebra for robot mapping, as a runnable course."""

from .paths import data_path

__version__ = "0.1.0"

__all__ = ["data_path", "__version__"]
