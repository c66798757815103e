"""The package's layers, read from its source: every module imports only from layers below its own.

Layer 0 is ``errors`` and ``scratch``, ``checks``, then ``paths``, ``files`` and ``config`` (a module there may import
those of a lower rank, ``LAYER0_RANK``); 1 ``algebra``; 2 ``conformal``; 3 ``symbolic``, ``mapping2d``, ``stereo``,
``exploration``, ``kinematics``; 4 ``map3d``, ``relocalization``; 5 ``equations``, ``exercises``, ``viz``; 6 ``cli``.
A module may import its own package's modules and any package of a lower layer, another package only through its
facade (its ``__init__``: names, not modules; ``viz`` is the one package whose modules are its face), and no private
name (``_x``) of another module; layers 0-4 never draw (no matplotlib, meshcat or widgets). The package's ``__init__``
(which re-exports ``data_path``) and ``__main__`` (which runs the command line) are its entry points and stand above
every layer.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import re
from pathlib import Path

import pytest

import cga_lessons

PACKAGE = Path(cga_lessons.__file__).resolve().parent
LAYERS = {
    "errors": 0,
    "scratch": 0,
    "checks": 0,
    "paths": 0,
    "files": 0,
    "config": 0,
    "algebra": 1,
    "conformal": 2,
    "symbolic": 3,
    "mapping2d": 3,
    "stereo": 3,
    "exploration": 3,
    "kinematics": 3,
    "map3d": 4,
    "relocalization": 4,
    "equations": 5,
    "exercises": 5,
    "viz": 5,
    "cli": 6,
}
#: The order within layer 0: a module there may import those of a lower rank.
LAYER0_RANK = {"errors": 0, "scratch": 0, "checks": 1, "paths": 2, "files": 2, "config": 2}
DRAWING = ("matplotlib", "meshcat", "ipywidgets", "IPython")
PACKAGES = {k for k in LAYERS if (PACKAGE / k / "__init__.py").is_file()}
MODULES_ARE_FACE = {"viz"}
ENTRY_POINTS = ("__init__.py", "__main__.py")


def module_name(path: Path) -> list[str]:
    """``cga_lessons/mapping2d/laser.py`` -> ``["cga_lessons", "mapping2d", "laser"]`` (a package: its folder)."""
    parts = ["cga_lessons", *path.relative_to(PACKAGE).with_suffix("").parts]
    return parts[:-1] if parts[-1] == "__init__" else parts


def imported_modules(source: str, name: list[str], is_package: bool):
    """``(line, dotted module)`` of every import in a module's source, relative imports resolved; for ``from X
    import a`` both ``X`` and ``X.a`` are given (``a`` may be a module)."""
    here = name if is_package else name[:-1]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node.lineno, alias.name, None
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[: len(here) - (node.level - 1)]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            yield node.lineno, module, [alias.name for alias in node.names]


def layer_of(dotted: str):
    """The layer package a ``cga_lessons...`` import reaches (``None`` for the root's own names)."""
    parts = dotted.split(".")
    if len(parts) >= 2:
        return parts[1]
    return None


def violations_of(path: Path, source: str | None = None) -> list[str]:
    """Imports of one module that break the layering, as ``"file:line: message"``."""
    source = path.read_text(encoding="utf-8") if source is None else source
    rel = path.relative_to(PACKAGE)
    if len(rel.parts) == 1 and rel.name in ENTRY_POINTS:
        return []
    name = module_name(path)
    own = name[1]
    if own not in LAYERS:
        return [f"{rel}: module outside every layer ({own}); add it to a layer"]
    out = []
    for line, module, names in imported_modules(source, name, path.name == "__init__.py"):
        where = f"{rel}:{line}"
        top = module.split(".")[0]
        if top in DRAWING and LAYERS[own] <= 4:
            out.append(f"{where}: {own} (layer {LAYERS[own]}) draws ({module}); drawing belongs to layer 5")
        if top != "cga_lessons":
            continue
        if names is not None and module != "cga_lessons":
            private = [n for n in names if n.startswith("_") and not n.startswith("__")]
            if private:
                out.append(f"{where}: imports the private name(s) {private} of {module}")
        parts = module.split(".")
        if len(parts) >= 2 and parts[1] != own and parts[1] in PACKAGES and parts[1] not in MODULES_ARE_FACE:
            if len(parts) > 2:
                out.append(f"{where}: reaches into {module}; import from the facade cga_lessons.{parts[1]}")
            elif names is None:
                out.append(f"{where}: imports {module} as a module path; import names from its facade")
            else:
                inner = [n for n in names if (PACKAGE / parts[1] / f"{n}.py").is_file()]
                if inner:
                    out.append(f"{where}: imports the module(s) {inner} of {module}; import names from its facade")
        targets = [layer_of(module)] if layer_of(module) else [n for n in (names or [])]
        for target in targets:
            if target == own:
                continue
            if target not in LAYERS:
                out.append(f"{where}: imports {target!r} from the package's root; import it from its layer")
            elif LAYERS[target] >= LAYERS[own] and not (
                LAYERS[own] == 0 and LAYERS[target] == 0 and LAYER0_RANK[target] < LAYER0_RANK[own]
            ):
                out.append(
                    f"{where}: {own} (layer {LAYERS[own]}) imports {module}{'' if names is None else ' ' + str(names)}"
                    f" of {target} (layer {LAYERS[target]}): only lower layers may be imported"
                )
    return out


def package_files():
    data = PACKAGE / "data"  # the bundled data's scripts (a link to the checkout's data/ folder)
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts and not p.is_relative_to(data))


