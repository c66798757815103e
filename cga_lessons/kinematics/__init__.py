"""Chapter 6's future work: kinematic chains of n joints as products of motors, their Jacobian and inverse kinematics,
and real arms from their published parameters.

Layer 3 of the package: imports layers 0-2 (errors, algebra, conformal) only (``tests/test_layers.py`` checks it).
Nothing here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in
``__all__``; its modules:

* :mod:`~cga_lessons.kinematics.arms`: Chains of real mechanisms as axis lines and a home motor: a UR5 and a Franka
  Panda
* :mod:`~cga_lessons.kinematics.ik`: Inverse kinematics of a chain of motors by damped least squares (Levenberg-
  Marquardt), batched
* :mod:`~cga_lessons.kinematics.motor_chain`: Kinematic chains of n joints as products of motors (the thesis's
  future work, section 6.2.2)
* :mod:`~cga_lessons.kinematics.motor_numbers`: A motor as 8 numbers: reading them off a multivector, back to a
  multivector, to a 4x4 matrix, to a twist
"""

from .arms import PANDA_DH, UR5_DH, DHParameters, panda, ur5
from .ik import IKOptions, inverse_kinematics
from .motor_chain import (
    Chain,
    Joint,
    chain,
    forward_coefficients,
    forward_matrix,
    forward_motor,
    prismatic,
    revolute,
    spatial_jacobian,
)
from .motor_numbers import coefficients_to_matrix, coefficients_to_motor, motor_coefficients, twist_of_bivector

__all__ = [
    "Joint",
    "Chain",
    "revolute",
    "prismatic",
    "chain",
    "motor_coefficients",
    "coefficients_to_motor",
    "coefficients_to_matrix",
    "forward_coefficients",
    "forward_motor",
    "forward_matrix",
    "spatial_jacobian",
    "twist_of_bivector",
    "DHParameters",
    "IKOptions",
    "PANDA_DH",
    "UR5_DH",
    "inverse_kinematics",
    "panda",
    "ur5",
]
