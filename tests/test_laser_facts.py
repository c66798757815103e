"""What a log says about its laser (cga_lessons.mapping2d.laser_facts): its reach, checked against counts made here."""

import math

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import read_carmen_log
from cga_lessons.mapping2d.laser_facts import no_return_codes, returns_reach


def test_returns_reach_is_the_range_within_which_the_share_of_returns_falls():
    rng = np.random.default_rng(0)
    r = rng.uniform(0.2, 30.0, 1000)
    r[::7] = np.inf  # no return: not counted
    finite = np.sort(r[np.isfinite(r)])
    for coverage in (0.5, 0.9, 0.99, 1.0):
        reach = returns_reach(r, coverage)
        assert reach == finite[math.ceil(coverage * len(finite)) - 1]  # the smallest with that share at or below it
        assert np.mean(finite <= reach) >= coverage > np.mean(finite < reach)


def test_the_bundled_logs_return_from_far_less_than_their_scanners_are_specified_for():
    """Every log's 99 % reach lies between 10 and 40 m, far below the SICK scanners' 80 m, and no no-return code
    is counted as a return (the codes are above the reach)."""
    for name in ("intel", "aces", "csail", "freiburg-101", "seattle", "orebro"):
        log = read_carmen_log(data_path("carmen", f"{name}-corrected.log.gz"))
        reach = returns_reach(log.ranges)
        finite = log.ranges[np.isfinite(log.ranges)]
        assert 10.0 < reach < 40.0 and np.mean(finite <= reach) >= 0.99
        assert all(c > reach for c in log.no_return_codes)


@pytest.mark.parametrize(
    "ranges, coverage, match",
    [
        ([np.inf, np.inf], 0.99, "ranges: holds no finite positive reading"),
        ([0.0, -1.0], 0.99, "ranges: holds no finite positive reading"),
        ([1.0, 2.0], 0.0, "coverage: must be > 0.0"),
        ([1.0, 2.0], 1.5, "coverage: must be <= 1.0"),
        ([1.0, 2.0], float("nan"), "coverage: is NaN or inf"),
        ([1.0, 2.0], "0.9", "coverage: must be a real number"),
        ([1.0, 2.0], True, "coverage: must be a real number, got the bool"),
    ],
)
def test_returns_reach_refuses_bad_input(ranges, coverage, match):
    with pytest.raises(InvalidInputError, match=f"returns_reach: {match}"):
        returns_reach(ranges, coverage)


def test_no_return_codes_of_a_log_without_returns_is_empty():
    assert no_return_codes([np.inf, np.inf]) == () and no_return_codes([]) == ()


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(min_beams=1), "min_beams: must be >= 2"),
        (dict(min_beams=2.5), "min_beams: must be a whole number"),
        (dict(band=float("nan")), "band: is NaN or inf"),
        (dict(band=1.0), "band: must be < 1.0"),
        (dict(band=-0.1), "band: must be >= 0.0"),
    ],
)
def test_no_return_codes_refuses_bad_settings(kw, match):
    with pytest.raises(InvalidInputError, match=f"no_return_codes: {match}"):
        no_return_codes([1.0, 2.0], **kw)
