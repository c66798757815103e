"""Chains of real mechanisms as axis lines and a home motor: a UR5 and a Franka Panda.

An arm published with Denavit-Hartenberg parameters becomes a :class:`~cga_lessons.kinematics.Chain` by
walking its links once at q = 0 with motors: the frame of link i is a product of rotors (2.94) and translators
(2.100), joint i's axis is the z axis of its frame, the line ``F L_z ~F`` (2.103 applied to the line 2.81),
and the last frame is the home motor M0.  Then ``M(q) = M_1(q_1) ... M_n(q_n) M0`` with
``M_i = exp(-q_i/2 L_i)`` (2.109) equals the DH product of 4x4 matrices (the product-of-exponentials
formula, Lynch & Park 2017, ch. 4).

* Standard DH (Denavit & Hartenberg 1955): link i is ``Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)`` and
  joint i turns about the z axis of frame i-1.  :data:`UR5_DH` is Universal Robots' table for the UR5.
* Modified DH (Craig 1986): link i is ``Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)`` and joint i turns
  about the z axis of frame i.  :data:`PANDA_DH` is Franka Emika's table for the Panda, rows indexed as in
  its documentation (row i holds a_{i-1}, alpha_{i-1} and d_i), with the flange 0.107 m along the last z.

The thesis's robot rebuilt with these chains is :func:`cga_lessons.map3d.geometer_chains` (it needs the robot's
geometry, a layer above).

>>> import numpy as np
>>> from cga_lessons import kinematics as kin
>>> kin.forward_matrix(ur5(), np.zeros(6))[:3, 3].round(5)  # the UR5 stretched out along -x at q = 0
array([-0.81725, -0.19145, -0.00549])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cga_lessons import checks
from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector

from .motor_chain import Chain, chain, revolute

__all__ = ["DHParameters", "UR5_DH", "PANDA_DH", "dh_chain", "ur5", "panda"]

_X, _Z = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class DHParameters:
    """A serial arm of revolute joints by its Denavit-Hartenberg table (metres, radians).

    ``convention`` is ``"standard"`` (link i = ``Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``) or ``"modified"``
    (link i = ``Rx(alpha_i) Tx(a_i) Rz(q_i) Tz(d_i)``, with row i holding Craig's a_{i-1}, alpha_{i-1}).
    ``flange`` is a last fixed offset along the last z axis (modified tables list it as a row of its own).
    """

    name: str
    convention: str
    d: tuple
    a: tuple
    alpha: tuple
    flange: float = 0.0

    def __post_init__(self):
        f = "DHParameters"
        checks.text(self.name, f, "name", empty=True)
        checks.choice(self.convention, f, "convention", ("standard", "modified"))
        rows = {k: checks.array(getattr(self, k), f, k, (None,), at_least=1) for k in ("d", "a", "alpha")}
        checks.same_length(f, **rows)
        object.__setattr__(self, "flange", checks.real(self.flange, f, "flange"))


#: The UR5, Universal Robots' standard DH parameters.
UR5_DH = DHParameters(
    name="UR5",
    convention="standard",
    d=(0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823),
    a=(0.0, -0.425, -0.39225, 0.0, 0.0, 0.0),
    alpha=(np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0),
)

#: The Franka Emika Panda, modified DH parameters from Franka's documentation (flange d = 0.107).
PANDA_DH = DHParameters(
    name="Panda",
    convention="modified",
    d=(0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0),
    a=(0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088),
    alpha=(0.0, -np.pi / 2, np.pi / 2, np.pi / 2, -np.pi / 2, np.pi / 2, np.pi / 2),
    flange=0.107,
)


def _axis_line(F: Multivector) -> Multivector:
    """The z axis of the frame F, ``F L_z ~F`` (2.103 on the line 2.81 through 0 and e3)."""
    return cga.apply(F, cga.line_from_points([0.0, 0.0, 0.0], _Z))


def dh_chain(p: DHParameters) -> Chain:
    """The chain of a DH table: axis lines and home motor from one walk along the links at q = 0.

    >>> two = DHParameters("planar", "standard", d=(0.0, 0.0), a=(1.0, 1.0), alpha=(0.0, 0.0))
    >>> from cga_lessons import kinematics as kin
    >>> kin.forward_matrix(dh_chain(two), [np.pi / 2, -np.pi / 2])[:3, 3].round(12) + 0.0
    array([1., 1., 0.])
    """
    checks.instance(p, "dh_chain", "p", DHParameters, "DHParameters")
    F = cga.G41.scalar(1.0)
    joints = []
    for i, (d, a, alpha) in enumerate(zip(p.d, p.a, p.alpha)):
        name = f"{p.name} joint {i + 1}"
        if p.convention == "standard":  # joint i turns about z of frame i-1, then the link Tz Tx Rx
            joints.append(revolute(_axis_line(F), name=name))
            F = F * cga.translator(d * _Z) * cga.translator(a * _X) * cga.rotor(_X, alpha)
        else:  # Rx Tx first, then the joint turns about z of frame i, then Tz
            F = F * cga.rotor(_X, alpha) * cga.translator(a * _X)
            joints.append(revolute(_axis_line(F), name=name))
            F = F * cga.translator(d * _Z)
    F = F * cga.translator(float(p.flange) * _Z)
    return chain(joints, F, name=p.name)


def ur5() -> Chain:
    """The UR5 as a chain (6 revolute joints), from :data:`UR5_DH`."""
    return dh_chain(UR5_DH)


def panda() -> Chain:
    """The Franka Panda as a chain (7 revolute joints) up to its flange, from :data:`PANDA_DH`."""
    return dh_chain(PANDA_DH)
