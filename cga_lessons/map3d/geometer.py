"""The robot geometer's sensors as kinematic chains (section 4.2, Eqs. 4.1-4.10, with the future work's chains).

Today's :mod:`cga_lessons.map3d.robot` writes the geometer's five degrees of freedom out by hand as the motor
chains of section 4.2; here the same robot is two :class:`~cga_lessons.kinematics.Chain` objects of joints
(x and y slides, the heading about z, then pan and tilt about their axis lines), so that everything the chains of
n joints do (Jacobian, inverse kinematics) applies to it, and the tests hold the two to the same numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons.kinematics import Chain, chain, prismatic, revolute

__all__ = ["GeometerChains", "geometer_chains"]

_X, _Z = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class GeometerChains:
    """The geometer's sensors as chains over ``q = (x, y, theta, pan, tilt)`` (:data:`cga_lessons.map3d.state.DOFS`).

    ``camera`` (5 joints) ends at the left camera, the pose of ``M_eu`` (4.9) or, for pan-tilt axes that miss
    each other, of the footnote's chain about the axis lines (``stereo_chain_about_lines``); ``laser``
    (x, y, theta) ends at the laser, ``M_lu = M_pos M_lsr`` (4.3 corrected).
    """

    camera: Chain
    laser: Chain

    def __post_init__(self):
        for name in ("camera", "laser"):
            checks.instance(getattr(self, name), "GeometerChains", name, Chain, "a Chain (kinematics.chain)")


def geometer_chains(geometry=None) -> GeometerChains:
    """Today's robot geometer (:mod:`cga_lessons.map3d.robot`) rebuilt as two chains of joints.

    ``T_pos`` (2.100, the position of 3.7) is two slides along x and y, ``R_pos`` (the heading) a turn about
    the z axis through the origin, pan and tilt turns about the lines ``L_pan`` and ``L_tilt`` at home
    (2.109; the footnote of 4.2.2); the home motors are the fixed parts ``M_eye = T_eje T_ojo`` (4.5, 4.7 at
    q = 0) and ``M_lsr`` (4.1 at theta = 0).  So the camera chain is
    ``T_x T_y R_pos R_Lpan R_Ltilt M_eye`` and the laser chain ``T_x T_y R_pos M_lsr``.

    >>> g = geometer_chains()
    >>> g.camera.n, g.laser.n, [j.name for j in g.camera.joints]
    (5, 3, ['x', 'y', 'theta', 'pan', 'tilt'])
    """
    from cga_lessons.map3d.motors import chain_motors
    from cga_lessons.map3d.state import RobotGeometry

    if geometry is not None:
        checks.instance(geometry, "geometer_chains", "geometry", RobotGeometry, "a RobotGeometry or None")
    fixed = chain_motors(geometry or RobotGeometry())
    base = [prismatic(_X, "x"), prismatic([0.0, 1.0, 0.0], "y"), revolute(_Z, name="theta")]
    head = [revolute(fixed.L_pan, name="pan"), revolute(fixed.L_tilt, name="tilt")]
    return GeometerChains(
        camera=chain(base + head, fixed.M_eye, name="geometer camera"),
        laser=chain(base, fixed.M_lsr, name="geometer laser"),
    )
