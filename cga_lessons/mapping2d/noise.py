"""The noise model of the 2D line map, estimated from the data as the map is built (beyond chapter 3).

The thesis's thresholds assume one laser and one robot.  The real logs differ
(measured on the six bundled CARMEN logs: the segments' scatter is 0.7 cm on
Intel and 1.4 cm on ACES; the logs' odometry fields repeat their corrected
poses, so their "odometry" has no error at all), so every noise level the
corrector needs is read from the data:

* :func:`segment_residual_sigma`, :func:`scan_range_noise`: the range noise,
  from the scatter of each segment's points about its own fitted line;
* :class:`NoiseFloors`: the model error of each kind of measurement (angle,
  offset, real edge) that the line fits do not explain;
* :class:`InnovationModel`: how good the odometry really is, relative to its
  stated drift model (:class:`cga_lessons.mapping2d.laser.OdometryModel`), and how good
  the registration of a scan on the map is, from the innovations of the
  corrections (maximum likelihood): perfect odometry is learnt to be perfect
  and then barely corrected, drifting odometry is corrected as its model says.
"""

from __future__ import annotations

from collections import deque

import numpy as np
from scipy import stats
from scipy.special import gammaln

from .geometry import SegmentSet

__all__ = ["RANGE_NOISE_FLOOR", "segment_residual_sigma", "scan_range_noise", "NoiseFloors", "InnovationModel"]

#: Smallest range noise (m) assumed: the CARMEN logs print ranges in centimetres or millimetres, and a SICK LMS's
#: stated accuracy is about 1 cm; below 2 mm a segment's scatter is quantisation, not information.
RANGE_NOISE_FLOOR = 0.002


def segment_residual_sigma(segs: SegmentSet) -> np.ndarray:
    """Standard deviation (m) of each segment's points about its own least-squares line, shape (n,).

    From the point sums: the smallest eigenvalue of the points' scatter
    matrix is the sum of squared perpendicular residuals; a line has two
    parameters, so it is divided by ``n - 2``.

    >>> from cga_lessons.mapping2d import Segment
    >>> x = np.linspace(0, 1, 11); y = 0.01 * (-1.0) ** np.arange(11)
    >>> sums = [11, x.sum(), y.sum(), x @ x, x @ y, y @ y]
    >>> s = SegmentSet.from_segments([Segment((0, 0), (1, 0), 11, sums)])
    >>> round(float(segment_residual_sigma(s)[0]), 4)  # 11 residuals of 1 cm about y = 0.0009, 9 degrees of freedom
    0.011
    """
    w = np.asarray(segs.sums, float)
    if len(w) == 0:
        return np.zeros(0)
    n = w[:, 0]
    c = w[:, 1:3] / n[:, None]
    sxx = w[:, 3] - n * c[:, 0] ** 2
    sxy = w[:, 4] - n * c[:, 0] * c[:, 1]
    syy = w[:, 5] - n * c[:, 1] ** 2
    half_trace, diff = 0.5 * (sxx + syy), np.hypot(0.5 * (sxx - syy), sxy)
    smallest = np.maximum(half_trace - diff, 0.0)
    return np.sqrt(smallest / np.maximum(n - 2, 1))


def scan_range_noise(segs: SegmentSet, floor: float = RANGE_NOISE_FLOOR) -> float | None:
    """The scan's range noise (m): the median of its segments' residual sigmas, at least ``floor``.

    The median keeps one curved or cluttered segment from setting the scale.
    Returns None when the scan has no segment (the caller keeps its previous
    estimate).

    >>> from cga_lessons.mapping2d import Segment
    >>> x = np.linspace(0, 1, 11); y = 0.01 * (-1.0) ** np.arange(11)
    >>> sums = [11, x.sum(), y.sum(), x @ x, x @ y, y @ y]
    >>> round(scan_range_noise(SegmentSet.from_segments([Segment((0, 0), (1, 0), 11, sums)] * 3)), 4)
    0.011
    """
    if len(segs) == 0:
        return None
    return float(max(np.median(segment_residual_sigma(segs)), floor))


