"""One 3D map fused from the laser and the stereo head through the robot's motor chains (section 4.2.3).

:func:`build_fused_map` takes what the robot recorded on a tour
(:func:`cga_lessons.map3d.tour.simulate_tour`) and

1. runs the chapter-3 map builder on the laser scans and odometry
   (:func:`cga_lessons.mapping2d.build_map`): corrected poses and a fused
   line map;
2. sends every scan's segments, as conformal point pairs in the laser's frame,
   to the unified frame with ``M_lu`` (4.3) as ``x' = M_lu x ~M_lu`` (4.4); they
   land at the laser's height;
3. turns every line of the fused map into a *virtual wall*: the vertical plane
   ``e ^ a ^ b ^ a_up`` (2.77) through the segment, drawn from the floor to a
   stated height (figures 4.5, 4.6);
4. finds the posts in each scan (short clusters of returns standing free of
   what is behind them), moves their centres with (4.4) and groups them;
5. for every stereo view, triangulates the points of each object (A.14), fits
   its conformal entity in the stereo frame (section 4.1: sphere, plane,
   circle, line) and sends the *entity itself* to the unified frame with
   ``M_eu`` (4.9) as ``x' = M_eu x ~M_eu`` (4.10), using the laser-corrected
   pose and the pan/tilt readings of that moment;
6. fuses the views of each object by refitting all its points, moved by the
   same motors; and compares laser with stereo, and both with the truth, in
   :func:`residual_table` (:mod:`cga_lessons.map3d.eval`).
"""

from __future__ import annotations

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import DegenerateGeometryError
from cga_lessons.mapping2d import MapResult, build_map, extract_segments

from .chains import to_unified
from .fits import blade_parameters, fit_entity
from .fused_map import FusedMap, FusedObject, PostGroup, StereoEntity
from .laser import group_detections, laser_posts, virtual_wall
from .motors import chain_motors
from .robot import Robot
from .state import RobotGeometry, RobotState
from .tour import Tour, triangulate_view

__all__ = ["build_fused_map", "stereo_depth_limit"]

_UP = np.array([0.0, 0.0, 1.0])

_KIND = {"Ball": "sphere", "Board": "plane", "Plate": "circle", "Post": "line"}
_MIN_POINTS = {"sphere": 20, "plane": 12, "circle": 12, "line": 8}


def stereo_depth_limit(geometry, noise_px: float, max_depth_sigma: float = 0.05) -> float:
    """Depth (m) at which a triangulated point's depth error reaches ``max_depth_sigma``.

    A disparity error of ``sqrt(2) noise_px`` pixels gives a depth error of
    ``Z^2 sqrt(2) noise_px / (f b)`` (notebook 07), so
    ``Z_max = sqrt(max_depth_sigma f b / (sqrt(2) noise_px))``: 2.44 m for
    the default head (f = 700 px, b = 0.12 m), 0.5 px and 5 cm.  Infinite
    without noise.

    >>> from cga_lessons.map3d.state import RobotGeometry
    >>> round(stereo_depth_limit(RobotGeometry(), 0.5, 0.05), 3)
    2.437
    """
    f = "stereo_depth_limit"
    checks.instance(geometry, f, "geometry", RobotGeometry, "a RobotGeometry")
    noise_px = checks.real(noise_px, f, "noise_px", low=0.0)
    max_depth_sigma = checks.real(max_depth_sigma, f, "max_depth_sigma", low=0.0, strict_low=True)
    if noise_px == 0:
        return float("inf")
    z = float(np.sqrt(max_depth_sigma * geometry.focal_px * geometry.baseline / (np.sqrt(2.0) * noise_px)))
    return checks.finite_result(z, f, "noise_px, max_depth_sigma: the depth")


