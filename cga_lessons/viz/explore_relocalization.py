"""An explorer for notebook 09: the thesis's vote matrix and the ranked candidate poses as the robot moves.

:class:`RelocalizationExplorer` puts the robot at a true pose in a simulated scene
(:func:`cga_lessons.mapping2d.laser.simulate_scan`), relocalizes its scan in the scene's walls
(:func:`cga_lessons.relocalization.relocalize`) and draws four panels:

* the vote matrix ``V`` of Eq. (5.6), map lines down and scan lines across, with the thesis's picks (the column
  maxima of step 6) and the true partners of the scan lines (the map segment each lies on at the true pose);
* the map with the true pose, the scan's points and the candidate poses, best first;
* Hough space (figure 5.1, Eq. 3.3): the map's lines ``M_h`` (``rho`` from the map's origin), the scan's ``L_h``
  (``rho`` from the laser) and ``L_h`` moved by the best candidate with the corrected shift (5.4);
* the candidates' scores, ranked, with the bar of the tie rule.

Turning the robot on the spot moves every point of ``L_h`` along ``theta`` by minus the turn (section 5.1);
driving changes its ``rho``.  :meth:`~RelocalizationExplorer.update` moves the robot and redraws in place;
:meth:`~RelocalizationExplorer.widget` adds sliders.

    >>> ex = RelocalizationExplorer(pose=(3.0, 3.0, 0.5), seed=0)
    >>> ex.best_is_true, ex.votes.shape == (len(ex.M_h), len(ex.L_h))
    (True, True)
    >>> ex.update(theta_deg=60.0)
    >>> bool(ex.best_is_true and abs(ex.best_error[1]) < 0.035)
    True
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection

from cga_lessons import mapping2d
from cga_lessons.checks import degenerate, integer, real, relabel
from cga_lessons.checks import seed as as_seed
from cga_lessons.relocalization import (
    HEADING_TOLERANCE,
    POSITION_TOLERANCE,
    RelocCheck,
    hough_set,
    pose_error,
    prepare_map,
    relocalize,
    shifted_set_corrected,
    transform_points,
)

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, coords, vector
from .inputs import scene as as_scene

__all__ = ["RelocalizationExplorer", "true_partners"]


def true_partners(map_segments, scan_segments, pose, distance: float = 0.05, angle: float = np.radians(5.0)):
    """The map segment each scan segment lies on when placed at the true ``pose`` (3.4), or -1.

    A scan segment (laser frame) is moved into the map by ``pose``; its partner is the map segment parallel to
    it (within ``angle``), whose line passes within ``distance`` of its midpoint and whose extent holds the
    midpoint (the nearest such line).  Collinear pieces of a wall cut by doors share one point of Hough space:
    the extent tells them apart.

    Parameters
    ----------
    map_segments : array_like, shape (M, 2, 2)
    scan_segments : array_like, shape (L, 2, 2)
    pose : array_like, shape (3,)
        ``(x, y, theta)`` of the laser in the map.

    Returns
    -------
    ndarray of int, shape (L,)

    >>> true_partners([[[0.0, 1.0], [4.0, 1.0]], [[0.0, -1.0], [4.0, -1.0]]], [[[1.0, 0.0], [2.0, 0.0]]],
    ...               (1.0, 1.0, 0.0)).tolist()
    [0]
    """
    func = "true_partners"
    M, S = (_segments(v, func, k) for k, v in (("map_segments", map_segments), ("scan_segments", scan_segments)))
    pose = vector(pose, func, "pose", (3,), limit=SQUARED, why=SQUARED_WHY)
    distance = real(distance, func, "distance", low=0.0, strict_low=True, high=1e6)
    angle = real(angle, func, "angle", low=0.0, strict_low=True, high=np.pi / 2)
    out = np.full(len(S), -1, int)
    if not len(M) or not len(S):
        return out
    placed = transform_points(S.reshape(-1, 2), pose).reshape(-1, 2, 2)
    d_map = M[:, 1] - M[:, 0]
    length = np.hypot(d_map[:, 0], d_map[:, 1])
    u = d_map / length[:, None]
    d_scan = placed[:, 1] - placed[:, 0]
    mid = placed.mean(axis=1)
    cross = np.abs(u[None, :, 0] * d_scan[:, None, 1] - u[None, :, 1] * d_scan[:, None, 0])
    sin_gap = cross / np.hypot(d_scan[:, 0], d_scan[:, 1])[:, None]  # (L, M)
    rel = mid[:, None, :] - M[None, :, 0, :]
    along = np.einsum("lmi,mi->lm", rel, u)
    off = np.abs(rel[..., 0] * u[None, :, 1] - rel[..., 1] * u[None, :, 0])
    ok = (sin_gap < np.sin(angle)) & (off < distance) & (along >= 0) & (along <= length[None, :])
    off = np.where(ok, off, np.inf)
    best = np.argmin(off, axis=1)
    has = np.isfinite(off[np.arange(len(S)), best])
    out[has] = best[has]
    return out


def _segments(value, func: str, name: str) -> np.ndarray:
    """Segments (k, 2, 2) of non-zero length, drawable."""
    segs = coords(value, func, name, (None, 2, 2), limit=SQUARED, why=SQUARED_WHY)
    short = np.flatnonzero(np.hypot(*(segs[:, 1] - segs[:, 0]).T) == 0)
    if len(short):
        raise degenerate(func, name, f"segment {short[0]} has zero length (its two ends coincide)")
    return segs


def _triangles(poses, size: float) -> tuple[list, list]:
    """Outline triangles pointing along each pose's heading, as one NaN-separated polyline."""
    xs, ys = [], []
    for x, y, th in np.asarray(poses, float).reshape(-1, 3):
        c, s = np.cos(th), np.sin(th)
        pts = [(x + size * (c * u - s * v), y + size * (s * u + c * v)) for u, v in
               ((1.0, 0.0), (-0.45, 0.45), (-0.45, -0.45), (1.0, 0.0))]  # fmt: skip
        xs += [p[0] for p in pts] + [np.nan]
        ys += [p[1] for p in pts] + [np.nan]
    return xs, ys


