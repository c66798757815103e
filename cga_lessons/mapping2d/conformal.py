"""Line maps with conformal point pairs and motors: the entities (thesis section 3.2, Eqs. 3.13-3.17).

Section 3.2 builds the same map as section 3.1 with the entities of G(4,1):

* the plane of the laser is the z = 0 plane of 3D; a 2D point enters the
  algebra by E2C (3.13) and leaves by its inverse;
* a segment is the point pair ``PP* = p_i ^ p_f`` (2.68) of its ends; its
  line is ``L* = PP* ^ e``, its Hesse distance comes from (3.14) = (2.130)
  with the origin, its closest point from (3.15) = (2.129), its direction from
  (2.127) and its moment from (2.128) (:func:`point_pair_structure`);
* the laser's points reach the global frame through the motor of the laser
  on the robot (3.16) and the robot's motor (3.17), as a sandwich (3.18).

Correspondence by spheres (3.19), fusion (3.20)-(3.21) and the map builder's
operations are in :mod:`cga_lessons.mapping2d.conformal_geometry`
(:class:`~cga_lessons.mapping2d.conformal_geometry.ConformalGeometry`).

Erratum (3.17): the thesis writes ``M_laser = M_l-r M_robot`` with
``M_l-r = R_robot M_laser-robot ~R_robot``.  This is right only when the laser
is not turned on the robot: with a mount rotation ``phi`` the translation comes
out as ``R_robot t_mount + R_phi t_robot`` instead of ``t_robot + R_robot
t_mount``.  Conjugating by the whole robot motor, ``M_l-r = M_robot
M_laser-robot ~M_robot``, gives ``M_laser = M_robot M_laser-robot``, correct
for any mount (see :func:`laser_motor`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector, finite_multivector

from .segment import TWO_PI, Segment

__all__ = [
    "Z_AXIS",
    "plane_points",
    "e2c",
    "c2e",
    "segment_point_pair",
    "PointPairStructure",
    "point_pair_structure",
    "robot_motor",
    "laser_motor",
]

Z_AXIS = np.array([0.0, 0.0, 1.0])  # the axis of the laser's turns: the plane of the laser is z = 0


def plane_points(p) -> np.ndarray:
    """Points ``(..., 2)`` of the laser's plane as points ``(..., 3)`` of space (z = 0)."""
    p = np.asarray(p, float)
    return np.concatenate([p, np.zeros(p.shape[:-1] + (1,))], axis=-1)


def e2c(xy) -> Multivector:
    """E2C: a 2D point into G(4,1), Eq. (3.13).

    ``E2C(x, y) = x e1 + y e2 + 0 e3 + (x^2 + y^2) e / 2 + e0``: the point of
    the z = 0 plane, made conformal by (2.62).

    Parameters
    ----------
    xy : array_like, shape (2,) or (N, 2)

    >>> X = e2c([3.0, 4.0]); float(X["e-"] - X["e+"]), float((X | X).scalar())
    (1.0, 0.0)
    """
    p, single = checks.batch(xy, "e2c", "xy", (2,))
    checks.magnitude(p, "e2c", "xy")
    return cga.up(plane_points(p[0] if single else p))


def c2e(X: Multivector) -> np.ndarray:
    """The inverse of E2C (3.13): ``(x, y)`` of a conformal point of the z = 0 plane, shape (2,) or (N, 2)."""
    checks.instance(X, "c2e", "X", Multivector, "a conformal point (a Multivector)")
    with checks.relabel("c2e", "X"):
        xyz = cga.down(X)
    return np.asarray(xyz, float)[..., :2]


def segment_point_pair(segments) -> Multivector:
    """Point pairs ``PP* = E2C(p_i) ^ E2C(p_f)`` of segments (2.68, section 3.2.1); a batch for a list."""
    f = "segment_point_pair"
    if isinstance(segments, Segment):
        with checks.relabel(f, "segments"):
            return cga.point_pair(plane_points(segments.start), plane_points(segments.end), frame=False)
    if not isinstance(segments, (list, tuple)) or not segments:
        raise checks.fail(f, "segments", f"expected a Segment or a non-empty list of them, got {segments!r:.60}")
    for s in segments:
        checks.instance(s, f, "segments", Segment, "a Segment or a list of them")
    starts = np.array([s.start for s in segments])
    ends = np.array([s.end for s in segments])
    with checks.relabel(f, "segments"):
        return cga.point_pair(plane_points(starts), plane_points(ends), frame=False)


