"""An explorer for notebook 07: the stereo rig's baseline, focal length and pixel noise against the depth error.

:class:`DepthErrorExplorer` builds a parallel head (:func:`cga_lessons.stereo.rig.stereo_head`), triangulates
noisy projections of points at several depths (A.14, :func:`cga_lessons.stereo.triangulation.triangulate`) and draws
their RMS depth error beside the first-order law ``sigma_Z = Z^2 sqrt(2) sigma / (f b)`` of a parallel rig.
:meth:`update` changes the rig or the noise and redraws in place; :meth:`widget` adds sliders for a live session.

    >>> ex = DepthErrorExplorer(seed=0)
    >>> bool(0.7 < ex.measured[-1] / ex.predicted[-1] < 1.3)  # the law holds to first order
    True
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import stereo
from cga_lessons.checks import fail, integer, real, relabel
from cga_lessons.stereo import stereo_head

from .controls import slider_panel
from .inputs import coords

__all__ = ["DepthErrorExplorer"]


def _rig(func: str, baseline, focal_px, noise_px) -> tuple[float, float, float]:
    """A baseline in [1 mm, 100 m], a focal length in [1, 1e5] px and a noise in [0, 1000] px."""
    return (real(baseline, func, "baseline", low=1e-3, high=100.0), real(focal_px, func, "focal_px", low=1.0, high=1e5),
            real(noise_px, func, "noise_px", low=0.0, high=1e3))  # fmt: skip


class DepthErrorExplorer:
    """RMS depth error of triangulated points against depth, measured and predicted; redrawn by :meth:`update`."""

    def __init__(self, baseline=0.12, focal_px=700.0, noise_px=0.5, depths=None, n_points=400, seed=0):
        func = "DepthErrorExplorer"
        self.baseline, self.focal_px, self.noise_px = _rig(func, baseline, focal_px, noise_px)
        if depths is None:
            self.depths = np.linspace(1.0, 6.0, 11)
        else:
            self.depths = coords(
                depths,
                func,
                "depths",
                (None,),
                at_least=1,
                limit=1e4,
                why="depths beyond 10 km are no stereo pair's (the error grows as z^2)",
            )
            if np.any(self.depths <= 0):
                raise fail(func, "depths", "depths must be > 0 (in front of the head)")
        self.n_points = integer(n_points, func, "n_points", low=1, high=100_000)
        self.seed = integer(seed, func, "seed", low=0)
        self.fig, self.ax = plt.subplots(figsize=(6.5, 4.2))
        (self._measured,) = self.ax.plot([], [], "o", color="tab:blue", label="triangulated (A.14), RMS")
        (self._predicted,) = self.ax.plot([], [], "-", color="0.3", label="Z^2 sqrt(2) sigma / (f b)")
        self.ax.set_xlabel("depth Z (m)")
        self.ax.set_ylabel("depth error (m)")
        self.ax.grid(alpha=0.3)
        self.ax.legend(loc="upper left", fontsize=8)
        self.update()

    def _errors(self) -> np.ndarray:
        """RMS depth error at each depth: points straight ahead of the head, both images' noise ``noise_px``."""
        rig = stereo_head(baseline=self.baseline, focal_px=self.focal_px, tilt=0.0, position=(0.0, 0.0, 0.0))
        rng = np.random.default_rng(self.seed)
        fwd, right, down = rig.R1[2], rig.R1[0], rig.R1[1]
        out = []
        for Z in self.depths:
            lateral = rng.uniform(-0.1, 0.1, (self.n_points, 2)) * Z  # a small patch in the middle of the view
            X = Z * fwd + lateral[:, :1] * right + lateral[:, 1:] * down
            x1, x2 = stereo.project(rig.P1, X), stereo.project(rig.P2, X)
            x1 = x1 + rng.normal(scale=self.noise_px, size=x1.shape)
            x2 = x2 + rng.normal(scale=self.noise_px, size=x2.shape)
            Xh = stereo.triangulate(rig.P1, rig.P2, x1, x2, method="dlt")
            out.append(np.sqrt(np.mean(((Xh - X) @ fwd) ** 2)))
        return np.array(out)

    def update(self, baseline=None, focal_px=None, noise_px=None) -> None:
        """Change the rig or the noise (None: unchanged), re-triangulate (same seed) and redraw in place."""
        func = "DepthErrorExplorer.update"
        new = [old if v is None else v for v, old in
               zip((baseline, focal_px, noise_px), (self.baseline, self.focal_px, self.noise_px))]  # fmt: skip
        self.baseline, self.focal_px, self.noise_px = _rig(func, *new)
        with relabel(func, "baseline"):
            self.measured = self._errors()
        self.predicted = self.depths**2 * np.sqrt(2.0) * self.noise_px / (self.focal_px * self.baseline)
        self._measured.set_data(self.depths, self.measured)
        zz = np.linspace(self.depths.min(), self.depths.max(), 100)
        self._predicted.set_data(zz, zz**2 * np.sqrt(2.0) * self.noise_px / (self.focal_px * self.baseline))
        self.ax.set_xlim(0, self.depths.max() * 1.05)
        self.ax.set_ylim(0, max(self.measured.max(), self.predicted.max()) * 1.15 + 1e-9)
        self.ax.set_title(f"baseline {100 * self.baseline:.0f} cm, f = {self.focal_px:.0f} px, "
                          f"noise {self.noise_px:.2f} px")  # fmt: skip
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders for the baseline, the focal length and the noise, bound to :meth:`update`."""
        from ipywidgets import FloatSlider

        def show(baseline_cm, focal_px, noise_px):
            self.update(baseline=baseline_cm / 100.0, focal_px=focal_px, noise_px=noise_px)
            return self.fig

        return slider_panel(
            show,
            baseline_cm=FloatSlider(value=100 * self.baseline, min=2, max=60, step=1, description="baseline (cm)"),
            focal_px=FloatSlider(value=self.focal_px, min=200, max=2000, step=50, description="f (px)"),
            noise_px=FloatSlider(value=self.noise_px, min=0.05, max=3.0, step=0.05, description="noise (px)"),
        )
