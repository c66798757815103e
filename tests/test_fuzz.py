"""Every public callable, called with bad input, refuses it clearly or computes something finite.

The cases (one valid call per public function, class or method, by package) are in ``tests/fuzz/cases_*.py``;
``tests/fuzz/harness.py`` spoils one argument at a time with the bad values its type suggests (NaN, inf, huge
magnitudes, None, strings, wrong shapes, empty batches, ragged rows, wrong kinds of entity, missing, empty, garbled
and truncated files) and sorts each call.  ``python tests/fuzz/report.py`` lists every input tried and its outcome;
the suite's summary line counts them.
"""

from __future__ import annotations

import pytest
from fuzz.catalogue import all_cases, uncovered
from fuzz.harness import Case, outcome, problems_of, run_case

CASES = all_cases()


def test_every_public_callable_has_a_case_or_an_exemption():
    assert uncovered() == []


@pytest.mark.parametrize("group, case", CASES, ids=[f"{g}:{c.id}" for g, c in CASES])
def test_bad_input_is_refused_clearly_or_computed_finite(group, case):
    problems = problems_of(run_case(case))
    assert problems == [], f"{case.id}:\n  " + "\n  ".join(problems)


def _silently(x):
    return float("nan") * x


def _refuses(x):
    from cga_lessons.checks import real

    return real(x, "_refuses", "x")


def _typeerror(x):
    return x + 1


def test_the_harness_sorts_outcomes():
    """The fuzz can fail: a silent NaN, a raw TypeError, a message that names nothing, an accepted wrong kind."""
    assert outcome(Case(_silently, {"x": 1.0}), "x", 2.0)[0] == "silent"
    assert outcome(Case(_refuses, {"x": 1.0}), "x", float("nan"))[0] == "clear"
    assert outcome(Case(_refuses, {"x": 1.0}, label="other_name"), "x", float("nan"))[0] == "unclear"
    assert outcome(Case(_typeerror, {"x": 1.0}), "x", "text")[0] == "unclear"
    assert outcome(Case(_refuses, {"x": 1.0}), "x", 2.0, must_refuse=True)[0] == "wrongly accepted"
    assert outcome(Case(_refuses, {"x": 1.0}), "x", 2.0)[0] == "accepted"
