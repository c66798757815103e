"""What a laser log says about its laser: the values its driver writes for "no return", and how far it returns.

Both are read from the readings themselves, so that a log from another robot needs no settings: a driver that
writes a fixed value for a beam that returned nothing (:func:`no_return_codes`), and the distance within which the
laser actually returns (:func:`returns_reach`), the reach the relocalizer should trust.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks

from .inputs import numbers

__all__ = ["no_return_codes", "returns_reach"]


def no_return_codes(ranges, *, min_beams: int = 10, band: float = 0.01) -> tuple:
    """The values a laser log uses for "no return", found in its readings.

    Some drivers write a fixed value where a beam returned nothing: ACES's log
    reports exactly 50.00 m in 620 beams, Örebro's SICK scanner the codes
    32.759-32.767 m (just below 2^15 mm) in 968.  A real surface at the laser's
    largest distance does not give one millimetre value in many beams (in the
    four other bundled logs no value within 1 % of the largest reading occurs
    more than three times).  So a value within ``band`` (relative) of the
    log's largest finite reading that at least ``min_beams`` beams share is a
    code.

    Parameters
    ----------
    ranges : array_like
        All readings of the log (any shape; ``inf`` for no return).

    Returns
    -------
    tuple of float
        The codes found, ascending (empty when none).

    >>> r = np.array([1.0, 2.5, 7.25] + [50.0] * 12 + [49.8])
    >>> no_return_codes(r)
    (50.0,)
    >>> no_return_codes(np.array([1.0, 2.5, 50.0]))
    ()
    """
    f = "no_return_codes"
    min_beams = checks.integer(min_beams, f, "min_beams", low=2)
    band = checks.real(band, f, "band", low=0.0, high=1.0, strict_high=True)
    r = numbers(ranges, f, "ranges", finite=False).ravel()
    r = r[np.isfinite(r)]
    if len(r) == 0:
        return ()
    top = r[r >= (1.0 - band) * r.max()]
    values, counts = np.unique(top, return_counts=True)
    return tuple(float(v) for v in values[counts >= min_beams])


def returns_reach(ranges, coverage: float = 0.99) -> float:
    """How far the laser returns: the distance within which ``coverage`` of its returns fall (m).

    The scanners of the bundled logs are specified to 80 m, but they return
    from much less: 99 % of the returns lie within 13.5 m (Intel), 26.1 m
    (ACES), 14.1 m (CSAIL), 30.6 m (Freiburg), 16.1 m (Seattle) and 19.3 m
    (Örebro).  Beyond that a return is rare (dark, glancing or distant
    surfaces), so a beam without return there says little about the walls it
    crosses; within it, a beam that crosses a wall without returning is
    evidence.  ``coverage`` 0.99 leaves out the rarest one in a hundred.

    Parameters
    ----------
    ranges : array_like
        The log's readings (any shape; ``inf`` for no return, as
        :func:`cga_lessons.mapping2d.carmen.read_carmen_log` gives them after its :func:`no_return_codes`).
    coverage : float
        In (0, 1].

    Raises
    ------
    InvalidInputError
        With no finite positive reading, or ``coverage`` outside (0, 1].

    >>> returns_reach(np.r_[np.linspace(0.5, 10.0, 99), 40.0, np.inf])  # one far return in a hundred
    10.0
    """
    f = "returns_reach"
    coverage = checks.real(coverage, f, "coverage", low=0.0, high=1.0, strict_low=True)
    r = numbers(ranges, f, "ranges", finite=False).ravel()
    r = r[np.isfinite(r) & (r > 0)]
    if len(r) == 0:
        raise checks.fail(f, "ranges", "holds no finite positive reading")
    return float(np.quantile(r, coverage, method="inverted_cdf"))