def build_fused_map(
    tour: Tour,
    *,
    method: str = "plain",
    virtual_wall_height: float = 1.0,
    post_radius: float = 0.05,
    min_post_detections: int = 3,
    poses_from: str = "laser",
    max_depth_sigma: float = 0.05,
    laser: MapResult | None = None,
) -> FusedMap:
    """Build the fused 3D map of a tour (steps 1-6 of the module docstring).

    Parameters
    ----------
    tour : Tour
    method : {"plain", "conformal"}
        Chapter 3's map builder (both give the same map; "plain" is faster).
    virtual_wall_height : float
        Height (m) to which laser lines are drawn as walls.
    post_radius : float
        Radius (m) of the posts the laser looks for (a known catalogue size).
    min_post_detections : int
        Scans that must agree on a post before the laser reports it.
    max_depth_sigma : float
        Stereo points are used up to the depth where a point's predicted depth
        error reaches this (m): :func:`stereo_depth_limit`.
    poses_from : {"laser", "truth", "odometry"}
        Which robot poses drive the chains: chapter 3's corrected poses (the
        map as the robot builds it), the true poses (to isolate the sensors'
        own errors) or the raw odometry (to see what the correction buys).
        The laser's line map (and so the virtual walls) always comes from
        chapter 3's corrected poses.
    laser : MapResult, optional
        A chapter-3 result of this tour to reuse (e.g. ``other.laser``) instead
        of building it again.
    """
    f = "build_fused_map"
    checks.instance(tour, f, "tour", Tour, "a Tour (simulate_tour)")
    method = checks.choice(method, f, "method", ("plain", "conformal"))
    virtual_wall_height = checks.real(virtual_wall_height, f, "virtual_wall_height", low=0.0, strict_low=True)
    post_radius = checks.real(post_radius, f, "post_radius", low=0.0, strict_low=True)
    min_post_detections = checks.integer(min_post_detections, f, "min_post_detections", low=1)
    poses_from = checks.choice(poses_from, f, "poses_from", ("laser", "truth", "odometry"))
    max_depth_sigma = checks.real(max_depth_sigma, f, "max_depth_sigma", low=0.0, strict_low=True)
    if laser is not None and (not isinstance(laser, MapResult) or len(laser.poses) != len(tour.scans)):
        raise checks.fail(f, "laser", "must be the MapResult of this tour's scans (or None)")
    g = tour.geometry
    lx, ly, h, yaw = (float(v) for v in g.laser_mount)
    if laser is None:
        laser = build_map(tour.scans, tour.odometry, method=method, mount=(lx, ly, yaw))
    robot = Robot(g)
    poses = {"laser": laser.poses, "truth": tour.truth, "odometry": tour.odometry}[poses_from]
    scan_segments = _moved_segments(tour, poses)
    detections, groups = _moved_posts(tour, poses, post_radius, min_post_detections, f)
    walls = [virtual_wall(s.start, s.end, h, virtual_wall_height) for s in laser.segments]  # 3. virtual walls
    kinds = {o.name: _KIND[type(o).__name__] for o in tour.world.objects if type(o).__name__ in _KIND}
    views, pooled = _stereo_views(tour, poses, robot, kinds, stereo_depth_limit(g, tour.noise_px, max_depth_sigma))
    objects = {name: _fused_object(kinds[name], parts) for name, parts in pooled.items()}
    return FusedMap(tour, laser, h, scan_segments, walls, detections, groups, views, objects,
                    float(virtual_wall_height), float(post_radius), robot)  # fmt: skip


def _moved_segments(tour: Tour, poses) -> list:
    """Step 2: every scan's segments, as point pairs, through M_lu (4.4): one batch of motors, one sandwich."""
    ends, seg_scan = [], []
    for k, (ranges, angles) in enumerate(tour.scans):
        for s in extract_segments(ranges, angles, max_range=5.0):
            ends.append([[*s.start, 0.0], [*s.end, 0.0]])
            seg_scan.append(k)
    ends, seg_scan = np.array(ends).reshape(-1, 2, 3), np.array(seg_scan, int)
    scan_segments = [np.zeros((0, 2, 3)) for _ in tour.scans]
    if len(ends):
        M = _laser_motors(tour.geometry, poses[seg_scan])
        PP = to_unified(M, cga.point_pair(ends[:, 0], ends[:, 1]))  # (4.4), segment i by the motor of its scan
        p1, p2 = (np.atleast_2d(p) for p in cga.point_pair_endpoints(PP))  # (2.131)
        moved = np.stack([p1, p2], axis=1)
        for k in np.unique(seg_scan):
            scan_segments[k] = moved[seg_scan == k]
    return scan_segments


