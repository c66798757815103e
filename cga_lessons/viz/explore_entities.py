"""An explorer for notebook 04: a point pair's two points read back by (2.131) as they approach each other.

:class:`PairExplorer` builds the pair ``a ^ b`` of two points ``separation``
apart around a midpoint ``distance`` from the origin, reads the points back
with :func:`cga_lessons.conformal.point_pair_endpoints` (guard off, to see the
formula's own error, and with the default guard), and draws the error of each
separation on a log-log plot with the current one marked.  :meth:`update`
changes the separation or the distance and redraws in place; :meth:`widget`
adds sliders for a live session.

    >>> ex = PairExplorer(separation=1e-2, distance=4.0)
    >>> bool(ex.result["error"] < 1e-6), ex.result["guard"]
    (True, 'accepted')
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.algebra import GeometryError

from .controls import slider_panel

__all__ = ["PairExplorer", "pair_readback"]


def pair_readback(separation: float, distance: float, direction=(0.48, 0.6, 0.64)) -> dict:
    """Build ``a ^ b`` (2.68) and read the points back (2.131): the error, and whether the default guard refuses.

    ``a`` and ``b`` lie ``separation`` apart along ``direction`` about the midpoint
    ``distance * (1, 1, 1)/sqrt(3)``.  Returns ``{"a", "b", "p1", "p2", "error", "guard"}`` with ``error`` the
    largest endpoint error (NaN when (2.131) has no real answer in floating point) and ``guard`` ``"accepted"`` or
    ``"refused"``.
    """
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    m = distance * np.ones(3) / np.sqrt(3.0)
    a, b = m - d * separation / 2, m + d * separation / 2
    pair = cga.point_pair(a, b)
    try:
        p1, p2 = cga.point_pair_endpoints(pair, min_separation=0.0)
        error = float(max(np.linalg.norm(p1 - a), np.linalg.norm(p2 - b)))
    except GeometryError:
        p1 = p2 = np.full(3, np.nan)
        error = float("nan")
    try:
        cga.point_pair_endpoints(pair)
        guard = "accepted"
    except GeometryError:
        guard = "refused"
    return {"a": a, "b": b, "p1": p1, "p2": p2, "error": error, "guard": guard}


class PairExplorer:
    """The error of (2.131) against the separation, for pairs at one distance from the origin; redrawn by update."""

    def __init__(self, separation: float = 1e-3, distance: float = 4.0, grid=None):
        self.separation, self.distance = float(separation), float(distance)
        self.grid = np.logspace(0, -10, 41) if grid is None else np.asarray(grid, float)
        self.fig, self.ax = plt.subplots(figsize=(6.5, 4.2))
        (self._curve,) = self.ax.loglog([], [], "-o", ms=3, color="tab:blue", label="worst endpoint error")
        (self._refused,) = self.ax.loglog([], [], "x", color="tab:red", ms=7, label="refused by the default guard")
        self.ax.loglog(self.grid, self.grid, ":", color="0.4", lw=1, label="error = separation")
        (self._marker,) = self.ax.loglog([], [], "o", ms=11, mfc="none", mec="k", mew=1.5, label="this pair")
        self.ax.set_xlabel("separation |a - b| (m)")
        self.ax.set_ylabel("endpoint error (m)")
        self.ax.grid(alpha=0.3, which="both")
        self.ax.legend(loc="lower left", fontsize=8)
        self.update()

    def update(self, separation: float | None = None, distance: float | None = None) -> None:
        """Change the separation and/or the distance from the origin, recompute and redraw in place."""
        if separation is not None:
            self.separation = float(separation)
        if distance is not None:
            self.distance = float(distance)
        rows = [pair_readback(s, self.distance) for s in self.grid]
        errors = np.array([r["error"] for r in rows])
        shown = np.where(np.isfinite(errors) & (errors > 0), errors, np.nan)
        self._curve.set_data(self.grid, np.maximum(shown, 1e-17))
        refused = np.array([r["guard"] == "refused" for r in rows])
        self._refused.set_data(self.grid[refused], np.maximum(np.nan_to_num(shown[refused], nan=1.0), 1e-17))
        self.result = pair_readback(self.separation, self.distance)
        err = self.result["error"]
        self._marker.set_data([self.separation], [max(err, 1e-17) if np.isfinite(err) else 1.0])
        self.ax.set_xlim(self.grid.min() / 2, self.grid.max() * 2)
        self.ax.set_ylim(1e-17, 10.0)
        what = f"error {err:.1e} m" if np.isfinite(err) else "no real answer"
        self.ax.set_title(f"(2.131) at {self.distance:g} m from the origin: separation {self.separation:.0e} m, "
                          f"{what}, {self.result['guard']}", fontsize=10)  # fmt: skip
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders (log10 of the separation, the distance) bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        def show(log10_separation, distance):
            self.update(separation=10.0**log10_separation, distance=distance)
            return self.fig

        return slider_panel(
            show,
            log10_separation=FloatSlider(value=float(np.log10(self.separation)), min=-10, max=0, step=0.25,
                                         description="log10 sep."),
            distance=FloatSlider(value=self.distance, min=0.5, max=64.0, step=0.5, description="distance (m)"),
        )  # fmt: skip