class RelocalizationExplorer:
    """The thesis's votes (5.6) and the ranked candidates of :func:`~cga_lessons.relocalization.relocalize`
    for one scan from a movable true pose; redrawn by :meth:`update` (metres, heading in degrees).

    Parameters
    ----------
    scene : str or Scene
        The simulated world; its walls are the map.
    pose : array_like, shape (3,), optional
        The true pose ``(x, y, theta)`` (radians); default a pose in the office's meeting room.
    seed : int or None
        The range noise's seed, the same at every pose (None: a noise-free scan).
    n_show : int
        At most this many candidates are drawn.
    """

    def __init__(self, scene="office", pose=None, seed: int | None = 0, n_show: int = 6):
        func = "RelocalizationExplorer"
        self.scene = as_scene(scene, func)
        start = (8.0, 3.5, np.radians(30.0)) if pose is None else pose
        self.pose = vector(start, func, "pose", (3,), limit=SQUARED, why=SQUARED_WHY)
        self.seed, self.n_show = as_seed(seed, func), integer(n_show, func, "n_show", low=1, high=50)
        with relabel(func, "scene"):
            self.ref = prepare_map(self.scene.walls)
        self.params = RelocCheck()  # the check stage of relocalize: its tie bar is drawn
        self.M_h = hough_set(self.ref.segments)  # figure 5.1: rho from the map's origin
        self._build_figure()
        self.update()

    # ------------------------------------------------------------------ drawing, once

    def _build_figure(self):
        self.fig = plt.figure(figsize=(13, 8.4))
        gs = self.fig.add_gridspec(2, 3, width_ratios=[0.5, 1.1, 1.0], height_ratios=[1.25, 1.0], left=0.05,
                                   right=0.985, bottom=0.07, top=0.9, wspace=0.22, hspace=0.28)  # fmt: skip
        self.ax_votes = self.fig.add_subplot(gs[:, 0])
        self.ax_map = self.fig.add_subplot(gs[0, 1:])
        self.ax_hough = self.fig.add_subplot(gs[1, 1])
        self.ax_rank = self.fig.add_subplot(gs[1, 2])
        nM = len(self.M_h)
        self._img = self.ax_votes.imshow(np.ones((nM, 1)), aspect="auto", cmap="viridis", interpolation="nearest",
                                         origin="upper", vmin=1, vmax=2)  # fmt: skip
        self._cbar = self.fig.colorbar(self._img, ax=self.ax_votes, label="votes", location="bottom", shrink=0.9,
                                       aspect=15, pad=0.07)  # fmt: skip
        (self._picks,) = self.ax_votes.plot([], [], "x", color="tab:red", ms=7, mew=2, label="step 6: column maximum")
        (self._truth_pairs,) = self.ax_votes.plot([], [], "o", mfc="none", mec="w", ms=9, mew=1.5,
                                                  label="true partner")  # fmt: skip
        self.ax_votes.set_xlabel("scan line l_j")
        self.ax_votes.set_ylabel("map line m_i")
        self.ax_votes.legend(loc="lower left", fontsize=8, framealpha=0.9)
        ax = self.ax_map
        ax.add_collection(LineCollection(self.ref.segments, colors="0.35", linewidths=1.0))
        lo, hi = self.ref.segments.reshape(-1, 2).min(axis=0), self.ref.segments.reshape(-1, 2).max(axis=0)
        ax.set_xlim(lo[0] - 0.3, hi[0] + 0.3)
        ax.set_ylim(lo[1] - 0.3, hi[1] + 0.3)
        ax.set_aspect("equal")
        ax.set_anchor("W")  # the legend goes on the right
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        (self._scan_pts,) = ax.plot([], [], ".", color="tab:blue", ms=2.5, label="scan from the true pose", zorder=4)
        (self._placed,) = ax.plot([], [], "-", color="tab:green", lw=4, alpha=0.5, label="its lines placed at the best")
        (self._rivals,) = ax.plot([], [], "-", color="tab:orange", lw=1.5, label="other candidates")
        (self._best,) = ax.plot([], [], "-", color="tab:green", lw=2.5, label="best candidate (red if wrong)")
        (self._robot,) = ax.plot([], [], "k-", lw=1.5, label="true pose")
        self._ranks = [ax.text(0, 0, "", fontsize=9, fontweight="bold", ha="center", va="center", visible=False)
                       for _ in range(self.n_show)]  # fmt: skip
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
        ax = self.ax_hough
        ax.plot(np.degrees(self.M_h[:, 1]), self.M_h[:, 0], ".", color="0.55", ms=4, label="map M_h (from its origin)")
        (self._L_pts,) = ax.plot([], [], "o", color="tab:red", ms=5, label="scan L_h (from the laser)")
        (self._moved,) = ax.plot([], [], "o", mfc="none", mec="tab:green", ms=9, mew=1.5,
                                 label="L_h moved by the best (5.4 corrected)")  # fmt: skip
        ax.set_xlim(-12, 372)  # points at 0 stay visible
        ax.set_xticks(range(0, 361, 90))
        ax.set_ylim(0, self.M_h[:, 0].max() * 1.05)
        ax.set_xlabel("theta (degrees)")
        ax.set_ylabel("rho (m)")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper left", fontsize=7, framealpha=0.9)
        ax.set_title("Hough space (figure 5.1, 3.3): moved by the best,\nthe scan's lines land on the map's",
                     fontsize=10)  # fmt: skip
        ax = self.ax_rank
        self._bars = ax.bar(np.arange(1, self.n_show + 1), np.zeros(self.n_show), color="0.6")
        self._bar_text = [ax.text(k + 1, 0, "", ha="center", va="bottom", fontsize=8) for k in range(self.n_show)]
        self._tie = ax.axhline(np.nan, color="k", ls="--", lw=1, label="tie bar: ambiguous above")
        ax.set_xticks(np.arange(1, self.n_show + 1))
        ax.set_xlabel("rank (labels: metres from the true pose)")
        ax.set_ylabel("score")
        ax.set_ylim(0, 1.25)
        ax.axhline(0.0, color="k", lw=0.8)
        ax.legend(loc="upper right", fontsize=8)

    # ------------------------------------------------------------------ the computation

    def _relocalize(self):
        """Scan from the true pose (same noise at every pose), relocalize, and read the thesis's votes."""
        rng = None if self.seed is None else np.random.default_rng(self.seed)
        self.scan = mapping2d.simulate_scan(self.scene, self.pose, rng)
        self.result = r = relocalize(self.ref, scan=self.scan)
        self.scan_segments = r.scan_segments
        self.L_h = hough_set(r.scan_segments) if len(r.scan_segments) else np.zeros((0, 2))  # rho from the laser
        self.votes = r.votes  # (5.1)-(5.6): |M| x |L|
        self.thesis_C = r.thesis_correspondences  # step 6: map line -> scan line, -1 for none
        self.partners = true_partners(self.ref.segments, r.scan_segments, self.pose)
        shown = r.candidates[: self.n_show]
        self.candidates = np.array([c.pose for c in shown]).reshape(-1, 3)
        self.scores = np.array([c.score for c in shown])
        self.errors = np.array([pose_error(p, self.pose) for p in self.candidates]).reshape(-1, 2)
        self.right = (self.errors[:, 0] < POSITION_TOLERANCE) & (self.errors[:, 1] < HEADING_TOLERANCE)
        self.best_error = tuple(self.errors[0]) if len(self.errors) else (np.inf, np.inf)
        self.best_is_true = bool(len(self.right) and self.right[0])
        if len(self.candidates):
            best = self.candidates[0]
            self.moved = shifted_set_corrected(self.L_h, best[2], best[:2])  # (5.4) corrected
        else:
            self.moved = np.zeros((0, 2))
        picks = np.flatnonzero(self.thesis_C >= 0)
        self.thesis_right = int(np.sum(self.partners[self.thesis_C[picks]] == picks))

    def summary(self) -> str:
        """One sentence on the result: the status, the best candidate's error and the thesis's picks."""
        r = self.result
        if not len(self.candidates):
            return f"{len(self.L_h)} scan lines: {r.status} ({r.message})"
        e, n = self.best_error, len(r.candidates)
        found = "the true pose" if self.best_is_true else "not the true pose"
        return (f"{len(self.L_h)} scan lines, status {r.status}: the best of {n} candidate{'s' if n != 1 else ''} "
                f"is {e[0]:.2f} m and {np.degrees(e[1]):.1f} deg from the true pose ({found}); the thesis's column "
                f"maxima pick the true partner for {self.thesis_right} of {int(np.sum(self.thesis_C >= 0))} scan "
                "lines")  # fmt: skip

    # ------------------------------------------------------------------ redrawing

    def update(self, x: float | None = None, y: float | None = None, theta_deg: float | None = None) -> None:
        """Move the true pose (metres, heading in degrees), rescan with the same noise, relocalize and redraw."""
        given = {
            k: real(v, "RelocalizationExplorer.update", k, low=-1e6, high=1e6)
            for k, v in (("x", x), ("y", y), ("theta_deg", theta_deg))
            if v is not None
        }  # all checked first
        if "x" in given:
            self.pose[0] = given["x"]
        if "y" in given:
            self.pose[1] = given["y"]
        if "theta_deg" in given:
            self.pose[2] = float(mapping2d.wrap_angle(np.radians(given["theta_deg"])))
        self._relocalize()
        self._draw_votes()
        self._draw_map()
        self._draw_hough()
        self._draw_ranking()
        self.fig.suptitle(f"true pose ({self.pose[0]:.1f}, {self.pose[1]:.1f}) m, heading "
                          f"{np.degrees(self.pose[2]):.0f} deg: {self.result.status}", fontsize=12)  # fmt: skip
        self.fig.canvas.draw_idle()

    def _draw_votes(self):
        V = self.votes
        nM, nL = V.shape
        self._img.set_data(V if nL else np.full((nM, 1), np.nan))
        self._img.set_extent((-0.5, max(nL, 1) - 0.5, nM - 0.5, -0.5))
        top = max(2, int(V.max()) if V.size else 2)
        self._img.set_clim(1, top)
        self._cbar.update_normal(self._img)
        self.ax_votes.set_xlim(-0.5, max(nL, 1) - 0.5)
        self.ax_votes.set_ylim(nM - 0.5, -0.5)
        self.ax_votes.set_xticks(np.arange(nL))
        picks = np.flatnonzero(self.thesis_C >= 0)
        self._picks.set_data(self.thesis_C[picks], picks)
        j = np.flatnonzero(self.partners >= 0)
        self._truth_pairs.set_data(j, self.partners[j])
        self.ax_votes.set_title(f"votes V (5.6): {nM} x {nL}\nstep 6 picks {self.thesis_right} of {len(picks)} right",
                                fontsize=10)  # fmt: skip

    def _draw_map(self):
        pts, _ = mapping2d.scan_points(*self.scan)
        world = transform_points(pts, self.pose) if len(pts) else np.zeros((0, 2))
        self._scan_pts.set_data(world[:, 0], world[:, 1])
        self._robot.set_data(*_triangles(self.pose, 0.45))
        colour = "tab:green" if self.best_is_true else "tab:red"
        self._best.set_color(colour)
        self._placed.set_color(colour)
        self._best.set_data(*_triangles(self.candidates[:1], 0.6))
        self._rivals.set_data(*_triangles(self.candidates[1:], 0.45))
        xs, ys = [], []
        if len(self.candidates):
            placed = transform_points(self.scan_segments.reshape(-1, 2), self.candidates[0]).reshape(-1, 2, 2)
            for a, b in placed:
                xs += [a[0], b[0], np.nan]
                ys += [a[1], b[1], np.nan]
        self._placed.set_data(xs, ys)
        for k, txt in enumerate(self._ranks):
            if k < len(self.candidates):
                x, y, th = self.candidates[k]
                txt.set_position((x - 0.8 * np.cos(th), y - 0.8 * np.sin(th)))
                txt.set_text(str(k + 1))
                txt.set_color(colour if k == 0 else "tab:orange")
            txt.set_visible(k < len(self.candidates))
        e = self.best_error
        verdict = "the true pose" if self.best_is_true else "NOT the true pose"
        self.ax_map.set_title(f"candidates (numbered by rank); the best is {e[0]:.2f} m, {np.degrees(e[1]):.1f} deg "
                              f"from the true pose: {verdict}", fontsize=10)  # fmt: skip

    def _draw_hough(self):
        self._L_pts.set_data(np.degrees(self.L_h[:, 1]), self.L_h[:, 0])
        self._moved.set_data(np.degrees(self.moved[:, 1]), self.moved[:, 0])
        self._moved.set_markeredgecolor("tab:green" if self.best_is_true else "tab:red")

    def _draw_ranking(self):
        n = len(self.scores)
        for k, (bar, txt) in enumerate(zip(self._bars, self._bar_text)):
            h = self.scores[k] if k < n else 0.0
            bar.set_height(h)
            bar.set_color(("tab:green" if self.right[k] else "0.6") if k < n else "0.6")
            txt.set_position((k + 1, max(h, 0.0) + 0.01))
            txt.set_text(f"{self.errors[k, 0]:.1f}" if k < n else "")
        tie = self.params.ambiguity_ratio * self.scores[0] if n else np.nan
        self._tie.set_ydata([tie, tie])
        self.ax_rank.set_ylim(min(0.0, *self.scores) - 0.05 if n else 0.0, 1.25)  # a score < 0: walls crossed
        m = len(self.result.candidates)
        self.ax_rank.set_title(f"{m} candidate{'s' if m != 1 else ''} ranked by score (green: the true pose)",
                               fontsize=10)  # fmt: skip

    def widget(self):
        """ipywidgets sliders for the true pose, bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        lo, hi = self.ref.segments.reshape(-1, 2).min(axis=0), self.ref.segments.reshape(-1, 2).max(axis=0)
        x0, y0, th0 = self.pose

        def show(x, y, theta_deg):
            self.update(x=x, y=y, theta_deg=theta_deg)
            return self.fig

        return slider_panel(
            show,
            x=FloatSlider(value=x0, min=float(lo[0]), max=float(hi[0]), step=0.1, description="x (m)"),
            y=FloatSlider(value=y0, min=float(lo[1]), max=float(hi[1]), step=0.1, description="y (m)"),
            theta_deg=FloatSlider(value=float(np.degrees(th0)), min=-180, max=180, step=5, description="heading"),
        )
