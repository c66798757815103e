"""An exhaustive coarse search of one scan over the whole map: the global proposal of the particle filter.

A uniform draw of particles over a building's free space lands within a scan's
reach of the true pose only by chance: the likelihood of 60 beams is a few
centimetres and a degree wide, the free space of the six CARMEN logs 180-780 m2
(at 20 cm from the walls).  Chapter 5's relocalizer proposes candidates, but
where it is ambiguous its list often lacks the true pose (measured on ACES, every
held-out scan, map from the other six sevenths of the log: of 272 ambiguous
answers 162 had no candidate within 50 cm and 10 degrees of the logged pose:
corridors, where the same walls fit along metres, and scans the map explains
poorly).

:class:`CoarseSearch` scores a scan at *every* pose of a coarse grid (cells of
``cell`` metres, ``n_headings`` headings) against a blurred likelihood field,
the correlative scan matching of Olson (*Real-time correlative scan matching*,
ICRA 2009): for each heading the scan's end points are integer shifts on the
coarse grid, and the score of every cell is a sum of shifted copies of the
grid, one per beam.  :meth:`CoarseSearch.sample` draws poses from the
(tempered) scores and returns each draw's proposal density against the uniform
prior over the free space, so the filter weighs the draws as importance
samples of the posterior (Thrun, Burgard and Fox, *Probabilistic Robotics*,
section 8.3.7: sampling from the measurement model).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial

import numpy as np
from scipy import ndimage

from cga_lessons import checks

from .beam import beam_likelihood
from .sampling import tempering

__all__ = ["SearchConfig", "CoarseSearch"]


@dataclass(frozen=True)
class SearchConfig:
    """The coarse grid of :class:`CoarseSearch`.

    Attributes
    ----------
    cell : float
        Coarse cell (m): 0.2, four cells of the likelihood field.  A 50 x 60 m
        building is 75,000 cells; scoring 60 beams at every cell and heading
        takes 0.25 s on one core (ACES, measured).
    pool : int
        The blurred grid holds, in each coarse cell, the best value within this
        many coarse cells: 1.  With it a pose anywhere in a cell, and a heading
        anywhere in its bin (below), scores no worse than the cell's centre.
    ess : float
        The draws' effective number of distinct (cell, heading) entries is kept
        at least this share of the draws: 0.05 (1,000 of 20,000), so that one
        scan cannot crowd the draws into a few wrong places (the proposal is
        tempered like the measurement, :func:`~cga_lessons.relocalization.sampling.tempering`).
        On ACES the cell holding the logged pose drew a median 0.4 % of the
        untempered proposal's mass, in one of seven scans 0.007 %.

    The number of headings is not a setting: a heading off by half a bin
    moves a beam's end point by ``max_range * step / 2``, which the pooling
    absorbs when it is at most one ``cell``: ``step = 2 cell / max_range``
    (2.9 degrees, 126 headings rounded up to 128, for the logs' 8 m).
    """

    cell: float = 0.2
    pool: int = 1
    ess: float = 0.05

    def __post_init__(self):
        checks.record(
            self,
            cell=partial(checks.real, low=0.0, strict_low=True),
            pool=partial(checks.integer, low=0),
            ess=partial(checks.real, low=0.0, high=1.0, strict_low=True),
        )


class CoarseSearch:
    """Every pose of a coarse grid scored against one scan.

    Parameters
    ----------
    field : LikelihoodField
        The fine field (its distances, known space and beam model).
    free : ndarray of bool (H, W)
        The field's cells where the laser may stand (the filter's free space).
    config : SearchConfig, optional

    Attributes
    ----------
    grid : ndarray of float32 (Hc, Wc)
        Log-likelihood of an end point in each coarse cell: the beam model
        with ``sigma_hit`` grown to ``hypot(sigma_hit, cell)`` at the smallest
        distance to a wall within the cell, pooled over ``pool`` cells;
        ``log_unknown`` where the map knows nothing.
    free : ndarray of bool (Hc, Wc)
        Coarse cells holding a free fine cell.
    headings : ndarray (n_headings,)
    """

    def __init__(self, field, free, config: SearchConfig | None = None):
        self.config = cfg = config or SearchConfig()
        if config is not None:
            checks.instance(config, "CoarseSearch", "config", SearchConfig, "a SearchConfig or None")
        if np.shape(free) != tuple(field.shape):
            raise checks.fail("CoarseSearch", "free", f"must have shape {field.shape}, got {np.shape(free)}")
        self.field = field
        m = field.model
        k = max(1, int(round(cfg.cell / m.resolution)))
        self.cell = k * m.resolution
        H, W = field.shape
        Hc, Wc = max(1, H // k), max(1, W // k)
        self.fine_free = np.asarray(free, bool)

        def blocks(a):
            a = a[: Hc * k, : Wc * k]
            return a.reshape(Hc, k, Wc, k)

        dist = blocks(np.where(np.isfinite(field.distance), field.distance, 1e3)).min(axis=(1, 3))
        known = blocks(field.known).any(axis=(1, 3))
        wide = replace(m, sigma_hit=float(np.hypot(m.sigma_hit, self.cell)))
        grid = np.where(known, np.log(beam_likelihood(dist, wide)), m.log_unknown).astype(np.float32)
        if cfg.pool:
            grid = ndimage.maximum_filter(grid, size=2 * cfg.pool + 1, mode="nearest")
        self.grid = grid
        self.outside = np.float32(m.log_unknown if field.coverage is not None else m.log_miss)
        self._k = k
        self.free_area = blocks(self.fine_free).sum(axis=(1, 3)).ravel() * m.resolution**2
        self.free = (self.free_area > 0).reshape(Hc, Wc)
        self._free_cells = np.flatnonzero(self.free.ravel())
        n = int(np.ceil(np.pi * m.max_range / self.cell))  # 2 pi / (2 cell / max_range)
        n = max(8, 8 * int(np.ceil(n / 8)))
        self.headings = np.arange(n) * (2 * np.pi / n)
        self.area = float(self.fine_free.sum()) * m.resolution**2  # of the prior: the fine free space

    def volume(self, beams) -> np.ndarray:
        """Coarse log-likelihood (``beam_weight`` times the sum over the returned beams) of the scan at every
        coarse cell and heading: shape ``(n_headings, Hc, Wc)``, float32."""
        r, a = beams[0], beams[1]
        Hc, Wc = self.grid.shape
        P = int(np.ceil(self.field.model.max_range / self.cell)) + 2
        G = np.pad(self.grid, P, constant_values=self.outside)
        out = np.zeros((len(self.headings), Hc, Wc), np.float32)
        for h, t in enumerate(self.headings):
            sx = np.round(r * np.cos(t + a) / self.cell).astype(int) + P
            sy = np.round(r * np.sin(t + a) / self.cell).astype(int) + P
            S = out[h]
            for x, y in zip(sx, sy):
                S += G[y : y + Hc, x : x + Wc]
        out *= np.float32(self.field.model.beam_weight)
        return out

    def scores(self, beams) -> np.ndarray:
        """:meth:`volume` at the free coarse cells: shape ``(n_headings, n_free_cells)``."""
        return self.volume(beams).reshape(len(self.headings), -1)[:, self._free_cells]

    def sample(self, beams, n: int, rng) -> tuple[np.ndarray, np.ndarray]:
        """``n`` poses drawn from the scan's coarse scores, and ``log(q / p0)`` of each.

        The scores are tempered so that their effective number of entries is
        at least ``ess * n``; an entry is drawn by its share, a pose uniform in
        its cell (a free fine cell of it) and heading bin.  ``q`` is the
        density of the draw, ``p0`` that of a uniform pose over the free
        space, so ``log p0 - log q`` is the importance weight that makes the
        draws a sample of the uniform prior (to be weighed by the scans).
        """
        n = int(n)
        if n <= 0:
            return np.zeros((0, 3)), np.zeros(0)
        S = self.scores(beams).ravel().astype(float)
        top = min(len(S), max(10 * n, 10_000))  # only the best 10 n entries are drawn: the belief's support
        idx = np.argpartition(-S, top - 1)[:top] if top < len(S) else np.arange(len(S))
        beta = tempering(np.zeros(len(idx)), S[idx], self.config.ess * n)
        logp = beta * S[idx]
        p = np.exp(logp - logp.max())
        p /= p.sum()
        j = rng.choice(len(idx), size=n, p=p)
        pick, share = idx[j], p[j]
        h, c = np.divmod(pick, len(self._free_cells))
        cells = self._free_cells[c]
        Wc = self.grid.shape[1]
        step = 2 * np.pi / len(self.headings)
        xy = self._uniform_in_free(cells // Wc, cells % Wc, rng)
        th = self.headings[h] + (rng.random(n) - 0.5) * step
        th = (th + np.pi) % (2 * np.pi) - np.pi
        # q = share / (free area of the cell * step); p0 = 1 / (area * 2 pi)
        free_area = self.free_area[cells]
        log_q_over_p0 = np.log(share) - np.log(free_area * step) + np.log(self.area * 2 * np.pi)
        return np.column_stack([xy, th]), log_q_over_p0

    def _uniform_in_free(self, rows, cols, rng) -> np.ndarray:
        """A point uniform over the free fine cells of each coarse cell (rows, cols): uniform in the coarse
        cell, drawn again where it falls in a fine cell that is not free."""
        xy = np.empty((len(rows), 2))
        todo = np.arange(len(rows))
        while len(todo):
            q = np.column_stack([cols[todo], rows[todo]]) + rng.random((len(todo), 2))
            fine = np.floor(q * self._k).astype(int)
            ok = self.fine_free[fine[:, 1], fine[:, 0]]
            xy[todo[ok]] = self.field.origin + self.cell * q[ok]
            todo = todo[~ok]
        return xy