class NoiseFloors:
    """Running estimates of the model error of each kind of measurement: what the fit variances do not explain.

    A matched pair's angle and offset differ by more than the two lines'
    fits say: walls are not perfectly straight, a map line carries the errors
    of the poses that built it, and a real edge's position depends on where
    the beams fell.  Those errors do not shrink with the number of points, so
    they are a floor added to each row's variance: ``var = fit variance +
    floor^2``.  The floor of each kind is estimated from the residuals of the
    recent inlier rows (the last ``window``): with ``median|r| / 0.6745`` their
    robust standard deviation, ``floor^2 = max(0, sd^2 - median(fit variance))``.

    Parameters
    ----------
    initial : array_like, shape (3,)
        Floors (standard deviations: rad, m, m) of angle, offset and edge rows until ``min_rows`` rows of a
        kind are in.
    window : int
        Rows of each kind kept.
    min_rows : int
        Rows needed before the estimate replaces the initial floor.

    >>> f = NoiseFloors((0.01, 0.02, 0.05), min_rows=3)
    >>> f.add(np.array([0, 0, 0, 1]), np.array([1e-4, 1e-4, 1e-4, 0.0]), np.array([0.03, -0.03, 0.03, 0.0]))
    >>> np.round(np.sqrt(f.variances), 4).tolist()  # sd 0.03 / 0.6745 = 0.0445, less the fit's 0.01
    [0.0433, 0.02, 0.05]
    """

    def __init__(self, initial, window: int = 1000, min_rows: int = 50):
        self.initial = np.asarray(initial, float) ** 2
        self.window, self.min_rows = int(window), int(min_rows)
        self.r2 = [deque(maxlen=self.window) for _ in range(3)]
        self.fit = [deque(maxlen=self.window) for _ in range(3)]
        self._cached = None

    @property
    def variances(self) -> np.ndarray:
        """The floors as variances, shape (3,)."""
        if self._cached is not None:
            return self._cached.copy()
        out = self.initial.copy()
        for kind in range(3):
            if len(self.r2[kind]) >= self.min_rows:
                sd2 = np.median(np.asarray(self.r2[kind])) / 0.6745**2
                out[kind] = max(sd2 - np.median(np.asarray(self.fit[kind])), 0.0)
        self._cached = out
        return out.copy()

    def add(self, kind, fit_var, residuals):
        """Record rows: their ``kind`` (0 angle, 1 offset, 2 edge), fit variance and residual (arrays (m,))."""
        self._cached = None
        for k in range(3):
            m = kind == k
            self.r2[k].extend(np.asarray(residuals)[m] ** 2)
            self.fit[k].extend(np.asarray(fit_var)[m])


