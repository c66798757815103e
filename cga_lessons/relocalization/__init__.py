"""Chapter 5: relocalization in a known line map by voting in Hough space, made to work on real logs, and the Monte
Carlo localization of the future work (6.3.2).

Layer 4 of the package: imports layers 0-3 only (``tests/test_layers.py`` checks it). Nothing here draws (figures
and widgets are in :mod:`cga_lessons.viz`).  This facade exports the names in ``__all__``; its modules:

* :mod:`~cga_lessons.relocalization.beam`: The laser beam model of the Monte Carlo localization: its parameters, and
  its likelihood for one beam
* :mod:`~cga_lessons.relocalization.candidates`: The steps of :func:`cga_lessons.relocalization.relocalize` after
  the hypotheses: candidates screened, verified, ranked and decided
* :mod:`~cga_lessons.relocalization.chain`: Chains of poses, one per scan, fitted to their scans and to the odometry
  between them at once.  (Beyond chapter 5.)
* :mod:`~cga_lessons.relocalization.chain_evidence`: What the scans taken so far say about a chain of poses: its
  beam counts per scan, the direction they fix least, the chain slid along it, and the decision
* :mod:`~cga_lessons.relocalization.coverage`: What a map knows: the space its own scans swept free and the places
  they hit, as a coverage grid
* :mod:`~cga_lessons.relocalization.eval`: Measuring the relocalization: random poses in a scene, and held-out scans
  of a real log
* :mod:`~cga_lessons.relocalization.evaluation`: The terms of a measured relocalization: the tolerances, the per-pose
  Evaluation, scan agreement
* :mod:`~cga_lessons.relocalization.geometry`: Geometry for the relocalization: inputs, map and scan lines as
  arrays, ray casting against a line map
* :mod:`~cga_lessons.relocalization.history`: What the last scans say of a pose the particle filter never held: the
  prior weight of new particles
* :mod:`~cga_lessons.relocalization.hough`: Chapter 5 as printed: relocalization by voting in Hough space (Eqs.
  5.1-5.6, steps 1-10)
* :mod:`~cga_lessons.relocalization.inputs`: Checks of the relocalization's arguments that the shared layer lacks,
  composed from :mod:`cga_lessons.checks`
* :mod:`~cga_lessons.relocalization.likelihood`: A likelihood field of a line map, and a laser beam model on it,
  vectorised over particles x beams
* :mod:`~cga_lessons.relocalization.logmap`: A line map from scans at known poses, for measuring the relocalization
  on real logs
* :mod:`~cga_lessons.relocalization.lookaround`: Measuring relocalization from a look around: the robot turns on the
  spot and scans again
* :mod:`~cga_lessons.relocalization.mcl`: Monte Carlo localization in a line map: the relocalization with
  probability terms (thesis, section 6.3.2)
* :mod:`~cga_lessons.relocalization.mcl_config`: The settings of
  :class:`~cga_lessons.relocalization.mcl.MonteCarloLocalizer`, each default with its reason
* :mod:`~cga_lessons.relocalization.mcl_proposal`: Chapter 5's relocalizer as the particle filter's proposal, and
  the test that confirms a mode with it
* :mod:`~cga_lessons.relocalization.mcl_search`: An exhaustive coarse search of one scan over the whole map: the
  global proposal of the particle filter
* :mod:`~cga_lessons.relocalization.odometry`: Does a chain of relocalized poses move as the odometry says?  (Beyond
  chapter 5.)
* :mod:`~cga_lessons.relocalization.params`: The thresholds of :func:`~cga_lessons.relocalization.relocalize`, by
  stage, each field checked where it is set
* :mod:`~cga_lessons.relocalization.relocalizer`: Relocalization in a known line map (thesis chapter 5, Eqs.
  5.1-5.6), made to work
* :mod:`~cga_lessons.relocalization.sampling`: Resampling a particle set: low-variance resampling to a size chosen
  by KLD sampling, and the main mode
* :mod:`~cga_lessons.relocalization.search`: Pose hypotheses for the relocalization: rotations from angle votes,
  exact translations from line pairs
* :mod:`~cga_lessons.relocalization.sequence`: Relocalization from a sequence of scans: keep every candidate until
  the scans tell them apart
* :mod:`~cga_lessons.relocalization.thesis`: Chapter 5 as printed, steps 6-10: correspondences from the votes,
  rotor, least squares, translator
* :mod:`~cga_lessons.relocalization.verify`: Checking and refining a relocalization hypothesis against the whole
  scan
"""

from .beam import BeamModel
from .candidates import Candidate
from .coverage import CoverageFractions
from .eval import evaluate_log, evaluate_poses, held_out_map_indices, random_free_poses, reference_from_log
from .evaluation import HEADING_TOLERANCE, POSITION_TOLERANCE, Evaluation, EvaluationSummary, scan_agreement
from .geometry import ReferenceMap, estimate_range_noise, pose_error, prepare_map, transform_points
from .hough import (
    hough_comparison,
    hough_differences,
    hough_set,
    shifted_set,
    shifted_set_corrected,
    vote_matrix,
    vote_matrix_indexed,
)
from .inputs import as_segment_array
from .lookaround import evaluate_look_around, look_around
from .mcl import MCLEstimate, MonteCarloLocalizer
from .mcl_config import MCLConfig
from .params import RelocCheck, RelocParams, RelocSearch
from .relocalizer import Relocalization, combined_noise, relocalize
from .sampling import kld_bound
from .sequence import Relocalizer, relocalize_sequence
from .thesis import (
    ThesisRelocalization,
    correspondences_from_votes,
    rotate_entities,
    thesis_relocalization,
    translate_entities,
)

__all__ = [
    "MonteCarloLocalizer",
    "MCLConfig",
    "MCLEstimate",
    "RelocParams",
    "RelocSearch",
    "RelocCheck",
    "Candidate",
    "Relocalization",
    "ReferenceMap",
    "prepare_map",
    "as_segment_array",
    "relocalize",
    "pose_error",
    "estimate_range_noise",
    "combined_noise",
    "HEADING_TOLERANCE",
    "POSITION_TOLERANCE",
    "hough_set",
    "relocalize_sequence",
    "shifted_set_corrected",
    "transform_points",
    "BeamModel",
    "Evaluation",
    "EvaluationSummary",
    "CoverageFractions",
    "ThesisRelocalization",
    "Relocalizer",
    "correspondences_from_votes",
    "evaluate_log",
    "evaluate_look_around",
    "evaluate_poses",
    "held_out_map_indices",
    "hough_comparison",
    "hough_differences",
    "kld_bound",
    "look_around",
    "random_free_poses",
    "reference_from_log",
    "rotate_entities",
    "scan_agreement",
    "shifted_set",
    "thesis_relocalization",
    "translate_entities",
    "vote_matrix",
    "vote_matrix_indexed",
]
