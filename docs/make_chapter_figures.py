"""Write docs/chapters/NN_name.png: one picture per notebook for the README's chapter map.

Each picture is a figure the notebook already stores (the outputs of its last execution), chosen as the most
telling one of the chapter; nothing is recomputed here, so the pictures are exactly what a reader of the
executed notebook sees. A figure is found by a piece of its cell's source (robust to cells moving around) and
the index of the image among that cell's outputs. Pictures wider than ``MAX_WIDTH`` are scaled down, and every
picture is reduced to a 256-colour palette when that keeps it under ``MAX_BYTES``.

Run from the project root after executing the notebooks: ``python docs/make_chapter_figures.py``
(``--check`` only reports which pictures are missing or differ from what the notebooks hold now).
"""

from __future__ import annotations

import argparse
import base64
import io
import json
import sys
from pathlib import Path

from PIL import Image  # a dependency of matplotlib

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"
OUT = ROOT / "docs" / "chapters"
MAX_WIDTH = 720  # pixels
MAX_BYTES = 150_000

#: notebook -> (a piece of the source of the cell that draws the figure, index of the image in its outputs, caption)
PICTURES = {
    "00_start_here": ('boxes = {"01"', 0, "how the chapters depend on each other"),
    "01_geometric_algebra": ("a_num, b_num = G2.vector", 0, "bivectors: oriented areas, a ^ b = -b ^ a"),
    "02_conformal_model": ("ch2_3d.fig_entities(", 0, "the conformal entities of table 2.1"),
    "03_conformal_transformations": (
        "center, radius = np.array([0.3, 0.2, 0.0]), 1.0",
        0,
        "a grid of lines under an inversion in a sphere (2.88)",
    ),
    "04_entity_properties": ("separations = np.logspace(", 0, "the accuracy of the point-pair extraction (2.131)"),
    "05_laser_line_maps": ("draw.map_figure(result.segments", 0, "the line map of the office and the trajectories"),
    "06_conformal_line_maps": ("draw.draw_point_pair_spheres([g, l]", 0, "the five sphere cases of (3.19)"),
    "07_stereo_reconstruction": ("px: least squares", 0, "conformal entities from two views"),
    "08_fused_3d_map": ("vz.plot_fused_map(fused", 0, "laser walls and stereo entities in one frame"),
    "09_relocalization": ("draw.steps_figure(", 0, "the four steps of relocalization (figure 5.2)"),
    "10_exploration": ("base = ex.run_scenario()", 0, "seen, unseen and occupied nodes"),
    "11_future_work": ("fw.mcl_figure(intel, rows", 0, "particles finding the robot on the Intel map (6.3.2)"),
}


class FigureNotFound(LookupError):
    """The notebook has no stored image where PICTURES says."""


def stored_image(notebook: str, marker: str, index: int) -> bytes:
    """The PNG bytes of image ``index`` among the outputs of the first code cell whose source contains ``marker``."""
    path = NOTEBOOKS / f"{notebook}.ipynb"
    if not path.is_file():
        raise FigureNotFound(f"{path}: no such notebook")
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    for cell in cells:
        if cell["cell_type"] == "code" and marker in "".join(cell["source"]):
            images = [o["data"]["image/png"] for o in cell.get("outputs", []) if "image/png" in o.get("data", {})]
            if index >= len(images):
                raise FigureNotFound(
                    f"{path}: the cell with {marker!r} stores {len(images)} image(s), not image {index}; "
                    "execute the notebook first"
                )
            data = images[index]
            return base64.b64decode("".join(data) if isinstance(data, list) else data)
    raise FigureNotFound(f"{path}: no code cell contains {marker!r}; update PICTURES in {Path(__file__).name}")


def thumbnail(png: bytes) -> bytes:
    """``png`` scaled to at most MAX_WIDTH pixels wide, as a palette PNG when that is needed to fit MAX_BYTES."""
    image = Image.open(io.BytesIO(png))
    image = image.convert("RGBA") if image.mode in ("RGBA", "LA", "P") else image.convert("RGB")
    if image.width > MAX_WIDTH:
        image = image.resize((MAX_WIDTH, round(image.height * MAX_WIDTH / image.width)), Image.LANCZOS)
    candidates = []
    for palette in (False, True):
        img = image
        if palette:
            img = image.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
        buf = io.BytesIO()
        img.save(buf, format="PNG", optimize=True)
        candidates.append(buf.getvalue())
        if len(candidates[-1]) <= MAX_BYTES:
            return candidates[-1]
    raise ValueError(f"thumbnail: even with 256 colours the picture takes {len(candidates[-1])} bytes > {MAX_BYTES}")


def build() -> dict[str, bytes]:
    """Every picture of PICTURES: file name -> PNG bytes."""
    return {f"{nb}.png": thumbnail(stored_image(nb, marker, index)) for nb, (marker, index, _) in PICTURES.items()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="report stale or missing pictures; write nothing")
    args = ap.parse_args(argv)
    try:
        pictures = build()
    except (FigureNotFound, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    stale = []
    OUT.mkdir(parents=True, exist_ok=True)
    for name, data in pictures.items():
        path = OUT / name
        current = path.read_bytes() if path.is_file() else None
        if current != data:
            stale.append(name)
            if not args.check:
                path.write_bytes(data)
        w, h = Image.open(io.BytesIO(data)).size
        state = "stale" if (args.check and current != data) else "ok"
        print(f"{name:36s} {w:4d} x {h:3d} px {len(data) / 1000:6.1f} kB  {state}")
    if args.check and stale:
        print(f"{len(stale)} picture(s) differ from the notebooks; run python docs/{Path(__file__).name}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
