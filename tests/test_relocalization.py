"""Tests of the relocalization (thesis chapter 5, Eqs. 5.1-5.6).

Truths used: the segment members of chapter 3 (lines.Segment.rho/theta), lines
moved by explicit rotation matrices, votes counted by hand, the simulator's
ground-truth poses, the simulator's own ray casting, and mapping2d's least
squares (3.12).
"""

import dataclasses

import numpy as np
import pytest

from cga_lessons import data_path
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError
from cga_lessons.mapping2d import Segment, compose, read_carmen_log, wrap_angle
from cga_lessons.mapping2d.laser import load_scene, simulate_scan
from cga_lessons.mapping2d.lines import diff_theta, extract_segments
from cga_lessons.relocalization import (
    Evaluation,
    ReferenceMap,
    Relocalization,
    RelocCheck,
    RelocParams,
    RelocSearch,
    prepare_map,
    relocalize,
)
from cga_lessons.relocalization.eval import evaluate_log, evaluate_poses, random_free_poses
from cga_lessons.relocalization.geometry import MapLines, Observation, ScanLines, first_hits, pose_error
from cga_lessons.relocalization.hough import (
    THETA_XI,
    hough_comparison,
    hough_differences,
    hough_set,
    shifted_set,
    shifted_set_corrected,
    vote_matrix,
    vote_matrix_indexed,
)
from cga_lessons.relocalization.params import noise_scaled, resolve_params
from cga_lessons.relocalization.search import pose_hypotheses, propose_rotations
from cga_lessons.relocalization.thesis import (
    correspondences_from_votes,
    mean_angle,
    rotate_entities,
    thesis_relocalization,
    translate_entities,
    translation_from_lines,
)
from cga_lessons.relocalization.verify import NO_RETURN_WEIGHT, refine_pose_points, score_pose


def _rot(t):
    return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


def _move(segs, pose):
    """Segments (K, 2, 2) moved by the rigid motion x -> R x + t (the truth for the thesis's steps)."""
    return np.asarray(segs) @ _rot(pose[2]).T + np.asarray(pose[:2])


def _to_laser(segs, pose):
    """Map segments seen from a laser at ``pose``: the inverse motion."""
    return (np.asarray(segs) - np.asarray(pose[:2])) @ _rot(pose[2])


# ---------------------------------------------------------------- figure 5.1 and Eqs. 5.1-5.5


def test_hough_set_is_the_segment_members_fig_5_1():
    rng = np.random.default_rng(0)
    segs = rng.uniform(-5, 5, size=(40, 2, 2))
    H = hough_set(segs)
    ref = np.array([[Segment(a, b).rho, Segment(a, b).theta] for a, b in segs])
    assert np.allclose(H, ref, atol=1e-12)
    assert np.all(H[:, 0] >= 0) and np.all((H[:, 1] >= 0) & (H[:, 1] < 2 * np.pi))
    # section 5.1: a rotation about the laser moves every point along theta only, cyclically
    turned = hough_set(_move(segs, (0.0, 0.0, 1.0)))
    assert np.allclose(turned[:, 0], H[:, 0])
    assert np.allclose(np.mod(turned[:, 1] - H[:, 1], 2 * np.pi), 1.0)


def test_hough_differences_5_1_to_5_3():
    m = np.array([3.0, 0.2])
    L_h = np.array([[1.0, 0.1], [2.5, 6.25], [0.5, 3.0]])
    phi = hough_differences(m, L_h)
    assert phi.shape == (3, 2)
    assert np.allclose(phi[:, 0], [2.0, 0.5, 2.5])  # (5.2)
    assert np.allclose(phi[:, 1], [diff_theta(0.2, t, THETA_XI) for t in L_h[:, 1]])  # (5.1)
    assert np.isclose(phi[0, 1], 0.1) and np.isclose(phi[2, 1], 0.2 - 3.0)


