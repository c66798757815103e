"""An explorer for notebook 08: the robot's five degrees of freedom in the fused 3D map.

:class:`RobotExplorer` draws the fused map once (:func:`cga_lessons.viz.map3d.plot_fused_map`) and the robot on
it (:func:`cga_lessons.viz.map3d.robot_primitives`: every pose read off a motor of the chains), with the left
camera's line of sight, twice: in the room, and close up from the robot's front right (turning with it), where the
pan and the tilt can be seen.  :meth:`update` changes some degrees of freedom through
:meth:`cga_lessons.map3d.robot.Robot.update`, which recomputes only the motors they enter (their names are the
close-up's title), and moves the robot's artists in place; :meth:`widget` adds sliders.  Given a meshcat viewer
(``vis``), the robot moves there as well.

    >>> import numpy as np
    >>> from cga_lessons.map3d import build_fused_map
    >>> from cga_lessons.map3d.tour import simulate_tour
    >>> tour = simulate_tour(np.random.default_rng(3), waypoints=((1.5, 1.5), (4.0, 1.5)), stops=(5,),
    ...                      pans=(0.4,), tilts=(0.3,))
    >>> ex = RobotExplorer(build_fused_map(tour))
    >>> ex.update(pan=0.5)
    ('R_pan', 'R_pt', 'T_opt', 'M_mpt', 'M_eu', 'R_Lpan', 'M_eu_lines')
"""

from __future__ import annotations

import textwrap

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from cga_lessons.algebra import InvalidInputError
from cga_lessons.checks import fail, instance, real
from cga_lessons.map3d import DOFS, FusedMap, Robot, RobotState

from .controls import slider_panel
from .map3d import plot_fused_map, robot_primitives
from .scene3d import FRAME_COLORS, Box, Cylinder, Frame
from .scene3d_matplotlib import box_faces, cylinder_grid

__all__ = ["RobotExplorer"]

_SIGHT = (0.85, 0.1, 0.55)  # the line of sight, magenta: no object of the map has this colour


def _faces(p) -> list:
    """The polygons of a solid of :func:`robot_primitives` (a box, or a cylinder's side and both caps)."""
    if isinstance(p, Box):
        return box_faces(p.corners())
    if not isinstance(p, Cylinder):
        raise InvalidInputError(f"RobotExplorer: cannot draw a {type(p).__name__} of the robot as a solid")
    grid = np.stack(cylinder_grid(p), axis=-1)  # (2, n + 1, 3): the rings at both ends, first point repeated
    sides = [np.array([grid[0, k], grid[0, k + 1], grid[1, k + 1], grid[1, k]]) for k in range(grid.shape[1] - 1)]
    return sides + [grid[0, :-1], grid[1, :-1]]


