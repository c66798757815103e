"""What the last scans say of a pose the particle filter never held: the prior weight of new particles.

A particle filter that takes in new particles (chapter 5's answers, random
draws after a kidnapping) must weigh them against the ones it has.  Weighed by
the newest scan alone, a newcomer wins whenever that one scan fits it better:
in a corridor, or where the map has a hole, a wrong place often does, and the
filter jumps there, though the scans before ruled it out.  The old particles
carry those scans in their number; a newcomer has not lived through them.

:class:`ScanHistory` remembers the last few scans (the beams the likelihood
field scores) and the odometry increments between them, and scores a pose by
the scans it would have taken, carried back through the increments (no drift
drawn: by chapter 3's drift model, 3 m of driving are good to about 4 cm and
one or two degrees).  :func:`merge` gives the newcomers their share of the weight in
proportion to how well each explains those scans against the particles kept.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import compose, invert

__all__ = ["ScanHistory", "merge", "normalise"]


def normalise(log_w) -> np.ndarray:
    """Weights from log-weights, summing to one."""
    w = np.exp(np.asarray(log_w, float) - np.max(log_w))
    return w / w.sum()


class ScanHistory:
    """The last ``length`` scans as scored beams, with the odometry increment after each.

    Parameters
    ----------
    field : LikelihoodField
        What scores a scan from poses.
    length : int
        Scans remembered (0: none; every newcomer is weighed by its share alone).
    """

    def __init__(self, field, length: int):
        self.field = field
        self.length = int(length)
        self.entries = []  # [(beams, increment after the scan or None)]

    def __len__(self):
        return len(self.entries)

    def clear(self):
        self.entries = []

    def moved(self, increment):
        """The robot moved by ``increment`` since the latest remembered scan."""
        if self.entries:
            self.entries[-1] = (self.entries[-1][0], np.asarray(increment, float))

    def add(self, beams):
        """Remember a scan (the beams :meth:`LikelihoodField.select_beams` chose of it), forgetting the oldest."""
        if self.length:
            self.entries = [*self.entries, (beams, None)][-self.length :]

    def log_likelihood(self, poses) -> np.ndarray:
        """The log-likelihood of the remembered scans from each pose (N, 3) carried back through the increments."""
        total = np.zeros(len(poses))
        back = np.asarray(poses, float)
        for beams, after in reversed(self.entries):
            if after is not None:
                back = compose(back, invert(after))
            total += self.field.log_likelihood(back, beams)[0]
        return total


def merge(history: ScanHistory, kept, log_kept, new, fraction: float, rng, sample: int = 256):
    """Particles ``kept`` (log-weights ``log_kept``) and newcomers ``new`` as one set: ``(particles, log_w)``.

    The newcomers hold ``fraction`` of the prior weight against the kept particles' ``1 - fraction``, shared
    in proportion to how well each explains the remembered scans, measured against how well the kept
    particles explain them (their mean likelihood over ``sample`` of them drawn by weight: 256, a mean good
    to a few per cent): a place the past rules out gets next to no weight, however well it fits the new scan.

    >>> from cga_lessons.relocalization.likelihood import LikelihoodField
    >>> h = ScanHistory(LikelihoodField([[[2.0, -5.0], [2.0, 5.0]]]), 3)
    >>> p, lw = merge(h, np.zeros((3, 3)), np.zeros(3), np.ones((1, 3)), 0.25, np.random.default_rng(0))
    >>> normalise(lw).round(3).tolist()  # nothing remembered: the newcomer holds its share
    [0.25, 0.25, 0.25, 0.25]
    """
    w_keep = normalise(log_kept)
    log_keep = np.log(np.maximum(w_keep, 1e-300)) + np.log(1 - fraction)
    if not len(new):
        return kept, log_keep
    log_new = np.full(len(new), np.log(fraction) - np.log(len(new)))
    if len(history):
        pick = rng.choice(len(kept), size=min(sample, len(kept)), p=w_keep)
        past_keep = history.log_likelihood(kept[pick])
        top = np.max(past_keep)
        log_new += history.log_likelihood(new) - (top + np.log(np.mean(np.exp(past_keep - top))))
    return np.concatenate([kept, new]), np.concatenate([log_keep, log_new])