def test_shifted_set_and_comparison_5_4_5_5():
    L_h = np.array([[1.0, 0.1], [2.0, 6.2]])
    phi = np.array([[0.5, 0.3], [-0.2, 0.2]])
    psi = shifted_set(L_h, phi)
    assert psi.shape == (2, 2, 2)
    assert np.allclose(psi[0, 1], [2.5, np.mod(6.5, 2 * np.pi)])  # theta wraps to [0, 2 pi)
    assert np.allclose(psi[1, 0], [0.8, 0.3])
    M_h = np.array([[2.5, 0.2], [0.8, 0.31]])
    xi = hough_comparison(M_h, psi)
    assert xi.shape == (2, 2, 2, 2)
    assert np.allclose(xi[1, 0, 1], [0.0, 0.01])
    assert np.allclose(xi[0, 1, 0], [0.0, diff_theta(0.2, np.mod(6.5, 2 * np.pi), THETA_XI)])


def test_shifted_set_as_printed_fails_under_a_translation_erratum_5_4():
    """(5.4) shifts every rho by the same Delta rho; a translation moves each by t . n(theta)."""
    rng = np.random.default_rng(3)
    scan = rng.uniform(-4, 4, size=(6, 2, 2))
    pose = np.array([1.5, -0.7, 0.4])
    truth = hough_set(_move(scan, pose))  # where the lines really are in the map
    L_h = hough_set(scan)
    # printed: shift all by the differences of the first (true) correspondence
    phi = hough_differences(truth[0], L_h[:1])
    printed = shifted_set(L_h, phi)[0]
    corrected = shifted_set_corrected(L_h, pose[2], pose[:2])
    assert np.allclose(corrected, truth, atol=1e-12)
    assert np.allclose(printed[0], truth[0])  # the anchor itself lands...
    assert np.max(np.abs(printed[1:, 0] - truth[1:, 0])) > 0.5  # ...the others do not
    # a rotation alone (section 5.1) is where the printed shift holds
    only_turn = shifted_set(L_h, hough_differences(hough_set(_move(scan[:1], (0, 0, 0.4)))[0], L_h[:1]))[0]
    assert np.allclose(only_turn, hough_set(_move(scan, (0, 0, 0.4))), atol=1e-12)


# ---------------------------------------------------------------- Eq. 5.6 and steps 6-10


def test_vote_matrix_hand_built_5_6():
    # two scan lines; the map holds them shifted by (0.5, 0.5) and one unrelated line
    L_h = np.array([[1.0, 0.0], [2.0, np.pi / 2]])
    M_h = np.array([[1.5, 0.5], [2.5, 0.5 + np.pi / 2], [4.0, 3.0]])
    # counted by hand: V[i, j] = pairs (k, m) with l_k + (m_i - l_j) within the thresholds of m
    expected = np.array([[2, 1], [1, 2], [1, 1]])
    V = vote_matrix(M_h, L_h, xi_theta=0.05, xi_rho=0.1)
    assert V.tolist() == expected.tolist()
    assert vote_matrix_indexed(M_h, L_h, xi_theta=0.05, xi_rho=0.1).tolist() == expected.tolist()
    assert correspondences_from_votes(V).tolist() == [0, 1, -1]  # step 6: column maxima


def test_vote_matrix_indexed_equals_the_literal_loop():
    rng = np.random.default_rng(11)
    for _ in range(10):
        M_h = np.column_stack([rng.uniform(0, 6, 40), rng.uniform(0, 2 * np.pi, 40)])
        L_h = np.column_stack([rng.uniform(0, 6, 7), rng.uniform(0, 2 * np.pi, 7)])
        for xr in (0.3, np.inf):
            assert np.array_equal(vote_matrix(M_h, L_h, 0.1, xr), vote_matrix_indexed(M_h, L_h, 0.1, xr))


def test_thesis_steps_6_to_10_find_a_rotation_about_the_laser():
    """Steps 6-10 as printed recover a pure rotation about the map's origin (where 5.4 holds)."""
    corners = np.array([[3, -1], [3.5, 2], [-1, 4], [-2.5, -1.5]], float)
    walls = np.stack([corners, np.roll(corners, -1, axis=0)], axis=1)
    pose = np.array([0.0, 0.0, 0.35])
    scan = _to_laser(walls, pose)
    out = thesis_relocalization(walls, scan, xi_theta=0.02, xi_rho=0.05)
    assert out.C.tolist() == [0, 1, 2, 3]
    assert np.allclose(out.pose, pose, atol=1e-9)
    assert np.allclose(out.placed, walls, atol=1e-9)  # rotor (2.96) and translator (2.100) on the point pairs
    # step 7 alone, and step 9 reusing the least squares (3.12) of mapping2d
    assert np.isclose(mean_angle(out.M_h, out.L_h, out.C), 0.35)
    t = translation_from_lines(out.M_h, hough_set(out.rotated), out.C)
    assert np.allclose(t, 0.0, atol=1e-9)


