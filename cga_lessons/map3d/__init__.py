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
* :mod:`~cga_lessons.map3d.geometer`: The robot geometer's sensors as kinematic chains (section 4.2, Eqs.
  4.1-4.10, with the future work's chains)
* :mod:`~cga_lessons.map3d.laser`: The laser's part of the fused 3D map: virtual walls (figures 4.5, 4.6) and posts
  (section 4.2.3)
* :mod:`~cga_lessons.map3d.robot`: The robot *geometer*: five degrees of freedom and its sensors as motor chains
  (section 4.2.2, Eqs. 4.1-4.10)
* :mod:`~cga_lessons.map3d.state`: The robot *geometer*'s fixed geometry and its five degrees of freedom (section
  4.2.2), with their checks
* :mod:`~cga_lessons.map3d.tour`: A tour of the synthetic world: the robot scans with its laser and looks around
  with its stereo head
* :mod:`~cga_lessons.map3d.world`: The synthetic world of the fused 3D map (section 4.2.3): a room and its objects
"""

from .chains import base_motor_as_printed, base_rotor, base_translator, laser_chain_as_printed, stereo_chain_as_printed
from .eval import COLUMNS, residual_table, view_errors
from .fits import entity_parameters, fit_line_3d
from .fuse import FusedMap, StereoEntity, build_fused_map, stereo_depth_limit
from .geometer import GeometerChains, geometer_chains
from .robot import Robot, chain_motors
from .state import DOFS, RobotGeometry, RobotState
from .tour import homogeneous_chains, simulate_tour

__all__ = [
    "StereoEntity",
    "FusedMap",
    "fit_line_3d",
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
    "simulate_tour",
    "stereo_chain_as_printed",
    "view_errors",
]
