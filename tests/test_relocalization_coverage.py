"""Relocalization on partial maps: the coverage grid, the scans-at-poses line map, the deficit tie rule,
and held-out scans of the Intel log against the true poses."""

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.mapping2d import CarmenLog, read_carmen_log
from cga_lessons.mapping2d.laser import simulate_odometry
from cga_lessons.relocalization import RelocCheck, prepare_map, relocalize
from cga_lessons.relocalization import verify as verify
from cga_lessons.relocalization.candidates import tie_bar
from cga_lessons.relocalization.coverage import FREE, UNKNOWN, WALL, build_coverage, map_noise
from cga_lessons.relocalization.eval import evaluate_log, held_out_map_indices, reference_from_log
from cga_lessons.relocalization.geometry import Observation, pose_error
from cga_lessons.relocalization.logmap import merge_segments, robust_end
from cga_lessons.relocalization.lookaround import evaluate_log_sequences
from cga_lessons.relocalization.verify import score_poses

# --------------------------------------------------------------------------- the coverage grid


def test_one_beam_sweeps_free_to_its_point_and_marks_the_wall():
    # two beams: 2 m along x, and one without return backwards (it sweeps -x only)
    scan = (np.array([2.0, np.inf]), np.array([0.0, np.pi]))
    cov = build_coverage([scan], [[0.01, 0.01, 0.0]], max_range=5.0, resolution=0.05)
    xs = np.arange(0.035, 3.0, 0.05)  # cell centres along the beam
    state = cov.classify(np.column_stack([xs, np.full_like(xs, 0.01)]))
    free_until = 2.01 - 0.1  # clearance
    assert np.all(state[xs < free_until - 0.05] == FREE)
    assert np.all(state[np.abs(xs - 2.01) < 0.05] == WALL)  # the hit's cell and its neighbours
    assert np.all(state[xs > 2.12] == UNKNOWN)  # behind the wall nobody looked
    assert cov.classify([[0.0, 1.0], [1e6, 0.0]]).tolist() == [UNKNOWN, UNKNOWN]  # beside the beam; off the grid


def test_a_beam_without_return_sweeps_free_to_max_range():
    pose = [1.01, 2.01, 0.0]
    cov = build_coverage([(np.array([np.inf, 30.0]), np.array([0.0, np.pi / 2]))], [pose], max_range=4.0)
    along_x = cov.classify([[1.01 + d, 2.01] for d in (0.5, 3.9, 4.2)]).tolist()
    along_y = cov.classify([[1.01, 2.01 + d] for d in (0.5, 3.9, 4.2)]).tolist()  # 30 m: beyond max_range
    assert along_x == along_y == [FREE, FREE, UNKNOWN]
    f = cov.fractions()
    assert f.wall == 0.0 and f.unknown + f.free + f.wall == pytest.approx(1.0)


def test_map_noise_recovers_the_spread_of_points_about_their_wall():
    rng = np.random.default_rng(3)
    wall = np.array([[[3.0, -5.0], [3.0, 5.0]]])
    angles = np.radians(np.linspace(-10, 10, 41))  # nearly square on: perpendicular error ~ range error
    poses = np.zeros((60, 3))
    scans = [(3.0 / np.cos(angles) + rng.normal(0.0, 0.02, angles.size), angles) for _ in poses]
    assert map_noise(scans, poses, wall, max_range=8.0, step=1) == pytest.approx(0.02, rel=0.12)


@pytest.fixture(scope="module")
def square_room():
    """A 4 m x 4 m room; the map knows three walls (not the east one) and was scanned facing away from it."""
    walls = np.array([[[0, 0], [4, 0]], [[4, 0], [4, 4]], [[4, 4], [0, 4]], [[0, 4], [0, 0]]], float)  # S, E, N, W
    centre = np.array([2.0, 2.0, 0.0])
    a = np.radians(np.arange(60.0, 300.0, 1.0))  # the mapping scan misses the east quarter
    r = np.array([_range_in_square(centre, t) for t in a])
    cov = build_coverage([(r, a)], centre[None], max_range=8.0)
    ref = prepare_map(walls[[0, 2, 3]], cov)
    a_test = np.radians(np.arange(-179.5, 180.0, 1.0))
    scan = (np.array([_range_in_square(centre, t) for t in a_test]), a_test)
    return walls, centre, ref, scan


def _range_in_square(pose, angle, size=4.0):
    d = np.array([np.cos(angle), np.sin(angle)])
    with np.errstate(divide="ignore"):
        t = [(size - pose[i]) / d[i] if d[i] > 0 else -pose[i] / d[i] if d[i] < 0 else np.inf for i in (0, 1)]
    return min(t)


