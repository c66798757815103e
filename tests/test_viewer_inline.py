"""The 3D scene embedded in a notebook's output (cga_lessons.viz.meshcat_scene.scene_iframe) and notebook 08's copy.

The iframe is read back with the standard library's HTML parser (which undoes the attribute escaping the way a
browser does), the stored notebook is read as JSON, and meshcat's commands are decoded from their msgpack bytes:
nothing here goes through the code that wrote them.  The exported page is opened in headless Chromium (skipped
without it, unless CGA_LESSONS_REQUIRE_CHROMIUM is set, as in tests/test_viewer.py) and the screenshot's pixels in
the scene's area are inspected.
"""

import base64
import json
import os
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import nbformat
import numpy as np
import pytest
import umsgpack
from headless import require_chromium, run_chromium

from cga_lessons import cli
from cga_lessons.algebra import InvalidInputError
from cga_lessons.viz.meshcat_scene import EmbeddedScene, scene_html, scene_iframe
from cga_lessons.viz.scene3d import Box, Polyline, Sphere

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK = ROOT / "notebooks" / "08_fused_3d_map.ipynb"


class Page(HTMLParser):
    """Every element's attributes (unescaped) and the text outside iframes."""

    def __init__(self, text):
        super().__init__()
        self.elements, self.text, self._in_iframe = [], [], 0
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        self.elements.append((tag, dict(attrs)))
        self._in_iframe += tag == "iframe"

    def handle_endtag(self, tag):
        self._in_iframe -= tag == "iframe"

    def handle_data(self, data):
        if not self._in_iframe:
            self.text.append(data)

    def iframes(self):
        return [a for t, a in self.elements if t == "iframe"]


def small_scene():
    return [
        Sphere("objects/ball", (1.0, 0.5, 0.3), 0.15, (0.9, 0.1, 0.1)),
        Box("robot/base", (0.0, 0.0, 0.15), (0.5, 0.4, 0.3), color=(0.2, 0.4, 0.8)),
        Polyline("robot/path", [[0, 0, 0], [1, 0, 0], [1, 1, 0]], (0.0, 0.0, 0.0)),
    ]


def commands(page: str) -> list:
    """meshcat's commands replayed by an offline page: the msgpack of each ``run("...")``, decoded."""
    return [umsgpack.unpackb(base64.b64decode(b)) for b in re.findall(r'\nrun\("([A-Za-z0-9+/=]+)"\);', page)]


def _without_commands(page: str) -> str:
    return re.sub(r'\nrun\("[A-Za-z0-9+/=]+"\);', "", page)


_UUID = re.compile(r"^[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}$")


