"""Fuzz cases of :mod:`cga_lessons.relocalization`: a tiny room of ten walls, scans of 90 beams, few particles."""

from __future__ import annotations

import numpy as np

from cga_lessons.mapping2d import CarmenLog, OdometryModel, Scene, simulate_scan
from cga_lessons.relocalization import (
    BeamModel,
    Candidate,
    CoverageFractions,
    Evaluation,
    EvaluationSummary,
    MCLConfig,
    MCLEstimate,
    MonteCarloLocalizer,
    ReferenceMap,
    Relocalization,
    Relocalizer,
    RelocParams,
    ThesisRelocalization,
    as_segment_array,
    combined_noise,
    correspondences_from_votes,
    estimate_range_noise,
    evaluate_log,
    evaluate_look_around,
    evaluate_poses,
    held_out_map_indices,
    hough_comparison,
    hough_differences,
    hough_set,
    kld_bound,
    look_around,
    pose_error,
    prepare_map,
    random_free_poses,
    reference_from_log,
    relocalize,
    relocalize_sequence,
    rotate_entities,
    scan_agreement,
    shifted_set,
    shifted_set_corrected,
    thesis_relocalization,
    transform_points,
    translate_entities,
    vote_matrix,
    vote_matrix_indexed,
)
from cga_lessons.relocalization.coverage import build_coverage
from cga_lessons.relocalization.mcl_search import SearchConfig
from cga_lessons.relocalization.sampling import KLDConfig
from conftest import wall_polygons  # the suite's own thin walls (tests/conftest.py)
from fuzz.harness import Case

_OUTLINE = np.array([[0, 0], [4, 0], [4, 1.5], [5, 1.5], [5, 3.5], [0, 3.5]], float)
_BOX = np.array([[1.0, 1.0], [1.6, 1.0], [1.6, 1.4], [1.0, 1.4]])
SCENE = Scene("tiny", wall_polygons(_OUTLINE) + [_BOX], np.zeros((1, 3)))
MAP = np.concatenate(
    [np.stack([_OUTLINE, np.roll(_OUTLINE, -1, axis=0)], axis=1), np.stack([_BOX, np.roll(_BOX, -1, axis=0)], axis=1)]
)
POSE = np.array([3.0, 2.2, 2.5])
POSE2 = np.array([3.0, 2.2, 2.5 + 1.5])
SCAN = simulate_scan(MAP, POSE, np.random.default_rng(0), n_beams=90)
SCAN2 = simulate_scan(MAP, POSE2, np.random.default_rng(1), n_beams=90)
RESULT = relocalize(MAP, scan=SCAN)
SCAN_SEGMENTS = RESULT.scan_segments
COVERAGE = build_coverage([SCAN, SCAN2], [POSE, POSE2], max_range=5.0)
REF = prepare_map(MAP)
M_H = hough_set(MAP)
L_H = hough_set(SCAN_SEGMENTS)
SMALL_KLD = KLDConfig(n_min=20, n_max=60)
MCL_CONFIG = MCLConfig(kld=SMALL_KLD, search=SearchConfig(cell=0.4))
QUICK_MCL = MCLConfig(kld=SMALL_KLD, search=None, hough=False)

_LOG_POSES = np.array([[1.0, 0.5, 0.3], [2.5, 2.5, -2.0], [4.5, 2.0, 2.8], [3.0, 2.2, 2.5]])
_LOG_SCANS = [simulate_scan(MAP, p, np.random.default_rng(i), n_beams=90) for i, p in enumerate(_LOG_POSES)]
LOG = CarmenLog(
    np.array([s[0] for s in _LOG_SCANS]),
    _LOG_SCANS[0][1],
    _LOG_POSES.copy(),
    _LOG_POSES.copy(),
    np.arange(4.0),
)


def _rng():
    return np.random.default_rng(0)


def _mcl(config=QUICK_MCL, **kw):
    return MonteCarloLocalizer(MAP, config=config, rng=0, **kw)


def _relocalizer(*scans):
    loc = Relocalizer(MAP)
    for scan, pose in scans:
        loc.add(scan, pose)
    return loc


