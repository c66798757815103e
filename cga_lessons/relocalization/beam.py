"""The laser beam model of the Monte Carlo localization: its parameters, and its likelihood for one beam.

A returned beam whose end point lies ``d`` from the nearest map wall has the
likelihood ``z_hit N(d; 0, sigma_hit) + z_rand / max_range`` (a wall seen with
Gaussian noise, or a random reading), ``1 / max_range`` where the map knows
nothing; a silent beam ``p_dropout`` when a map wall lies across its ray within
reach, ``1 - z_rand`` otherwise (Thrun, Burgard and Fox, *Probabilistic
Robotics*, section 6.4).  :class:`BeamModel` holds the parameters, each
measured on the bundled logs or set by the sensor;
:class:`~cga_lessons.relocalization.likelihood.LikelihoodField` evaluates the
model on a grid for many particles at once.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from cga_lessons import checks

__all__ = ["BeamModel", "beam_likelihood"]


@dataclass(frozen=True)
class BeamModel:
    """The beam model's parameters and the field's grid.

    Attributes
    ----------
    max_range : float
        The laser's reach (m): readings at or beyond it are no return.  5 m:
        the thesis's robot (chapter 4) and :func:`cga_lessons.mapping2d.laser.simulate_scan`;
        the CARMEN log benchmark uses 8 m, the reach its maps are built with.
    sigma_hit : float
        Standard deviation (m) of an end point's distance to its wall: 5 cm.
        Not the range noise alone (1 cm simulated; the logs' points lie
        1.2-2.2 cm about their maps, :func:`~cga_lessons.relocalization.coverage.map_noise`):
        a particle is a sample, never exactly at the pose, and must still score
        a few centimetres off (one step's drift, 2 cm per metre by
        :class:`~cga_lessons.mapping2d.laser.OdometryModel`, and the grid's rounding).
        8 cm located as many sequences on Orebro, Seattle and the office
        (``benchmarks/bench_mcl.py``, seed 0).
    z_rand : float
        Share of returned beams that no map wall explains: 0.1.  Measured at
        the logged poses of the six CARMEN logs against maps of the other scans:
        0.2-5 % of the returned beams end more than 30 cm from every map line
        where the mapping scans saw free space, 4-9 % between 10 and 30 cm.
    p_dropout : float
        Probability that a beam with a map wall within reach returns nothing:
        0.05.  Measured on Intel, ACES and Orebro: 2-3 % of the beams whose ray
        crosses a map wall within 8 m returned nothing; glass and black
        surfaces vary more from building to building.
    resolution : float
        Grid cell (m): 5 cm, the coverage grid's.  The distance is exact at a
        cell's centre near the walls, so a look-up is off by at most half a
        cell diagonal (3.5 cm, 2 cm RMS), below ``sigma_hit``.
    max_beams : int
        Beams scored per scan, evenly spread: 60, 3-6 degrees apart on the
        logs' 180-361 beams (30 cm at 5 m).  The cost is linear in it (12 ms
        for an update of 2,000 particles on Intel's map, one core).
    beam_weight : float
        Power of each beam's likelihood in a particle's weight: 1/3, so a scan
        counts as 20 independent readings, about three per scan line (5-8 lines
        are extracted from a log scan, median).  Neighbouring beams share their
        wall's and the pose's errors; counted as independent they make the
        weights sharper, not wiser.  1/6 located as many sequences on Orebro,
        Seattle and the office (``benchmarks/bench_mcl.py``, seed 0).
    ray_step : float
        Spacing (m) of the samples along a silent beam's ray; a wall across
        the ray passes within ``ray_step / 2`` of a sample.  20 cm: 40 samples
        to 8 m, and a door (70 cm or more) is never taken for a wall.
    max_silent_beams : int
        Most silent beams ray-checked per scan (evenly chosen): 12, a fifth of
        ``max_beams``; each costs as much as 40 returned beams.
    """

    max_range: float = 5.0
    sigma_hit: float = 0.05
    z_rand: float = 0.1
    p_dropout: float = 0.05
    resolution: float = 0.05
    max_beams: int = 60
    beam_weight: float = 1.0 / 3.0
    ray_step: float = 0.2
    max_silent_beams: int = 12

    def __post_init__(self):
        positive = partial(checks.real, low=0.0, strict_low=True)
        fraction = partial(checks.real, low=0.0, high=1.0, strict_low=True, strict_high=True)
        count = partial(checks.integer, low=1)
        checks.record(
            self,
            **dict.fromkeys(("max_range", "sigma_hit", "resolution", "ray_step", "beam_weight"), positive),
            **dict.fromkeys(("z_rand", "p_dropout"), fraction),
            **dict.fromkeys(("max_beams", "max_silent_beams"), count),
        )

    @property
    def log_unknown(self) -> float:
        """Log-likelihood of an end point where the map knows nothing: ``-log(max_range)``."""
        return float(-np.log(self.max_range))

    @property
    def log_miss(self) -> float:
        """Log-likelihood of an end point far from every map wall in mapped space: ``log(z_rand / max_range)``."""
        return float(np.log(self.z_rand / self.max_range))


def beam_likelihood(distance, model: BeamModel | None = None, *, known=True):
    """The likelihood of one returned beam whose end point lies ``distance`` (m) from the nearest map wall.

    ``z_hit N(d; 0, sigma_hit) + z_rand / max_range`` with ``z_hit = 1 - z_rand``
    (``1 / max_range`` where the map knows nothing, ``known=False``).

    >>> m = BeamModel(sigma_hit=0.05, z_rand=0.1, max_range=5.0)
    >>> round(float(beam_likelihood(0.0, m)), 4)  # 0.9 / (0.05 sqrt(2 pi)) + 0.1 / 5
    7.201
    """
    m = model or BeamModel()
    d = np.asarray(distance, float)
    gauss = np.exp(-0.5 * (d / m.sigma_hit) ** 2) / (m.sigma_hit * np.sqrt(2 * np.pi))
    p = (1 - m.z_rand) * gauss + m.z_rand / m.max_range
    return np.where(known, p, 1.0 / m.max_range)
