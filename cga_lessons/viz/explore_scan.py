"""An explorer for notebook 05: a scan's segments in the world and in Hough space as the robot drives and turns.

:class:`HoughExplorer` simulates one laser scan of a scene at a pose
(:func:`cga_lessons.mapping2d.laser.simulate_scan`), splits it into segments (3.1-3.3,
:func:`cga_lessons.mapping2d.lines.extract_segments`) and draws them twice: in the world
(moved by the pose, 3.4) and as points ``(theta, rho)`` of Hough space seen
from the robot (3.3).  Turning the robot on the spot moves the points along
``theta`` only (section 5.1), driving changes their ``rho``.  :meth:`update`
moves the robot and redraws in place; :meth:`widget` adds sliders.

    >>> ex = HoughExplorer(seed=0)
    >>> ex.update(theta_deg=ex.pose[2] * 180 / 3.141592653589793 + 30)
    >>> len(ex.hough) == len(ex.segments) > 0
    True
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import mapping2d
from cga_lessons.checks import fail, real, relabel
from cga_lessons.checks import seed as as_seed

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, vector
from .inputs import scene as as_scene
from .laser import draw_scene

__all__ = ["HoughExplorer"]


class HoughExplorer:
    """One scan of ``scene`` from a movable pose, drawn in the world and in Hough space."""

    def __init__(self, scene="office", pose=None, seed: int | None = 0, max_range: float = 5.0):
        func = "HoughExplorer"
        self.scene = as_scene(scene, func)
        if pose is None and len(self.scene.trajectory) <= 60:
            raise fail(func, "pose", f"the scene's trajectory has no pose 60 ({len(self.scene.trajectory)} poses)")
        self.pose = vector(
            self.scene.trajectory[60] if pose is None else pose, func, "pose", (3,), limit=SQUARED, why=SQUARED_WHY
        ).copy()
        self.seed = as_seed(seed, func)  # seed None: a noise-free scan
        self.max_range = real(max_range, func, "max_range", low=0.0, strict_low=True, high=1e3)
        self.fig, (self.ax_world, self.ax_hough) = plt.subplots(1, 2, figsize=(11, 4.3))
        draw_scene(self.scene, ax=self.ax_world)
        self.ax_world.set_xlim(self.pose[0] - 5.5, self.pose[0] + 5.5)
        self.ax_world.set_ylim(self.pose[1] - 4.5, self.pose[1] + 4.5)
        self.ax_world.set_aspect("equal")
        self._segs = self.ax_world.plot([], [], color="tab:red", lw=2.5)[0]
        (self._robot,) = self.ax_world.plot([], [], "k-", lw=2)
        (self._points,) = self.ax_hough.plot([], [], "o", color="tab:red", ms=6)
        self.ax_hough.set_xlim(0, 360)
        self.ax_hough.set_ylim(-self.max_range, self.max_range)
        self.ax_hough.set_xlabel("theta (degrees), seen from the robot")
        self.ax_hough.set_ylabel("rho (m)")
        self.ax_hough.grid(alpha=0.3)
        self.ax_hough.set_title("Hough space of the scan (3.3)")
        self._redraw(func)

    def update(self, x: float | None = None, y: float | None = None, theta_deg: float | None = None) -> None:
        """Move the robot (world metres, heading in degrees; None: unchanged), rescan with the same noise seed and
        redraw.  Values are checked first (finite, within +-1e6): a bad one changes nothing."""
        func = "HoughExplorer.update"
        given = {k: real(v, func, k, low=-1e6, high=1e6) for k, v in (("x", x), ("y", y), ("theta_deg", theta_deg))
                 if v is not None}  # fmt: skip
        if "x" in given:
            self.pose[0] = given["x"]
        if "y" in given:
            self.pose[1] = given["y"]
        if "theta_deg" in given:
            self.pose[2] = float(mapping2d.wrap_angle(np.radians(given["theta_deg"])))
        self._redraw(func)

    def _redraw(self, func: str) -> None:
        rng = None if self.seed is None else np.random.default_rng(self.seed)  # the same noise at every pose
        with relabel(func, "pose"):
            ranges, angles = mapping2d.simulate_scan(self.scene, self.pose, rng, max_range=self.max_range)
            self.segments = mapping2d.extract_segments(ranges, angles, max_range=self.max_range)
        self.hough = np.array([s.hough() for s in self.segments]).reshape(-1, 2)  # (rho, theta), robot frame
        world = [s.transformed(self.pose) for s in self.segments]
        xs, ys = [], []
        for s in world:
            xs += [s.start[0], s.end[0], np.nan]
            ys += [s.start[1], s.end[1], np.nan]
        self._segs.set_data(xs, ys)
        c, s_ = np.cos(self.pose[2]), np.sin(self.pose[2])
        tip, left, right = (
            self.pose[:2] + r * np.array([c * u - s_ * v, s_ * u + c * v])
            for r, (u, v) in ((1.0, (0.35, 0.0)), (1.0, (-0.15, 0.15)), (1.0, (-0.15, -0.15)))
        )
        tri = np.array([tip, left, right, tip])
        self._robot.set_data(tri[:, 0], tri[:, 1])
        self._points.set_data(np.degrees(self.hough[:, 1]), self.hough[:, 0])
        self.ax_world.set_title(f"{len(self.segments)} segments at ({self.pose[0]:.1f}, {self.pose[1]:.1f}) m, "
                                f"heading {np.degrees(self.pose[2]):.0f} deg")  # fmt: skip
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders for the robot's pose, bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        x0, y0, th0 = self.pose

        def show(x, y, theta_deg):
            self.update(x=x, y=y, theta_deg=theta_deg)
            return self.fig

        return slider_panel(
            show,
            x=FloatSlider(value=x0, min=x0 - 3, max=x0 + 3, step=0.1, description="x (m)"),
            y=FloatSlider(value=y0, min=y0 - 3, max=y0 + 3, step=0.1, description="y (m)"),
            theta_deg=FloatSlider(value=float(np.degrees(th0)), min=-180, max=180, step=5, description="heading"),
        )