def test_beams_into_a_hole_of_the_map_are_neither_for_nor_against(square_room, monkeypatch):
    walls, centre, ref, scan = square_room
    obs = Observation.from_scan(*scan, 8.0)
    east = np.abs(np.arctan2(obs.points[:, 1], obs.points[:, 0])) < np.pi / 4
    no_cov = prepare_map(ref.segments)
    s0, inl0, vio0 = score_poses(no_cov.lines, obs, centre[None], 0.06, 0.08)
    # without coverage the beams on the unmapped east wall are in the count but explained by nothing
    assert s0[0] == pytest.approx(1 - east.mean(), abs=0.01) and vio0[0] == 0
    # with it (MIN_KNOWN = 1) they end in unknown space: unexplained, not violations
    s1, inl1, vio1 = score_poses(ref.lines, obs, centre[None], 0.06, 0.08)
    assert s1[0] == pytest.approx(1 - east.mean(), abs=0.01) and vio1[0] == 0
    # a wrong pose still scores low: its beams end where the mapping scan looked through
    wrong = centre + np.array([0.5, 0.3, 0.0])
    assert score_poses(ref.lines, obs, wrong[None], 0.06, 0.08)[0][0] < 0.5
    # with MIN_KNOWN below 1 they leave the count instead: the right pose explains all it can be judged on
    monkeypatch.setattr(verify, "MIN_KNOWN", 0.5)
    assert score_poses(ref.lines, obs, centre[None], 0.06, 0.08)[0][0] > 0.98


def test_a_point_in_space_the_map_saw_free_counts_against(square_room):
    walls, centre, ref, scan = square_room
    r, a = scan[0].copy(), scan[1]
    west = np.abs(np.degrees(a)) > 150
    r[west] = 1.0  # something 1 m away to the west, where the mapping scan looked through
    obs = Observation.from_scan(r, a, 8.0)
    base = score_poses(ref.lines, Observation.from_scan(*scan, 8.0), centre[None], 0.06, 0.08)
    s, inl, vio = score_poses(ref.lines, obs, centre[None], 0.06, 0.08)
    n = len(obs.points)
    # the west beams are violations now (one each: MIN_KNOWN = 1, no rescaling)
    assert vio[0] - base[2][0] == pytest.approx(west.sum(), abs=3)
    assert s[0] == pytest.approx((inl[0] - vio[0]) / n)


def test_tie_bar_closed_form():
    p = RelocCheck()
    assert tie_bar(0.99, p) == pytest.approx(0.98 * 0.99)  # a complete map: the ratio decides
    assert tie_bar(0.9, p) == pytest.approx(0.8)  # a deficit of 10 %: a rival failing on 20 % ties
    assert tie_bar(0.9, RelocCheck(deficit_ratio=0.0)) == pytest.approx(0.882)
    # summed over four scans the margin halves: a rival failing on 15 % where the best fails on 10 % ties
    assert tie_bar(0.9, p, 4) == pytest.approx(0.85)
    assert tie_bar(0.99, p, 4) == pytest.approx(0.98 * 0.99)  # the ratio still decides on a complete map


# --------------------------------------------------------------------------- the line map of a log


def test_merge_segments_joins_one_wall_and_keeps_faces_and_doors_apart():
    segs = np.array(
        [
            [[0.0, 0.00], [2.0, 0.00]],
            [[1.5, 0.02], [3.0, 0.02]],  # the same wall, seen again 2 cm off: joins
            [[0.0, 0.10], [3.0, 0.10]],  # the other face of a 10 cm wall: apart
            [[4.0, 0.00], [5.0, 0.00]],  # beyond a 1 m door: apart
        ]
    )
    lines, support = merge_segments(segs)
    assert len(lines) == 3 and sorted(support.tolist()) == [1, 1, 2]
    joined = lines[np.argmax(support)]
    assert np.sort(joined[:, 0]) == pytest.approx([0.0, 3.0], abs=1e-9)
    # the length-weighted mean line: 2 m at 0 and 1.5 m at 0.02
    assert joined[:, 1] == pytest.approx([0.02 * 1.5 / 3.5] * 2, abs=1e-9)