def test_rotor_and_translator_steps_move_point_pairs_like_matrices():
    rng = np.random.default_rng(5)
    segs = rng.uniform(-3, 3, size=(5, 2, 2))
    assert np.allclose(rotate_entities(segs, 0.7), _move(segs, (0, 0, 0.7)), atol=1e-12)
    assert np.allclose(translate_entities(segs, [1.0, -2.0]), segs + [1.0, -2.0], atol=1e-12)
    # far away (2.131) loses accuracy; the versor then moves the spanning points, still exact
    far = translate_entities(segs, [3e4, 1e4])
    assert np.allclose(far, segs + [3e4, 1e4], atol=1e-6)


def test_thesis_method_fails_on_a_translated_pose(hall):
    """Read literally the method does not find a pose that includes a translation (DESIGN.md)."""
    pose = np.array([4.0, 3.0, 0.6])
    r, a = simulate_scan(hall, pose)
    res = relocalize(hall.walls, scan=(r, a))
    assert res.status == "ok" and pose_error(res.pose, pose)[0] < 0.05
    thesis = res.thesis_pose
    assert thesis is None or pose_error(thesis, pose)[0] > 0.5
    assert res.votes.shape == (len(hall.walls), len(res.scan_segments))


# ---------------------------------------------------------------- the search


def test_pose_hypotheses_include_the_exact_translation_3_12():
    walls = np.array([[[0, 0], [6, 0]], [[6, 0], [6, 4]], [[6, 4], [0, 4]], [[0, 4], [0, 0]], [[2, 1], [3, 1.5]]])
    pose = np.array([2.2, 2.9, -0.8])
    r, a = simulate_scan(walls, pose)
    L = np.array([[s.start, s.end] for s in extract_segments(r, a, max_range=5.0)])
    M, S = MapLines(walls), ScanLines(L)
    rots, _ = propose_rotations(M.angle, S.angle, S.length, np.radians(3))
    assert np.min(np.abs(wrap_angle(rots - pose[2]))) < 1e-3
    rot = rots[np.argmin(np.abs(wrap_angle(rots - pose[2])))]
    kw = dict(n_anchor_pairs=4, min_anchor_angle=np.radians(30), overlap_margin=0.3, min_overlap=0.5)
    poses, quick = pose_hypotheses(M, S, rot, parallel_tol=np.radians(4), line_tolerance=0.1, **kw)
    d = np.hypot(*(poses[:, :2] - pose[:2]).T)
    assert d.min() < 0.01 and quick[np.argmin(d)] == pytest.approx(quick.max())  # up to the voted rotation's error


def test_first_hits_is_the_simulators_ray_cast():
    scene = load_scene("office")
    M = MapLines(scene.walls)
    rng = np.random.default_rng(2)
    poses = random_free_poses(scene, 20, rng)
    a = np.linspace(-np.pi / 2, np.pi / 2, 361)
    hits, _ = first_hits(M, poses, np.column_stack([np.cos(a), np.sin(a)]), reach=6.0)
    for p, h in zip(poses, hits):
        r, _ = simulate_scan(scene, p, max_range=5.0)
        ok = np.isfinite(r)
        assert np.allclose(h[ok], r[ok], atol=1e-5)
        assert np.all(h[~ok] > 5.0 - 1e-6)


def test_score_counts_beams_that_cross_walls():
    wall = np.array([[[2.0, -3.0], [2.0, 3.0]]])
    M = MapLines(wall)
    a = np.linspace(-0.5, 0.5, 11)
    r = np.full(11, 2.0) / np.cos(a)  # all on the wall at x = 2
    r[:3] = np.inf  # three beams saw nothing: impossible with the wall 2 m ahead and a 5 m laser
    obs = Observation.from_scan(r, a, 5.0)
    w = NO_RETURN_WEIGHT  # a beam without return counts this much of a violation (a returned one counts 1)
    score, inl, vio = score_pose(M, obs, [0.0, 0.0, 0.0], 0.05, 0.08)
    assert (inl, vio) == (8, 3 * w) and score == pytest.approx((8 - 3 * w) / 8)
    # moved 0.5 m back, the returned beams end before the wall: not inliers, not violations
    assert score_pose(M, obs, [-0.5, 0.0, 0.0], 0.05, 0.08)[1:] == (0, 3 * w)
    # 0.5 m forward, every beam would pass through the wall
    assert score_pose(M, obs, [0.5, 0.0, 0.0], 0.05, 0.08)[1:] == (0, 8 + 3 * w)


