"""Monte Carlo localization in a line map: the relocalization with probability terms (thesis, section 6.3.2).

Chapter 5's relocalizer answers from one scan, and says "ambiguous" when one
scan cannot tell two places apart.  A particle filter (Thrun, Burgard and Fox,
*Probabilistic Robotics*, chapter 8) carries every place the robot may be as a
weighted sample of laser poses and lets the scans and the odometry between
them tell the places apart:

1. **global initialisation**: ``n_max`` poses over the map's free space
   (:meth:`~cga_lessons.relocalization.likelihood.LikelihoodField.free_space`),
   drawn at the first scan by importance from an exhaustive coarse search of
   it (:class:`~cga_lessons.relocalization.mcl_search.CoarseSearch`: every
   20 cm cell and 3 degree heading) and weighed back to the uniform prior;
   or around a given pose;
2. **motion**: every particle moved by the reported odometry increment with
   its own draw of chapter 3's drift (:class:`~cga_lessons.mapping2d.laser.OdometryModel`);
3. **proposal**: while the filter tracks no confirmed place (or suspects a
   kidnapping) the scan is relocalized by chapter 5's method
   (:func:`~cga_lessons.relocalization.relocalize`); around a confident answer,
   or around each of its tied candidates, a share of the particles is
   redrawn, weighed against the rest by the last scans carried back through
   the odometry (:mod:`cga_lessons.relocalization.history`,
   :mod:`cga_lessons.relocalization.mcl_proposal`);
4. **measurement**: each particle weighed by the scan's likelihood
   (:class:`~cga_lessons.relocalization.likelihood.LikelihoodField`),
   tempered when one scan would leave almost no particle with weight
   (:func:`~cga_lessons.relocalization.sampling.tempering`);
5. **augmented MCL**: fast and slow averages of the likelihood per beam;
   when the fast one falls below the slow one the scans fit worse than they
   used to (a kidnapping), and a share ``1 - w_fast / w_slow`` of the next
   particles is drawn anew over the free space, weighed like the proposals;
6. **resampling**: low-variance resampling when the effective sample size
   falls below ``ess_fraction`` of the particles, to a number chosen by KLD
   sampling (:mod:`cga_lessons.relocalization.sampling`): many while the
   particles spread over many places, few once they agree.

:meth:`MonteCarloLocalizer.estimate` gives the mean pose of the main mode, its
covariance and whether the filter has converged: the mode heavy and tight for
``converged_updates`` updates in a row, moving as the odometry says, and
confirmed by chapter 5 (which searches every place): confident answers
within it, or ambiguous answers whose best candidate lies within it and
whose other tied candidates the remembered scans have ruled out
(:func:`~cga_lessons.relocalization.mcl_proposal.confirms`).  The fit the
augmented filter watches counts only the beams the map can judge: a scan
looking into unmapped space is no sign of a kidnapping.
The settings and the reasons for their defaults are in
:mod:`cga_lessons.relocalization.mcl_config`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import compose, wrap_angle

from .coverage import Coverage
from .geometry import ReferenceMap, prepare_map
from .history import ScanHistory, merge, normalise
from .inputs import as_segment_array, check_pose, check_scan, spread
from .likelihood import LikelihoodField
from .mcl_config import MCLConfig
from .mcl_proposal import confirms, propose
from .mcl_search import CoarseSearch
from .params import STATUSES
from .sampling import kld_resample, mode_estimate, tempering

__all__ = ["MCLEstimate", "MonteCarloLocalizer"]


@dataclass
class MCLEstimate:
    """The filter's answer after an update.

    Attributes
    ----------
    pose : ndarray, shape (3,)
        Weighted mean ``(x, y, theta)`` of the main mode (laser pose, map frame).
    covariance : ndarray, shape (3, 3)
        Of the main mode's particles about ``pose``.
    converged : bool
        The main mode has held ``converged_mass`` of the weight within
        ``converged_sd`` for ``converged_updates`` updates, moving with the
        odometry, and is ``anchored``.
    mass : float
        Share of the weight in the main mode.
    n_particles : int
    ess : float
        Effective sample size after the measurement.
    hough_status : str
        Chapter 5's answer on this update's scan (``"ok"``, ``"ambiguous"``,
        ``"failed"``), ``""`` when it was not asked.
    fit : float
        Share of the scan's beams the map explains at ``pose``
        (:meth:`~cga_lessons.relocalization.likelihood.LikelihoodField.fit`), a diagnostic.
    streak : int
        Updates in a row the mode has been heavy and tight.
    anchored : bool
        Chapter 5 has confirmed the mode at least ``confirmations`` times since
        it was first tracked (always, without ``hough``): see
        :func:`~cga_lessons.relocalization.mcl_proposal.confirms`.
    confirmations : int
        How many.
    """

    pose: np.ndarray
    covariance: np.ndarray
    converged: bool
    mass: float
    n_particles: int
    ess: float
    hough_status: str = ""
    fit: float = float("nan")
    streak: int = 0
    anchored: bool = False
    confirmations: int = 0

    def __post_init__(self):
        f = "MCLEstimate"
        self.pose = checks.array(self.pose, f, "pose", (3,))
        self.covariance = checks.array(self.covariance, f, "covariance", (3, 3))
        self.converged = checks.flag(self.converged, f, "converged")
        self.mass = checks.real(self.mass, f, "mass", low=0.0, high=1.0 + 1e-9)
        self.n_particles = checks.integer(self.n_particles, f, "n_particles", low=1)
        self.ess = checks.real(self.ess, f, "ess", low=0.0)
        self.hough_status = checks.choice(self.hough_status, f, "hough_status", ("", *STATUSES))
        if not (isinstance(self.fit, (float, np.floating)) and np.isnan(self.fit)):  # NaN: no beam counted
            self.fit = checks.real(self.fit, f, "fit", low=0.0, high=1.0)
        self.streak = checks.integer(self.streak, f, "streak", low=0)
        self.anchored = checks.flag(self.anchored, f, "anchored")
        self.confirmations = checks.integer(self.confirmations, f, "confirmations", low=0)


class MonteCarloLocalizer:
    """A particle filter over laser poses in a line map.

    Parameters
    ----------
    map_segments : array_like (M, 2, 2), list of Segment, or ReferenceMap
        The map (a ReferenceMap brings its coverage grid).
    coverage : Coverage, optional
        What the map knows (:func:`~cga_lessons.relocalization.coverage.build_coverage`).
    config : MCLConfig, optional
    rng : numpy.random.Generator or int
        The source of every random draw (an int seeds a new Generator).
    initial_pose : array_like (3,), optional
        Start around this pose (tracking) instead of globally.
    initial_sd : array_like (3,), optional
        Standard deviations (m, m, rad) around ``initial_pose``; default 10 cm, 10 cm, 2 degrees.

    Examples
    --------
    >>> from cga_lessons.mapping2d.laser import load_scene, simulate_scan
    >>> scene = load_scene("room")
    >>> mcl = MonteCarloLocalizer(scene.walls, rng=0, initial_pose=[3.0, 2.0, 0.0])
    >>> est = mcl.update([0.0, 0.0, 0.0], simulate_scan(scene, [3.0, 2.0, 0.0]))
    >>> bool(np.hypot(*(est.pose[:2] - [3.0, 2.0])) < 0.1)
    True
    """

    def __init__(
        self,
        map_segments,
        coverage=None,
        *,
        config: MCLConfig | None = None,
        rng=None,
        initial_pose=None,
        initial_sd=None,
    ):
        func = "MonteCarloLocalizer"
        if isinstance(map_segments, ReferenceMap):
            coverage = map_segments.coverage if coverage is None else coverage
            map_segments = map_segments.segments
        segs = as_segment_array(map_segments, func, "map_segments")
        if config is not None:
            checks.instance(config, func, "config", MCLConfig, "an MCLConfig or None")
        if coverage is not None:
            checks.instance(coverage, func, "coverage", Coverage, "a Coverage (build_coverage) or None")
        self.config = cfg = config or MCLConfig()
        self.rng = checks.generator(rng, func, seeds=True)
        start = None
        if initial_pose is not None:
            start = check_pose(initial_pose, func, "initial_pose"), spread(initial_sd, func, "initial_sd")
        elif initial_sd is not None:
            raise checks.fail(
                func, "initial_sd, initial_pose", "initial_sd given without an initial_pose to spread around"
            )
        self.field = LikelihoodField(segs, coverage, cfg.beam, func=func)
        self.reference = prepare_map(segs, coverage)
        free_mask = self.field.free_space(cfg.clearance)
        free = np.flatnonzero(free_mask.ravel())
        if not len(free):
            raise checks.fail(func, "map_segments", f"leave no free space {cfg.clearance} m from the walls")
        self._free = free
        self.search = CoarseSearch(self.field, free_mask, cfg.search) if cfg.search is not None else None
        self.pending_global = False
        self.w_slow = self.w_fast = None
        self.n_updates = 0
        self._estimate = None
        self.history = ScanHistory(self.field, cfg.history)
        if start is None:
            self.reset_global()
        else:
            self._start_at(*start)

    # ----------------------------------------------------------------- initialisation

    def sample_free(self, n: int) -> np.ndarray:
        """``n`` poses uniform over the free space (a uniform cell, a uniform point in it), headings uniform."""
        H, W = self.field.shape
        cells = self.rng.choice(self._free, size=int(n))
        res = self.field.model.resolution
        xy = self.field.origin + res * (np.column_stack([cells % W, cells // W]) + self.rng.random((int(n), 2)))
        return np.column_stack([xy, self.rng.uniform(-np.pi, np.pi, int(n))])

    def reset_global(self):
        """Forget the pose: ``n_max`` particles over the free space, equal weights."""
        self.particles = self.sample_free(self.config.kld.n_max)
        self.log_w = np.zeros(len(self.particles))
        self.pending_global = self.config.search is not None
        self.w_slow = self.w_fast = None
        self._estimate = None
        self.history.clear()

    def reset_local(self, pose, sd=None):
        """Start around a known pose: ``n_min`` particles drawn with standard deviations ``sd`` (m, m, rad)."""
        func = "MonteCarloLocalizer.reset_local"
        self._start_at(check_pose(pose, func), spread(sd, func, "sd"))

    def _start_at(self, pose, sd):
        self.particles = self._around(pose, sd, self.config.kld.n_min)
        self.log_w = np.zeros(len(self.particles))
        self.pending_global = False
        self.w_slow = self.w_fast = None
        self._estimate = None
        self.history.clear()

    def _around(self, pose, sd, n):
        p = pose + self.rng.normal(size=(int(n), 3)) * sd
        p[:, 2] = wrap_angle(p[:, 2])
        return p

    # ----------------------------------------------------------------- the filter

    def drift(self, increment) -> np.ndarray:
        """Standard deviations (m, m, rad) of the drift model's noise on an odometry increment (3,)."""
        u, m = np.asarray(increment, float), self.config.odometry
        d = float(np.hypot(u[0], u[1]))
        sd_xy = m.sigma_xy * np.sqrt(d)
        sd_th = np.sqrt(m.sigma_heading**2 * d + m.sigma_turn**2 * abs(u[2]) + (m.heading_bias * d) ** 2)
        return np.array([sd_xy, sd_xy, sd_th])

    def move(self, increment):
        """Move every particle by the odometry increment with its own draw of the drift model."""
        u = np.asarray(increment, float)
        inc = u + self.rng.normal(size=(len(self.particles), 3)) * self.drift(u)
        self.particles = compose(self.particles, inc)

    def update(self, odometry_increment, scan) -> MCLEstimate:
        """One step: move by ``odometry_increment``, weigh by ``scan``, resample if due; the new estimate.

        Parameters
        ----------
        odometry_increment : array_like, shape (3,)
            The laser's motion since the last scan as the odometry reports it,
            in the frame of its previous pose (:func:`cga_lessons.mapping2d.poses.relative`
            of two odometry poses); zeros for the first scan.
        scan : (ranges, angles)
            Arrays (n,) in the laser frame; ``inf`` or NaN for no return.

        Raises
        ------
        InvalidInputError
            For an increment that is not 3 finite numbers or a malformed scan.
        """
        func = "MonteCarloLocalizer.update"
        u = check_pose(odometry_increment, func, "odometry_increment")
        with np.errstate(over="ignore"):
            checks.finite_result(self.drift(u), func, "odometry_increment: the drift of the motion")
        scan = check_scan(scan, func)
        beams = self.field.select_beams(scan, func)
        cfg = self.config
        previous = self._estimate
        tracking = previous is not None and previous.anchored
        suspicious = self.random_share() > 0
        if self.pending_global:  # the uniform prior drawn by importance from the scan's coarse scores
            self.particles, log_q = self.search.sample(beams, cfg.kld.n_max, self.rng)
            self.log_w = -log_q
            self.pending_global = False
        else:
            self.move(u)
        self.history.moved(u)
        hough = propose(self, scan) if cfg.hough and (not tracking or suspicious) else None
        log_l, per_beam = self.field.log_likelihood(self.particles, beams)
        prior = normalise(self.log_w)
        w_avg = float(np.sum(prior * np.exp(per_beam)))
        self.w_fast = w_avg if self.w_fast is None else self.w_fast + cfg.alpha_fast * (w_avg - self.w_fast)
        if tracking:  # the long-term average: how well the scans have fitted since the filter knew its place
            self.w_slow += cfg.alpha_slow * (w_avg - self.w_slow)
        else:
            self.w_slow = self.w_fast
        self.beta = tempering(self.log_w, log_l, cfg.ess_floor * len(log_l))
        self.log_w = self.log_w + self.beta * log_l
        w = normalise(self.log_w)
        ess = 1.0 / float(np.sum(w**2))
        self._estimate = self._estimate_from(w, ess, hough, scan, previous, u)
        self.n_updates += 1
        self.history.add(beams)
        share = self.random_share()
        if ess < cfg.ess_fraction * len(w) or share > 0:
            self._resample(w, share)
        return self._estimate

    def random_share(self) -> float:
        """Share of the next particles to draw anew: ``1 - w_fast / w_slow`` past ``random_threshold``, capped."""
        if self.w_slow is None or self.w_slow <= 0:
            return 0.0
        share = 1.0 - self.w_fast / self.w_slow
        if share <= self.config.random_threshold:
            return 0.0
        return float(min(share, self.config.max_random_fraction))

    def inject(self, centres, fraction: float) -> list:
        """Replace ``fraction`` of the particles, chosen at random, by draws around ``centres`` (``proposal_sd``),
        as many around each, weighed against the rest by the remembered scans
        (:func:`~cga_lessons.relocalization.history.merge`); the indices of each centre's newcomers."""
        n = int(round(fraction * len(self.particles)))
        if not len(centres) or n < len(centres):
            return []
        n -= n % len(centres)
        sd = np.asarray(self.config.proposal_sd)
        each = n // len(centres)
        new = np.concatenate([self._around(np.asarray(c, float), sd, each) for c in centres])
        keep = np.ones(len(self.particles), bool)
        keep[self.rng.choice(len(self.particles), size=n, replace=False)] = False
        self.particles, self.log_w = merge(
            self.history, self.particles[keep], self.log_w[keep], new, fraction, self.rng
        )
        start = len(self.particles) - n
        return [start + each * k + np.arange(each) for k in range(len(centres))]

    def _resample(self, w, share):
        """KLD-sized low-variance resampling; a share ``share`` of the new set drawn over the free space."""
        idx = kld_resample(self.particles, w, self.config.kld, self.rng)
        n_random = int(round(share * len(idx)))
        kept = self.particles[idx[: len(idx) - n_random]]
        new = self.sample_free(n_random)
        self.particles, self.log_w = merge(self.history, kept, np.zeros(len(kept)), new, share, self.rng)

    def _estimate_from(self, w, ess, hough=None, scan=None, previous=None, u=None) -> MCLEstimate:
        """The main mode.  Converged once it has been heavy, tight and fitting the scans ``converged_updates``
        updates in a row, moving as the odometry says in between, and chapter 5 has confirmed it
        ``confirmations`` times (:func:`~cga_lessons.relocalization.mcl_proposal.confirms`) while tracked."""
        cfg = self.config
        pose, cov, mass = mode_estimate(self.particles, w, cfg.gate)
        sd_xy = float(np.sqrt(max(np.linalg.eigvalsh(cov[:2, :2]).max(), 0.0)))
        sd_th = float(np.sqrt(max(cov[2, 2], 0.0)))
        fit = self.field.fit(pose, scan) if scan is not None else float("nan")
        good = mass >= cfg.converged_mass and sd_xy <= cfg.converged_sd[0] and sd_th <= cfg.converged_sd[1]
        same = False
        if previous is not None and u is not None:
            moved = compose(previous.pose, u)
            same = bool(
                np.hypot(*(moved[:2] - pose[:2])) <= cfg.gate[0] and abs(wrap_angle(moved[2] - pose[2])) <= cfg.gate[1]
            )
        streak = (previous.streak + 1 if same else 1) if good and previous is not None else int(good)
        confirmed = confirms(hough, pose, w, cfg.gate, cfg.converged_mass)
        confirmations = (previous.confirmations if same else 0) + int(confirmed)
        anchored = not cfg.hough or confirmations >= cfg.confirmations
        converged = streak >= cfg.converged_updates and anchored
        status = "" if hough is None else hough.status
        return MCLEstimate(
            pose,
            cov,
            bool(converged),
            float(mass),
            len(self.particles),
            float(ess),
            status,
            fit,
            streak,
            bool(anchored),
            confirmations,
        )

    def estimate(self) -> MCLEstimate:
        """The estimate after the latest update (before any update: of the initial particles, equal weights)."""
        if self._estimate is None:
            w = normalise(self.log_w)
            self._estimate = self._estimate_from(w, 1.0 / float(np.sum(w**2)))
        return self._estimate
