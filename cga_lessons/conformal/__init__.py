"""The conformal model G(4,1): one import for the whole of chapter 2.

``from cga_lessons import conformal as cga`` gives the basis and constants and
up/down (:mod:`cga_lessons.conformal.model`, 2.52-2.60, and :mod:`cga_lessons.conformal.points`, 2.61-2.67,
2.111-2.114), the entities of
table 2.1 and their properties (:mod:`cga_lessons.conformal.entities`, :mod:`cga_lessons.conformal.lines_circles`,
section 2.4; exact far from the origin through their local frames, :mod:`cga_lessons.conformal.anchored`, and so are
raw wedges of points, ``up(a) ^ up(b) ^ ...``, :mod:`cga_lessons.conformal.point_wedges`) and
the versors of table 2.2 (:mod:`cga_lessons.conformal.versors`, 2.82-2.110, 2.135-2.145),
and beyond the thesis the logarithm, roots and interpolation of motors and the
dilator (:mod:`cga_lessons.conformal.versor_log`, :mod:`cga_lessons.conformal.versor_powers`), contractions,
duals, meet and join,
projections, blade factorisation and the classification of blades (:mod:`cga_lessons.conformal.blades`,
:mod:`cga_lessons.conformal.blades_span`, :mod:`cga_lessons.conformal.blades_classify`), motors estimated from
corresponding points or lines, their mean, and quaternions (:mod:`cga_lessons.conformal.motor_estimation`,
:mod:`cga_lessons.conformal.motor_lines`),
the motor between two objects (:mod:`cga_lessons.conformal.object_motors`), the least-squares line
(:mod:`cga_lessons.conformal.line_fit`), and an entity's Euclidean parameters
as typed records (:mod:`cga_lessons.conformal.parameters`).

Basis vectors ``e1 e2 e3`` (Euclidean), ``ep`` (e+, squares to +1) and ``em``
(e-, squares to -1), (2.52).  The null basis (2.53), with the thesis's signs::

    eo   = (e- - e+)/2      the origin, e_0
    einf = e- + e+          the point at infinity, e (the thesis writes plain e)

``E = e+ e- = einf ^ eo`` (2.55, corrected), ``IE = e1 e2 e3``, ``Ic = E IE`` (2.60).

    >>> from cga_lessons import conformal as cga
    >>> X = cga.up([1.0, 2.0, 3.0])
    >>> float(X | X), float(X | cga.einf)
    (0.0, -1.0)
    >>> cga.down(X)
    array([1., 2., 3.])
"""

from cga_lessons.algebra import DegenerateGeometryError, GeometryError, InvalidInputError, Multivector, exp  # noqa: F401

from .blades import *  # noqa: F403
from .blades import __all__ as _blades_all
from .blades_classify import *  # noqa: F403
from .blades_classify import __all__ as _blades_classify_all
from .blades_span import *  # noqa: F403
from .blades_span import __all__ as _blades_span_all
from .entities import *  # noqa: F403
from .entities import __all__ as _entities_all
from .fitting import (  # noqa: F401
    CircleFit,
    PlaneFit,
    SphereFit,
    fit_circle,
    fit_circle_euclidean,
    fit_plane,
    fit_plane_euclidean,
    fit_sphere,
    fit_sphere_geometric,
    fit_sphere_kasa,
)
from .line_fit import LineFit, fit_line  # noqa: F401
from .lines_circles import *  # noqa: F403
from .lines_circles import __all__ as _lines_circles_all
from .model import *  # noqa: F403
from .model import __all__ as _model_all
from .motor_estimation import *  # noqa: F403
from .motor_estimation import __all__ as _motor_estimation_all
from .motor_lines import motor_from_lines  # noqa: F401
from .object_motors import motor_between  # noqa: F401
from .parameters import (  # noqa: F401
    ENTITY_PARAMETERS,
    CircleParameters,
    LineParameters,
    PlaneParameters,
    SphereParameters,
)
from .plane_ransac import segment_planes  # noqa: F401
from .point_wedges import framed_points  # noqa: F401  (importing it registers G41's operation hook)
from .points import *  # noqa: F403
from .points import __all__ as _points_all
from .points import point_weight  # noqa: F401
from .versor_log import *  # noqa: F403
from .versor_log import __all__ as _versor_log_all
from .versor_powers import *  # noqa: F403
from .versor_powers import __all__ as _versor_powers_all
from .versors import *  # noqa: F403
from .versors import __all__ as _versors_all
from .versors_build import motor, rotor, rotor_about_line, screw, translator  # noqa: F401
from .versors_rigid import (  # noqa: F401
    decompose_motor,
    matrix_to_motor,
    motor_to_matrix,
    rotor_angle_axis,
    why_not_motor,  # noqa: F401
)

__all__ = (
    list(_model_all)
    + list(_points_all)
    + ["point_weight", "Multivector", "exp", "GeometryError", "DegenerateGeometryError", "InvalidInputError"]
    + list(_entities_all)
    + list(_lines_circles_all)
    + list(_versors_all)
    + ["translator", "rotor", "rotor_about_line", "motor", "screw"]
    + ["rotor_angle_axis", "decompose_motor", "motor_to_matrix", "matrix_to_motor"]
    + list(_versor_log_all)
    + list(_versor_powers_all)
    + list(_blades_all)
    + list(_blades_span_all)
    + list(_blades_classify_all)
    + list(_motor_estimation_all)
    + ["motor_from_lines"]
    + ["motor_between", "why_not_motor"]
    + ["fit_sphere", "fit_sphere_kasa", "fit_sphere_geometric", "fit_plane", "fit_plane_euclidean"]
    + ["fit_circle", "fit_circle_euclidean", "segment_planes", "fit_line", "LineFit"]
    + ["SphereFit", "PlaneFit", "CircleFit"]
    + ["SphereParameters", "PlaneParameters", "CircleParameters", "LineParameters", "ENTITY_PARAMETERS"]
)
