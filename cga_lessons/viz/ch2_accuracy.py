"""The accuracy of the point-pair extraction (2.131), section 2.4.5: the experiment and its figure.

:func:`point_pair_accuracy` builds random point pairs of a given separation and reads their endpoints back;
:func:`fig_point_pair_accuracy` draws the worst error against the separation, on log-log axes.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError
from cga_lessons.checks import fail, generator, integer

from .inputs import DPI, SQUARED, SQUARED_WHY, accuracy_curves, coord, coords

__all__ = ["point_pair_accuracy", "fig_point_pair_accuracy"]


def point_pair_accuracy(separations, distance, rng, trials=20):
    """The experiment behind the accuracy figure of (2.131).

    For each separation, ``trials`` random pairs centred at ``distance`` from
    the origin (random directions) are built with ``cga.point_pair``, kept as
    their stored coefficients alone (``.plain()``: without the local frame the
    library's pairs carry, which reads them exactly) and read back twice with
    ``cga.point_pair_endpoints``: once with the guard switched
    off (``min_separation=0``) to measure the error of the formula, once with
    the default guard to see which pairs it refuses.

    Returns
    -------
    worst : array, the largest endpoint error over the trials, guard off (NaN if all raised)
    failed : array of int, how many trials raised a ``GeometryError`` with the guard off
    refused : array of int, how many trials the default guard refused
    """
    func = "point_pair_accuracy"
    separations = coords(separations, func, "separations", (None,), at_least=1, limit=SQUARED, why=SQUARED_WHY)
    if np.any(separations <= 0):
        raise fail(func, "separations", "must all be > 0 (two distinct points)")
    distance = coord(distance, func, "distance", low=0.0, limit=SQUARED)
    rng, trials = generator(rng, func), integer(trials, func, "trials", low=1, high=10**5)
    worst, failed, refused = [], [], []
    for s in separations:
        errs, bad, ref = [], 0, 0
        for _ in range(trials):
            m, d = rng.normal(size=3), rng.normal(size=3)
            m, d = distance * m / np.linalg.norm(m), d / np.linalg.norm(d)
            a, b = m - d * s / 2, m + d * s / 2
            PP = cga.point_pair(a, b).plain()  # its stored coefficients alone, without the pair's local frame
            try:
                p1, p2 = cga.point_pair_endpoints(PP, min_separation=0.0)
                errs.append(max(np.linalg.norm(p1 - a), np.linalg.norm(p2 - b)))
            except GeometryError:
                bad += 1
            try:
                cga.point_pair_endpoints(PP)
            except GeometryError:
                ref += 1
        worst.append(max(errs) if errs else np.nan)
        failed.append(bad)
        refused.append(ref)
    return np.array(worst), np.array(failed), np.array(refused)


def fig_point_pair_accuracy(separations, curves):
    """Log-log error of (2.131) against the separation of the two points.

    ``curves`` maps a label to ``(worst, failed, refused)`` from
    :func:`point_pair_accuracy`.  Crosses at the top mark separations where
    some trials raised even with the guard off; the dashed vertical line of
    each curve is the largest separation that the default guard refused.
    """
    seps, curves = accuracy_curves(separations, curves, "fig_point_pair_accuracy")
    fig, ax = plt.subplots(figsize=(8, 5.5), dpi=DPI)
    ax.loglog(seps, seps, "k:", lw=1, label="error = separation")
    colors = plt.cm.viridis(np.linspace(0, 0.85, len(curves)))
    for k, ((label, (worst, failed, refused)), color) in enumerate(zip(curves.items(), colors)):
        ok = np.isfinite(worst)
        ax.loglog(seps[ok], worst[ok], "o-", color=color, ms=4, label=label)
        bad = failed > 0
        ax.plot(seps[bad], np.full(bad.sum(), 3.0 * 0.2**k), "x", color=color, ms=7)
        if np.any(refused > 0):
            ax.axvline(seps[refused > 0].max(), color=color, ls="--", lw=1.2)
    ax.plot([], [], "kx", label="some trials raised (guard off)")
    ax.plot([], [], "k--", lw=1.2, label="default guard refuses from here leftwards")
    ax.set_xlabel("separation $|a-b|$")
    ax.set_ylabel("worst endpoint error")
    ax.set_ylim(1e-17, 10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="lower left", fontsize=9)
    ax.set_title("Accuracy of the point-pair extraction (2.131)")
    fig.tight_layout()
    return fig
