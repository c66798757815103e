"""Section 4.2: the robot geometer as motor chains and one 3D map fused from its laser and stereo head.

Layer 4 of the package: imports layers 0-3 only (``tests/test_layers.py`` checks it). Nothing here draws (figures
and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in ``__all__``; its modules:

* :mod:`~cga_lessons.map3d.chains`: The motor chains of the robot *geometer*, one function per equation
  (4.1)-(4.10), and their fixed parts
* :mod:`~cga_lessons.map3d.eval`: How good is the fused 3D map: laser against stereo on the objects both saw, and
  both against the truth
* :mod:`~cga_lessons.map3d.fits`: Fitting an object's conformal entity to its points and reading its Euclidean
  parameters back (section 4.1, used by the fused 3D map of section 4.2.3)
* :mod:`~cga_lessons.map3d.fuse`: One 3D map fused from the laser and the stereo head through the robot's motor
  chains (section 4.2.3)
* :mod:`~cga_lessons.map3d.fused_map`: What the fused 3D map holds (section 4.2.3): each stereo view's entities,
  the laser's posts, the objects fused over the views, and the map itself
* :mod:`~cga_lessons.map3d.geometer`: The robot geometer's sensors as kinematic chains (section 4.2, Eqs.
  4.1-4.10, with the future work's chains)
* :mod:`~cga_lessons.map3d.laser`: The laser's part of the fused 3D map: virtual walls (figures 4.5, 4.6) and posts
  (section 4.2.3)
* :mod:`~cga_lessons.map3d.motors`: Every motor of the robot *geometer*'s chains at once (section 4.2.2, Eqs.
  4.1-4.10): which degrees of freedom and parts each is built from, the fixed parts, and :func:`chain_motors` for
  one or many configurations
* :mod:`~cga_lessons.map3d.parameters`: The truth of the synthetic world's objects where it says more than an
  entity's parameters (section 4.2.3), and the checks of the package's typed results
* :mod:`~cga_lessons.map3d.robot`: The robot *geometer*: five degrees of freedom and its sensors as motor chains
  (section 4.2.2, Eqs. 4.1-4.10)
* :mod:`~cga_lessons.map3d.state`: The robot *geometer*'s fixed geometry and its five degrees of freedom (section
  4.2.2), with their checks
* :mod:`~cga_lessons.map3d.tour`: A tour of the synthetic world: the robot scans with its laser and looks around
  with its stereo head
* :mod:`~cga_lessons.map3d.world`: The synthetic world of the fused 3D map (section 4.2.3): a room and its objects
"""

from .chains import base_motor_as_printed, base_rotor, base_translator, laser_chain_as_printed, stereo_chain_as_printed
from .eval import COLUMNS, ResidualRow, ViewErrorRow, residual_table, view_errors
from .fits import entity_parameters
from .fuse import build_fused_map, stereo_depth_limit
from .fused_map import FusedMap, FusedObject, PostGroup, StereoEntity
from .geometer import GeometerChains, geometer_chains
from .motors import ChainMotors, chain_motors
from .parameters import (
    BoardTruth,
    BoxTruth,
    PostTruth,
)
from .robot import Robot, RobotFrames
from .state import DOFS, RobotGeometry, RobotState
from .tour import HomogeneousChains, homogeneous_chains, simulate_tour

__all__ = [
    "StereoEntity",
    "PostGroup",
    "FusedObject",
    "FusedMap",
    "BoardTruth",
    "PostTruth",
    "BoxTruth",
    "ChainMotors",
    "RobotFrames",
    "HomogeneousChains",
    "build_fused_map",
    "stereo_depth_limit",
    "entity_parameters",
    "GeometerChains",
    "geometer_chains",
    "DOFS",
    "Robot",
    "RobotGeometry",
    "RobotState",
    "COLUMNS",
    "base_motor_as_printed",
    "base_rotor",
    "base_translator",
    "chain_motors",
    "homogeneous_chains",
    "laser_chain_as_printed",
    "residual_table",
    "ResidualRow",
    "ViewErrorRow",
    "simulate_tour",
    "stereo_chain_as_printed",
    "view_errors",
]
