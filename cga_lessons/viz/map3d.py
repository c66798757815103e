"""The fused 3D map and the robot as scene primitives (section 4.2.3, figures 4.1, 4.5, 4.6).

:func:`robot_primitives` and :func:`map_primitives` turn the robot (at a
state) and a :class:`~cga_lessons.map3d.FusedMap` into the backend-free
primitives of :mod:`cga_lessons.viz.scene3d`, at 1:1 scale in the unified
frame: the same list feeds the matplotlib figures here and the meshcat viewer
(:mod:`cga_lessons.viz.meshcat_scene`).  Every pose comes from a motor of the
chains (:func:`cga_lessons.conformal.motor_to_matrix` of ``M_pos``, ``M_lu``,
``M_eu``), so the drawing is a picture of (4.1)-(4.9).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons.checks import flag, instance, real, relabel
from cga_lessons.map3d import FusedMap, Robot, RobotState

from .inputs import axes, optional_text, slash_path
from .inputs import figsize as fig_size
from .scene3d import Box, Cylinder, Frame, PointCloud, Polyline, Quad, Sphere, scene_bounds
from .scene3d_matplotlib import draw_matplotlib

__all__ = [
    "robot_primitives",
    "map_primitives",
    "truth_primitives",
    "plot_robot",
    "plot_fused_map",
    "plot_virtual_walls",
]

_BASE, _DARK, _LASER, _CAM = (0.25, 0.42, 0.75), (0.2, 0.2, 0.22), (0.95, 0.75, 0.1), (0.08, 0.08, 0.08)
_WALL, _LINE, _OBJ = (0.72, 0.72, 0.78), (0.85, 0.15, 0.1), (0.15, 0.65, 0.3)


def _apply(H, p):
    return H[:3, :3] @ np.asarray(p, float) + H[:3, 3]


def robot_primitives(robot: Robot, state: RobotState | None = None, *, prefix: str = "robot", frames: bool = True):
    """Geometer as simple solids: body, wheels, laser, mast, pan-tilt head and both cameras.

    ``state`` (optional) is set on ``robot`` first (only the touched motors are
    recomputed).  Poses: the body by ``M_pos`` (4.2), the laser by ``M_lu``
    (4.3), the head at the pan-tilt point turned by ``R_pt`` (4.5, 4.6, 4.8)
    and the cameras by ``M_eu`` (4.9).

    Returns
    -------
    list of scene3d primitives named ``prefix/...``
    """
    func = "robot_primitives"
    _robot(robot, state, func)
    prefix, frames = slash_path(prefix, func, "prefix"), flag(frames, func, "frames")
    return _robot_primitives(robot, prefix, frames)


def _robot(robot, state, func: str) -> None:
    """Check the robot and put it at ``state`` (if given)."""
    instance(robot, func, "robot", Robot, "a Robot")
    if state is not None:
        instance(state, func, "state", RobotState, "a RobotState or None")
        with relabel(func, "state"):
            robot.set_state(state)


def _robot_primitives(robot: Robot, prefix: str, frames: bool) -> list:
    g = robot.geometry
    F = robot.frames()
    Hb, Hl, Hh, Hc = F.base, F.laser, F.head, F.camera_left
    L, W, Hgt = g.base_size
    z0 = g.base_clearance
    R = Hb[:3, :3]
    out = []
    r_wheel = max(z0 + 0.03, 0.05)
    for side, s in (("left", 1), ("right", -1)):
        c = [0.0, s * (W / 2 + 0.03), r_wheel]
        out.append(Cylinder(f"{prefix}/wheel_{side}", _apply(Hb, np.add(c, [0, -0.02, 0])),
                            _apply(Hb, np.add(c, [0, 0.02, 0])), r_wheel, _DARK))  # fmt: skip
    out.append(Box(f"{prefix}/base", _apply(Hb, [0.0, 0.0, z0 + Hgt / 2]), (L, W, Hgt), R, _BASE, 0.85))
    out.append(Box(f"{prefix}/laser", _apply(Hl, [-0.01, 0.0, -0.02]), (0.10, 0.11, 0.10), Hl[:3, :3], _LASER))
    top = z0 + Hgt
    eje_base = robot.eje_point
    out.append(Cylinder(f"{prefix}/mast", _apply(Hb, [eje_base[0], eje_base[1], top]),
                        _apply(Hb, [eje_base[0], eje_base[1], eje_base[2] - 0.06]), 0.025, _DARK))  # fmt: skip
    out.append(Box(f"{prefix}/pan_tilt", Hh[:3, 3], (0.08, 0.10, 0.08), Hh[:3, :3], _DARK))
    b = g.baseline
    out.append(
        Box(f"{prefix}/stereo_bar", _apply(Hc, [-0.01, -b / 2, 0.0]), (0.03, b + 0.06, 0.025), Hc[:3, :3], _DARK)
    )
    for side, y in (("left", 0.0), ("right", -b)):
        out.append(Box(f"{prefix}/camera_{side}", _apply(Hc, [0.02, y, 0.0]), (0.05, 0.04, 0.04), Hc[:3, :3], _CAM))
    if frames:
        out += [Frame(f"{prefix}/frames/{k}", H, 0.25) for k, H in (("base", Hb), ("laser", Hl), ("camera_left", Hc))]
    return out


def map_primitives(fused: FusedMap, *, virtual_walls: bool = True, scans: bool = False, path: bool = True,
                   points: bool = False, prefix: str = "map"):  # fmt: skip
    """The fused map as primitives: virtual walls (or only the laser lines), posts, stereo entities, the path.

    Parameters
    ----------
    fused : FusedMap
    virtual_walls : bool
        Draw each laser line as a wall of the map's ``wall_height`` (figure
        4.6); otherwise only the lines at the laser's height (figure 4.5, left).
    scans : bool
        Also draw every scan's segments as sent by (4.4) (thin lines).
    path : bool
        The robot's corrected path on the floor.
    points : bool
        Also the triangulated stereo points of each object (unified frame).
    """
    func = "map_primitives"
    instance(fused, func, "fused", FusedMap, "a FusedMap (map3d.build_fused_map)")
    options = [flag(v, func, k) for k, v in (("virtual_walls", virtual_walls), ("scans", scans), ("path", path),
                                             ("points", points))]  # fmt: skip
    return _map_primitives(fused, *options, slash_path(prefix, func, "prefix"))


def _map_primitives(fused: FusedMap, virtual_walls: bool, scans: bool, path: bool, points: bool, prefix: str):
    out = []
    for k, w in enumerate(fused.virtual_walls):
        out.append(Polyline(f"{prefix}/laser_lines/{k}", np.array([w.start, w.end]), _LINE, 3.0))
        if virtual_walls:
            out.append(Quad(f"{prefix}/walls/{k}", w.corners, _WALL, 0.55))
    if scans:
        for k, segs in enumerate(fused.scan_segments):
            for j, s in enumerate(segs):
                out.append(Polyline(f"{prefix}/scans/{k}_{j}", s, (0.95, 0.55, 0.5), 1.0))
    for k, gp in enumerate(fused.laser_post_groups):
        c = gp.center
        out.append(
            Cylinder(f"{prefix}/laser_posts/{k}", c - [0, 0, 0.02], c + [0, 0, 0.02], fused.post_radius * 1.6, _LINE)
        )
    for name, obj in fused.objects.items():
        p, nm = obj.params, f"{prefix}/objects/{name}"
        if obj.kind == "sphere":
            out.append(Sphere(nm, p.center, p.radius, _OBJ))
        elif obj.kind == "plane":
            out.append(Quad(nm, obj.corners, (0.35, 0.55, 0.9), 0.9))
        elif obj.kind == "circle":
            n = p.normal * 0.012
            out.append(Cylinder(nm, p.center - n, p.center + n, p.radius, (0.95, 0.55, 0.1)))
        elif obj.kind == "line":
            out.append(Cylinder(nm, obj.ends[0], obj.ends[1], fused.post_radius, (0.55, 0.35, 0.2)))
        if points:
            out.append(PointCloud(f"{prefix}/points/{name}", obj.points, (0.1, 0.3, 0.9), 0.01))
    if path:
        poses = fused.laser.poses
        out.append(
            Polyline(f"{prefix}/path", np.column_stack([poses[:, :2], np.full(len(poses), 0.01)]), (0.2, 0.2, 0.9), 1.5)
        )
    return out


def truth_primitives(fused: FusedMap, prefix: str = "truth"):
    """The true objects as faint wireframes (for comparison; not something the robot knows)."""
    instance(fused, "truth_primitives", "fused", FusedMap, "a FusedMap (map3d.build_fused_map)")
    return _truth_primitives(fused, slash_path(prefix, "truth_primitives", "prefix"))


def _truth_primitives(fused: FusedMap, prefix: str) -> list:
    out = []
    for o in fused.tour.world.objects:
        t = o.truth()
        nm = f"{prefix}/{o.name}"
        if t.kind == "sphere":
            u = np.linspace(0, 2 * np.pi, 33)
            ring = np.column_stack([np.cos(u), np.sin(u), np.zeros_like(u)])
            out.append(Polyline(nm, t.center + t.radius * ring, (0, 0, 0), 1.0))
        elif t.kind in ("plane",):
            out.append(Polyline(nm, np.vstack([t.corners, t.corners[:1]]), (0, 0, 0), 1.0))
        elif t.kind == "circle":
            u = np.linspace(0, 2 * np.pi, 33)
            out.append(Polyline(nm, t.center + t.radius * np.column_stack([np.cos(u), np.sin(u), 0 * u]),
                                (0, 0, 0), 1.0))  # fmt: skip
        elif t.kind == "line":
            out.append(Polyline(nm, t.ends, (0, 0, 0), 1.0))
        elif t.kind == "box":
            out.append(Box(nm, t.center, t.size, np.eye(3), (0.6, 0.5, 0.4), 0.35))
    return out


def plot_fused_map(fused: FusedMap, ax=None, *, robot: Robot | None = None, state: RobotState | None = None,
                   virtual_walls: bool = True, truth: bool = False, elev: float = 38.0, azim: float = -62.0,
                   title: str | None = None):  # fmt: skip
    """The fused map in a matplotlib 3D axis (equal scale), optionally with the robot and the truth."""
    func = "plot_fused_map"
    instance(fused, func, "fused", FusedMap, "a FusedMap (map3d.build_fused_map)")
    virtual_walls, truth = flag(virtual_walls, func, "virtual_walls"), flag(truth, func, "truth")
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    ax, title = axes(ax, func, three_d=True), optional_text(title, func, "title")
    if robot is not None:
        _robot(robot, state, func)
    elif state is not None:
        instance(state, func, "state", RobotState, "a RobotState or None")  # drawn only with a robot
    prims = _map_primitives(fused, virtual_walls, False, True, False, "map")
    if robot is not None:
        prims += _robot_primitives(robot, "robot", False)
    if truth:
        prims += _truth_primitives(fused, "truth")
    if ax is None:
        ax = plt.figure(figsize=(9, 6.5)).add_subplot(projection="3d")
    ax.computed_zorder = False  # draw in list order: walls, then objects, then the robot on top
    draw_matplotlib(ax, prims, pad=0.0)
    lo, hi = scene_bounds(prims)
    lo[2] = min(lo[2], 0.0)
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        set_lim(a, b)
    ax.set_box_aspect(hi - lo)  # the box's sides in proportion: one metre is the same length on every axis
    ax.set_zticks(np.arange(0.0, hi[2] + 1e-9, 1.0 if hi[2] > 1.5 else 0.5))
    ax.view_init(elev=elev, azim=azim)
    if title:
        ax.set_title(title)
    return ax


def plot_robot(robot: Robot, state: RobotState | None = None, ax=None, *, elev: float = 22.0, azim: float = -55.0):
    """Geometer alone (figure 4.1): its solids and the base, laser and camera frames (x red, y green, z blue)."""
    func = "plot_robot"
    _robot(robot, state, func)
    ax = axes(ax, func, three_d=True)
    elev, azim = real(elev, func, "elev", low=-1e6, high=1e6), real(azim, func, "azim", low=-1e6, high=1e6)
    if ax is None:
        ax = plt.figure(figsize=(5.5, 5.5)).add_subplot(projection="3d")
    ax.computed_zorder = False  # list order: the body first, the sensors on top of it
    draw_matplotlib(ax, _robot_primitives(robot, "robot", True), pad=0.02)
    ax.view_init(elev=elev, azim=azim)
    return ax


def plot_virtual_walls(fused: FusedMap, figsize=(13, 5.5)):
    """Figure 4.5: the same map without and with virtual walls."""
    instance(fused, "plot_virtual_walls", "fused", FusedMap, "a FusedMap (map3d.build_fused_map)")
    fig = plt.figure(figsize=fig_size(figsize, "plot_virtual_walls"))
    for i, (vw, title) in enumerate(((False, "laser lines only"), (True, "with virtual walls"))):
        plot_fused_map(fused, fig.add_subplot(1, 2, i + 1, projection="3d"), virtual_walls=vw, title=title)
    fig.tight_layout()
    return fig