class InnovationModel:
    """How good the odometry and the registration really are, learnt from the innovations of the corrections.

    Each correction compares the prediction with the lines: its innovation
    ``g`` (in the ``r`` directions the lines fix) has covariance

    .. math:: S = C + c\\,R + q\\,B

    with ``C`` what is known (the line fits and the pose carried from the last
    scan), ``B`` the odometry step's covariance by its drift model
    (:class:`cga_lessons.mapping2d.laser.OdometryModel`), scaled by ``q``, and ``R`` a
    registration error common to all the lines of a scan (the scan is not a
    rigid snapshot, the map lines carry the errors of the poses that built
    them), scaled by ``c``.  The two are told apart because ``B`` grows with
    the step (the turn and the distance) and ``R`` does not.  ``(q, c)``
    are read from the likelihood of the last ``window`` innovations, on a
    grid of ``log q`` and ``log c``:

    * **a test before the odometry is called inexact.**  ``q`` leaves
      ``q_min`` (an exact odometry) only if a larger ``q`` explains the
      innovations significantly better: the likelihood ratio beyond the
      chi-square quantile of one degree of freedom at ``level`` (the
      corrections' own ``significance``).  The registration error of a scan is
      not one independent error per scan: measured on the logs' own poses, it
      is correlated over neighbouring scans, which at the lags the builder
      registers (one and ``learn_lag`` scans) looks like a little odometry
      drift (0.01-0.2 of the drift model).  An odometry that drifts as its
      model says gave ratios of 60-150 per window (CSAIL, Seattle, Orebro,
      seed 0), the logs' own poses 0-7.5.  The test is two-sided: ``q_min`` is
      taken only when the drift model as stated (``q = 1``) is rejected too;
      while the evidence is thin (the first innovations) neither is, and the
      maximum likelihood ``q`` stands (a drifting odometry called exact after
      its first 20 innovations was left uncorrected: CSAIL, seed 1, 2 m off
      before the model caught up).
    * **a heavy-tailed likelihood for the test.**  A registration of one scan
      on another now and then takes a wrong pair of lines: on the CSAIL log fed
      its own poses the innovations' standard deviation was 45 cm against a
      robust (MAD) 2.6 cm, and a Gaussian likelihood explains those by the
      largest covariance it may scale, the odometry's (its ratios reached 12-32
      on the logs' own poses).  The test reads the innovations as multivariate
      Student t, its degrees of freedom ``nu`` estimated with ``(q, c)``
      (powers of two from 1 to 64, and infinity: the Gaussian).  The value of
      the running ``(q, c)`` once the test has let ``q`` go is the Gaussian
      maximum likelihood, a covariance, as the corrections' chi-square tests
      read it (the t's scale, smaller where the tails are heavy, refused right
      corrections of a drifting odometry: ACES's first 160 scans, seed 0,
      corrected 8.7 times instead of 13.6 without the final adjustment);
      :meth:`overall` gives the t's.

    Fed perfect odometry (the CARMEN corrected logs, whose odometry repeats
    their poses) ``q`` falls to ``q_min`` and the corrections stop moving the
    poses, whatever the registration's own error; fed odometry that drifts as
    its model says, ``q`` stays near 1.

    Parameters
    ----------
    window : int
        Innovations remembered (100 scans).
    q_bounds, c_bounds : (float, float)
        Search ranges.  ``q_min = 1e-4``: odometry a hundred times better than its model (in standard
        deviation) is taken as exact; ``c`` from 1e-3 to 1e2 times ``R``.
    min_count : int
        While fewer innovations are in, the model is *learning* (:attr:`learning`): ``(q, c)`` are
        re-estimated after every innovation, and the caller should settle a disagreement between the lines
        and the odometry with the odometry's stated model rather than refuse the correction.  Twenty: the mean
        of 20 chi-square variables of 3 degrees of freedom is known within 18 % at one sigma.
    every : int
        After learning, re-estimate after this many new innovations.
    initial : (float, float)
        ``(q, c)`` before the first innovation: the odometry is taken as good (``q_min``: a right odometry
        is not moved while the model learns; a wrong one shows at once in the first innovations) and the
        registration error as ``R``.
    level : float
        The test's level: ``q`` leaves ``q_min`` when the likelihood ratio exceeds the chi-square quantile
        of one degree of freedom at ``level`` (0.999: 10.8).
    """

    #: Degrees of freedom of the Student t the innovations may follow (inf: the Gaussian).
    DOFS = (1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0, np.inf)

    def __init__(self, window=100, q_bounds=(1e-4, 1e2), c_bounds=(1e-3, 1e2), min_count=20, every=10,
                 initial=(1e-4, 1.0), level=0.999):  # fmt: skip
        self.window = int(window)
        self.history = []  # every innovation, padded to 3: (g, C, B, R, rank); the window is its last rows
        self.q_bounds, self.c_bounds = np.log(q_bounds), np.log(c_bounds)
        self.min_count, self.every = int(min_count), int(every)
        self.q, self.c = (float(v) for v in initial)
        self.threshold = float(stats.chi2.ppf(level, 1))
        self.ratio = self.ratio_model = 0.0  # the last test's ratios: the best q against q_min and against 1
        self._new = 0

    def add(self, innovation, known_cov, step_cov, registration_cov):
        """Record one innovation ``g`` (r,) with ``C``, ``B`` and ``R`` (r, r); re-estimate now and then.

        >>> m = InnovationModel()
        >>> rng = np.random.default_rng(0)
        >>> R = np.diag([6e-4, 6e-4, 8e-5]); C = np.diag([1e-5, 1e-5, 1e-6])
        >>> for k in range(100):
        ...     B = np.diag([4e-4, 4e-4, 3e-4]) * rng.uniform(0.1, 3.0)  # steps of every size
        ...     m.add(rng.multivariate_normal(np.zeros(3), C + 0.5 * R), C, B, R)
        >>> m.q < 0.05 and 0.2 < m.c < 1.0  # a perfect odometry; half the reference registration error
        True
        """
        r = len(innovation)
        row = [np.zeros(3), np.eye(3), np.zeros((3, 3)), np.zeros((3, 3))]
        row[0][:r] = innovation
        for full, val in zip(row[1:], (known_cov, step_cov, registration_cov)):
            full[:r, :r] = val
        self.history.append((*row, r))
        self._new += 1
        if self.learning or self._new >= self.every:
            self._new = 0
            self.q, self.c, self.ratio, self.ratio_model = self._estimate()

    @property
    def g(self) -> list:
        """The innovations (padded to 3) of the last ``window``."""
        return [row[0] for row in self.history[-self.window :]]

    @property
    def learning(self) -> bool:
        """Fewer than ``min_count`` innovations are in."""
        return len(self.history) < self.min_count

    def overall(self):
        """``(q, c)`` from every innovation of the run (not the last ``window``), with the same test: the
        odometry's scale for a batch estimate of the whole run, in which one robot's odometry has one drift
        model (a running window passed the test by chance now and then, and the adjustment bent the steps of
        those windows: on the CSAIL log fed its own poses 26 of its 405 steps, 6.3 cm RMS against 3.2 cm).
        Its value is the Student t's: the batch adjustment weighs the odometry by its typical error, which the
        Gaussian inflates by the wrong registrations (the Intel log fed its own poses: held within 4.8 cm RMS
        with the Gaussian's value, 2.7 cm with the t's).  ``(q, c)`` as they stand while fewer than
        ``min_count`` innovations are in."""
        if self.learning:
            return self.q, self.c
        q, c, _, _ = self._estimate(self.history, robust_values=True)
        return q, c

    @staticmethod
    def _nll(rows, log_q, log_c, chunk=500):
        """Negative log-likelihood of the innovations ``rows = (G, C, B, R, rank)`` at each (log q, log c) pair
        (arrays of shape (k,)), for each degrees of freedom of :attr:`DOFS`: shape (len(DOFS), k).  The padded
        directions of an innovation of rank below 3 (unit variance, zero value) add nothing: each is counted
        with its rank.  Summed over ``chunk`` innovations at a time (the memory of a whole run's)."""
        out = np.zeros((len(InnovationModel.DOFS), len(log_q)))
        q, c = np.exp(log_q)[:, None, None, None], np.exp(log_c)[:, None, None, None]
        for start in range(0, len(rows[0]), chunk):
            G, C, B, R, r = (np.asarray(x[start : start + chunk], float) for x in rows)
            S = C[None] + c * R[None] + q * B[None]  # (k, n, 3, 3)
            _, logdet = np.linalg.slogdet(S)
            x = np.linalg.solve(S, np.broadcast_to(G[None, ..., None], S.shape[:-1] + (1,)))[..., 0]
            m = np.einsum("kni,ni->kn", x, G)  # squared Mahalanobis distances
            for i, nu in enumerate(InnovationModel.DOFS):
                if np.isinf(nu):
                    per = 0.5 * (m + r * np.log(2 * np.pi))
                else:
                    const = gammaln((nu + r) / 2) - gammaln(nu / 2) - r / 2 * np.log(nu * np.pi)
                    per = (nu + r) / 2 * np.log1p(m / nu) - const
                out[i] += (0.5 * logdet + per).sum(axis=1)
        return out

    def _estimate(self, rows=None, robust_values=False):
        """``(q, c, ratio, ratio_model)`` for the window's innovations (or the records ``rows``, as in
        :attr:`history`): ``(q_min, c)`` when the
        ratio test (Student t likelihoods, profiled over ``c`` and ``nu``) establishes an odometry better than
        its model and not one worse than exact, else the maximum likelihood ``(q, c)`` on the grid (steps of
        10^(1/3) in ``q``, 10^(1/2) in ``c``) of the Gaussian (or, ``robust_values``, of the t); the two ratios
        are twice the log-likelihood ratios of the best ``q`` against ``q_min`` and against 1."""
        rows = [np.array(x) for x in zip(*(self.history[-self.window :] if rows is None else rows))]
        lq, lc = np.linspace(*self.q_bounds, 19), np.linspace(*self.c_bounds, 11)
        Q, Cg = np.meshgrid(lq, lc, indexing="ij")
        every = self._nll(rows, Q.ravel(), Cg.ravel())
        robust = every.min(axis=0).reshape(Q.shape)  # profiled over nu
        one = int(np.argmin(np.abs(lq)))  # q = 1: the drift model as stated
        ratio = float(2.0 * (robust[0].min() - robust.min()))
        ratio_model = float(2.0 * (robust[one].min() - robust.min()))
        values = robust if robust_values else every[-1].reshape(Q.shape)  # the last nu is inf: the Gaussian
        if ratio <= self.threshold < ratio_model:
            return float(np.exp(lq[0])), float(np.exp(lc[int(np.argmin(values[0]))])), ratio, ratio_model
        best = np.unravel_index(int(np.argmin(values)), values.shape)
        return float(np.exp(lq[best[0]])), float(np.exp(lc[best[1]])), ratio, ratio_model