def test_every_module_imports_only_lower_layers():
    problems = [v for path in package_files() for v in violations_of(path)]
    assert problems == [], "\n".join(problems)


def test_the_check_finds_an_upward_import_a_root_import_and_a_drawing(tmp_path):
    fake = PACKAGE / "mapping2d" / "_not_a_file.py"
    upward = "from cga_lessons.relocalization import relocalize\n"
    assert any("layer 4" in v for v in violations_of(fake, upward))
    relative = "from ..map3d import robot\n"
    assert any("map3d" in v for v in violations_of(fake, relative))
    assert violations_of(fake, "from .laser import Scene\nfrom cga_lessons.conformal import up\n") == []
    assert any("root" in v for v in violations_of(fake, "from cga_lessons import data_path\n"))
    assert any("draws" in v for v in violations_of(fake, "def f():\n    import matplotlib.pyplot as plt\n"))
    assert violations_of(PACKAGE / "viz" / "_not_a_file.py", "import matplotlib.pyplot as plt\n") == []
    assert any("facade" in v for v in violations_of(fake, "from cga_lessons.conformal.model import up\n"))
    assert any("facade" in v for v in violations_of(fake, "from cga_lessons.conformal import model\n"))
    assert any("private" in v for v in violations_of(fake, "from .geometry import _hidden\n"))
    assert any("private" in v for v in violations_of(fake, "from cga_lessons.conformal import _hidden\n"))
    assert violations_of(fake, "from cga_lessons.errors import InvalidInputError\n") == []
    # within layer 0: config may use checks, checks may not use config
    assert violations_of(PACKAGE / "config.py", "from cga_lessons import checks\n") == []
    assert any("layer 0" in v for v in violations_of(PACKAGE / "checks.py", "from cga_lessons import config\n"))


def test_the_root_holds_at_most_eight_modules_and_every_layer_is_a_package():
    root = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(root) <= 8, root
    packages = sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file())
    assert set(packages) == {k for k in LAYERS if not (PACKAGE / f"{k}.py").is_file()}, packages


@pytest.mark.parametrize("layer", sorted(k for k in LAYERS if (PACKAGE / k / "__init__.py").is_file()))
def test_each_facade_lists_what_it_exports_and_every_name_resolves(layer):
    module = importlib.import_module(f"cga_lessons.{layer}")
    exported = getattr(module, "__all__", None)
    assert isinstance(exported, list) and exported, f"cga_lessons.{layer} has no __all__"
    assert len(set(exported)) == len(exported), "a name listed twice"
    missing = [
        n
        for n in exported
        if not hasattr(module, n) and importlib.util.find_spec(f"cga_lessons.{layer}.{n}") is None  # or a module
    ]
    assert missing == []
    assert not any(n.startswith("_") for n in exported)


NOTEBOOKS = sorted((PACKAGE.parent / "notebooks").glob("*.ipynb"))
IMPORT_LINE = re.compile(r"\s*(?:from\s+(cga_lessons[\w.]*)\s+import\s+([^#]+)|import\s+(cga_lessons[\w.]*))")


def notebook_import_problem(line: str):
    """Why a line of a notebook imports past a facade (None when it does not)."""
    m = IMPORT_LINE.match(line)
    if not m:
        return None
    module = m.group(1) or m.group(3)
    parts = module.split(".")
    names = [n.strip().split(" as ")[0].strip() for n in (m.group(2) or "").split(",") if n.strip()]
    face = len(parts) > 1 and parts[1] in MODULES_ARE_FACE
    if len(parts) > (3 if face else 2) or (m.group(3) and len(parts) > 1 and not face):
        return "reaches past the facade"
    if len(parts) == 2 and not face:
        if any((PACKAGE / parts[1] / f"{n}.py").is_file() for n in names) or any(n.startswith("_") for n in names):
            return "imports a module or a private name of the facade"
    return None


def test_the_notebook_check_tells_a_facade_from_a_module():
    assert notebook_import_problem("from cga_lessons import mapping2d, conformal as cga") is None
    assert notebook_import_problem("from cga_lessons.relocalization import Relocalizer, pose_error") is None
    assert notebook_import_problem("from cga_lessons.viz.explore_scan import HoughExplorer") is None
    assert notebook_import_problem("from cga_lessons.viz import laser as draw") is None
    assert notebook_import_problem("from cga_lessons.relocalization.eval import evaluate_log")
    assert notebook_import_problem("from cga_lessons.mapping2d import laser, lines")
    assert notebook_import_problem("import cga_lessons.mapping2d.laser as L")
    assert notebook_import_problem("from cga_lessons.mapping2d import _private")


@pytest.mark.skipif(not NOTEBOOKS, reason="the notebooks are not beside the package (an installed copy)")
def test_notebooks_import_only_facades():
    """A student's imports: ``from cga_lessons import P`` or names from ``cga_lessons.P`` (``viz``'s modules too)."""
    import nbformat

    problems = []
    for path in NOTEBOOKS:
        nb = nbformat.read(str(path), as_version=4)
        for k, cell in enumerate(nb.cells):
            if cell.cell_type == "code":
                for line in cell.source.splitlines():
                    why = notebook_import_problem(line)
                    if why:
                        problems.append(f"{path.name}, cell {k}: {line.strip()}: {why}")
    assert problems == [], "\n".join(problems)
