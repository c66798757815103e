"""Appendix A and section 4.1: pinhole cameras, two-view geometry, the robot's stereo head and conformal entities
reconstructed and detected from its points.

Layer 3 of the package: imports layers 0-2 (errors, algebra, conformal) only (``tests/test_layers.py`` checks it).
Nothing here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in
``__all__``; its modules:

* :mod:`~cga_lessons.stereo.accuracy`: The accuracy of reconstructed entities: their errors against the truth
  (section 4.1)
* :mod:`~cga_lessons.stereo.camera`: Pinhole cameras and triangulation (appendix A of the thesis, Eqs. A.1-A.5 and
  A.14)
* :mod:`~cga_lessons.stereo.detect`: Automatic registration of conformal entities in a 3D point cloud (the thesis's
  future work, 6.2.2)
* :mod:`~cga_lessons.stereo.detect_ml`: Maximum-likelihood refinement of a detected entity, and the covariance of
  its parameters
* :mod:`~cga_lessons.stereo.detect_models`: The four kinds of entity a detector looks for: hypotheses, residuals and
  fits (section 4.1, table 2.1)
* :mod:`~cga_lessons.stereo.detect_params`: The parameters of a detected (or true) entity:
  :mod:`cga_lessons.conformal`'s records, a true patch's sides, and the helpers the detector uses on them
* :mod:`~cga_lessons.stereo.detect_noise`: The noise model of entity detection: per-point covariances, chi-square
  gates, Mahalanobis residuals
* :mod:`~cga_lessons.stereo.detect_scenes`: Test scenes with ground truth for entity detection: entities placed in
  front of a stereo head, and clutter
* :mod:`~cga_lessons.stereo.detect_scores`: The scoring of entity detections against a scene's ground truth:
  position errors, matches, precision and recall
* :mod:`~cga_lessons.stereo.detect_search`: The search behind :func:`cga_lessons.stereo.detect.detect_entities`: one
  round of RANSAC, model selection,
* :mod:`~cga_lessons.stereo.entities`: The objects of section 4.1 as typed records: points, a point pair, a line, a
  circle, a plane and a sphere
* :mod:`~cga_lessons.stereo.epipolar`: Two-view geometry: the fundamental matrix and cameras from it (appendix A.2,
  Eqs. A.6-A.13)
* :mod:`~cga_lessons.stereo.experiments`: The numerical experiments of the stereo notebook (appendix A and section
  4.1), seeded and repeatable
* :mod:`~cga_lessons.stereo.head`: A synthetic stereo head, its scene, and conformal entities from two views
  (section 4.1)
* :mod:`~cga_lessons.stereo.polylines`: Drawing the entities of section 4.1: the segment of a line, a circle and a
  plane's square as polylines
* :mod:`~cga_lessons.stereo.real`: Real stereo data: the Middlebury 2014 motorcycle pair shipped with scikit-image
* :mod:`~cga_lessons.stereo.reconstruct`: The conformal entities of section 4.1 rebuilt from a stereo pair:
  triangulated minimal point sets (A.14) and the point, point pair, line, circle, plane and sphere through them in
  G(4,1)
* :mod:`~cga_lessons.stereo.render`: What the stereo head's two cameras see, drawn with OpenCV (for the notebook of
  section 4.1)
* :mod:`~cga_lessons.stereo.rig`: The robot's stereo head: two calibrated pinhole cameras (appendix A, used by
  section 4.1)
* :mod:`~cga_lessons.stereo.triangulation`: Triangulation: the point two cameras' rays meet at (appendix A of the
  thesis, Eq. A.14 and figure A.4)
* :mod:`~cga_lessons.stereo.validate`: The stereo package's argument checks, composed from the shared checking layer
  (:mod:`cga_lessons.checks`)
"""

from .accuracy import CircleError, LineError, PlaneError, PositionError, SphereError, entity_errors
from .camera import camera_center, optical_planes, project, projection_matrix_rt
from .detect import DetectConfig, detect_entities
from .detect_noise import triangulation_covariance
from .detect_params import PatchParameters
from .detect_scenes import KINDS, SceneConfig, TruthEntity, scene_rig, stereo_scene
from .detect_scores import DetectionError, DetectionMatch, DetectionScore, KindScore, evaluate
from .detect_search import DetectedEntity, SelectionEvidence
from .entities import SceneCircle, SceneLine, ScenePair, ScenePlane, ScenePoints, SceneSphere
from .epipolar import (
    cameras_from_fundamental,
    eight_point_matrix,
    epipolar_distance,
    epipolar_lines,
    epipoles,
    fundamental_8point,
)
from .experiments import (
    EntityErrorRow,
    FundamentalRow,
    TriangulationCurve,
    entity_error_table,
    format_table,
    fundamental_comparison,
    random_points_in_view,
    triangulation_error_curve,
)
from .head import StereoScene, load_scene, observe, random_scene, sample_scene
from .polylines import circle_polyline, line_polyline, square_polyline
from .real import MOTORCYCLE_CALIBRATION, disparity_to_points, label_image, load_motorcycle, motorcycle_cameras
from .reconstruct import circle_center_via_plane, reconstruct_entities
from .render import render_views
from .rig import StereoRig, load_rig, look_at_rotation, random_rig, rotation_matrix, stereo_head
from .triangulation import closest_points_on_rays, triangulate

__all__ = [
    "StereoRig",
    "StereoScene",
    "stereo_head",
    "random_rig",
    "load_rig",
    "load_scene",
    "random_scene",
    "sample_scene",
    "observe",
    "reconstruct_entities",
    "circle_center_via_plane",
    "entity_errors",
    "line_polyline",
    "circle_polyline",
    "square_polyline",
    "rotation_matrix",
    "look_at_rotation",
    "label_image",
    "closest_points_on_rays",
    "epipolar_lines",
    "project",
    "triangulate",
    "DetectConfig",
    "KINDS",
    "MOTORCYCLE_CALIBRATION",
    "SceneConfig",
    "camera_center",
    "cameras_from_fundamental",
    "detect_entities",
    "disparity_to_points",
    "eight_point_matrix",
    "entity_error_table",
    "epipolar_distance",
    "epipoles",
    "evaluate",
    "format_table",
    "fundamental_8point",
    "fundamental_comparison",
    "load_motorcycle",
    "motorcycle_cameras",
    "optical_planes",
    "projection_matrix_rt",
    "random_points_in_view",
    "render_views",
    "scene_rig",
    "stereo_scene",
    "triangulation_covariance",
    "triangulation_error_curve",
    "TriangulationCurve",
    "FundamentalRow",
    "EntityErrorRow",
    "ScenePoints",
    "ScenePair",
    "SceneLine",
    "SceneCircle",
    "ScenePlane",
    "SceneSphere",
    "PositionError",
    "LineError",
    "PlaneError",
    "CircleError",
    "SphereError",
    "DetectedEntity",
    "SelectionEvidence",
    "TruthEntity",
    "PatchParameters",
    "DetectionError",
    "DetectionMatch",
    "KindScore",
    "DetectionScore",
]
