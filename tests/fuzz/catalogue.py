"""Every public callable of the package, and the cases and exemptions that cover them.

A public callable is a function or class in the ``__all__`` of a layer's facade (``cga_lessons.algebra``, ...,
``cga_lessons.cli``) or of one of ``cga_lessons.viz``'s modules (that package's modules are its face), and
``cga_lessons.data_path``.  Each ``cases_<group>.py`` module beside this one holds ``CASES`` (a list of
:class:`~fuzz.harness.Case`) and ``EXEMPT`` (``"package.name" -> why it is not fuzzed``).  A dataclass whose fields
all have defaults (a configuration) gets a strict case of its own here: its defaults are the valid call, and a
value of the wrong type for a field must be refused when the configuration is made, not when it is used.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
from pathlib import Path

import cga_lessons
from fuzz.harness import Case, public_callables

FACADES = (
    "algebra",
    "conformal",
    "symbolic",
    "mapping2d",
    "stereo",
    "exploration",
    "kinematics",
    "map3d",
    "relocalization",
    "equations",
    "exercises",
    "cli",
)


def public() -> dict[str, object]:
    """``"package.name" -> object`` of every public callable (the first facade that exports an object names it)."""
    out, seen = {}, set()

    def add(prefix, module):
        for name, obj in public_callables(module).items():
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue  # the errors themselves
            if id(obj) not in seen:
                seen.add(id(obj))
                out[f"{prefix}.{name}"] = obj

    out["cga_lessons.data_path"] = cga_lessons.data_path
    seen.add(id(cga_lessons.data_path))
    for facade in FACADES:
        add(facade, importlib.import_module(f"cga_lessons.{facade}"))
    viz = importlib.import_module("cga_lessons.viz")
    for info in sorted(pkgutil.iter_modules(viz.__path__), key=lambda m: m.name):
        add(f"viz.{info.name}", importlib.import_module(f"cga_lessons.viz.{info.name}"))
    return out


def groups() -> list[str]:
    return sorted(p.stem.removeprefix("cases_") for p in Path(__file__).parent.glob("cases_*.py"))


def load(group: str):
    return importlib.import_module(f"fuzz.cases_{group}")


def config_case(cls) -> Case | None:
    """A case for a configuration dataclass whose fields all have defaults: the defaults are the valid call."""
    if not (inspect.isclass(cls) and dataclasses.is_dataclass(cls)):
        return None
    args = {}
    for f in dataclasses.fields(cls):
        if not f.init:
            continue
        if f.default is not dataclasses.MISSING:
            args[f.name] = f.default
        elif f.default_factory is not dataclasses.MISSING:
            args[f.name] = f.default_factory()
        else:
            return None
    return Case(cls, args, strict=True)


def all_cases() -> list[tuple[str, Case]]:
    """``(group, case)`` of every written case, then the generated ones of configuration dataclasses."""
    out = [(g, c) for g in groups() for c in load(g).CASES]
    written = {id(c.func) for _, c in out}
    for obj in public().values():
        if id(obj) not in written:
            case = config_case(obj)
            if case is not None:
                out.append(("config", case))
    return out


def exempt() -> dict[str, str]:
    out = {}
    for g in groups():
        out.update(load(g).EXEMPT)
    return out


def uncovered() -> list[str]:
    """Public callables with neither a case nor an exemption."""
    covered = {id(c.func) for _, c in all_cases()}
    ex = exempt()
    return [k for k, obj in public().items() if id(obj) not in covered and k not in ex]
