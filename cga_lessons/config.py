"""Configurations made of stages, and the one place where a user's overrides are merged into them.

A configuration here is a frozen dataclass whose fields are *stages* (frozen dataclasses of their own, such as the
map builder's correspondence or loop-closure settings) and, at most, a few plain fields.  Users give overrides in the
way that reads best at the call: a whole stage (``loops=LoopParams(...)``), some fields of a stage
(``loops={"every": 2.0}``), or a single field by its name when exactly one stage has a field of that name
(``build_map(..., gate=4.0)``).  :func:`merged` resolves all three, refuses names it does not know and lets each
dataclass check its own values (in its ``__post_init__``), re-labelled in the name of the function the user called.

>>> from dataclasses import dataclass, field
>>> @dataclass(frozen=True)
... class Search:
...     width: float = 1.0
>>> @dataclass(frozen=True)
... class Params:
...     search: Search = field(default_factory=Search)
>>> merged(None, {"width": 2.0}, "find", Params).search.width
2.0
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from cga_lessons import checks

__all__ = ["stages", "field_stage", "check_stages", "merged"]


def stages(kind: type) -> dict[str, type]:
    """The stage fields of the configuration class ``kind``: name -> the stage's dataclass (fields whose default is
    made by a dataclass, via ``default_factory``)."""
    out = {}
    for f in dataclasses.fields(kind):
        factory = f.default_factory
        if factory is not dataclasses.MISSING and isinstance(factory, type) and dataclasses.is_dataclass(factory):
            out[f.name] = factory
    return out


def field_stage(kind: type) -> dict[str, str | None]:
    """Every name an override may use for the configuration class ``kind``: a stage's field -> its stage (only
    names that exactly one stage has), a plain field or a stage's own name -> None."""
    own = stages(kind)
    out: dict[str, str | None] = {f.name: None for f in dataclasses.fields(kind)}
    seen: dict[str, list[str]] = {}
    for stage, cls in own.items():
        for f in dataclasses.fields(cls):
            seen.setdefault(f.name, []).append(stage)
    for name, owners in seen.items():
        if len(owners) == 1 and name not in out:
            out[name] = owners[0]
    return out


def check_stages(config) -> None:
    """Refuse a configuration whose stage fields do not hold their stages (for its ``__post_init__``)."""
    for stage, cls in stages(type(config)).items():
        article = "an" if cls.__name__[0] in "AEIOU" else "a"
        checks.instance(getattr(config, stage), type(config).__name__, stage, cls, f"{article} {cls.__name__}")


def _replaced(base, values: Mapping, func: str, prefix: str = ""):
    """``base`` with ``values`` put in one field at a time, so that a refused value is named (``prefix`` + field)."""
    for key, value in values.items():
        with checks.relabel(func, prefix + key):
            base = dataclasses.replace(base, **{key: value})
    return base


def _stage_value(value, stage: str, cls: type, base, func: str):
    """A stage given as an instance of its class or as a mapping of some of its fields."""
    if isinstance(value, cls):
        return value
    if isinstance(value, Mapping):
        names = {f.name for f in dataclasses.fields(cls)}
        bad = sorted(map(str, set(value) - names))
        if bad:
            raise checks.fail(func, stage, f"unknown field(s) {bad} of {cls.__name__}")
        return _replaced(base, value, func, f"{stage}.")
    raise checks.fail(func, stage, f"expected a {cls.__name__} or a dict of its fields, got {value!r}")


def merged(config, overrides: Mapping, func: str, kind: type, name: str = "params"):
    """``config`` (None: ``kind()``) with ``overrides`` applied, checked in the name of ``func``.

    ``overrides`` maps a stage's name to an instance of the stage or a dict of its fields, a plain field of
    ``kind`` to its value, or a field of one stage to its value.  Names that are none of these, and names that
    two stages share (give the stage then), are refused; the values are checked by the dataclasses themselves.
    """
    if config is None:
        config = kind()
    config = checks.instance(config, func, name, kind, f"a {kind.__name__} (or None)")
    if not overrides:
        return config
    own = stages(kind)
    owner = field_stage(kind)
    bad = sorted(map(str, set(overrides) - set(owner)))
    if bad:
        shared = [b for b in bad if any(b in {f.name for f in dataclasses.fields(c)} for c in own.values())]
        if shared:
            raise checks.fail(func, ", ".join(shared), "belongs to more than one stage: give it inside its stage")
        raise checks.fail(func, ", ".join(bad), f"unknown parameter(s) (see {kind.__name__})")
    top: dict = {}
    per_stage: dict[str, dict] = {}
    for key, value in overrides.items():
        stage = owner[key]
        if stage is None and key in own:
            top[key] = _stage_value(value, key, own[key], getattr(config, key), func)
        elif stage is None:
            top[key] = value
        else:
            per_stage.setdefault(stage, {})[key] = value
    for stage, values in per_stage.items():
        top[stage] = _replaced(top.get(stage, getattr(config, stage)), values, func)
    config = _replaced(config, {key: top.pop(key) for key in list(top) if key not in own}, func)
    with checks.relabel(func, name):
        return dataclasses.replace(config, **top)