def _no_uuid(value):
    """A command with each uuid (drawn afresh for every object, and referred to by its mesh) made the same."""
    if isinstance(value, dict):
        return {k: _no_uuid(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_no_uuid(v) for v in value]
    return "<uuid>" if isinstance(value, str) and _UUID.match(value) else value


# ============================================================ the helper
def test_scene_iframe_holds_the_offline_page_in_a_sandboxed_iframe():
    prims = small_scene()
    view = scene_iframe(prims, height=300)
    assert isinstance(view, EmbeddedScene) and view._repr_html_() == view.html
    assert repr(view) == "<meshcat scene of 3 primitives, an interactive 3D view 300 px high>"
    page = Page(view.html)
    (frame,) = page.iframes()
    # the whole page, escaped and read back unchanged (but for the uuids meshcat draws for each object)
    want = scene_html(prims)
    assert _without_commands(frame["srcdoc"]) == _without_commands(want)
    assert [_no_uuid(c) for c in commands(frame["srcdoc"])] == [_no_uuid(c) for c in commands(want)]
    assert frame["sandbox"] == "allow-scripts"  # meshcat runs; no access to the notebook's page
    assert "height: 100%" in frame["style"] and "position: absolute" in frame["style"]
    box = page.elements[0][1]
    assert page.elements[0][0] == "div" and "height: 300px" in box["style"]
    # the srcdoc attribute is one quoted value: no raw quote or '<' of the page is left in the markup
    inside = view.html.split('srcdoc="', 1)[1].rsplit('"></iframe>', 1)[0]
    assert '"' not in inside and "<" not in inside
    # camera framing is the export's: same commands, a closer camera changes only the camera's position
    near = Page(scene_iframe(prims, camera_distance=0.5).html).iframes()[0]["srcdoc"]
    far = commands(frame["srcdoc"])
    assert [c["path"] for c in commands(near)] == [c["path"] for c in far]
    assert len(far) == 2 * len(prims) + 2


def test_a_sanitized_output_keeps_the_note():
    """JupyterLab drops iframes from an untrusted notebook's outputs: the note beside the iframe is what remains."""
    view = scene_iframe(small_scene())
    note = " ".join("".join(Page(view.html).text).split())
    assert "interactive 3D view of 3 primitives" in note and "Trust Notebook" in note
    stripped = re.sub(r"<iframe\b.*?</iframe>", "", view.html, flags=re.S)
    assert "<iframe" not in stripped and "Trust Notebook" in stripped


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"height": 50}, "height"),
        ({"height": 480.0}, "height"),
        ({"height": True}, "height"),
        ({"height": "480px"}, "height"),
        ({"camera_distance": 0.0}, "camera_distance"),
        ({"camera_distance": np.nan}, "camera_distance"),
    ],
)
def test_scene_iframe_rejects_bad_sizes(kwargs, words):
    with pytest.raises(InvalidInputError, match="scene_iframe") as info:
        scene_iframe(small_scene(), **kwargs)
    assert words in str(info.value) and isinstance(info.value, ValueError)


def test_scene_iframe_rejects_bad_scenes():
    with pytest.raises(InvalidInputError, match="scene_iframe: primitives: the scene is empty"):
        scene_iframe([])
    with pytest.raises(InvalidInputError, match="scene_iframe"):
        scene_iframe([small_scene()[0], "a ball"])


# ============================================================ notebook 08's stored output
def _stored_view():
    nb = json.loads(NOTEBOOK.read_text(encoding="utf-8"))
    cells = [c for c in nb["cells"] if c["cell_type"] == "code"]
    (cell,) = [c for c in cells if "scene_iframe(" in "".join(c["source"])]
    (explorer,) = [c for c in cells if "RobotExplorer(" in "".join(c["source"])]
    return nb, cell, explorer


def test_notebook_08_stores_one_embedded_scene():
    nb, cell, explorer = _stored_view()
    assert "".join(cell["source"]).startswith("# NBVAL_IGNORE_OUTPUT")  # large, and floating-point bytes
    outputs = [o for o in cell["outputs"] if "text/html" in o.get("data", {})]
    assert len(outputs) == 1
    html = "".join(outputs[0]["data"]["text/html"])
    (frame,) = Page(html).iframes()
    page = frame["srcdoc"]
    assert page.startswith("<!DOCTYPE html>") and "MeshCat.Viewer" in page
    # one copy of meshcat's library in the whole notebook (about 0.85 MB): the view is embedded once
    assert json.dumps(nb).count("MeshCat.Viewer(") == 1
    cmds = commands(page)
    objects = {c["path"] for c in cmds if c["type"] == "set_object"}
    n = int(re.search(r"of (\d+) primitives", "".join(outputs[0]["data"]["text/plain"])).group(1))
    assert len(objects) == n and len(cmds) == 2 * n + 2  # an object and a pose each, and the camera
    groups = {p.split("/")[2] for p in objects}
    assert groups == {"map", "robot", "truth"}
    # the robot stands where the explorer's stored text says it does: x, y and heading of the second stop
    said = re.search(r"x (-?[\d.]+) m, y (-?[\d.]+) m, heading (-?[\d.]+) rad",
                     "".join("".join(o.get("text", "")) for o in explorer["outputs"]))  # fmt: skip
    x, y, heading = (float(v) for v in said.groups())
    (pose,) = [c for c in cmds if c["type"] == "set_transform" and c["path"] == "/meshcat/robot/base"]
    T = np.array(pose["matrix"], float).reshape(4, 4).T  # meshcat sends column-major
    assert np.allclose(T[:2, 3], [x, y], atol=0.006)
    assert abs(np.arctan2(T[1, 0], T[0, 0]) - heading) < 0.006


