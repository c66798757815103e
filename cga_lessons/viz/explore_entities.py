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
from cga_lessons.algebra import DegenerateGeometryError, GeometryError
from cga_lessons.checks import fail, real

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, coords, vector

__all__ = ["PairExplorer", "pair_readback"]


def pair_readback(separation: float, distance: float, direction=(0.48, 0.6, 0.64)) -> dict:
    """Build ``a ^ b`` (2.68), keep its stored coefficients alone (without the local frame of ``cga.point_pair``)
    and read the points back (2.131): the error, and whether the default guard refuses.

    ``a`` and ``b`` lie ``separation`` apart along ``direction`` about the midpoint
    ``distance * (1, 1, 1)/sqrt(3)``.  Returns ``{"a", "b", "p1", "p2", "error", "guard"}`` with ``error`` the
    largest endpoint error (NaN when (2.131) has no real answer in floating point, or when ``a`` and ``b`` are
    the same floating-point point) and ``guard`` ``"accepted"`` or ``"refused"``.  ``separation`` lies in (0, 1e6]
    m, ``distance`` in [0, 1e6] m.
    """
    func = "pair_readback"
    separation, distance = _separation(separation, func), _distance(distance, func)
    d = vector(direction, func, "direction", (3,))
    if not np.linalg.norm(d) > 0:
        raise fail(func, "direction", "must not be the zero vector")
    return _readback(separation, distance, d / np.linalg.norm(d))


def _separation(value, func: str, name: str = "separation") -> float:
    return real(value, func, name, low=0.0, strict_low=True, high=1e6)


def _distance(value, func: str) -> float:
    return real(value, func, "distance", low=0.0, high=1e6)


def _readback(separation: float, distance: float, d: np.ndarray) -> dict:
    m = distance * np.ones(3) / np.sqrt(3.0)
    a, b = m - d * separation / 2, m + d * separation / 2
    try:
        pair = cga.point_pair(a, b).plain()  # its stored coefficients alone, without the pair's local frame
    except DegenerateGeometryError:  # a and b are one float point: no pair, no answer
        nan = np.full(3, np.nan)
        return {"a": a, "b": b, "p1": nan, "p2": nan.copy(), "error": float("nan"), "guard": "refused"}
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
        func = "PairExplorer"
        self.separation, self.distance = _separation(separation, func), _distance(distance, func)
        self.grid = (
            np.logspace(0, -10, 41)
            if grid is None
            else coords(grid, func, "grid", (None,), at_least=1, limit=SQUARED, why=SQUARED_WHY)
        )
        if np.any(self.grid <= 0):
            raise fail(func, "grid", "separations must lie in (0, 1e6] m (a log scale)")
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
        """Change the separation and/or the distance from the origin (None: unchanged), recompute and redraw."""
        func = "PairExplorer.update"
        separation = self.separation if separation is None else _separation(separation, func)
        distance = self.distance if distance is None else _distance(distance, func)
        self.separation, self.distance = separation, distance
        d = np.array([0.48, 0.6, 0.64])
        rows = [_readback(s, self.distance, d) for s in self.grid]
        errors = np.array([r["error"] for r in rows])
        shown = np.where(np.isfinite(errors) & (errors > 0), errors, np.nan)
        self._curve.set_data(self.grid, np.maximum(shown, 1e-17))
        refused = np.array([r["guard"] == "refused" for r in rows])
        self._refused.set_data(self.grid[refused], np.maximum(np.nan_to_num(shown[refused], nan=1.0), 1e-17))
        self.result = _readback(self.separation, self.distance, d)
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
