"""Exercises that check themselves, one module per chapter or document.

Layer 5 of the package: imports layers 0-4 only (``tests/test_layers.py`` checks it).  This facade exports the names
in ``__all__``; its modules:

* :mod:`~cga_lessons.exercises.ch2`: Exercises of chapter 2, notebooks 01 and 02: products and the conformal model
* :mod:`~cga_lessons.exercises.ch2_motions`: Exercises of chapter 2, notebooks 03 and 04: versors (motors, rotors
  about lines, screws) and entity properties
* :mod:`~cga_lessons.exercises.ch3`: Exercises of chapter 3 (notebooks 05 and 06): diffTheta, rho seen from where, a
  corridor, point pairs, spheres
* :mod:`~cga_lessons.exercises.ch4`: Exercises of chapter 4, section 4.2 (notebook 08): the stereo chain as a 4x4,
  the erratum of (4.3), rotor order
* :mod:`~cga_lessons.exercises.ch5`: Exercises of chapter 5 (notebook 09): a symmetric room, a translation from two
  lines, the printed shift (5.4)
* :mod:`~cga_lessons.exercises.ch6`: Exercises of chapter 6, the future work (notebook 11): a two-joint arm, its
  singular elbow, KLD sampling
* :mod:`~cga_lessons.exercises.checking`: Exercises that check themselves: ``check("ch2.4", answer)`` says right or
  wrong, and why
* :mod:`~cga_lessons.exercises.compare`: The comparisons behind :func:`cga_lessons.exercises.check`: read an answer,
  compare it, say what is off
* :mod:`~cga_lessons.exercises.exploration`: Exercises of the exploration document (notebook 10): tangent bearings,
  crossings of a path, and (3.1)
* :mod:`~cga_lessons.exercises.stereo`: Exercises of appendix A (notebook 07): camera centres, epipoles, and the
  8-point algorithm on a plane
"""

from .answers import Malformed, Wrong, as_array, as_expression, as_float
from .checking import CheckResult, Exercise, UnknownExerciseError, check, evaluate, exercise, get, given, list_exercises
from .compare import compare_expression, compare_matrix, compare_multivector, compare_number, compare_vector

__all__ = [
    "Exercise",
    "CheckResult",
    "Wrong",
    "Malformed",
    "UnknownExerciseError",
    "exercise",
    "check",
    "evaluate",
    "get",
    "given",
    "list_exercises",
    "compare_number",
    "compare_vector",
    "compare_matrix",
    "compare_multivector",
    "compare_expression",
    "as_float",
    "as_array",
    "as_expression",
]
