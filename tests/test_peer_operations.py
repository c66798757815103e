"""The operations users of clifford and kingdon reach for: each has an equivalent here, or the README names it.

Each operation's accuracy is tested in its own file (tests/test_blades.py, test_versor_log.py,
test_motor_estimation.py, test_object_motors.py); this file keeps the list, the public names and the README
honest, and checks one round trip per operation against kingdon where kingdon has it.
"""

import re
from pathlib import Path

import numpy as np
import pytest

from cga_lessons import conformal as cga

# (peer operation, our public names in cga_lessons.conformal; empty: no equivalent, the README must name it)
PEER_OPERATIONS = [
    ("meet", ["meet"]),
    ("join", ["join"]),
    ("regressive product", ["regressive_product"]),
    ("line-plane intersection", ["intersect"]),
    ("plane-plane intersection", ["intersect"]),
    ("sphere-sphere intersection", ["intersect"]),
    ("sphere-line intersection", ["intersect"]),
    ("logarithm of a rotor", ["rotor_log"]),
    ("logarithm of a motor", ["motor_log", "screw_parameters"]),
    ("interpolation of motors", ["motor_interpolate"]),
    ("square root of a versor", ["versor_sqrt"]),
    ("n-th root of a versor", ["versor_root"]),
    ("dilator", ["dilator"]),
    ("right contraction", ["right_contraction"]),
    ("projection", ["project"]),
    ("rejection", ["reject"]),
    ("blade and versor predicates", ["is_blade", "is_versor"]),
    ("blade factorisation", ["blade_factors"]),
    ("classification of a blade (round, flat, tangent, direction, imaginary)", ["classify"]),
    ("motor between two objects", ["motor_between"]),
    ("motor from corresponding points", ["motor_from_points"]),
    ("motor from corresponding lines", ["motor_from_lines"]),
    ("rotor to and from quaternions", ["rotor_to_quaternion", "quaternion_to_rotor"]),
    ("averaging motors", ["mean_motor"]),
    ("averaging objects", []),
]


def test_every_equivalent_is_public_and_at_most_four_operations_lack_one():
    for _, names in PEER_OPERATIONS:
        for name in names:
            assert name in cga.__all__ and callable(getattr(cga, name)), name
    missing = [op for op, names in PEER_OPERATIONS if not names]
    assert len(missing) <= 4


def test_the_readme_names_every_operation_without_an_equivalent():
    readme = Path(__file__).resolve().parents[1].joinpath("README.md").read_text()
    section = re.search(r"Without an equivalent here: (.*?)\.", readme, re.S)
    assert section is not None
    for op, names in PEER_OPERATIONS:
        if not names:
            assert op in section.group(1), op


def test_kingdon_round_trips_agree():
    """One input per operation kingdon also offers: regressive product, contractions, dual, sqrt of a motor."""
    kingdon = pytest.importorskip("kingdon")
    K = kingdon.Algebra(4, 1)  # e4 = e+, e5 = e-: the bitmap order of G41

    def to_k(X):
        name = {b: "e" + "".join(str(i + 1) for i in range(5) if b >> i & 1) if b else "e" for b in range(32)}
        return K.multivector({name[b]: float(v) for b, v in X.coeffs.items()})

    def from_k(Y):
        out = {}
        for key, v in zip(Y.keys(), Y.values()):
            out[int(key)] = float(v)
        return cga.Multivector(cga.G41, {b: v for b, v in out.items() if v != 0.0})

    rng = np.random.default_rng(4)
    A = cga.plane_from_points(*rng.normal(size=(3, 3)))
    B = cga.line_from_points(*rng.normal(size=(2, 3)))
    assert from_k(to_k(A).lc(to_k(B))).isclose(cga.left_contraction(A, B))
    assert from_k(to_k(B).rc(to_k(A))).isclose(cga.right_contraction(B, A))
    # kingdon's sqrt holds for Study numbers (it warns it cannot check): a rotation about a line off the origin is
    # one; for a screw with a slide along its axis kingdon's root does not square back to the motor, ours does.
    R_L = cga.translator([1.0, -2.0, 0.5]) * cga.rotor([0.3, 0.4, 0.5], 1.2) * ~cga.translator([1.0, -2.0, 0.5])
    with pytest.warns(RuntimeWarning, match="Study number"):
        root = from_k(to_k(R_L).sqrt())
    assert root.isclose(cga.versor_sqrt(R_L)) or root.isclose(-cga.versor_sqrt(R_L))
    M = cga.motor(rng.normal(size=3), 1.2, rng.normal(size=3))
    half = cga.versor_sqrt(M)
    assert (half * half).isclose(M)
