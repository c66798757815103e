"""An explorer for notebook 06: a scan placed with a wrong pose, and the correcting motor that puts it back.

:class:`CorrectionExplorer` takes one noise-free scan of a scene from the robot's true pose, as point pairs of its
segments (section 3.2.1).  The map holds the same segments placed with the true pose; the robot believes it stands at
the true pose plus an error ``(dx, dy, dtheta)``, so the laser motor (3.16-3.17) of the believed pose puts the scan's
point pairs in the wrong place (the sandwich 3.18).  :func:`conformal_correction` then finds the correction of
section 3.1.3 from the lines of the point pairs, all seen from the believed position: the heading correction (3.8)
from the angles of corresponding lines (3.5, with the Hough members 3.14, 3.15 and the direction 2.127), the rotation
about the robot applied as a motor, then the position correction (3.9-3.12) from their distances.  Together they make
the correcting motor ``C``; ``C M_believed = M_true``, so ``C`` undoes the error motor ``E = M_believed ~M_true``:
``C = ~E``, and the corrected pose is the true one (3.6-3.7).  Correspondences are known here (the scan is the map
seen from the true pose), so any error within the angle gate is undone exactly.

:meth:`CorrectionExplorer.update` changes the error and redraws in place; :meth:`CorrectionExplorer.widget` adds
sliders for a live session.

    >>> ex = CorrectionExplorer(dx=0.4, dy=-0.3, dtheta_deg=10.0)
    >>> bool(abs(ex.corrected_pose - ex.pose).max() < 1e-9), ex.correction.round(6).tolist()[:2]
    (True, [-0.4, 0.3])
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import mapping2d
from cga_lessons.algebra import Multivector, finite_multivector
from cga_lessons.checks import fail, real, relabel
from cga_lessons.mapping2d import SegmentSet, theta_correction, translation_correction

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, coord, point_pairs, vector
from .inputs import scene as as_scene
from .laser import draw_scene

__all__ = [
    "CorrectionExplorer",
    "place",
    "ends",
    "line_members",
    "rotor_about",
    "ConformalCorrection",
    "conformal_correction",
]


def place(PP: Multivector, pose) -> tuple[Multivector, Multivector]:
    """Point pairs of the laser frame put in the world by the laser motor of ``pose`` (3.17), ``M PP ~M`` (3.18)."""
    PP, pose = point_pairs(PP, "place"), vector(pose, "place", "pose", (3,), limit=SQUARED, why=SQUARED_WHY)
    with relabel("place", "pose"):
        M = mapping2d.laser_motor(pose)
    return (M * PP * ~M).grade(2), M


def ends(PP: Multivector) -> tuple[np.ndarray, np.ndarray]:
    """The two points (2.131) of each point pair, (n, 2) each."""
    return _ends(point_pairs(PP, "ends"), "ends")


def _ends(PP: Multivector, func: str) -> tuple[np.ndarray, np.ndarray]:
    with relabel(func, "PP"):
        p1, p2 = cga.point_pair_endpoints(PP)
    return np.atleast_2d(p1)[:, :2], np.atleast_2d(p2)[:, :2]


def line_members(PP: Multivector, centre) -> tuple[np.ndarray, np.ndarray]:
    """Oriented ``(rho, theta)`` of the lines ``PP ^ e`` seen from ``centre``: (3.14), (3.15) and (2.127)."""
    func = "line_members"
    return _members(
        point_pairs(PP, func), vector(centre, func, "centre", (2, 3), limit=SQUARED, why=SQUARED_WHY)[:2], func
    )


def _members(PP: Multivector, centre: np.ndarray, func: str) -> tuple[np.ndarray, np.ndarray]:
    p1, p2 = _ends(PP, func)
    segs = SegmentSet(p1, p2, np.zeros((len(p1), 6)), np.zeros((len(p1), 2), int))
    with relabel(func, "PP"):
        return mapping2d.ConformalGeometry().hough(segs, centre)


def rotor_about(centre, angle: float) -> Multivector:
    """The motor turning the plane by ``angle`` about the point ``centre``: ``T R ~T`` (2.94, 2.100)."""
    c = vector(centre, "rotor_about", "centre", (2, 3), limit=SQUARED, why=SQUARED_WHY)
    angle = real(angle, "rotor_about", "angle", low=-1e6, high=1e6)
    return _rotor_about(c, angle)


def _rotor_about(c: np.ndarray, angle: float) -> Multivector:
    return mapping2d.robot_motor([c[0], c[1], angle]) * cga.translator([-c[0], -c[1], 0.0])


@dataclass(frozen=True)
class ConformalCorrection:
    """The result of :func:`conformal_correction`.

    Attributes
    ----------
    theta : float
        The heading correction (3.8), radians.
    t : ndarray, shape (2,)
        The position correction (3.9-3.12), m.
    rotor : Multivector
        The turn by ``theta`` about the centre, ``R_centre(theta)``.
    motor : Multivector
        The whole correction ``T(t) R_centre(theta)``.
    turned, corrected : Multivector
        The scan's point pairs after the turn alone and after the whole correction (3.18).
    """

    theta: float
    t: np.ndarray
    rotor: Multivector
    motor: Multivector
    turned: Multivector
    corrected: Multivector

    def __post_init__(self):
        f = "ConformalCorrection"
        object.__setattr__(self, "theta", real(self.theta, f, "theta"))
        object.__setattr__(self, "t", vector(self.t, f, "t", (2,)))
        for name in ("rotor", "motor", "turned", "corrected"):
            finite_multivector(getattr(self, name), f, name)


def conformal_correction(
    PP_map: Multivector, PP_scan: Multivector, centre, theta_xi: float = np.radians(30)
) -> ConformalCorrection:
    """The correction of section 3.1.3 for corresponding point pairs (the i-th of each), as a motor.

    ``theta_corr`` (3.8) is the mean ``diffTheta`` (3.5, gate ``theta_xi``) of the lines seen from ``centre``; the
    scan is turned by it about ``centre``, and ``t`` (3.9-3.12) solves ``n . t = rho_G - rho_L'`` by least squares.
    Returns the motor ``T(t) R_centre(theta)`` and the scan's point pairs after the turn alone and after the whole
    correction (3.18), as a :class:`ConformalCorrection`.
    """
    func = "conformal_correction"
    PP_map, PP_scan = point_pairs(PP_map, func, "PP_map"), point_pairs(PP_scan, func, "PP_scan")
    if PP_map.shape != PP_scan.shape:
        raise fail(func, "PP_scan", f"expected as many point pairs as PP_map {PP_map.shape}, got {PP_scan.shape}")
    centre = vector(centre, func, "centre", (2, 3), limit=SQUARED, why=SQUARED_WHY)[:2]
    theta_xi = real(theta_xi, func, "theta_xi", low=0.0, strict_low=True, high=np.pi / 2)
    rho_g, th_g = _members(PP_map, centre, func)
    rho_l, th_l = _members(PP_scan, centre, func)
    with relabel(func, "PP_scan"):
        theta = theta_correction(mapping2d.diff_theta(th_g, th_l, theta_xi))  # (3.8)
    R = _rotor_about(centre, theta)
    turned = (R * PP_scan * ~R).grade(2)
    rho_l, th_l = _members(turned, centre, func)
    with relabel(func, "PP_scan"):
        t = np.asarray(translation_correction(rho_g, rho_l, th_l), float)  # (3.12)
    C = cga.translator([t[0], t[1], 0.0]) * R
    corrected = (C * PP_scan * ~C).grade(2)
    return ConformalCorrection(theta=float(theta), t=t, rotor=R, motor=C, turned=turned, corrected=corrected)


def _check(value, func: str, name: str) -> float:
    """A slider's value (a pose error, m or degrees) as a float; NaN, inf, a bool, a string or None raise
    InvalidInputError (a ValueError) naming both; an error beyond +-1000 (m or degrees) is refused."""
    return real(value, func, name, low=-1000.0, high=1000.0)


def _polyline(p1: np.ndarray, p2: np.ndarray) -> tuple[list, list]:
    xs, ys = [], []
    for a, b in zip(p1, p2):
        xs += [a[0], b[0], np.nan]
        ys += [a[1], b[1], np.nan]
    return xs, ys


def _robot(pose) -> np.ndarray:
    c, s = np.cos(pose[2]), np.sin(pose[2])
    tri = np.array([[0.3, 0.0], [-0.15, 0.15], [-0.15, -0.15], [0.3, 0.0]])
    return tri @ np.array([[c, s], [-s, c]]) + np.asarray(pose[:2])


class CorrectionExplorer:
    """A scan placed with the true pose plus an error, and its correction by a motor; redrawn by :meth:`update`.

    The error is ``dx``, ``dy`` (metres) and ``dtheta_deg`` (degrees, within the angle gate ``theta_xi_deg`` of 3.5).
    """

    def __init__(self, scene="room", pose=(3.0, 2.0, 0.3), dx: float = 0.4, dy: float = -0.3,
                 dtheta_deg: float = 10.0, max_range: float = 5.0, theta_xi_deg: float = 30.0):  # fmt: skip
        func = "CorrectionExplorer"
        self.scene, self.pose = as_scene(scene, func), vector(pose, func, "pose", (3,), limit=SQUARED, why=SQUARED_WHY)
        error = [_check(v, func, k) for k, v in (("dx", dx), ("dy", dy), ("dtheta_deg", dtheta_deg))]
        self.theta_xi_deg = real(theta_xi_deg, func, "theta_xi_deg", low=0.0, strict_low=True, high=90.0)
        if abs(error[2]) >= self.theta_xi_deg:
            raise fail(func, "dtheta_deg", f"must lie within the angle gate of (3.5), +-{self.theta_xi_deg:g} deg")
        max_range = coord(max_range, func, "max_range", low=0.0, strict_low=True, limit=SQUARED)
        with relabel(func, "pose"):
            ranges, angles = mapping2d.simulate_scan(self.scene, self.pose, None, max_range=max_range)
            self.segments = mapping2d.extract_segments(ranges, angles, max_range=max_range)  # laser frame
        if not self.segments:
            raise fail(func, "pose", f"the scan from {self.pose.tolist()} sees no segment")
        self.local = mapping2d.segment_point_pair(self.segments)  # PP* = p_i ^ p_f, section 3.2.1
        self.map, self.true_motor = place(self.local, self.pose)
        self.error = np.zeros(3)
        ratios = {"width_ratios": [1.25, 1]}
        self.fig, (self.ax, self.ax_hough) = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw=ratios)
        draw_scene(self.scene, ax=self.ax, color="0.93", edge="0.8")
        g1, g2 = ends(self.map)
        self.ax.plot(*_polyline(g1, g2), color="0.25", lw=5, alpha=0.35, solid_capstyle="butt", label="map")
        (self._placed,) = self.ax.plot([], [], "o-", color="tab:red", lw=1.8, ms=4, label="scan at the believed pose")
        (self._turned,) = self.ax.plot([], [], ":", color="tab:orange", lw=1.8, label="turned by theta_corr (3.8)")
        (self._fixed,) = self.ax.plot([], [], "--", color="tab:green", lw=1.8, label="after the correcting motor")
        self.ax.plot(*_robot(self.pose).T, "k-", lw=1.5, label="true pose")
        (self._believed,) = self.ax.plot([], [], "-", color="tab:red", lw=1.5, label="believed pose")
        self.ax.set_aspect("equal")
        self.ax.set_xlim(self.pose[0] - 4.0, self.pose[0] + 4.0)
        self.ax.set_ylim(self.pose[1] - 3.2, self.pose[1] + 3.2)
        self.ax.set_xlabel("x (m)")
        self.ax.set_ylabel("y (m)")
        self.ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, fontsize=8)
        h = self.ax_hough
        (self._h_steps,) = h.plot([], [], "-", color="0.55", lw=0.8)  # placed -> turned -> corrected
        (self._h_map,) = h.plot([], [], "o", color="0.4", ms=11, alpha=0.45, label="map")
        (self._h_placed,) = h.plot([], [], "x", color="tab:red", ms=8, mew=2, label="scan at the believed pose")
        (self._h_turned,) = h.plot([], [], "+", color="tab:orange", ms=10, mew=2, label="turned by theta_corr")
        (self._h_fixed,) = h.plot([], [], ".", color="tab:green", ms=8, label="corrected")
        h.set_xlabel("theta (degrees), seen from the believed position")
        h.set_ylabel("rho (m)")
        h.grid(alpha=0.3)
        h.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=8)
        self.update(dx=dx, dy=dy, dtheta_deg=dtheta_deg)

    def update(self, dx=None, dy=None, dtheta_deg=None) -> None:
        """Change the pose error (metres, degrees), place the scan with it, find the correction and redraw."""
        func = "CorrectionExplorer.update"
        error = self.error.copy()
        for i, (name, value) in enumerate((("dx", dx), ("dy", dy), ("dtheta_deg", dtheta_deg))):
            if value is not None:
                error[i] = _check(value, func, name)
        if abs(error[2]) >= self.theta_xi_deg:
            raise fail(func, "dtheta_deg", f"must lie within the angle gate of (3.5), +-{self.theta_xi_deg:g} deg, "
                       f"got {error[2]:g}")  # fmt: skip
        self.error = error
        err = self.error * np.array([1.0, 1.0, np.pi / 180])
        self.believed = self.pose + err
        self.placed, self.believed_motor = place(self.local, self.believed)  # (3.17), (3.18)
        self.error_motor = self.believed_motor * ~self.true_motor  # moves the map onto the misplaced scan
        centre = self.believed[:2]
        self.result = conformal_correction(self.map, self.placed, centre, np.radians(self.theta_xi_deg))
        self.correction = np.array([*self.result.t, self.result.theta])
        self.corrected_pose = self.believed + self.correction  # (3.6), (3.7)
        self.corrected_pose[2] = mapping2d.wrap_angle(self.corrected_pose[2])
        self._draw(centre)

    def _draw(self, centre) -> None:
        for line, PP in ((self._placed, self.placed), (self._turned, self.result.turned),
                         (self._fixed, self.result.corrected)):  # fmt: skip
            line.set_data(*_polyline(*ends(PP)))
        self._believed.set_data(*_robot(self.believed).T)
        hough = ((self._h_map, self.map), (self._h_placed, self.placed), (self._h_turned, self.result.turned),
                 (self._h_fixed, self.result.corrected))  # fmt: skip
        ref = np.degrees(line_members(self.map, centre)[1])
        for line, PP in hough:
            rho, theta = line_members(PP, centre)
            line.set_data(ref + np.mod(np.degrees(theta) - ref + 180.0, 360.0) - 180.0, rho)  # beside the map's line
        steps = [np.asarray(line.get_data(), float) for line in (self._h_placed, self._h_turned, self._h_fixed)]
        gap = np.full((2, len(steps[0][0])), np.nan)
        self._h_steps.set_data(*np.stack(steps + [gap], axis=-1).reshape(2, -1))
        all_theta = np.concatenate([line.get_xdata() for line in (self._h_map, self._h_placed)])
        all_rho = np.concatenate([line.get_ydata() for line in (self._h_map, self._h_placed)])
        self.ax_hough.set_xlim(all_theta.min() - 30, all_theta.max() + 30)
        self.ax_hough.set_ylim(min(all_rho.min() - 0.5, 0.0), all_rho.max() + 0.5)
        dx, dy, dth = self.error
        x, y, h = self.corrected_pose
        off = np.abs(np.r_[self.corrected_pose[:2] - self.pose[:2], mapping2d.wrap_angle(h - self.pose[2])]).max()
        self.ax.set_title(f"pose error dx {dx:+.2f} m, dy {dy:+.2f} m, dtheta {dth:+.1f} deg\n"
                          f"corrected pose ({x:.2f} m, {y:.2f} m, {np.degrees(h):.1f} deg) "
                          f"{'=' if off < 1e-9 else '!='} the true pose", fontsize=10)  # fmt: skip
        t, th = self.result.t, np.degrees(self.result.theta)
        self.ax_hough.set_title(f"theta_corr (3.8) = {th:+.1f} deg, t (3.12) = ({t[0]:+.2f}, {t[1]:+.2f}) m\n"
                                "correcting motor C = T(t) R(theta_corr) = ~E", fontsize=10)  # fmt: skip
        self.fig.tight_layout()
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders for the pose error, bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        def show(dx, dy, dtheta_deg):
            self.update(dx=dx, dy=dy, dtheta_deg=dtheta_deg)
            return self.fig

        gate = float(np.floor(self.theta_xi_deg - 1.0))
        return slider_panel(
            show,
            dx=FloatSlider(value=self.error[0], min=-1.0, max=1.0, step=0.05, description="dx (m)",
                           continuous_update=False),
            dy=FloatSlider(value=self.error[1], min=-1.0, max=1.0, step=0.05, description="dy (m)",
                           continuous_update=False),
            dtheta_deg=FloatSlider(value=self.error[2], min=-gate, max=gate, step=1.0, description="dtheta (deg)",
                                   continuous_update=False),
        )  # fmt: skip