def test_refine_pose_points_converges_to_the_truth(hall):
    pose = np.array([3.0, 2.5, 0.3])
    obs = Observation.from_scan(*simulate_scan(hall, pose), 5.0)
    start = pose + np.array([[0.06, -0.05, 0.015], [-0.1, 0.08, -0.02]])
    out = refine_pose_points(MapLines(hall.walls), obs, start)
    assert np.allclose(out, pose, atol=1e-6)


# ---------------------------------------------------------------- relocalize


def test_relocalize_random_poses_in_an_irregular_hall(hall):
    rng = np.random.default_rng(7)
    ev = evaluate_poses(hall, hall.walls, random_free_poses(hall, 40, rng), rng)
    s = ev.summary()
    assert s.confidently_wrong == 0
    assert s.success_rate_distinguishable >= 0.95
    assert s.success_rate >= 0.85
    assert np.all(ev.position_error[ev.success] < 0.03) and np.all(ev.heading_error[ev.success] < np.radians(0.5))


def test_relocalize_office_never_confidently_wrong():
    """The office's rooms repeat every 6 m: most poses are flagged ambiguous, with a witness, never wrong."""
    scene = load_scene("office")
    rng = np.random.default_rng(1)
    ev = evaluate_poses(scene, scene.walls, random_free_poses(scene, 30, rng), rng)
    s = ev.summary()
    assert s.confidently_wrong == 0
    assert s.success + s.indistinguishable >= 0.85 * s.n
    # an ambiguous answer carries the truth among its tied candidates
    amb = [i for i in range(s.n) if ev.status[i] == "ambiguous"]
    near_truth = [any(pose_error(c.pose, ev.truth[i])[0] < 0.1 for c in ev.results[i].candidates[:8]) for i in amb]
    assert np.mean(near_truth) >= 0.9


def test_symmetric_room_is_ambiguous():
    room = load_scene("room")  # a plain 6 m x 4 m rectangle
    pose = np.array([2.0, 1.5, 0.4])
    res = relocalize(room.walls, scan=simulate_scan(room, pose, np.random.default_rng(0)))
    assert res.ambiguous and res.status == "ambiguous"
    centre = room.walls.reshape(-1, 2).mean(axis=0)
    mirror = np.array([*(2 * centre - pose[:2]), wrap_angle(pose[2] + np.pi)])  # turned by pi about the centre
    found = [c.pose for c in res.candidates]
    assert any(pose_error(p, pose)[0] < 0.05 for p in found)
    assert any(pose_error(p, mirror)[0] < 0.05 for p in found)
    assert np.isfinite(res.score) and not np.any(np.isnan(res.pose))