# ============================================================ drawn by a browser


def screenshot(url, png_path, size=(1000, 800), budget_ms=10000, timeout=90):
    """Headless Chromium's picture of ``url``, with a longer virtual-time budget than a plain page's.

    The page parses a megabyte of srcdoc before meshcat draws; virtual time lets it finish however busy the machine
    is.  A sandboxed iframe gets a process of its own, whose frames a busy machine may not have drawn by the time the
    page's virtual time is up: it is kept in the page's process.
    """
    code, _, err = run_chromium(
        url,
        screenshot=png_path,
        size=size,
        budget_ms=budget_ms,
        timeout=timeout,
        extra=("--disable-features=IsolateSandboxedIframes", "--disable-site-isolation-trials"),
    )
    return code, err


def _sky(img):
    """meshcat's background, a gradient from light to dark blue: blue well above red."""
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    return (b > r + 40) & (b > g + 20)


@pytest.mark.parametrize("kept", [True, False], ids=["trusted", "iframe-removed"])
def test_the_exported_page_draws_the_stored_scene(tmp_path, capsys, kept):
    """The stored output, through ``cga-lessons export-html`` (nbconvert), in headless Chromium: the scene is drawn.

    The negative control removes the iframe (as JupyterLab's sanitizer does): no sky is left, only the note.
    """
    from PIL import Image

    require_chromium()
    _, cell, _ = _stored_view()
    nb = nbformat.v4.new_notebook()
    code = nbformat.from_dict(cell)
    if not kept:
        for o in code["outputs"]:
            o["data"]["text/html"] = re.sub(r"<iframe\b.*?</iframe>", "", "".join(o["data"]["text/html"]), flags=re.S)
    nb.cells = [nbformat.v4.new_markdown_cell("# The scene"), code]
    nbdir = tmp_path / "nb"
    nbdir.mkdir()
    nbformat.write(nb, nbdir / "08_scene.ipynb")
    assert cli.main(["export-html", "--notebook-dir", str(nbdir), "--out-dir", str(tmp_path / "site")]) == 0
    capsys.readouterr()
    png = tmp_path / "page.png"
    code_, err = screenshot((tmp_path / "site" / "08_scene.html").resolve().as_uri(), png)
    assert code_ == 0 and png.exists(), err[-2000:]
    if os.environ.get("CGA_KEEP_SCREENSHOT"):
        shutil.copy(png, f"{os.environ['CGA_KEEP_SCREENSHOT']}_inline_{'trusted' if kept else 'removed'}.png")
    img = np.asarray(Image.open(png).convert("RGB")).astype(int)
    sky = _sky(img)
    if not kept:
        assert sky.sum() < 100  # nothing drawn without the iframe (the control: the check below can fail)
        return
    rows = np.nonzero(sky.sum(axis=1) > 300)[0]  # rows mostly sky (a stray blue glyph of the page is no row)
    assert len(rows), "no scene drawn"
    top, bottom = rows.min(), rows.max()
    cols = np.nonzero(sky[top : bottom + 1].mean(axis=0) > 0.5)[0]
    left, right = cols.min(), cols.max()
    assert 400 <= bottom - top <= 480 and right - left > 600, (top, bottom, left, right)  # the 480 px iframe
    area = img[top : bottom + 1, left : right + 1]
    assert sky[top : bottom + 1, left : right + 1].mean() > 0.5  # the scene's own background fills its area
    r, g, b = area[..., 0], area[..., 1], area[..., 2]
    laser_red = (r > 150) & (g < 90) & (b < 90)  # the laser lines of the map, (0.85, 0.15, 0.1)
    pale = (r > 150) & (g > 150) & (b > 150)  # the grid, the virtual walls, the board's points
    assert laser_red.sum() > 200 and pale.sum() > 2000, (laser_red.sum(), pale.sum())
