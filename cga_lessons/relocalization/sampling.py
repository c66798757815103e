"""Resampling a particle set: low-variance resampling to a size chosen by KLD sampling, and the main mode.

:func:`kld_resample` draws the next particle set of
:class:`~cga_lessons.relocalization.mcl.MonteCarloLocalizer`.  Its size follows
Fox's KLD sampling (*Adapting the sample size in particle filters through
KLD-sampling*, IJRR 2003): with the poses cut into bins, ``k`` of them
occupied, the number of samples that keeps the Kullback-Leibler divergence of
the sampled histogram from the true one below ``epsilon`` with probability
``1 - delta`` is about (the Wilson-Hilferty form of the chi-square quantile)::

    n = (k - 1) / (2 epsilon) * (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) z_{1 - delta}) ** 3

Many particles while they spread over many bins (global localization), few
once they agree.  The draw itself is low-variance (systematic) resampling:
one random offset, then evenly spaced pointers into the cumulative weights.

:func:`mode_estimate` finds the heaviest cluster of particles and its mean and
covariance: the mean of all particles of a belief with two modes lies between
them, where no particle is.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from cga_lessons import checks
from cga_lessons.mapping2d import wrap_angle

from .inputs import ndim

__all__ = ["KLDConfig", "kld_bound", "low_variance_indices", "kld_resample", "mode_estimate", "tempering"]


@dataclass(frozen=True)
class KLDConfig:
    """The particle counts and the KLD bound.

    Attributes
    ----------
    n_min : int
        Fewest particles.  300: a converged cloud of a few centimetres
        needs no more (its occupied bins, 1-8, ask for at most about 200), and
        a few hundred keep enough spread to follow the drift of a 1 m step
        (2 cm, 1 degree by :class:`~cga_lessons.mapping2d.laser.OdometryModel`).
    n_max : int
        Most particles, and the global initialisation: 20,000.  On Intel's
        free space (336 m2 at 20 cm from the walls) one particle per 0.1 m2 per
        radian of heading: too few for a uniform draw to land within a scan's
        reach of the pose (centimetres and a degree); the draw is made from
        the first scan's coarse search instead
        (:mod:`cga_lessons.relocalization.mcl_search`), and chapter 5's
        proposals add particles at its answers.  Scoring them costs about ten tracking
        updates of 2,000 (7 ms each on Intel's map, one core).
    epsilon : float
        Bound on the KL divergence: 0.05, KLD sampling's usual value.
    z : float
        Upper ``1 - delta`` quantile of the standard normal, ``delta = 0.01``: 2.326.
    bin_xy, bin_theta : float
        Bin sizes (m, rad): 0.5 m and 10 degrees, coarse next to a converged
        cloud (centimetres and a degree: one to eight bins, ``n_min``
        particles) and fine next to the places one scan confuses (metres
        apart, or turned round).
    """

    n_min: int = 300
    n_max: int = 20_000
    epsilon: float = 0.05
    z: float = 2.326
    bin_xy: float = 0.5
    bin_theta: float = np.radians(10.0)

    def __post_init__(self):
        checks.record(self, n_min=partial(checks.integer, low=1), n_max=partial(checks.integer, low=1))
        if self.n_min > self.n_max:
            raise checks.fail("KLDConfig", "n_min, n_max", f"n_min ({self.n_min}) must not exceed n_max ({self.n_max})")
        positive = partial(checks.real, low=0.0, strict_low=True)
        checks.record(self, epsilon=positive, z=positive, bin_xy=positive, bin_theta=positive)


def kld_bound(k, epsilon: float = 0.05, z: float = 2.326):
    """The KLD sample count for ``k`` occupied bins (1 for ``k <= 1``).

    >>> [int(kld_bound(k)) for k in (1, 2, 10, 100)]
    [1, 66, 217, 1347]
    """
    func = "kld_bound"
    k = checks.array(k, func, "k", (None,) * ndim(k))
    if np.any(k < 0):
        raise checks.fail(func, "k", "must be >= 0 (a count of occupied bins)")
    epsilon = checks.real(epsilon, func, "epsilon", low=0.0, strict_low=True)
    z = checks.real(z, func, "z", low=0.0)
    return checks.finite_result(bound(k, epsilon, z), func, "k, epsilon, z: the sample count")


def bound(k, epsilon: float, z: float):
    """:func:`kld_bound` of checked arguments."""
    km1 = np.maximum(k - 1, 1e-12)
    a = 2.0 / (9.0 * km1)
    n = km1 / (2 * epsilon) * (1 - a + np.sqrt(a) * z) ** 3
    return np.where(k <= 1, 1.0, np.ceil(n))


def low_variance_indices(weights, n: int, rng) -> np.ndarray:
    """``n`` indices drawn by low-variance (systematic) resampling of normalised ``weights``."""
    c = np.cumsum(weights)
    c[-1] = 1.0
    u = (rng.random() + np.arange(int(n))) / int(n)
    return np.minimum(np.searchsorted(c, u, side="right"), len(c) - 1)


def _bin_keys(particles, bin_xy: float, bin_theta: float) -> np.ndarray:
    """One integer per bin of ``bin_xy`` x ``bin_xy`` x ``bin_theta`` (distinct bins, distinct keys on any
    map under a thousand kilometres and a bin over a thousandth of a radian)."""
    b = np.floor(particles[:, :2] / bin_xy).astype(np.int64) + 2**20
    t = np.floor(np.mod(particles[:, 2], 2 * np.pi) / bin_theta).astype(np.int64)
    return (b[:, 0] * 2**21 + b[:, 1]) * 2**13 + t


def kld_resample(particles, weights, cfg: KLDConfig, rng) -> np.ndarray:
    """Indices of the next particle set: its size by KLD sampling, the draw low-variance.

    The bins are counted along a random-order draw of ``n_max`` particles, as
    KLD sampling draws one by one, and the size is the first count ``n`` at
    which ``n >= kld_bound(bins so far)`` (within ``n_min .. n_max``); the ``n``
    particles are then drawn afresh by low-variance resampling.
    """
    w = np.asarray(weights, float)
    trial = rng.permutation(low_variance_indices(w, cfg.n_max, rng))
    keys = _bin_keys(np.asarray(particles)[trial], cfg.bin_xy, cfg.bin_theta)
    _, first = np.unique(keys, return_index=True)
    new_bin = np.zeros(len(keys), bool)
    new_bin[first] = True
    k = np.cumsum(new_bin)
    m = np.arange(1, len(keys) + 1)
    enough = np.flatnonzero((m >= bound(k, cfg.epsilon, cfg.z)) & (m >= cfg.n_min))
    n = int(m[enough[0]]) if len(enough) else cfg.n_max
    return low_variance_indices(w, n, rng)


def mode_estimate(particles, weights, gate) -> tuple[np.ndarray, np.ndarray, float]:
    """The main mode of a weighted particle set: its mean pose, its covariance and its share of the weight.

    The heaviest cell of a grid of ``gate`` (position m, heading rad) starts a
    mean shift: the weighted mean of the particles within ``gate`` of the
    current mean, three times.

    >>> p = np.array([[0.0, 0.0, 0.0], [0.02, 0.0, 0.0], [5.0, 5.0, 1.0]])
    >>> pose, cov, mass = mode_estimate(p, np.array([0.4, 0.4, 0.2]), (0.5, 0.2))
    >>> pose.round(3).tolist(), round(mass, 2)
    ([0.01, 0.0, 0.0], 0.8)
    """
    P = np.asarray(particles, float)
    w = np.asarray(weights, float)
    g_xy, g_th = gate
    keys = _bin_keys(P, g_xy, g_th)
    _, inv = np.unique(keys, return_inverse=True)
    inv = inv.ravel()
    heavy = np.argmax(np.bincount(inv, weights=w))
    near = inv == heavy
    centre = _weighted_mean(P[near], w[near])
    for _ in range(3):
        within = (np.hypot(P[:, 0] - centre[0], P[:, 1] - centre[1]) <= g_xy) & (
            np.abs(wrap_angle(P[:, 2] - centre[2])) <= g_th
        )
        if w[within].sum() <= 0:
            break
        near = within
        centre = _weighted_mean(P[near], w[near])
    wn = w[near] / w[near].sum() if w[near].sum() > 0 else np.full(int(near.sum()), 1.0 / near.sum())
    d = P[near] - centre
    d[:, 2] = wrap_angle(d[:, 2])
    cov = (d * wn[:, None]).T @ d
    return centre, cov, float(w[near].sum() / w.sum())


def _weighted_mean(P, w) -> np.ndarray:
    w = w / w.sum() if w.sum() > 0 else np.full(len(w), 1.0 / len(w))
    xy = w @ P[:, :2]
    th = np.arctan2(w @ np.sin(P[:, 2]), w @ np.cos(P[:, 2]))
    return np.array([xy[0], xy[1], th])


def tempering(log_w, log_l, floor: float) -> float:
    """The largest ``beta`` in (0, 1] for which the weights ``log_w + beta log_l`` keep an effective sample
    size of at least ``floor`` (or that of ``log_w``, if lower): 1 when no tempering is needed, else found by
    bisection (12 halvings: to 0.02 %).

    A likelihood of many beams is so sharp that one scan can leave a single particle of thousands with all
    the weight (the best of a uniform draw, rarely at the pose): the rest of the scan's evidence is held back
    rather than the belief collapsed (the adaptive tempering of sequential Monte Carlo samplers).

    >>> tempering(np.zeros(4), np.array([0.0, -1.0, -2.0, -3.0]), 1.0)
    1.0
    >>> b = tempering(np.zeros(1000), np.linspace(0.0, -500.0, 1000), 100.0)
    >>> 0.0 < b < 1.0
    True
    """
    log_w = np.asarray(log_w, float)
    log_l = np.asarray(log_l, float)

    def ess(b):
        w = np.exp(log_w + b * log_l - np.max(log_w + b * log_l))
        return float(w.sum() ** 2 / np.sum(w**2))

    floor = min(floor, ess(0.0))
    if ess(1.0) >= floor:
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(12):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ess(mid) >= floor else (lo, mid)
    return max(lo, 1e-3)