def test_relocalize_input_forms_agree(hall):
    pose = np.array([5.0, 3.5, 2.0])
    r, a = simulate_scan(hall, pose, np.random.default_rng(4))
    segs = extract_segments(r, a, max_range=5.0)
    arr = np.array([[s.start, s.end] for s in segs])
    map_list = [Segment(w[0], w[1]) for w in hall.walls]
    ref = prepare_map(hall.walls)
    assert isinstance(ref, ReferenceMap)
    results = [
        relocalize(hall.walls, scan=(r, a)),
        relocalize(map_list, segs, scan=(r, a)),
        relocalize(ref, arr, scan=(r, a)),
        relocalize(hall.walls, arr),  # segments only: checked against points along them
    ]
    for res in results:
        assert res.status == "ok"
        assert pose_error(res.pose, pose)[0] < 0.05 and pose_error(res.pose, pose)[1] < np.radians(1)
        assert len(res.correspondences) >= 2
        assert np.all(res.correspondences[:, 1] < len(segs))


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(map_segments=np.zeros((0, 2, 2)), scan_segments=np.ones((2, 2, 2))), "map_segments: is empty"),
        (dict(map_segments=np.full((3, 2, 2), np.nan), scan_segments=np.ones((2, 2, 2))), "NaN"),
        (
            dict(map_segments=np.ones((3, 4)), scan_segments=np.ones((2, 2, 2))),
            r"map_segments: expected shape \(N, 2, 2\)",
        ),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan_segments=[[[0, 0], [1, np.inf]]]), "NaN or inf"),
        (dict(map_segments=[[[0, 0], [1, 0]]]), "give scan_segments"),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan=(np.ones(5), np.linspace(0, 1, 4))), "equal 1-D shapes"),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan=(np.ones(4), np.array([0, 1, 1, 2.0]))), "strictly increasing"),
        (
            dict(map_segments=[[[0, 0], [1, 0]]], scan=(np.ones(4), np.array([0, 1, np.nan, 2.0]))),
            "angles: contains NaN",
        ),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan=np.ones(4)), "pair"),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan_segments=np.ones((2, 2, 2)), max_range=0.0), "max_range"),
        (dict(map_segments=[[[0, 0], [1, 0]]], scan_segments=np.ones((2, 2, 2)), nonsense=1), "unknown parameter"),
    ],
)
def test_relocalize_bad_input_raises(kwargs, match):
    with pytest.raises(InvalidInputError, match=match) as info:
        relocalize(**kwargs)
    assert str(info.value).startswith("relocalize: ")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(xi_theta=np.nan), "relocalize: xi_theta: is NaN or inf"),
        (dict(xi_rho=None), "relocalize: xi_rho: must be a real number"),
        (dict(min_score="0.5"), "relocalize: min_score: must be a real number"),
        (dict(n_verify=2.5), "relocalize: n_verify: must be a whole number"),
        (dict(params="strict"), "relocalize: params: expected a RelocParams"),
        (dict(extraction={"nonsense": 1}), "relocalize: extraction: unknown setting"),
        (dict(max_range="5"), "relocalize: max_range: must be a real number"),
    ],
)
def test_relocalize_refuses_bad_thresholds(kwargs, match):
    """Thresholds of the wrong type or NaN are refused, not turned into a failed relocalization."""
    with pytest.raises(InvalidInputError, match=match):
        relocalize([[[0, 0], [1, 0]]], np.ones((2, 2, 2)), **kwargs)


def test_a_zero_length_segment_is_degenerate():
    with pytest.raises(DegenerateGeometryError, match="relocalize: map_segments: segment 0 has zero length"):
        relocalize([[[0, 0], [0, 0]]], np.ones((2, 2, 2)))


def test_too_few_lines_is_an_explicit_failure():
    walls = np.array([[[3.0, -10.0], [3.0, 10.0]]])  # one long wall ahead: one line
    r, a = simulate_scan(walls, [0.0, 0.0, 0.0])
    res = relocalize(walls, scan=(r, a))
    assert res.status == "failed" and res.ambiguous and res.pose is None
    assert "too few lines" in res.message and res.score == -np.inf
    nothing = relocalize(walls, scan=(np.full(10, np.inf), np.linspace(-1, 1, 10)))
    assert nothing.status == "failed" and nothing.pose is None
    assert nothing.votes.shape == (1, 0)


def test_relocalize_intel_log_against_the_rest_of_it():
    log = read_carmen_log(data_path("carmen", "intel-corrected.log.gz"))
    test = np.arange(40, len(log), 90)  # 10 scans spread over the log
    ev, segs = evaluate_log(log, test, exclude=2, map_step=3)
    s = ev.summary()
    assert len(segs) > 100
    assert s.success >= 6
    assert np.median(ev.position_error[ev.status == "ok"]) < 0.1
    # the map lies in the frame of the logged poses: at the truth most of a scan lies on it
    obs = Observation.from_scan(*log.scans[test[0]], 8.0)
    M = MapLines(np.asarray(segs))
    assert score_pose(M, obs, log.poses[test[0]], 0.06, 0.08)[0] > 0.5


def test_pose_error_and_compose_agree():
    a, b = np.array([1.0, 2.0, 0.3]), np.array([1.5, 1.0, -0.4])
    d = compose(a, [0.5, 0.0, 0.0])
    assert pose_error(d, a) == pytest.approx((0.5, 0.0))
    assert pose_error(a, b)[1] == pytest.approx(0.7)


# --------------------------------------------------------------------------- stages and typed results


