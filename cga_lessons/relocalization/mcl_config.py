"""The settings of :class:`~cga_lessons.relocalization.mcl.MonteCarloLocalizer`, each default with its reason."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import OdometryModel

from .beam import BeamModel
from .mcl_search import SearchConfig
from .sampling import KLDConfig

__all__ = ["MCLConfig"]


@dataclass(frozen=True)
class MCLConfig:
    """The filter's settings.

    Attributes
    ----------
    beam : BeamModel
        The sensor (reach, noise) and the likelihood field's grid.
    odometry : OdometryModel
        The drift each particle's motion is drawn from: chapter 3's model, the
        one :func:`cga_lessons.mapping2d.laser.simulate_odometry` drives with.
    kld : KLDConfig
        Particle counts (``n_min``, ``n_max``) and the KLD bound's bins.
    ess_fraction : float
        Resample when the effective sample size falls below this share of the
        particles: 0.5, the usual rule (below it, half the particles carry
        next to no weight).
    ess_floor : float
        Share of the particles whose effective number a scan may not push
        below (:func:`~cga_lessons.relocalization.sampling.tempering`): 0.01,
        200 of a global 20,000, enough for a few places to survive a scan; in
        tracking, 3 of 300, a bound a converged update hardly ever meets.
    alpha_slow, alpha_fast : float
        Smoothing of the long- and short-term averages of the likelihood per
        beam (augmented MCL): 0.05 and 0.5, about 20 updates (a few rooms at
        the logs' metre between scans) against 2, so a kidnapping shows within
        two scans.  The slow one starts once the filter tracks a confirmed place.
    random_threshold : float
        Particles are drawn anew when ``1 - w_fast / w_slow`` exceeds this: 0.05,
        the augmented filter's rule taken almost literally.  Measured in
        tracking (Intel, ACES, Orebro), the ratio falls below 0.95 in 7-40 % of
        the updates; each such false alarm costs a chapter-5 relocalization,
        not the pose: the newcomers are weighed by the remembered scans.  On
        the office scene a kidnapping dropped it to 0.4-0.8 at once.
    max_random_fraction : float
        Cap on that share: 0.25, so three quarters of the belief stay put.
    clearance : float
        The laser stands at least this far (m) from any wall: 0.2, half of the
        40 cm a robot carrying a laser measures at the least.
    hough : bool
        Use chapter 5's relocalizer as a proposal while the filter tracks no
        confirmed place or suspects a kidnapping.
    search : SearchConfig or None
        The coarse exhaustive search the global initialisation draws from
        (:class:`~cga_lessons.relocalization.mcl_search.CoarseSearch`): the
        ``n_max`` particles are drawn by importance from the first scan's
        coarse scores over every free cell and heading, weighed back to the
        uniform prior.  None: a uniform draw.  On ACES's 539 m2 of free space
        a uniform draw of 20,000 puts 0.013 particles (expected) within 10 cm
        and 2 degrees of the pose; the coarse search drew a median 0.4 % of
        its draws (80) into the 3 x 3 cells and 3 heading bins around the
        logged pose (the 7 first scans of fold 0's held-out sequences), 0.007 %
        in the worst.  With chapter 5's proposals on top, 15 of ACES's first
        20 held-out sequences (folds 0-2, seed 0) were located against 14 with
        the uniform draw: most of the gain on ACES is the confirmation rule.
    proposal_fraction : float
        Share of the particles redrawn around chapter 5's answer: 0.2.  The
        newcomers hold that share of the prior weight, shared by how well they
        explain the remembered scans (:func:`~cga_lessons.relocalization.history.merge`):
        four fifths of the belief stay, in case the answer is one of the 1-2 %
        confidently wrong ones (``benchmarks/bench_reloc_logs.py``).
    proposal_sd : tuple of float
        Spread (m, m, rad) of the newcomers: 5 cm and 1 degree, half the
        tolerance within which a right confident answer lies.
    proposal_candidates : int
        Where chapter 5 is ambiguous, newcomers go around at most this many
        tied candidates, as many around each: 12, chapter 5's own ``n_verify``
        (the clearly different poses it refines).  Its tied candidates
        numbered a median 7 on ACES's ambiguous scans; with more, the answer
        cannot confirm anything
        (:func:`~cga_lessons.relocalization.mcl_proposal.confirms`).
    history : int
        Scans remembered to weigh newcomers: 3 (the current one included),
        about 3 m of driving on the logs, over which the odometry drifts a few
        centimetres and a degree.  5 made no difference on Orebro and Seattle
        (``benchmarks/bench_mcl.py``, seed 0).
    gate : tuple of float
        Half-widths (m, rad) of the main mode: 0.5 m and 10 degrees, a KLD bin.
    converged_mass : float
        The main mode holds at least this share of the weight: 0.95.
    converged_sd : tuple of float
        ... its standard deviation along its widest direction and in heading
        are within the tolerance, 10 cm and 2 degrees ...
    converged_updates : int
        ... for this many updates in a row, moving as the odometry says: 2,
        one scan seen through the odometry besides chapter 5's own ...
    confirmations : int
        ... and chapter 5 has confirmed the mode this many times while it was
        tracked: a confident answer within ``gate``, or an ambiguous one whose
        best candidate lies within ``gate`` and whose other tied candidates
        all lost to the mode by a Bayes factor of at most
        ``(1 - converged_mass) / converged_mass`` over the remembered scans
        (:mod:`cga_lessons.relocalization.mcl_proposal`).  2: with one, a
        wrong first confident answer (1-2 % of them on the logs) would be
        enough.
    """

    beam: BeamModel = field(default_factory=BeamModel)
    odometry: OdometryModel = field(default_factory=OdometryModel)
    kld: KLDConfig = field(default_factory=KLDConfig)
    ess_fraction: float = 0.5
    ess_floor: float = 0.01
    alpha_slow: float = 0.05
    alpha_fast: float = 0.5
    random_threshold: float = 0.05
    max_random_fraction: float = 0.25
    clearance: float = 0.2
    hough: bool = True
    search: SearchConfig | None = field(default_factory=SearchConfig)
    proposal_fraction: float = 0.2
    proposal_sd: tuple = (0.05, 0.05, np.radians(1.0))
    proposal_candidates: int = 12
    history: int = 3
    gate: tuple = (0.5, np.radians(10.0))
    converged_mass: float = 0.95
    converged_sd: tuple = (0.1, np.radians(2.0))
    converged_updates: int = 2
    confirmations: int = 2

    def __post_init__(self):
        f = "MCLConfig"
        if self.search is not None:
            checks.instance(self.search, f, "search", SearchConfig, "a SearchConfig or None")
        for name, cls in (("beam", BeamModel), ("odometry", OdometryModel), ("kld", KLDConfig)):
            checks.instance(getattr(self, name), f, name, cls, f"a {cls.__name__}")
        for name in ("ess_fraction", "ess_floor", "alpha_slow", "alpha_fast", "converged_mass"):
            self._set(name, checks.real(getattr(self, name), f, name, low=0.0, high=1.0, strict_low=True))
        for name in ("random_threshold", "max_random_fraction", "proposal_fraction"):
            self._set(name, checks.real(getattr(self, name), f, name, low=0.0, high=1.0, strict_high=True))
        for name, n in (("proposal_sd", 3), ("gate", 2), ("converged_sd", 2)):
            v = checks.magnitude(checks.array(getattr(self, name), f, name, (n,)), f, name)
            if np.any(v <= 0):
                raise checks.fail(f, name, f"must be {n} numbers > 0, got {v.tolist()}")
        for name in ("proposal_candidates", "history", "converged_updates", "confirmations"):
            self._set(name, checks.integer(getattr(self, name), f, name, low=0))
        self._set("clearance", checks.real(self.clearance, f, "clearance", low=0.0))
        self._set("hough", checks.flag(self.hough, f, "hough"))

    def _set(self, name, value):
        object.__setattr__(self, name, value)