# the results and configurations, as the package builds them
_CANDIDATE = dict(pose=POSE.copy(), score=0.9, inliers=80.0, violations=2.0)
_RELOCALIZATION = dict(
    pose=POSE.copy(),
    score=0.9,
    status="ok",
    candidates=[Candidate(**_CANDIDATE)],
    correspondences=np.array([[0, 1], [2, 0]]),
    scan_segments=SCAN_SEGMENTS.copy(),
    rotations=np.array([2.5]),
    n_hypotheses=4,
    covariance=np.diag([1e-4, np.inf, 1e-6]),  # inf: along a direction the scan does not fix (a corridor)
    range_noise=0.01,
    message="",
)
_FAILED = dict(pose=None, score=-np.inf, status="failed", message="too few lines in the scan (1)")
_ESTIMATE = dict(
    pose=POSE.copy(),
    covariance=np.eye(3) * 1e-4,
    converged=False,
    mass=0.9,
    n_particles=60,
    ess=12.0,
    hough_status="ok",
    fit=float("nan"),
    streak=1,
    anchored=False,
    confirmations=1,
)
_EVALUATION = dict(
    truth=np.array([POSE, POSE2]),
    pose=np.array([POSE, [np.nan] * 3]),
    status=np.array(["ok", "failed"]),
    position_error=np.array([0.01, np.inf]),
    heading_error=np.array([0.001, np.inf]),
    n_lines=np.array([5, 1]),
    score=np.array([0.9, -np.inf]),
    witness=np.array([np.nan, np.nan]),
    seconds=np.array([0.01, 0.01]),
)
_WRONG_MAPS = [COVERAGE, SCENE]
_ZERO_LENGTH = np.array([[[1.0, 1.0], [1.0, 1.0]]])  # a segment whose ends coincide