def test_the_thresholds_are_two_stages_with_unique_field_names():
    """Each threshold lives in one stage (search or check), so a single name overrides it: the three ways of
    overriding (a name, a dict of a stage's fields, a whole stage) give one configuration."""
    search = {f.name for f in dataclasses.fields(RelocSearch)}
    check = {f.name for f in dataclasses.fields(RelocCheck)}
    assert not search & check and len(search | check) == 23
    assert {"xi_theta", "slide_below", "n_screen"} <= search and {"min_score", "n_verify", "deficit_ratio"} <= check
    a = resolve_params(None, {"xi_theta": 0.1, "min_score": 0.4})
    b = resolve_params(None, {"search": {"xi_theta": 0.1}, "check": RelocCheck(min_score=0.4)})
    assert a == b == RelocParams(search=RelocSearch(xi_theta=0.1), check=RelocCheck(min_score=0.4))
    assert RelocParams().check.distinct_heading == pytest.approx(np.radians(4.0))
    with pytest.raises(InvalidInputError, match="RelocParams: check: expected a RelocCheck"):
        RelocParams(check=RelocSearch())
    with pytest.raises(InvalidInputError, match="RelocSearch: n_rotations: must be a whole number"):
        RelocSearch(n_rotations=2.5)


def test_noise_grows_the_distance_thresholds_of_both_stages():
    p = noise_scaled(RelocParams(), 0.03)
    assert p.search.line_tolerance == pytest.approx(0.15) and p.check.inlier_distance == pytest.approx(0.12)
    assert p.check.ray_margin == pytest.approx(0.15) and p.search.xi_theta == RelocParams().search.xi_theta
    assert noise_scaled(RelocParams(), 0.001) == RelocParams()  # below the thresholds' own 1 cm: unchanged


def test_overrides_by_name_and_by_stage_relocalize_alike():
    room = load_scene("room")
    scan = simulate_scan(room, np.array([2.0, 1.5, 0.4]), np.random.default_rng(0))
    by_name = relocalize(room.walls, scan=scan, n_rotations=4, ambiguity_ratio=0.9)
    by_stage = relocalize(room.walls, scan=scan, search={"n_rotations": 4}, check={"ambiguity_ratio": 0.9})
    assert np.array_equal(by_name.pose, by_stage.pose) and by_name.score == by_stage.score
    assert len(by_name.rotations) <= 8  # four proposals, two rotations each


def test_a_relocalization_is_built_by_keyword_and_its_ambiguity_is_its_status():
    with pytest.raises(TypeError):
        Relocalization(None, -np.inf, "failed")
    failed = Relocalization(pose=None, score=-np.inf, status="failed")
    ok = Relocalization(pose=np.zeros(3), score=0.9, status="ok")
    assert failed.ambiguous and not ok.ambiguous
    assert Relocalization(pose=np.zeros(3), score=0.9, status="ambiguous").ambiguous


def test_the_summary_of_an_evaluation_counts_its_poses():
    n = 4
    ev = Evaluation(
        truth=np.zeros((n, 3)),
        pose=np.array([[0.0, 0.0, 0.0], [0.05, 0, 0], [1.0, 0, 0], [np.nan] * 3]),
        status=np.array(["ok", "ambiguous", "ok", "failed"]),
        position_error=np.array([0.0, 0.05, 1.0, np.inf]),
        heading_error=np.array([0.0, 0.0, 0.0, np.inf]),
        n_lines=np.array([5, 4, 3, 1]),
        score=np.array([0.9, 0.8, 0.7, -np.inf]),
        witness=np.array([np.nan, 0.99, np.nan, np.nan]),
        seconds=np.array([0.01, 0.02, 0.03, 0.04]),
    )
    s = ev.summary()
    assert (s.n, s.success, s.confidently_wrong, s.ambiguous, s.indistinguishable, s.failed) == (4, 1, 1, 1, 1, 1)
    assert s.success_rate == 0.25 and s.success_rate_distinguishable == pytest.approx(1 / 3)
    assert s.median_ms == pytest.approx(25.0)
    empty = ev.take(np.zeros(n, bool)).summary()
    assert empty.n == 0 and np.isnan(empty.success_rate) and np.isnan(empty.median_ms)
    with pytest.raises(InvalidInputError, match="EvaluationSummary: success_rate"):
        dataclasses.replace(s, success_rate=np.nan)  # NaN only when nothing was counted
