"""Chapter 3: the 2D laser line map, plain (3.1-3.12) and with conformal point pairs (3.13-3.21), with the laser logs,
lines, corrections, loop closure and the trajectory measures around it.

Layer 3 of the package: imports layers 0-2 (errors, algebra, conformal) only (``tests/test_layers.py`` checks it).
Nothing here draws (figures and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in
``__all__``; its modules:

* :mod:`~cga_lessons.mapping2d.adjust`: All the poses and all the map lines estimated together from every
  observation (beyond section 3.1)
* :mod:`~cga_lessons.mapping2d.adjust_rows`: The rows of the final adjustment: what each measurement says and how
  it moves with the unknowns
* :mod:`~cga_lessons.mapping2d.carmen`: Laser logs in the CARMEN text format (chapter 3, section 3.1): their
  FLASER lines as scans and poses
* :mod:`~cga_lessons.mapping2d.build`: Line maps from laser scans and odometry (thesis sections 3.1.2-3.1.4, Eqs.
  3.4-3.12), with loop closure
* :mod:`~cga_lessons.mapping2d.builder`: The incremental line-map builder behind
  :func:`cga_lessons.mapping2d.build_map` (sections 3.1.2-3.1.4)
* :mod:`~cga_lessons.mapping2d.conformal`: Line maps with conformal point pairs and motors: the entities (thesis
  section 3.2, Eqs. 3.13-3.17)
* :mod:`~cga_lessons.mapping2d.conformal_geometry`: Line maps with conformal point pairs and motors, the map
  builder's side (thesis section 3.2, Eq. 3.18-3.21): ConformalGeometry and the five cases of figure 3.5
* :mod:`~cga_lessons.mapping2d.correction`: The correction of one scan's pose against line segments (thesis section
  3.1.3, Eqs. 3.5-3.12), as an estimator
* :mod:`~cga_lessons.mapping2d.corrections`: Heading and position corrections of the 2D line map (thesis section
  3.1.3, Eqs. 3.6-3.12)
* :mod:`~cga_lessons.mapping2d.extraction`: The settings of the segment extractor (thesis section 3.1.1):
  :class:`ExtractionParams`
* :mod:`~cga_lessons.mapping2d.fusion`: The fusion of one segment into a map line (sections 3.1.4, 3.2.4, Eqs.
  3.20-3.21), with real edges
* :mod:`~cga_lessons.mapping2d.estimation`: The per-scan pose correction as a robust estimate with a prior, and the
  test that admits it (beyond 3.1.3)
* :mod:`~cga_lessons.mapping2d.eval`: Errors of a trajectory and of a line map against the truth (for chapter 3's
  result tables)
* :mod:`~cga_lessons.mapping2d.geometry`: Segments, their geometry and their correspondence for the 2D line map
  (sections 3.1.2, 3.2; Eqs. 3.3-3.5)
* :mod:`~cga_lessons.mapping2d.graph`: A pose graph for the 2D line map: poses tied by relative-pose measurements,
  relaxed by sparse least squares
* :mod:`~cga_lessons.mapping2d.hypotheses`: Revisit hypotheses for loop closure: rigid motions that lay the recent
  map lines on the old ones
* :mod:`~cga_lessons.mapping2d.index`: A spatial index of the 2D line map: a uniform grid of buckets over the boxes
  of the map's segments
* :mod:`~cga_lessons.mapping2d.inputs`: The argument checks of the 2D line map that the shared layer
  (:mod:`cga_lessons.checks`) lacks, built on it
* :mod:`~cga_lessons.mapping2d.laser`: A 2D laser scanner, robot odometry and laser log reading (chapter 3, section
  3.1)
* :mod:`~cga_lessons.mapping2d.laser_facts`: What a laser log says about its laser: the values its driver writes for
  "no return", and how far it returns
* :mod:`~cga_lessons.mapping2d.least_squares`: Robust sparse least squares for the final adjustment: the kernels'
  weights, and the solve of sparse positive definite normal equations
* :mod:`~cga_lessons.mapping2d.lines`: Line segments from laser scans (thesis section 3.1.1, equations 3.1-3.5)
* :mod:`~cga_lessons.mapping2d.loops`: Loop closure for the 2D line map: revisits found by matching lines, a pose
  graph relaxed by least squares
* :mod:`~cga_lessons.mapping2d.noise`: The noise model of the 2D line map, estimated from the data as the map is
  built (beyond chapter 3)
* :mod:`~cga_lessons.mapping2d.observations`: What the 2D line map was built from: every scan's local segments, kept
  so that the map can be refitted
* :mod:`~cga_lessons.mapping2d.params`: The thresholds of the 2D line-map builder
  (:func:`cga_lessons.mapping2d.build_map`), stage by stage, with the thesis's meaning
* :mod:`~cga_lessons.mapping2d.poses`: Planar poses ``(x, y, theta)``: their composition (the rigid motion 3.4),
  inverse and difference, and angle wrapping
* :mod:`~cga_lessons.mapping2d.run`: One build of the 2D line map, scan by scan: the loop of
  :func:`cga_lessons.mapping2d.build_map`
* :mod:`~cga_lessons.mapping2d.scan_points`: A scan's returns as points: in the laser frame, and a sequence of scans
  placed in the world with their poses
* :mod:`~cga_lessons.mapping2d.scan_registration`: Two laser scans registered by the motor that fits their
  corresponding points (iterative closest points)
* :mod:`~cga_lessons.mapping2d.segment`: Lines and line segments of the 2D map (thesis section 3.1.1, equations
  3.1-3.3): the :class:`Segment` structure
* :mod:`~cga_lessons.mapping2d.support`: How points lie on map segments: their distances, and the score that
  checks a correction and verifies a revisit
* :mod:`~cga_lessons.mapping2d.trajectories`: Planar trajectory evaluation: absolute and relative pose errors
  (chapter 3's maps, measured the field's way)
* :mod:`~cga_lessons.mapping2d.tum`: TUM trajectory files: the text format of ``evo`` and most SLAM evaluation
  tools, written and read
"""

