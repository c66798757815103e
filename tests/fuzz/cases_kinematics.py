"""Fuzz cases of :mod:`cga_lessons.kinematics`: joints, chains of motors, forward and inverse kinematics, DH arms.

Each valid call is small (a chain of two or three joints); see :mod:`fuzz.harness`.
"""

from __future__ import annotations

import numpy as np

from cga_lessons import conformal as cga
from cga_lessons import kinematics as kin
from fuzz.harness import Case

_J1 = kin.revolute([0.0, 0.0, 1.0])
_J2 = kin.revolute([0.0, 0.0, 1.0], point=[1.0, 0.0, 0.0])
_J3 = kin.prismatic([0.0, 0.0, 1.0])
_ARM = kin.chain([_J1, _J2, _J3], home=[2.0, 0.0, 0.0], name="arm")
_Q = np.array([0.3, -0.4, 0.1])
_QS = np.array([[0.3, -0.4, 0.1], [0.0, 0.2, -0.3]])
_MOTOR = cga.motor([0.0, 0.0, 1.0], 0.4, [1.0, 2.0, 0.5])
_TARGET = kin.forward_motor(_ARM, [0.4, 0.1, 0.2])
_OPTIONS = kin.IKOptions(max_iterations=8)
_C8 = np.array([0.9, 0.1, -0.2, 0.3, 0.5, -0.4, 0.2, 0.1])

_LINE = cga.line_from_points([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
_SPHERE = cga.sphere([0.0, 0.0, 0.0], 1.0)
_CIRCLE = cga.circle_from_points([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0])
_PLANE = cga.plane([0.0, 0.0, 1.0], 1.0)
_POINT = cga.up([1.0, 2.0, 3.0])
_PAIR = cga.point_pair([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
_NOT_MOTORS = [_SPHERE, _LINE, _POINT, _PLANE]  # a motor's reader given entities
_NOT_LINES = [_SPHERE, _CIRCLE, _POINT, _PLANE, _PAIR, _MOTOR]  # an axis line's reader given other entities
_NOT_CHAINS = [_J1, kin.UR5_DH, [_J1, _J2], _MOTOR]  # a chain's reader given a joint, a DH table, a list, a motor
_DH = {"name": "planar", "convention": "standard", "d": (0.1, 0.0), "a": (1.0, 1.0), "alpha": (0.0, np.pi / 2),
       "flange": 0.05}  # fmt: skip


def _(args: dict):
    """The valid arguments, fresh for each call but not deep-copied (a deep copy of a multivector is no longer one
    of G(4,1): its copied algebra is another object)."""
    return lambda: dict(args)


CASES = [
    Case(kin.Joint, {"kind": "revolute", "direction": (0.0, 0.0, 1.0), "point": (1.0, 0.0, 0.0), "name": "j"},
         strict=True, extra={"direction": [(0.0, 0.0, 0.0)]}, kinds={"direction": [_LINE]}),
    Case(kin.Chain, _({"joints": (_J1, _J2), "home": cga.translator([1.0, 0.0, 0.0]), "name": "c"}), strict=True,
         kinds={"joints": [(_LINE,), (), (_J1, "j")], "home": [_SPHERE, _POINT, _LINE]}),
    Case(kin.revolute, {"axis": (0.0, 0.0, 2.0), "point": (1.0, 0.0, 0.0), "name": "r"}, strict=True,
         kinds={"axis": _NOT_LINES}, extra={"axis": [(0.0, 0.0, 0.0)]}),
    Case(kin.revolute, _({"axis": _LINE, "name": "r"}), name="revolute(line)", kinds={"axis": _NOT_LINES}),
    Case(kin.prismatic, {"direction": (0.0, 0.0, 1.0), "name": "p"}, strict=True,
         kinds={"direction": [_LINE]}, extra={"direction": [(0.0, 0.0, 0.0)]}),
    Case(kin.chain, _({"joints": [_J1, _J2], "home": cga.translator([1.0, 0.0, 0.0]), "name": "c"}), strict=True,
         allow={"home": ["None"]},
         kinds={"joints": [[_LINE], [], _J1, [_J1, "j"]], "home": [_SPHERE, _POINT, _LINE, _PLANE]}),
    Case(kin.chain, _({"joints": [_J1], "home": (1.0, 0.0, 0.0)}), name="chain(home translation)"),
    Case(kin.chain, _({"joints": [_J1], "home": np.diag([1.0, -1.0, -1.0, 1.0])}), name="chain(home matrix)",
         extra={"home": [np.diag([1.0, 1.0, -1.0, 1.0]), np.diag([2.0, 2.0, 2.0, 1.0])]}),
    Case(kin.motor_coefficients, _({"M": _MOTOR}), kinds={"M": _NOT_MOTORS + [_CIRCLE]},
         extra={"M": [cga.G41.scalar(0.0), 1e300 * _MOTOR]}),
    Case(kin.coefficients_to_motor, {"c": _C8}, extra={"c": [np.zeros(8)]}),
    Case(kin.coefficients_to_motor, {"c": np.array([_C8, 2 * _C8])}, name="coefficients_to_motor(batch)"),
    Case(kin.coefficients_to_matrix, {"c": np.array([_C8, 2 * _C8])}, extra={"c": [np.zeros(8), 1e-300 * _C8]}),
    Case(kin.twist_of_bivector, {"c": _C8}),
    Case(kin.forward_coefficients, _({"ch": _ARM, "q": _Q}), kinds={"ch": _NOT_CHAINS}),
    Case(kin.forward_motor, _({"ch": _ARM, "q": _QS}), kinds={"ch": _NOT_CHAINS}),
    Case(kin.forward_matrix, _({"ch": _ARM, "q": _Q}), kinds={"ch": _NOT_CHAINS}),
    Case(kin.spatial_jacobian, _({"ch": _ARM, "q": _QS}), kinds={"ch": _NOT_CHAINS}),
    Case(kin.DHParameters, _DH, strict=True, extra={"d": [(0.1,)], "alpha": [()]}),
    Case(kin.IKOptions, {"max_iterations": 50, "tol_position": 1e-10, "tol_rotation": 1e-10, "damping": 1e-3,
                         "max_step": 1.0, "restart_after": 3, "seed": 0}, strict=True,
         allow={"restart_after": ["None"]}, extra={"damping": [0.0], "max_iterations": [10**12]}),
    Case(kin.inverse_kinematics, _({"ch": _ARM, "target": _TARGET, "q0": _Q, "options": _OPTIONS}),
         strict=True, allow={"options": ["None"]},
         kinds={"ch": _NOT_CHAINS, "target": _NOT_MOTORS, "options": [_ARM, {"max_iterations": 3}]}),
    Case(kin.inverse_kinematics, _({"ch": _ARM, "target": kin.forward_matrix(_ARM, _QS), "q0": _Q}),
         name="inverse_kinematics(matrices)", extra={"target": [np.diag([1.0, 1.0, -1.0, 1.0])]}),
    Case(kin.panda),
    Case(kin.ur5),
]  # fmt: skip

EXEMPT: dict[str, str] = {}
