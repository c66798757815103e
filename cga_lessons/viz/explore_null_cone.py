"""An explorer for notebook 02: a point of the line, its stereographic image (2.48) and its conformal point (2.62).

:class:`StereographicExplorer` draws the point ``x e1``, the ray from the pole ``e+`` through it, the image on
the unit circle, and, beside it, the conformal point ``up(x) = x e1 + (x^2 - 1)/2 e+ + (x^2 + 1)/2 e-``: the
null vectors with ``X . e = -1`` of the line form the parabola ``X_- = (X_1^2 + 1)/2`` (its ``e+`` part is
``X_- - 1``), and the cell prints ``X . X = 0`` and ``X . e = -1``.  :meth:`update`
moves ``x`` and redraws in place; :meth:`widget` adds a slider for a live session.

    >>> ex = StereographicExplorer(x=2.0)
    >>> ex.image.round(6).tolist(), round(ex.null_check, 12)
    ([0.8, 0.6], 0.0)
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.checks import real

from .controls import slider_panel

__all__ = ["StereographicExplorer"]


def _x(value, func: str) -> float:
    return real(value, func, "x", low=-1e6, high=1e6)


class StereographicExplorer:
    """One point ``x e1``: its stereographic image and its conformal point; redrawn by :meth:`update`."""

    def __init__(self, x: float = 1.5):
        x = _x(x, "StereographicExplorer")
        self.fig, (self.ax, self.ax_cone) = plt.subplots(1, 2, figsize=(11, 4.6),
                                                          gridspec_kw={"width_ratios": [1.5, 1]})  # fmt: skip
        t = np.linspace(0, 2 * np.pi, 200)
        self.ax.plot(np.cos(t), np.sin(t), "k", lw=1)
        self.ax.axhline(0, color="grey", lw=0.8)
        self.ax.plot(0, 1, "ko")
        self.ax.text(0.08, 1.08, "pole e+")
        (self._ray,) = self.ax.plot([], [], color="tab:blue", lw=1)
        (self._x,) = self.ax.plot([], [], "o", color="tab:blue", label="x e1")
        (self._img,) = self.ax.plot([], [], "s", color="tab:blue", mfc="white", label="its image on the circle (2.48)")
        self.ax.set_xlim(-4.2, 4.2)
        self.ax.set_ylim(-1.3, 1.5)
        self.ax.set_aspect("equal")
        self.ax.set_xlabel("e1")
        self.ax.set_ylabel("e+")
        self.ax.legend(loc="lower right", fontsize=8)
        s = np.linspace(-4.2, 4.2, 200)
        self.ax_cone.plot(
            s, (s**2 + 1) / 2, "-", color="0.7", label="null vectors with X.e = -1: the conformal points (2.61, 2.62)"
        )
        (self._cone_pt,) = self.ax_cone.plot([], [], "o", color="tab:red", ms=8)
        self.ax_cone.set_xlim(-4.2, 4.2)
        self.ax_cone.set_ylim(0, 10)
        self.ax_cone.set_xlabel("coefficient of e1")
        self.ax_cone.set_ylabel("coefficient of e-")
        self.ax_cone.legend(loc="upper center", fontsize=8)
        self._move(x)

    def update(self, x: float) -> None:
        """Move the point to ``x e1`` (``|x| <= 1e6``) and redraw."""
        self._move(_x(x, "StereographicExplorer.update"))

    def _move(self, x: float) -> None:
        self.x = x
        X = cga.up([self.x, 0.0, 0.0])
        self.point = X
        self.image = np.array([2 * self.x / (self.x**2 + 1), (self.x**2 - 1) / (self.x**2 + 1)])  # (2.48)
        self.null_check = float((X | X).scalar())
        self.weight = float((X | cga.einf).scalar())
        far = (self.x, 0.0) if abs(self.x) >= abs(self.image[0]) else tuple(self.image)
        self._ray.set_data([0, far[0]], [1, far[1]])
        self._x.set_data([self.x], [0.0])
        self._img.set_data([self.image[0]], [self.image[1]])
        self._cone_pt.set_data([X["e1"]], [X["e-"]])
        self.ax.set_title(f"x = {self.x:.2f}: image ({self.image[0]:.3f}, {self.image[1]:.3f})")
        self.ax_cone.set_title(f"up(x) = {X['e1']:.2f} e1 + {X['e+']:.2f} e+ + {X['e-']:.2f} e-:  "
                               f"X.X = {self.null_check:.0f}, X.e = {self.weight:.0f}", fontsize=9)  # fmt: skip
        self.fig.tight_layout()
        self.fig.canvas.draw_idle()

    def widget(self):
        """An ipywidgets slider for ``x`` bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        def show(x):
            self.update(x)
            return self.fig

        return slider_panel(show, x=FloatSlider(value=self.x, min=-4, max=4, step=0.05, description="x"))
