"""Shared fixtures of the tests, and Hypothesis run deterministically.

The property tests draw their examples from a fixed seed (``derandomize``): a run of the suite on any machine is
the run that passed here, and a failure found by exploring (``pytest --hypothesis-seed=N``) is reproducible.
"""

import numpy as np
import pytest
from hypothesis import settings

from cga_lessons.mapping2d.laser import Scene

settings.register_profile("cga-lessons", derandomize=True)
settings.load_profile("cga-lessons")


def wall_polygons(outline, thickness=0.1):
    """Thin wall polygons along a closed outline (k, 2)."""
    out = []
    for a, b in zip(outline, np.roll(outline, -1, axis=0)):
        d = (b - a) / np.hypot(*(b - a))
        n = np.array([-d[1], d[0]]) * thickness / 2
        a2, b2 = a - d * thickness / 2, b + d * thickness / 2
        out.append(np.array([a2 - n, b2 - n, b2 + n, a2 + n]))
    return out


@pytest.fixture(scope="module")
def hall():
    """An irregular hall of orthogonal walls with three boxes (no symmetry)."""
    outline = np.array(
        [[0, 0], [7, 0], [7, 2], [9.5, 2], [9.5, 6], [6, 6], [6, 8.5], [2.5, 8.5], [2.5, 5], [0, 5]], float
    )
    boxes = [
        np.array([[1.5, 1.2], [2.7, 1.2], [2.7, 1.8], [1.5, 1.8]]),
        np.array([[7.5, 4.0], [8.2, 4.0], [8.2, 5.2], [7.5, 5.2]]),
        np.array([[3.6, 6.8], [4.4, 6.8], [4.4, 7.3], [3.6, 7.3]]),
    ]
    return Scene("hall", wall_polygons(outline) + boxes, np.zeros((1, 3)))


def pytest_terminal_summary(terminalreporter):
    """The fuzz of bad inputs counts what it tried (``tests/test_fuzz.py``)."""
    import sys

    harness = sys.modules.get("fuzz.harness")
    if harness is not None and harness.CALLS["inputs"]:
        counts = ", ".join(f"{k} {v}" for k, v in harness.TALLY.most_common())
        terminalreporter.write_line(
            f"fuzz of bad inputs: {harness.CALLS['cases']} cases, {harness.CALLS['inputs']} bad inputs: {counts}"
        )