class RobotExplorer:
    """The fused map with the robot at a state you choose: five degrees of freedom, the robot redrawn in place.

    Parameters
    ----------
    fused : FusedMap
    robot : Robot, optional
        Moved by :meth:`update` (default: a robot of the tour's geometry).
    state : RobotState, optional
        The first state (default: the first corrected pose, head straight ahead).
    sight : float
        Length (m) of the drawn line of sight along the left camera's optical axis (its +x); it stops
        sooner where it meets the floor.
    vis : meshcat Visualizer, optional
        A viewer (:func:`cga_lessons.viz.meshcat_server.open_viewer`) in which the robot moves too.
    """

    def __init__(self, fused: FusedMap, robot: Robot | None = None, state: RobotState | None = None, *,
                 sight: float = 2.0, vis=None):  # fmt: skip
        func = "RobotExplorer"
        instance(fused, func, "fused", FusedMap, "a FusedMap (map3d.build_fused_map)")
        if robot is not None:
            instance(robot, func, "robot", Robot, "a Robot")
        if state is not None:
            instance(state, func, "state", RobotState, "a RobotState")
        sight = real(sight, func, "sight", low=0.0, strict_low=True, high=1e3)
        if vis is not None:
            from .meshcat_scene import Visualizer

            instance(vis, func, "vis", Visualizer, "a meshcat Visualizer (open_viewer()) or None")
        self.fused, self.sight, self.vis = fused, sight, vis
        self.robot = robot or Robot(fused.tour.geometry)
        try:
            self.recomputed = self.robot.set_state(state or RobotState(*fused.laser.poses[0]))
        except InvalidInputError as exc:
            raise fail(func, "state", str(exc)) from None
        self.fig = plt.figure(figsize=(12, 5.4))
        self.ax_room = self.fig.add_subplot(1, 2, 1, projection="3d")
        self.ax_close = self.fig.add_subplot(1, 2, 2, projection="3d")
        plot_fused_map(fused, self.ax_room, elev=48.0, azim=-62.0)
        self.ax_close.computed_zorder = False  # list order, as in the room: the body first, the sensors on top
        self.ax_close.set_box_aspect((1, 1, 1))
        self.ax_close.xaxis.set_major_locator(MaxNLocator(4))
        self.ax_close.yaxis.set_major_locator(MaxNLocator(4))
        self.fig.subplots_adjust(left=0.0, right=0.98, bottom=0.03, top=0.9, wspace=0.02)
        for a, label in zip((self.ax_close.set_xlabel, self.ax_close.set_ylabel, self.ax_close.set_zlabel), "xyz"):
            a(f"{label} (m)")
        self._artists = [self._add_robot(ax) for ax in (self.ax_room, self.ax_close)]
        self._redraw()

    # -- drawing
    def _add_robot(self, ax) -> dict:
        """Artists of the robot on ``ax``, by primitive name; their data is set by :meth:`_redraw`."""
        out = {}
        for p in robot_primitives(self.robot):
            if isinstance(p, Frame):
                out[p.name] = [ax.plot([], [], [], color=c, lw=1.5)[0] for c in FRAME_COLORS]
            else:
                out[p.name] = Poly3DCollection(_faces(p), facecolors=p.color, alpha=p.opacity, edgecolors="0.25",
                                               linewidths=0.3)  # fmt: skip
                # no autoscaling: the limits are set here, and matplotlib would read a ragged collection's padding
                ax.add_collection3d(out[p.name], autolim=False)
        out["sight"] = ax.plot([], [], [], color=_SIGHT, lw=2.0)[0]
        out["camera"] = ax.plot([], [], [], "o", color=_SIGHT, ms=4)[0]
        return out

    def _redraw(self) -> None:
        prims = robot_primitives(self.robot)  # at the robot's current state: read off its motors
        eye, end = self.camera_position, self.sight_end
        for artists in self._artists:
            for p in prims:
                if isinstance(p, Frame):
                    for line, seg in zip(artists[p.name], p.axes()):
                        line.set_data_3d(*seg.T)
                else:
                    artists[p.name].set_verts(_faces(p))
            artists["sight"].set_data_3d(*np.array([eye, end]).T)
            artists["camera"].set_data_3d([eye[0]], [eye[1]], [eye[2]])
        s = self.robot.state
        x, y = s.x, s.y
        self.ax_close.set_xlim(x - 0.9, x + 0.9)
        self.ax_close.set_ylim(y - 0.9, y + 0.9)
        self.ax_close.set_zlim(0.0, 1.8)
        self.ax_close.view_init(elev=18.0, azim=np.degrees(s.theta) - 50.0)  # from the robot's front right
        self.ax_room.set_title(f"x {s.x:.2f} m, y {s.y:.2f} m, heading {s.theta:.2f} rad, "
                               f"pan {s.pan:.2f} rad, tilt {s.tilt:.2f} rad", fontsize=10)  # fmt: skip
        names = ", ".join(self.recomputed) or "nothing"
        self.ax_close.set_title(textwrap.fill(f"recomputed: {names}", 60), fontsize=10)
        if self.vis is not None:
            from .meshcat_scene import show

            show(self.vis, prims)
        self.fig.canvas.draw_idle()

    # -- the state
    @property
    def state(self) -> RobotState:
        return self.robot.state

    @property
    def camera_position(self) -> np.ndarray:
        """The left camera's centre in the world (m), from the stereo chain's motor ``M_eu`` (4.9)."""
        return self.robot.frames().camera_left[:3, 3]

    @property
    def sight_direction(self) -> np.ndarray:
        """Where the left camera looks: its +x axis in the world (a unit vector)."""
        return self.robot.frames().camera_left[:3, 0]

    @property
    def sight_end(self) -> np.ndarray:
        """The far end of the drawn line of sight: ``sight`` metres ahead of the camera, or the floor if nearer."""
        eye, look = self.camera_position, self.sight_direction
        reach = self.sight if look[2] >= 0 else min(self.sight, eye[2] / -look[2])
        return eye + reach * look

    def update(self, x: float | None = None, y: float | None = None, theta: float | None = None,
               pan: float | None = None, tilt: float | None = None) -> tuple:  # fmt: skip
        """Change the given degrees of freedom (m, rad), redraw the robot in place; return the recomputed motors.

        Raises the robot's ``InvalidInputError`` (a ``ValueError``) for a pan or tilt outside its joint range
        or a value that is not a finite number, and leaves the robot where it was.
        """
        func = "RobotExplorer.update"
        g = self.robot.geometry
        limits = {"pan": g.pan_limits, "tilt": g.tilt_limits}  # the joints' ranges (rad); the rest within 1e6
        given = {k: real(v, func, k, low=limits.get(k, (-1e6,))[0], high=limits.get(k, (0, 1e6))[1])
                 for k, v in zip(DOFS, (x, y, theta, pan, tilt)) if v is not None}  # fmt: skip
        try:
            self.recomputed = self.robot.update(**given)
        except InvalidInputError as exc:
            raise fail(func, ", ".join(given), str(exc)) from None
        self._redraw()
        return self.recomputed

    def widget(self):
        """ipywidgets sliders for the five degrees of freedom, bound to :meth:`update` (a live session)."""
        from ipywidgets import FloatSlider

        g, s = self.robot.geometry, self.robot.state
        walls = np.vstack(self.fused.tour.world.walls)
        lo, hi = walls.min(axis=0), walls.max(axis=0)

        def slider(name, value, a, b, step):
            return FloatSlider(value=min(max(value, a), b), min=a, max=b, step=step, description=name,
                               continuous_update=False)  # fmt: skip

        def show(x, y, theta, pan, tilt):
            self.update(x=x, y=y, theta=theta, pan=pan, tilt=tilt)
            return self.fig

        return slider_panel(
            show,
            x=slider("x (m)", s.x, lo[0], hi[0], 0.05),
            y=slider("y (m)", s.y, lo[1], hi[1], 0.05),
            theta=slider("theta (rad)", s.theta, -np.pi, np.pi, 0.02),
            pan=slider("pan (rad)", s.pan, *g.pan_limits, 0.02),
            tilt=slider("tilt (rad)", s.tilt, *g.tilt_limits, 0.02),
        )
