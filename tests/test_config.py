"""The one place where overrides are merged into staged configurations (``cga_lessons.config``)."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from cga_lessons import checks
from cga_lessons.config import check_stages, field_stage, merged, stages
from cga_lessons.errors import InvalidInputError


@dataclass(frozen=True)
class Search:
    width: float = 1.0
    tries: int = 3

    def __post_init__(self):
        checks.real(self.width, "Search", "width", low=0.0, strict_low=True)
        checks.integer(self.tries, "Search", "tries", low=1)


@dataclass(frozen=True)
class Check:
    width: float = 0.5  # shares a name with Search: must be given inside its stage
    score: float = 0.5

    def __post_init__(self):
        checks.real(self.score, "Check", "score", low=0.0, high=1.0)


@dataclass(frozen=True)
class Params:
    search: Search = field(default_factory=Search)
    check: Check = field(default_factory=Check)
    verbose: bool = False

    def __post_init__(self):
        check_stages(self)
        checks.flag(self.verbose, "Params", "verbose")


def test_stages_and_owners_are_read_off_the_class():
    assert stages(Params) == {"search": Search, "check": Check}
    owner = field_stage(Params)
    assert owner["tries"] == "search" and owner["score"] == "check"
    assert "width" not in owner  # two stages have it
    assert owner["verbose"] is None and owner["search"] is None


def test_the_three_ways_of_overriding_give_one_result():
    a = merged(None, {"tries": 5, "score": 0.9}, "find", Params)
    b = merged(None, {"search": {"tries": 5}, "check": Check(score=0.9)}, "find", Params)
    c = merged(Params(), {"search": Search(tries=5), "check": {"score": 0.9}}, "find", Params)
    assert a == b == c == Params(search=Search(tries=5), check=Check(score=0.9))
    # an explicit stage and a single field of it combine; the base is not changed
    base = Params(search=Search(width=2.0))
    d = merged(base, {"search": {"tries": 7}, "verbose": True}, "find", Params)
    assert d == Params(search=Search(width=2.0, tries=7), verbose=True)
    assert base.search.tries == 3
    assert merged(base, {}, "find", Params) is base


@pytest.mark.parametrize(
    "overrides, words",
    [
        ({"nope": 1}, ["find: nope: unknown parameter", "Params"]),
        ({"width": 2.0}, ["find: width: belongs to more than one stage"]),
        ({"search": {"depth": 1}}, ["find: search: unknown field(s) ['depth'] of Search"]),
        ({"search": 3}, ["find: search: expected a Search or a dict"]),
        ({"tries": 0}, ["find: tries:", "(said by Search)"]),
        ({"search": {"width": -1.0}}, ["find: search.width:", "(said by Search)"]),
        ({"verbose": "yes"}, ["find: verbose:", "(said by Params)"]),
    ],
)
def test_bad_overrides_name_the_function_and_the_argument(overrides, words):
    with pytest.raises(InvalidInputError) as info:
        merged(None, overrides, "find", Params)
    for w in words:
        assert w in str(info.value)


def test_a_config_of_the_wrong_kind_is_refused():
    with pytest.raises(InvalidInputError, match="find: params: expected a Params"):
        merged(Search(), {}, "find", Params)


def test_a_stage_of_the_wrong_kind_is_refused_when_the_configuration_is_made():
    with pytest.raises(InvalidInputError, match=r"^Params: check: expected a Check, got Search"):
        Params(check=Search())


# ------------------------------------------------------------ records checked when made (checks.record)
@dataclass(frozen=True)
class Disc:
    center: object
    radius: object
    label: object = None

    def __post_init__(self):
        checks.record(self, center=checks.vector3, radius=checks.length, label=checks.text)


def test_a_record_normalises_its_fields_and_skips_an_optional_field_left_unset():
    d = Disc([1, 2, 3], 2)
    assert d.center.dtype == float and d.center.tolist() == [1.0, 2.0, 3.0] and d.radius == 2.0
    assert d.label is None and Disc([0, 0, 0], 1.0, "a").label == "a"


@pytest.mark.parametrize(
    "args, words",
    [
        (([1, 2], 1.0), "Disc: center:"),
        (([0, 0, float("nan")], 1.0), "Disc: center:"),
        ((None, 1.0), "Disc: center:"),  # required: None is refused, not skipped
        (([0, 0, 0], -1.0), "Disc: radius: must be >= 0"),
        (([0, 0, 0], 1.0, 3), "Disc: label:"),
    ],
)
def test_a_record_refuses_bad_fields_in_its_own_name(args, words):
    with pytest.raises(InvalidInputError, match="^" + words):
        Disc(*args)