@dataclass(frozen=True)
class PointPairStructure:
    """The thesis's segment structure (3.3) recovered from a point pair: the result of :func:`point_pair_structure`.

    Attributes
    ----------
    start, end : ndarray, shape (2,)
        The ends, by (2.131) and E2C^-1.
    line : Multivector
        The line ``L* = PP* ^ e``.
    rho : float
        Hesse distance from the origin, by (3.14).
    closest_point : ndarray, shape (2,)
        The line's closest point to the origin, by (3.15) (= 2.129).
    theta : float
        The polar angle of the closest point, in [0, 2 pi) (of the line's normal when it passes through the origin).
    abc : ndarray, shape (3,)
        The line ``a x + b y + c = 0`` (3.1) in Hesse form: ``(cos theta, sin theta, -rho)``.
    """

    start: np.ndarray
    end: np.ndarray
    line: Multivector
    rho: float
    closest_point: np.ndarray
    theta: float
    abc: np.ndarray

    def __post_init__(self):
        f = "PointPairStructure"
        for name, shape in (("start", (2,)), ("end", (2,)), ("closest_point", (2,)), ("abc", (3,))):
            object.__setattr__(self, name, checks.array(getattr(self, name), f, name, shape))
        finite_multivector(checks.instance(self.line, f, "line", Multivector, "a line (a Multivector)"), f, "line")
        object.__setattr__(self, "rho", checks.real(self.rho, f, "rho", low=0.0))
        object.__setattr__(self, "theta", checks.real(self.theta, f, "theta", low=0.0, high=TWO_PI))


def point_pair_structure(PP: Multivector) -> PointPairStructure:
    """The thesis's segment structure recovered from a point pair (section 3.2.1).

    * start and end: (2.131) and E2C^-1;
    * the line ``L* = PP* ^ e``;
    * Hesse distance ``rho`` by (3.14): ``rho^2 = ((L* . e0) / (L* . e0 . e))^2``;
    * closest point to the origin by (3.15) (= 2.129);
    * ``theta``: the polar angle of the closest point, in [0, 2 pi).

    Returns
    -------
    PointPairStructure

    >>> from cga_lessons.mapping2d import Segment
    >>> d = point_pair_structure(segment_point_pair(Segment([1.0, -1.0], [1.0, 1.0])))
    >>> round(d.rho, 12), round(d.theta, 12), (d.closest_point.round(12) + 0.0).tolist()
    (1.0, 0.0, [1.0, 0.0])
    """
    f = "point_pair_structure"
    checks.instance(PP, f, "PP", Multivector, "a point pair (a Multivector)")
    if PP.shape:
        raise checks.fail(f, "PP", f"expected one point pair, got a batch of shape {PP.shape}")
    with checks.relabel(f, "PP"):
        p1, p2 = cga.point_pair_endpoints(PP)  # (2.131)
    L = PP ^ cga.einf
    rho = float(cga.point_line_distance(np.zeros(3), L))  # (3.14) = (2.130) with x = e0
    closest = np.asarray(cga.line_closest_point(L), float)[:2]  # (3.15) = (2.129)
    if rho > 1e-12:
        theta = float(np.mod(np.arctan2(closest[1], closest[0]), TWO_PI))
    else:
        r = np.asarray(cga.line_direction(L), float)
        theta = float(np.mod(np.arctan2(-r[0], r[1]), TWO_PI))
    return PointPairStructure(
        start=np.asarray(p1, float)[:2],
        end=np.asarray(p2, float)[:2],
        line=L,
        rho=rho,
        closest_point=closest,
        theta=theta,
        abc=np.array([np.cos(theta), np.sin(theta), -rho]),
    )


def robot_motor(pose) -> Multivector:
    """Motor ``M = T R`` of a planar pose ``(x, y, theta)``: rotor about e3 (2.94), translator (2.100), (2.102)."""
    return _motor(_planar_pose(pose, "robot_motor", "pose"))


def _planar_pose(value, func: str, name: str) -> np.ndarray:
    """A pose (3,) whose position's square is finite (a motor squares it)."""
    p = checks.array(value, func, name, (3,))
    checks.magnitude(p[:2], func, name)
    return p


def _motor(pose) -> Multivector:
    x, y, th = pose
    return cga.translator([x, y, 0.0]) * cga.rotor(Z_AXIS, th)


def laser_motor(pose, mount=(0.0, 0.0, 0.0), printed: bool = False) -> Multivector:
    """Motor taking laser coordinates to global ones, Eqs. (3.16)-(3.17).

    ``M_laser-robot`` (3.16) is the laser's pose on the robot, ``M_robot`` the
    robot's pose from (3.6)-(3.7).  The thesis's (3.17) reads
    ``M_laser = M_l-r M_robot`` with ``M_l-r = R_robot M_laser-robot ~R_robot``
    (``printed=True``); it is right only for a laser that is not turned on the
    robot.  The default is the corrected form ``M_l-r = M_robot M_laser-robot
    ~M_robot``, i.e. ``M_laser = M_robot M_laser-robot``.

    Parameters
    ----------
    pose : array_like, shape (3,)
        Robot pose ``(x, y, theta)``.
    mount : array_like, shape (3,)
        Laser pose on the robot ``(t_x, t_y, theta_laser-robot)``.
    printed : bool
        Use (3.17) as printed.
    """
    f = "laser_motor"
    pose, mount = _planar_pose(pose, f, "pose"), _planar_pose(mount, f, "mount")
    printed = checks.flag(printed, f, "printed")
    checks.magnitude(np.abs(pose[:2]) + np.abs(mount[:2]), f, "pose, mount")
    M_robot = _motor(pose)
    M_lr = _motor(mount)  # (3.16) M_laser-robot = T_laser-robot R_laser-robot
    if printed:
        R = cga.rotor(Z_AXIS, float(pose[2]))
        M_l_r = R * M_lr * ~R
    else:
        M_l_r = M_robot * M_lr * ~M_robot
    return M_l_r * M_robot  # (3.17)
