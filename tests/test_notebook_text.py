"""The notebooks' narrative holds no hand-typed measurements: every measured number is printed by a cell (nbval then
catches drift).  A number with a unit in a Markdown cell is allowed only when it is an input, not a result: a
parameter of a scene, a sensor or a method's default, a thesis constant, an exercise's data or its worked answer.
Each allowed one is listed below with its reason; anything else fails, and so does a listed one that is gone.
"""

import re
from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"

UNIT = r"(?:cm|mm|km|m|%|px|°|deg|degrees|ms|µs|us|s|rad|×|x)"
NUMBER = r"\d+(?:[.,]\d+)*(?:\s*(?:–|-|to)\s*\d+(?:\.\d+)?)?"
MEASURE = re.compile(r"(?<![\w.\\])(" + NUMBER + r")\s?(" + UNIT + r")(?![\w])")

SCENE = "a parameter of the simulated scene, robot or sensor (an input)"
METHOD = "a method's documented default or a drawing choice (an input)"
DATA = "a stated fact of the bundled data or its calibration (its README / docstring)"
THESIS = "the thesis's own setting or figure parameter"
EXERCISE = "an exercise's data or its worked answer (checked by exercises.check)"

ALLOWED = {
    "05_laser_line_maps.ipynb": {
        THESIS: ["180°", "0.5°", "5 m"],
        METHOD: ["8 m"],
        DATA: ["1°", "80 m"],
        EXERCISE: ["12 m", "25°"],
    },
    "06_conformal_line_maps.ipynb": {METHOD: ["0.3 m"]},
    "07_stereo_reconstruction.ipynb": {DATA: ["4×"]},
    "09_relocalization.ipynb": {EXERCISE: ["6 m", "4 m"]},
    "teacher_solutions.ipynb": {EXERCISE: ["2 rad", "12 m"]},
}


def _prose(source: str) -> str:
    """Markdown without its math, inline code and equation references (numbers there are not measurements)."""
    source = re.sub(r"\$\$.*?\$\$", " ", source, flags=re.S)
    source = re.sub(r"\$[^$]*\$", " ", source)
    source = re.sub(r"`[^`]*`", " ", source)
    return re.sub(r"\((?:[0-9A]+\.\d+[a-z]?)(?:\s*[-–,]\s*[0-9A]+\.\d+)*\)", " ", source)


def _measurements(path: Path) -> list[tuple[int, str]]:
    nb = nbformat.read(path, as_version=4)
    return [(i, m.group(0)) for i, cell in enumerate(nb.cells) if cell.cell_type == "markdown"
            for m in MEASURE.finditer(_prose(cell.source))]  # fmt: skip


def test_the_scanner_finds_a_typed_measurement():
    assert [m.group(0) for m in MEASURE.finditer(_prose("the error is 3.7 cm, see (2.62) and $x = 5 m$"))] == ["3.7 cm"]


@pytest.mark.parametrize("path", sorted(NOTEBOOKS.glob("*.ipynb")), ids=lambda p: p.name)
def test_no_hand_typed_measurements_in_the_narrative(path):
    allowed = {text for texts in ALLOWED.get(path.name, {}).values() for text in texts}
    found = _measurements(path)
    unexpected = [(i, text) for i, text in found if text not in allowed]
    assert not unexpected, f"{path.name}: numbers with units typed in Markdown (print them from a cell): {unexpected}"
    stale = allowed - {text for _, text in found}
    assert not stale, f"{path.name}: allowed but no longer in the text (remove from ALLOWED): {sorted(stale)}"


def test_the_allowance_is_reported():
    """Each allowed number is listed once per notebook, under one of the five reasons; the counts are printed."""
    reasons = (SCENE, METHOD, DATA, THESIS, EXERCISE)
    for name, groups in ALLOWED.items():
        assert set(groups) <= set(reasons), name
        texts = [t for v in groups.values() for t in v]
        assert len(texts) == len(set(texts)), f"{name}: listed twice"
    counts = {reason: sum(len(v.get(reason, [])) for v in ALLOWED.values()) for reason in reasons}
    print("allowed numbers with units, by reason:", counts)
