"""An explorer for notebook 10: the cameras' heading, field of view and the obstacle's size against the nodes' labels.

:class:`NodeExplorer` runs one scenario of the second document (:func:`cga_lessons.exploration.cases.run_scenario`:
nodes seen / not seen in the field of view, occluded by the sphere, occupied by its points) and draws its x-y view
(:func:`cga_lessons.viz.exploration.plot_nodes`).  :meth:`update` changes the heading, the field of view or the
sphere's diameter and redraws; :meth:`widget` adds sliders for a live session.

    >>> ex = NodeExplorer(diameter=0.0)
    >>> wide = ex.counts["seen"]
    >>> ex.update(fov_deg=60.0)
    >>> ex.counts["seen"] < wide
    True
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import exploration
from cga_lessons.checks import real, relabel

from .controls import slider_panel
from .exploration import plot_nodes

__all__ = ["NodeExplorer"]


def _settings(func: str, heading_deg, fov_deg, diameter) -> tuple[float, float, float]:
    return (real(heading_deg, func, "heading_deg", low=-1e6, high=1e6),
            real(fov_deg, func, "fov_deg", low=0.0, strict_low=True, high=360.0),
            real(diameter, func, "diameter", low=0.0, high=1000.0))  # fmt: skip


class NodeExplorer:
    """The labelled nodes of one scenario, x-y view; redrawn by :meth:`update` (degrees and centimetres)."""

    def __init__(self, heading_deg: float = 180.0, fov_deg: float = 150.0, diameter: float = 15.0):
        self.heading_deg, self.fov_deg, self.diameter = _settings("NodeExplorer", heading_deg, fov_deg, diameter)
        self.fig, self.ax = plt.subplots(figsize=(8.2, 5.2))
        self._redraw("NodeExplorer")

    def update(self, heading_deg=None, fov_deg=None, diameter=None) -> None:
        """Change the robot's heading, the cameras' field of view or the sphere's diameter (0: no sphere); redraw.

        None leaves a setting as it is.  The heading is in degrees (within +-1e6), the field of view in (0, 360]
        degrees, the diameter in [0, 1000] cm.
        """
        func = "NodeExplorer.update"
        old = (self.heading_deg, self.fov_deg, self.diameter)
        new = (heading_deg, fov_deg, diameter)
        given = _settings(func, *(o if v is None else v for v, o in zip(new, old)))
        self.heading_deg, self.fov_deg, self.diameter = given
        self._redraw(func)

    def _redraw(self, func: str) -> None:
        changes = {"heading": np.radians(self.heading_deg), "fov": np.radians(min(self.fov_deg, 359.0))}
        if self.diameter > 0:
            changes["sphere_diameter"] = self.diameter
        else:
            changes["sphere_center"] = None
        with relabel(func, "diameter"):
            self.result = exploration.run_scenario(**changes)
        self.counts = self.result.labels.counts()
        self.ax.clear()
        plot_nodes(self.ax, self.result, "xy")
        self.ax.set_title(f"heading {self.heading_deg:.0f} deg, field of view {self.fov_deg:.0f} deg, sphere "
                          f"{self.diameter:.0f} cm\n" + ", ".join(f"{v} {k}" for k, v in self.counts.items() if v),
                          fontsize=9)  # fmt: skip
        self.fig.tight_layout()
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        def show(heading_deg, fov_deg, diameter):
            self.update(heading_deg=heading_deg, fov_deg=fov_deg, diameter=diameter)
            return self.fig

        return slider_panel(
            show,
            heading_deg=FloatSlider(value=self.heading_deg, min=0, max=360, step=5, description="heading"),
            fov_deg=FloatSlider(value=self.fov_deg, min=10, max=355, step=5, description="view (deg)"),
            diameter=FloatSlider(value=self.diameter, min=0, max=40, step=1, description="sphere (cm)"),
        )