def test_robust_end_is_the_median_of_the_ends_near_the_last():
    # four segments saw the end of the wall (one 10 cm long by noise), one stopped short at an occlusion
    assert robust_end([3.0, 3.02, 2.98, 3.1, 1.0], gap=0.3) == pytest.approx(3.01)
    assert robust_end([2.0], gap=0.3) == 2.0


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: build_coverage([(np.ones(3), np.arange(3.0))], np.zeros((2, 3)), max_range=5.0), "one per scan"),
        (lambda: build_coverage([(np.ones(3), np.arange(3.0))], [[0, 0, np.nan]], max_range=5.0), "NaN"),
        (lambda: build_coverage([(np.ones(3), np.arange(3.0))], np.zeros((1, 3)), max_range=0.0), "max_range"),
        (lambda: build_coverage([(np.ones(3), np.zeros(3))], np.zeros((1, 3)), max_range=5.0), "increasing"),
        (lambda: prepare_map([[[0, 0], [1, 0]]], coverage="grid"), "prepare_map: coverage: expected a Coverage"),
    ],
)
def test_bad_inputs_raise(call, match):
    with pytest.raises(InvalidInputError, match=match):
        call()


def test_a_segment_of_zero_length_is_degenerate():
    with pytest.raises(DegenerateGeometryError, match="merge_segments: segments: segment 0 has zero length"):
        merge_segments([[[0, 0], [0, 0]]])


# --------------------------------------------------------------------------- a real log


@pytest.fixture(scope="module")
def intel_slice():
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    n = 280
    return CarmenLog(log.ranges[:n], log.angles, log.poses[:n], log.odometry[:n], log.timestamps[:n])


def test_held_out_intel_scans_are_located_or_doubted_never_confidently_wrong(intel_slice):
    """The first 280 scans of Intel, every 7th held out, map from the rest, the laser's reach read off the log
    (14.4 m): 35 of 40 located (measured; 28 with an 8 m reach, 1 confidently wrong), none confidently wrong; the
    method without coverage and deficit rule located 31 and was wrong on 4 (8 m)."""
    test = np.arange(3, len(intel_slice), 7)
    ev, segs = evaluate_log(intel_slice, test, exclude=0, map_step=1)
    s = ev.summary()
    assert s.n == 40 and s.success >= 27 and s.confidently_wrong == 0
    assert np.median(ev.position_error[ev.success]) < 0.05
    # the corridor at scan 129: located, by the lines across it that the map's scans saw from two places (merged
    # by their midpoints: with the ends tested against the line, as before, they were dropped as seen once, poses
    # along the corridor tied, and the answer was ambiguous; the check below: without coverage and deficit rule
    # the answer is confident, 0.4 m along it)
    k = int(np.flatnonzero(test == 129)[0])
    r = ev.results[k]
    assert r.status == "ok" and pose_error(r.pose, intel_slice.poses[129])[0] < 0.1


def test_the_method_before_was_confidently_wrong_in_that_corridor(intel_slice):
    """The check above can fail: without the coverage grid and the deficit rule the same scan is answered
    confidently 0.4 m along the corridor."""
    test = np.arange(3, len(intel_slice), 7)
    ref = reference_from_log(intel_slice, held_out_map_indices(len(intel_slice), test, 0, 1), coverage=False)
    r = relocalize(ref, scan=intel_slice.scans[129], max_range=8.0, deficit_ratio=0.0)
    assert r.status == "ok" and pose_error(r.pose, intel_slice.poses[129])[0] > 0.3


def test_runs_of_three_with_simulated_odometry(intel_slice):
    odo = simulate_odometry(intel_slice.poses, np.random.default_rng(0))
    starts = np.arange(1, len(intel_slice) - 2, 20)
    ev, n_scans, _ = evaluate_log_sequences(intel_slice, starts, length=3, stride=1, odometry=odo, exclude=0)
    s = ev.summary()
    # measured with the log's reach (14.4 m): 12 of 14 located, and two confident just outside the tolerances
    # (10.5 cm; 0.9 cm and 2.3 degrees); with an 8 m reach 12 located and those two ambiguous (the second 6 degrees
    # off); without coverage and deficit rule: 9 located, 1 confidently wrong
    assert s.n == len(starts) == 14 and np.all(n_scans == 3) and s.success >= 12
    wrong = (ev.status == "ok") & ~ev.success
    assert wrong.sum() <= 2
    assert np.all(ev.position_error[wrong] < 0.2) and np.all(ev.heading_error[wrong] < np.radians(4))  # not gross
    with pytest.raises(InvalidInputError, match=r"evaluate_log_sequences: odometry: expected shape \(280, 3\)"):
        evaluate_log_sequences(intel_slice, starts, odometry=odo[:-1])
