"""What the fused 3D map holds (section 4.2.3): each stereo view's entities, the laser's posts, the objects fused
over the views, and the map itself (:class:`FusedMap`, made by :func:`~cga_lessons.map3d.build_fused_map`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cga_lessons import checks
from cga_lessons.conformal import ENTITY_PARAMETERS
from cga_lessons.mapping2d import MapResult

from .chains import check_entity
from .fits import ENTITY_KINDS, check_kind
from .parameters import corner_points, count, end_points
from .robot import Robot
from .state import RobotState
from .tour import Tour

__all__ = ["StereoEntity", "PostGroup", "FusedObject", "FusedMap"]


@dataclass
class StereoEntity:
    """One object seen in one stereo view: its entity in the stereo frame and in the unified frame (4.10).

    ``params`` are the Euclidean parameters of ``blade_world`` (:func:`~cga_lessons.map3d.entity_parameters`: a
    :class:`~cga_lessons.conformal.SphereParameters`, ... of the entity's ``kind``); ``points_world`` (N, 3) the
    triangulated points moved by the same motor.
    """

    name: str
    kind: str
    view: int
    scan: int
    state: RobotState
    blade_stereo: object
    blade_world: object
    params: object
    points_world: np.ndarray

    def __post_init__(self):
        f = "StereoEntity"
        checks.text(self.name, f, "name")
        checks.choice(self.kind, f, "kind", ENTITY_KINDS)
        self.view, self.scan = (checks.integer(getattr(self, k), f, k, low=0) for k in ("view", "scan"))
        checks.instance(self.state, f, "state", RobotState, "a RobotState")
        check_entity(self.blade_stereo, f, "blade_stereo")
        check_entity(self.blade_world, f, "blade_world")
        checks.instance(self.params, f, "params", ENTITY_PARAMETERS[self.kind], f"the {self.kind}'s parameters")
        self.points_world = checks.rows(self.points_world, f, "points_world", 3)


@dataclass(frozen=True, eq=False)
class PostGroup:
    """A post the laser found: the mean ``center`` (3,) of its detections (unified frame, laser height), ``n``
    detections (one per scan) and their ``spread`` (m, the larger standard deviation of x and y)."""

    center: np.ndarray
    n: int
    spread: float

    def __post_init__(self):
        checks.record(self, center=checks.vector3, n=count, spread=checks.length)


@dataclass(frozen=True, eq=False)
class FusedObject:
    """One object of the fused map: the entity refitted to the points of all the views that saw it (step 6).

    Attributes
    ----------
    kind : str
        ``"sphere"``, ``"plane"``, ``"circle"`` or ``"line"``.
    blade : Multivector
        The entity (unified frame).
    params : SphereParameters, PlaneParameters, CircleParameters or LineParameters
        Its Euclidean parameters (:func:`~cga_lessons.map3d.entity_parameters`).
    n_views : int
        The views that saw it.
    points : ndarray (N, 3)
        Their points (unified frame).
    rms : float
        RMS distance (m) of the points from the entity.
    ends : ndarray (2, 3) or None
        A line's ends (the extreme points' projections): how far the cameras saw the post.
    corners : ndarray (4, 3) or None
        A plane's rectangle spanned by its points, one side horizontal.
    """

    kind: str
    blade: object
    params: object
    n_views: int
    points: np.ndarray
    rms: float
    ends: np.ndarray | None = None
    corners: np.ndarray | None = None

    def __post_init__(self):
        f = "FusedObject"
        kind = checks.choice(self.kind, f, "kind", ENTITY_KINDS)
        checks.instance(self.params, f, "kind, params", ENTITY_PARAMETERS[kind], f"the {kind}'s parameters")
        check_kind(self.blade, kind, f, "kind, blade")
        checks.record(self, n_views=count, points=lambda v, f, n: checks.rows(v, f, n, 3), rms=checks.length)
        for name, check, owner in (("ends", end_points, "line"), ("corners", corner_points, "plane")):
            if (getattr(self, name) is None) != (kind != owner):
                has, got = "has" if kind == owner else "has no", type(getattr(self, name)).__name__
                raise checks.fail(f, f"kind, {name}", f"a {kind} {has} {name}, got {got}")
            if kind == owner:
                checks.record(self, **{name: check})


@dataclass
class FusedMap:
    """The 3D map: laser walls and posts, stereo entities per view and fused per object.

    Attributes
    ----------
    tour : Tour
        The recording (and the truth, for evaluation only).
    laser : MapResult
        Chapter 3's result: corrected poses and the fused 2D line map.
    laser_height : float
    scan_segments : list of ndarray (k, 2, 3)
        Each scan's segments moved to the unified frame by (4.4).
    virtual_walls : list of VirtualWall
    laser_post_detections : ndarray (m, 3)
        Post centres of every scan at laser height, unified frame.
    laser_post_groups : list of PostGroup
        One per post found by the laser.
    views : list of StereoEntity
    objects : dict
        name -> :class:`FusedObject`, fused over the views.
    """

    tour: Tour
    laser: MapResult
    laser_height: float
    scan_segments: list
    virtual_walls: list
    laser_post_detections: np.ndarray
    laser_post_groups: list
    views: list
    objects: dict
    wall_height: float = 1.0
    post_radius: float = 0.05
    robot: Robot | None = field(default=None, repr=False)

    def __post_init__(self):
        f = "FusedMap"
        checks.instance(self.tour, f, "tour", Tour, "a Tour (simulate_tour)")
        checks.instance(self.laser, f, "laser", MapResult, "a MapResult (mapping2d.build_map)")
        self.laser_height = checks.real(self.laser_height, f, "laser_height")
        for name in ("scan_segments", "virtual_walls", "laser_post_groups", "views"):
            checks.instance(getattr(self, name), f, name, list, "a list")
        for k, segs in enumerate(self.scan_segments):
            checks.array(segs, f, f"scan_segments[{k}]", (None, 2, 3))
        self.laser_post_detections = checks.rows(self.laser_post_detections, f, "laser_post_detections", 3)
        checks.instance(self.objects, f, "objects", dict, "a dict")
        for name in ("wall_height", "post_radius"):
            setattr(self, name, checks.real(getattr(self, name), f, name, low=0.0, strict_low=True))
        if self.robot is not None:
            checks.instance(self.robot, f, "robot", Robot, "a Robot or None")