def _moved_posts(tour: Tour, poses, post_radius: float, min_post_detections: int, f: str):
    """Step 4: the posts' centres of every scan through M_lu (4.4), and their groups (the posts the laser reports)."""
    centres, post_scan = [], []
    for k, (ranges, angles) in enumerate(tour.scans):
        c, _ = laser_posts(ranges, angles, radius=post_radius)
        centres += [[*p, 0.0] for p in c]
        post_scan += [k] * len(c)
    detections = np.zeros((0, 3))
    if centres and not np.max(np.abs(centres)) <= 1e6:  # a circle fit of a huge radius lands its centre far away
        raise checks.fail(f, "post_radius", f"{post_radius:g} m: the posts' centres land beyond 1e6 m")
    if centres:
        M = _laser_motors(tour.geometry, poses[np.array(post_scan)])
        detections = np.atleast_2d(cga.down(to_unified(M, cga.up(np.array(centres)))))  # (4.4)
    groups = [
        PostGroup(
            center=detections[idx].mean(axis=0),
            n=len(idx),
            spread=float(detections[idx][:, :2].std(axis=0).max()),
        )
        for idx in group_detections(detections, 3 * post_radius)
        if len(idx) >= min_post_detections
    ]
    return detections, groups


def _stereo_views(tour: Tour, poses, robot: Robot, kinds: dict, z_max: float):
    """Step 5: each view's entities through M_eu (4.10), with the pose of the moment; and each object's points."""
    views, pooled = [], {}
    for vi, view in enumerate(tour.views):
        if not view.pixels:
            continue
        x, y, th = poses[view.scan]
        robot.set_state(RobotState(x, y, th, view.state.pan, view.state.tilt))
        tri = triangulate_view(tour.geometry, view)  # (A.14), stereo frame
        for name, X_s in tri.items():
            kind = kinds[name]
            X_s = X_s[X_s[:, 0] <= z_max]  # depth is x in the stereo frame
            if len(X_s) < _MIN_POINTS[kind]:
                continue
            try:
                fit = fit_entity(kind, X_s)  # section 4.1, in the stereo frame
            except DegenerateGeometryError:
                continue
            blade_w = robot.stereo_to_unified(fit.blade)  # (4.10): the entity itself
            X_w = cga.apply_to_points(robot["M_eu"], X_s)  # its points, by the same motor
            views.append(StereoEntity(name, kind, vi, view.scan, robot.state, fit.blade, blade_w,
                                      blade_parameters(kind, blade_w), X_w))  # fmt: skip
            pooled.setdefault(name, []).append(X_w)
    return views, pooled


def _fused_object(kind: str, parts: list) -> FusedObject:
    """Step 6: one entity of an object from the points of all its views."""
    X = np.vstack(parts)
    fit = fit_entity(kind, X)
    params = blade_parameters(kind, fit.blade)
    corners = _plane_rectangle(X, params.normal, params.distance) if kind == "plane" else None
    return FusedObject(kind, fit.blade, params, len(parts), X, fit.rms,
                       ends=fit.ends if kind == "line" else None, corners=corners)  # fmt: skip


def _laser_motors(geometry, poses):
    """``M_lu`` (4.3) for many poses (k, 3) at once: one batched motor."""
    return chain_motors(geometry, x=poses[:, 0], y=poses[:, 1], theta=poses[:, 2]).M_lu


def _plane_rectangle(X, n, d) -> np.ndarray:
    """The rectangle (4, 3) in the plane ``n . x = d`` spanned by points X, with one side horizontal."""
    along = np.cross(_UP, n)
    if np.linalg.norm(along) < 1e-6:  # a horizontal plane: any horizontal axis
        along = np.array([1.0, 0.0, 0.0])
    along /= np.linalg.norm(along)
    vert = np.cross(n, along)
    c = X.mean(axis=0)
    c = c - (c @ n - d) * n
    u, v = (X - c) @ along, (X - c) @ vert
    return np.array([c + a * along + b * vert for a, b in
                     ((u.min(), v.min()), (u.max(), v.min()), (u.max(), v.max()), (u.min(), v.max()))])  # fmt: skip