from .build import MapResult, build_map
from .builder import MapBuilder
from .carmen import CarmenLog, read_carmen_log
from .conformal import (
    PointPairStructure,
    c2e,
    e2c,
    laser_motor,
    point_pair_structure,
    robot_motor,
    segment_point_pair,
)
from .conformal_geometry import ConformalGeometry, sphere_case
from .corrections import line_variances, pose_correction, theta_correction, translation_correction
from .eval import format_log_benchmark, map_errors, map_point_errors, pose_errors, read_log_benchmark
from .extraction import ExtractionParams
from .geometry import PlainGeometry, SegmentSet, correspondences, proximity_matrix
from .graph import PoseGraph
from .laser import (
    OdometryModel,
    Scene,
    load_scene,
    simulate_odometry,
    simulate_scan,
    simulate_scans,
)
from .laser_facts import returns_reach
from .lines import diff_theta, diff_theta_as_printed, extract_segments, split_points
from .params import (
    CleanupParams,
    CorrectionParams,
    CorrespondenceParams,
    LoopParams,
    MapParams,
    OdometryPriorParams,
)
from .poses import compose, invert, relative, wrap_angle
from .scan_points import scan_points, scans_to_world
from .scan_registration import register_scans
from .segment import TWO_PI, Segment
from .trajectories import absolute_trajectory_error, odometry_repeats_poses, relative_pose_error
from .tum import write_tum

__all__ = [
    "MapParams",
    "CorrespondenceParams",
    "CorrectionParams",
    "OdometryPriorParams",
    "LoopParams",
    "CleanupParams",
    "ExtractionParams",
    "MapResult",
    "build_map",
    "proximity_matrix",
    "correspondences",
    "theta_correction",
    "translation_correction",
    "pose_correction",
    "line_variances",
    "pose_errors",
    "map_errors",
    "map_point_errors",
    "read_log_benchmark",
    "format_log_benchmark",
    "PlainGeometry",
    "SegmentSet",
    "MapBuilder",
    "PoseGraph",
    "OdometryModel",
    "Scene",
    "Segment",
    "TWO_PI",
    "absolute_trajectory_error",
    "compose",
    "diff_theta",
    "extract_segments",
    "invert",
    "odometry_repeats_poses",
    "read_carmen_log",
    "relative",
    "relative_pose_error",
    "returns_reach",
    "robot_motor",
    "simulate_odometry",
    "simulate_scan",
    "wrap_angle",
    "write_tum",
    "ConformalGeometry",
    "laser_motor",
    "load_scene",
    "scan_points",
    "segment_point_pair",
    "CarmenLog",
    "c2e",
    "diff_theta_as_printed",
    "e2c",
    "point_pair_structure",
    "PointPairStructure",
    "register_scans",
    "scans_to_world",
    "simulate_scans",
    "sphere_case",
    "split_points",
]