CASES = [
    # ------------------------------------------------------------------ maps and geometry
    Case(prepare_map, dict(map_segments=MAP), kinds={"map_segments": [COVERAGE]}),
    Case(
        prepare_map,
        dict(map_segments=MAP, coverage=COVERAGE),
        name="prepare_map (coverage)",
        kinds={"coverage": [REF, SCENE]},
    ),
    Case(
        as_segment_array, dict(segments=MAP, allow_empty=False), strict=True, extra={"segments": [[[[0, 0], [0, 0]]]]}
    ),
    Case(
        ReferenceMap, lambda: dict(segments=MAP.copy(), lines=prepare_map(MAP).lines), kinds={"lines": [MAP, COVERAGE]}
    ),
    Case(pose_error, dict(pose=POSE.copy(), truth=POSE2.copy())),
    Case(transform_points, dict(points=SCAN_SEGMENTS[:, 0].copy(), pose=POSE.copy())),
    Case(estimate_range_noise, dict(ranges=SCAN[0].copy())),
    Case(
        combined_noise,
        dict(scan_noise=0.01, ref=prepare_map(MAP, COVERAGE)),
        strict=True,
        kinds={"ref": [MAP, COVERAGE]},
    ),
    # ------------------------------------------------------------------ relocalization
    Case(
        relocalize,
        dict(map_segments=MAP, scan=SCAN, max_range=5.0, params=RelocParams(), xi_theta=np.radians(3.0), min_score=0.0),
        strict=True,
        allow={"params": ("None",)},
        kinds={"map_segments": _WRONG_MAPS, "params": [MCL_CONFIG], "scan": [SCENE]},
        extra={"nonsense": [1.0], "map_segments": [_ZERO_LENGTH, np.concatenate([MAP, _ZERO_LENGTH])]},
    ),
    Case(
        relocalize,
        dict(map_segments=REF, scan_segments=SCAN_SEGMENTS, extraction={"xi": 0.03}, xi_rho=0.2),
        name="relocalize (segments)",
        strict=True,
        nonfinite_ok="no scan segment (an empty array) is a failed relocalization: score -inf, covariance inf",
        allow={"extraction": ("None",)},
        kinds={"map_segments": _WRONG_MAPS, "scan_segments": [SCENE]},
    ),
    Case(Relocalization, _RELOCALIZATION, strict=True),
    Case(Relocalization, _FAILED, name="Relocalization (failed)", strict=True, allow={"pose": ("None",)}),
    Case(Candidate, _CANDIDATE, strict=True),
    Case(
        Relocalizer,
        dict(
            map_segments=MAP,
            max_range=5.0,
            params=None,
            max_chains=8,
            keep_ratio=0.7,
            odometry_model=OdometryModel(),
            joint=True,
            window=3,
            xi_rho=0.2,
        ),
        strict=True,
        allow={"params": ("None",), "odometry_model": ("None",)},
        kinds={"map_segments": _WRONG_MAPS, "odometry_model": [BeamModel()]},
    ),
    Case(
        Relocalizer.add,
        lambda: {"self": _relocalizer(), "scan": SCAN, "odometry": POSE.copy()},
        label="Relocalizer.add",
        positional=("self",),
    ),
    Case(
        Relocalizer.add,
        lambda: {"self": _relocalizer((SCAN, POSE)), "scan": SCAN2, "odometry": POSE2.copy()},
        label="Relocalizer.add",
        name="Relocalizer.add (a second scan)",
        positional=("self",),
    ),
    Case(
        relocalize_sequence,
        dict(
            map_segments=MAP,
            scans=[SCAN, SCAN2],
            odometry=np.array([POSE, POSE2]),
            max_range=5.0,
            stop_when_confident=True,
            window=2,
        ),
        strict=True,
        kinds={"map_segments": _WRONG_MAPS},
    ),
    # ------------------------------------------------------------------ chapter 5 as printed
    Case(hough_set, dict(segments=MAP, origin=(0.5, -0.5)), extra={"segments": [[[[0, 0], [0, 0]]]]}),
    Case(hough_differences, dict(m=M_H[0].copy(), L_h=L_H.copy(), theta_xi=2 * np.pi / 100), strict=True),
    Case(shifted_set, dict(L_h=L_H.copy(), phi=hough_differences(M_H[0], L_H))),
    Case(shifted_set_corrected, dict(L_h=L_H.copy(), rotation=0.3, translation=np.array([0.5, -0.2])), strict=True),
    Case(
        hough_comparison,
        dict(M_h=M_H.copy(), psi=shifted_set(L_H, hough_differences(M_H[0], L_H)), theta_xi=0.06),
        strict=True,
    ),
    Case(vote_matrix, dict(M_h=M_H.copy(), L_h=L_H.copy(), xi_theta=0.05, xi_rho=0.2, theta_xi=0.06), strict=True),
    Case(
        vote_matrix_indexed, dict(M_h=M_H.copy(), L_h=L_H.copy(), xi_theta=0.05, xi_rho=0.2, theta_xi=0.06), strict=True
    ),
    Case(correspondences_from_votes, dict(V=np.array([[1, 5], [3, 1], [1, 1]]), min_votes=2), strict=True),
    Case(rotate_entities, dict(segments=SCAN_SEGMENTS.copy(), angle=0.4), strict=True),
    Case(translate_entities, dict(segments=SCAN_SEGMENTS.copy(), translation=np.array([0.3, -0.2])), strict=True),
    Case(
        ThesisRelocalization,
        lambda: dict(vars(thesis_relocalization(MAP, SCAN_SEGMENTS, xi_theta=0.05, xi_rho=0.2))),
        strict=True,
        allow={"rotated": ("None",), "placed": ("None",)},
    ),
    Case(
        thesis_relocalization,
        dict(
            map_segments=MAP,
            scan_segments=SCAN_SEGMENTS,
            xi_theta=0.05,
            xi_rho=0.2,
            theta_xi=0.06,
            min_votes=2,
            entities=True,
        ),
        strict=True,
    ),
    # ------------------------------------------------------------------ measuring
    Case(
        random_free_poses,
        lambda: dict(scene=SCENE, n=2, rng=_rng(), clearance=0.3),
        strict=True,
        kinds={"scene": [MAP]},
    ),
    Case(
        scan_agreement,
        dict(walls=MAP, pose_a=POSE.copy(), pose_b=np.array([POSE, POSE2]), tolerance=0.03, n_beams=30),
        strict=True,
    ),
    Case(
        evaluate_poses,
        lambda: dict(
            scene=SCENE,
            map_segments=MAP,
            poses=POSE[None].copy(),
            rng=_rng(),
            range_noise=0.01,
            max_range=5.0,
            n_beams=90,
            fov=np.pi,
            witness=True,
            xi_rho=0.2,
        ),
        strict=True,
        kinds={"scene": [MAP], "map_segments": _WRONG_MAPS},
    ),
    Case(
        look_around,
        lambda: dict(
            scene=SCENE,
            pose=POSE.copy(),
            rng=_rng(),
            looks=2,
            range_noise=0.01,
            max_range=5.0,
            n_beams=90,
            fov=np.pi,
            odometry_model=None,
        ),
        strict=True,
        allow={"odometry_model": ("None",)},
        kinds={"scene": [MAP, COVERAGE], "odometry_model": [BeamModel()]},
    ),
    Case(
        evaluate_look_around,
        lambda: dict(
            scene=SCENE,
            map_segments=MAP,
            poses=POSE[None].copy(),
            rng=_rng(),
            looks=2,
            stop_when_confident=True,
            range_noise=0.01,
            max_range=5.0,
            n_beams=90,
            fov=np.pi,
            odometry_model=None,
            witness=True,
        ),
        strict=True,
        allow={"odometry_model": ("None",)},
        kinds={"scene": [MAP], "map_segments": _WRONG_MAPS},
    ),
    Case(Evaluation, _EVALUATION),
    Case(
        EvaluationSummary,
        dict(
            n=10,
            success=6,
            confidently_wrong=0,
            ambiguous=3,
            indistinguishable=2,
            failed=1,
            success_rate=0.6,
            success_rate_distinguishable=0.75,
            median_ms=12.5,
        ),
        strict=True,
    ),
    Case(CoverageFractions, dict(unknown=0.5, free=0.3, wall=0.2), strict=True),
    Case(held_out_map_indices, dict(n=10, test_indices=np.array([3, 7]), exclude=1, map_step=2), strict=True),
    Case(
        reference_from_log,
        dict(log=LOG, indices=np.array([0, 1, 2]), max_range=5.0, coverage=True, builder=False),
        strict=True,
        kinds={"log": [SCENE]},
    ),
    Case(
        evaluate_log,
        dict(log=LOG, test_indices=np.array([3]), exclude=0, map_step=1, max_range=5.0, coverage=True, xi_rho=0.2),
        strict=True,
        allow={"max_range": ("None",)},
        kinds={"log": [SCENE]},
    ),
    # ------------------------------------------------------------------ Monte Carlo localization
    Case(kld_bound, dict(k=np.array([1.0, 2.0, 10.0]), epsilon=0.05, z=2.326), strict=True),
    Case(
        MonteCarloLocalizer,
        dict(
            map_segments=MAP,
            coverage=None,
            config=QUICK_MCL,
            rng=0,
            initial_pose=POSE.copy(),
            initial_sd=np.array([0.1, 0.1, 0.03]),
        ),
        strict=True,
        allow={"coverage": ("None",), "config": ("None",), "initial_pose": ("None",), "initial_sd": ("None",)},
        kinds={"map_segments": _WRONG_MAPS, "config": [RelocParams()], "coverage": [REF, SCENE]},
    ),
    Case(
        MonteCarloLocalizer.update,
        lambda: {"self": _mcl(), "odometry_increment": np.array([0.05, 0.0, 0.02]), "scan": SCAN},
        label="MonteCarloLocalizer.update",
        positional=("self",),
    ),
    Case(
        MonteCarloLocalizer.update,
        lambda: {"self": _mcl(MCL_CONFIG), "odometry_increment": np.zeros(3), "scan": SCAN},
        label="MonteCarloLocalizer.update",
        name="MonteCarloLocalizer.update (global, chapter 5)",
        positional=("self",),
    ),
    Case(
        MonteCarloLocalizer.estimate,
        lambda: {"self": _mcl()},
        label="MonteCarloLocalizer.estimate",
        positional=("self",),
    ),
    Case(MCLEstimate, _ESTIMATE, strict=True, allow={"fit": ("nan",)}),
    Case(
        MCLConfig,
        dict(
            beam=BeamModel(),
            odometry=OdometryModel(),
            kld=SMALL_KLD,
            ess_fraction=0.5,
            ess_floor=0.01,
            alpha_slow=0.05,
            alpha_fast=0.5,
            random_threshold=0.05,
            max_random_fraction=0.25,
            clearance=0.2,
            hough=True,
            search=SearchConfig(),
            proposal_fraction=0.2,
            proposal_sd=(0.05, 0.05, 0.02),
            proposal_candidates=12,
            history=3,
            gate=(0.5, 0.17),
            converged_mass=0.95,
            converged_sd=(0.1, 0.03),
            converged_updates=2,
            confirmations=2,
        ),
        strict=True,
        allow={"search": ("None",)},
        kinds={"beam": [OdometryModel()], "odometry": [BeamModel()], "kld": [SearchConfig()], "search": [SMALL_KLD]},
    ),
]

EXEMPT: dict[str, str] = {}
