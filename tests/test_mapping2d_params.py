"""The map builder's configuration, stage by stage (cga_lessons.mapping2d.params), and the extractor's settings."""

import dataclasses
import inspect

import numpy as np
import pytest

from cga_lessons.algebra import InvalidInputError
from cga_lessons.config import field_stage, stages
from cga_lessons.mapping2d import (
    CleanupParams,
    CorrectionParams,
    CorrespondenceParams,
    ExtractionParams,
    LoopParams,
    MapParams,
    OdometryPriorParams,
    build_map,
    extract_segments,
    load_scene,
    simulate_scans,
)

# Every field of the flat MapParams of before the stages: each must still name one field of one stage.  Fields
# added since are in NEW_NAMES.
FLAT_NAMES = """delta theta_xi xi_d xi_m overlap_margin t_xi theta_max n_iterations range_noise significance
estimate_odometry robust_kernel registration_xy registration_theta angle_floor offset_floor estimate_floors gate
consensus_angle odo_sigma_xy odo_sigma_heading odo_sigma_turn odo_heading_bias edge_match edge_sigma dup_angle
dup_distance cleanup_every support_distance neighbourhood active_path loop_closure loop_every loop_angle_tol
loop_shift_tol loop_max_angle loop_max_shift loop_min_lines loop_min_support loop_max_sigma loop_ambiguity
graph_sigma_xy graph_sigma_theta adjust learn_lag""".split()
NEW_NAMES = ["graph_horizon"]


def test_every_flat_name_of_before_names_one_field_of_one_stage():
    owner = field_stage(MapParams)
    assert stages(MapParams) == {
        "correspondence": CorrespondenceParams,
        "correction": CorrectionParams,
        "odometry_prior": OdometryPriorParams,
        "loops": LoopParams,
        "cleanup": CleanupParams,
    }
    assert len(FLAT_NAMES) == 45
    for name in FLAT_NAMES + NEW_NAMES:
        assert owner.get(name) in stages(MapParams), name
    fields = [f.name for stage in stages(MapParams).values() for f in dataclasses.fields(stage)]
    assert sorted(fields) == sorted(FLAT_NAMES + NEW_NAMES)  # no field lost, none added unlisted, none shared


def test_stages_check_their_fields_and_the_configuration_its_stages():
    with pytest.raises(InvalidInputError, match="CorrectionParams: significance: must be < 1.0"):
        CorrectionParams(significance=1.0)
    with pytest.raises(InvalidInputError, match="LoopParams: loop_max_angle: must be <= "):
        LoopParams(loop_max_angle=4.0)
    with pytest.raises(InvalidInputError, match="CleanupParams: cleanup_every: must be >= 0"):
        CleanupParams(cleanup_every=-1)
    with pytest.raises(InvalidInputError, match="MapParams: loops: expected a LoopParams"):
        MapParams(loops=CleanupParams())
    assert LoopParams(loop_max_shift=np.inf).loop_max_shift == np.inf  # no bound
    assert OdometryPriorParams(odo_heading_bias=-0.01).odo_heading_bias == -0.01  # a drift either way


def _room(n=12):
    room = load_scene("room")
    truth = room.trajectory[:n]
    return simulate_scans(room, truth, np.random.default_rng(1)), truth + [0.02, -0.01, 0.003]


def test_build_map_takes_a_stage_a_dict_of_its_fields_or_a_field_alike():
    scans, odometry = _room()
    runs = [
        build_map(scans, odometry, loop_closure=False, gate=4.0),
        build_map(scans, odometry, loops={"loop_closure": False}, correction=CorrectionParams(gate=4.0)),
        build_map(scans, odometry, params=MapParams(loops=LoopParams(loop_closure=False)), gate=4.0),
    ]
    for res in runs[1:]:
        assert np.array_equal(res.poses, runs[0].poses)
        assert [s.start.tolist() for s in res.segments] == [s.start.tolist() for s in runs[0].segments]
    with pytest.raises(InvalidInputError, match="build_map: nonsense: unknown parameter"):
        build_map(scans, odometry, nonsense=1)
    with pytest.raises(InvalidInputError, match=r"build_map: loops.loop_every: .*said by LoopParams"):
        build_map(scans, odometry, loops={"loop_every": -1.0})


def test_extraction_settings_are_one_dataclass_whose_defaults_are_extract_segments():
    defaults = inspect.signature(extract_segments).parameters
    for f in dataclasses.fields(ExtractionParams):
        assert defaults[f.name].default == f.default, f.name
    with pytest.raises(InvalidInputError, match="ExtractionParams: min_points: must be >= 2"):
        ExtractionParams(min_points=1)
    scans, odometry = _room(6)
    as_dict = build_map(scans, odometry, extraction={"min_points": 4})
    as_params = build_map(scans, odometry, extraction=ExtractionParams(min_points=4))  # max_range: build_map's 5 m
    assert np.array_equal(as_dict.poses, as_params.poses) and len(as_dict.segments) == len(as_params.segments)
    with pytest.raises(InvalidInputError, match="build_map: extraction: xi: must be > 0"):
        build_map(scans, odometry, extraction={"xi": 0.0})


def test_stages_hold_their_fields_as_plain_numbers_as_relocalizations_stages_do():
    # checks.record converts as it checks: a whole float count becomes an int, a NumPy number a float, and an
    # optional field left None stays None
    from cga_lessons.relocalization import RelocSearch

    c = CorrectionParams(n_iterations=3.0, gate=np.float64(4.0), range_noise=None)
    assert type(c.n_iterations) is int and c.n_iterations == 3
    assert type(c.gate) is float and c.gate == 4.0 and c.range_noise is None
    assert type(LoopParams(loop_max_shift=np.float64(np.inf)).loop_max_shift) is float
    assert type(ExtractionParams(min_points=7.0).min_points) is int
    assert type(RelocSearch(n_rotations=8.0).n_rotations) is int
    with pytest.raises(InvalidInputError, match="CorrectionParams: n_iterations"):
        CorrectionParams(n_iterations=2.5)
