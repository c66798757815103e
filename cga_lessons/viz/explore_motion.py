"""An explorer for notebook 03: a screw motion's axis, angle and pitch acting on a tool, with sliders.

:class:`ScrewExplorer` holds a matplotlib figure and redraws it in place when
its parameters change (:meth:`ScrewExplorer.update`): the screw of (2.110)
built by :func:`cga_lessons.conformal.screw`, the tool moved by it at
fractions ``s`` of the motion (the screw's angle and slide times ``s``, its
one-parameter group), the screw axis and the helix the tool's tip follows.  The logic lives here and
is tested without a browser; :meth:`ScrewExplorer.widget` wraps it in
ipywidgets sliders for a live session, and the figure drawn at the default
values is what a reader sees where no kernel runs.

    >>> ex = ScrewExplorer()
    >>> ex.update(angle=90.0, pitch=0.0)
    >>> bool(abs(ex.tip_path()[-1] - ex.expected_tip()).max() < 1e-12)
    True
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons.checks import fail, instance, integer, real

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, vector
from .motions import tool_outline

__all__ = ["ScrewParams", "ScrewExplorer"]


@dataclass(frozen=True)
class ScrewParams:
    """A screw motion: axis direction by azimuth and elevation (degrees), through ``point``, turning by ``angle``
    (degrees) and sliding ``pitch`` metres per full turn; the tool is shown at ``steps`` fractions of the motion."""

    azimuth: float = 20.0
    elevation: float = 70.0
    point: tuple = (0.3, -0.2, 0.0)
    angle: float = 150.0
    pitch: float = 0.6
    steps: int = 7

    def __post_init__(self):
        for name, value in _checked("ScrewParams", vars(self)).items():
            object.__setattr__(self, name, value)

    def axis(self) -> np.ndarray:
        az, el = np.radians(self.azimuth), np.radians(self.elevation)
        return np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])

    def distance(self) -> float:
        """The slide along the axis for this angle: ``pitch`` per full turn."""
        return self.pitch * self.angle / 360.0


def _checked(func: str, values: dict) -> dict:
    """The given fields of :class:`ScrewParams` checked: angles in degrees within +-1e6, the axis point within 1e6 m,
    the pitch within +-1e3 m per turn, 1 to 100 steps."""
    out = {}
    for name, value in values.items():
        if name in ("azimuth", "elevation", "angle"):
            out[name] = real(value, func, name, low=-1e6, high=1e6)
        elif name == "pitch":
            out[name] = real(value, func, name, low=-1e3, high=1e3)
        elif name == "point":
            out[name] = tuple(float(v) for v in vector(value, func, name, (3,), limit=SQUARED, why=SQUARED_WHY))
        elif name == "steps":
            out[name] = integer(value, func, name, low=1, high=100)
        else:
            known = ", ".join(f.name for f in fields(ScrewParams))
            raise fail(func, name, f"not a parameter of the screw (one of {known})")
    return out


class ScrewExplorer:
    """The tool of :func:`~cga_lessons.viz.motions.tool_outline` moved along a screw; redrawn by :meth:`update`."""

    def __init__(self, params: ScrewParams | None = None, start=(0.9, 0.2, 0.1)):
        func = "ScrewExplorer"
        self.params = ScrewParams() if params is None else instance(params, func, "params", ScrewParams, "ScrewParams")
        self.start = cga.translator(
            vector(start, func, "start", (3,), limit=SQUARED, why=SQUARED_WHY)
        )  # the tool's first pose
        self.outline = tool_outline()
        self.fig = plt.figure(figsize=(6.5, 5.5))
        self.ax = self.fig.add_subplot(projection="3d")
        cmap = plt.get_cmap("viridis")
        self._tools = [[self.ax.plot([], [], [], color=cmap(i / max(self.params.steps - 1, 1)), lw=2)[0]
                        for _ in self.outline] for i in range(self.params.steps)]  # fmt: skip
        (self._axis_line,) = self.ax.plot([], [], [], ":", color="crimson", lw=1.5, label="screw axis")
        (self._helix,) = self.ax.plot([], [], [], "-", color="0.5", lw=1, label="path of the fingertip")
        self.ax.set_xlim(-1.2, 1.2)
        self.ax.set_ylim(-1.2, 1.2)
        self.ax.set_zlim(-0.4, 1.6)
        self.ax.set_box_aspect((1, 1, 0.85))
        self.ax.set_xlabel("x (m)")
        self.ax.set_ylabel("y (m)")
        self.ax.set_zlabel("z (m)")
        self.ax.legend(loc="upper left", fontsize=8)
        self.update()

    def motor(self, s: float = 1.0) -> cga.Multivector:
        """The screw of (2.110) run a fraction ``s`` of the way: angle ``s angle`` and slide ``s distance``."""
        s = real(s, "ScrewExplorer.motor", "s", low=-1e3, high=1e3)
        p = self.params
        angle, slide = s * np.radians(p.angle), s * p.distance()
        if abs(angle) < 1e-12:
            return cga.translator(slide * p.axis())
        return cga.screw(p.axis(), p.point, angle, slide)

    def poses(self) -> list:
        """The tool's motors at the fractions ``s = 0 .. 1`` of the screw (a one-parameter group, any angle)."""
        return [self.motor(float(v)) * self.start for v in np.linspace(0.0, 1.0, self.params.steps)]

    def tip_path(self, n: int = 60) -> np.ndarray:
        """The fingertip (the end of the longer finger) along the motion, (n, 3), n from 2 to 10000."""
        n = integer(n, "ScrewExplorer.tip_path", "n", low=2, high=10_000)
        tip = self.outline[1, 1]
        return np.array([cga.apply_to_points(self.motor(float(v)) * self.start, tip) for v in np.linspace(0, 1, n)])

    def expected_tip(self) -> np.ndarray:
        """Where the fingertip ends, by Rodrigues' rotation about the axis line plus the slide (plain NumPy)."""
        p = self.params
        n, c, th = p.axis(), np.asarray(p.point, float), np.radians(p.angle)
        K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
        R = np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K
        x = self.outline[1, 1] + cga.decompose_motor(self.start)[1]
        return R @ (x - c) + c + p.distance() * n

    def update(self, **changes) -> None:
        """Change parameters (those of :class:`ScrewParams`) and redraw the lines in place."""
        if changes:
            self.params = replace(self.params, **_checked("ScrewExplorer.update", changes))
        flat = self.outline.reshape(-1, 3)
        for lines, M in zip(self._tools, self.poses()):
            moved = cga.apply_to_points(M, flat).reshape(self.outline.shape)
            for line, (a, b) in zip(lines, moved):
                line.set_data_3d(*np.stack([a, b]).T)
        d, c = self.params.axis(), np.asarray(self.params.point, float)
        seg = np.stack([c - 1.5 * d, c + 1.5 * d])
        self._axis_line.set_data_3d(*seg.T)
        self._helix.set_data_3d(*self.tip_path().T)
        p = self.params
        self.ax.set_title(f"screw: {p.angle:.0f} deg about the axis, sliding {p.distance():.2f} m (2.110)")
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        p = self.params

        def show(azimuth, elevation, angle, pitch):
            self.update(azimuth=azimuth, elevation=elevation, angle=angle, pitch=pitch)
            return self.fig

        return slider_panel(
            show,
            azimuth=FloatSlider(value=p.azimuth, min=-180, max=180, step=5, description="azimuth"),
            elevation=FloatSlider(value=p.elevation, min=-90, max=90, step=5, description="elevation"),
            angle=FloatSlider(value=p.angle, min=-360, max=360, step=5, description="angle (deg)"),
            pitch=FloatSlider(value=p.pitch, min=-1.0, max=1.0, step=0.05, description="pitch (m)"),
        )
