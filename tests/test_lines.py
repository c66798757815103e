"""Tests of line extraction (cga_lessons.mapping2d.lines, thesis 3.1-3.5)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cga_lessons.algebra import InvalidInputError
from cga_lessons.mapping2d import TWO_PI, Segment
from cga_lessons.mapping2d.laser import load_scene, simulate_scan
from cga_lessons.mapping2d.lines import diff_theta, diff_theta_as_printed, extract_segments, split_points
from cga_lessons.mapping2d.segment import fit_line, line_through, point_line_distance

angles = st.floats(0, TWO_PI, exclude_max=True, allow_nan=False)


# ---------------------------------------------------------------- diffTheta (3.5)


def test_diff_theta_thesis_example():
    # the thesis's worked example: diffTheta(199 pi/100, 2 pi/100) = -3 pi/100 with theta_xi = 2 pi/100
    assert np.isclose(diff_theta(199 * np.pi / 100, 2 * np.pi / 100), -3 * np.pi / 100)
    assert np.isclose(diff_theta(2 * np.pi / 100, 199 * np.pi / 100), 3 * np.pi / 100)
    # the example's invariance: adding pi to both angles gives the same difference
    assert np.isclose(diff_theta(99 * np.pi / 100, 102 * np.pi / 100), -3 * np.pi / 100)


def test_diff_theta_erratum_printed_form_fails_its_own_example():
    # printed: "theta_b + theta_xi <= 0", impossible for theta_b >= 0: the example would give 197 pi/100
    printed = diff_theta_as_printed(199 * np.pi / 100, 2 * np.pi / 100)
    assert np.isclose(printed, 197 * np.pi / 100)
    assert not np.isclose(printed, -3 * np.pi / 100)


@given(angles, angles)
@settings(max_examples=200, deadline=None)
def test_diff_theta_properties(a, b):
    d = diff_theta(a, b)
    assert np.isclose(diff_theta(b, a), -d)  # antisymmetric
    assert np.isclose(np.mod(d - (a - b) + np.pi, TWO_PI) - np.pi, 0.0, atol=1e-9)  # same angle mod 2 pi
    short = np.mod(a - b + np.pi, TWO_PI) - np.pi
    if abs(short) < 2 * np.pi / 100 - 1e-9:
        assert np.isclose(d, short, atol=1e-12)  # small differences are taken the short way round


def test_diff_theta_broadcasts():
    d = diff_theta(np.array([[0.01], [6.27]]), np.array([6.27, 0.01]))
    assert d.shape == (2, 2)
    assert np.allclose(d, [[0.01 - 6.27 + TWO_PI, 0.0], [0.0, 6.27 - 0.01 - TWO_PI]])


# ---------------------------------------------------------------- lines (3.1-3.3)


def test_line_through_and_point_distance_3_1_3_2():
    abc = line_through([0.0, 0.0], [3.0, 4.0])
    assert np.isclose(abc @ [3.0, 4.0, 1.0], 0.0) and np.isclose(abc @ [0, 0, 1.0], 0.0)
    # distance of (4, -3) to the line through the origin along (3, 4) is 5
    assert np.isclose(abs(point_line_distance(abc, [4.0, -3.0])), 5.0)
    assert np.allclose(point_line_distance([0, 1, -1], [[0, 1], [0, 3], [5, -1]]), [0, 2, -2])
    with pytest.raises(InvalidInputError, match="point_line_distance"):
        point_line_distance([0, 0, 1], [1.0, 1.0])


def test_split_points_at_a_corner_and_not_on_a_line():
    leg1 = np.column_stack([np.linspace(0, 2, 21), np.zeros(21)])
    leg2 = np.column_stack([np.full(20, 2.0), np.linspace(0.1, 2, 20)])
    pts = np.vstack([leg1, leg2])
    assert split_points(pts, 0.05) == [(0, 20), (21, 40)]  # v_md (the corner) ends the first group
    assert split_points(leg1, 0.05) == [(0, 20)]
    assert split_points(np.zeros((0, 2)), 0.05) == []
    with pytest.raises(InvalidInputError, match="xi"):
        split_points(pts, 0.0)


def test_fit_line_is_orthogonal_not_y_on_x():
    rng = np.random.default_rng(0)
    t = np.linspace(-1, 1, 200)
    d_true = np.array([np.cos(1.5), np.sin(1.5)])  # nearly vertical
    pts = np.outer(t, d_true) + rng.normal(0, 0.01, (200, 2))
    c, d, res = fit_line(pts)
    assert abs(abs(d @ d_true) - 1) < 1e-4
    slope_yx = np.polyfit(pts[:, 0], pts[:, 1], 1)[0]  # y on x is far off for a steep line
    assert abs(np.arctan(slope_yx) - 1.5) > 5 * abs(np.arccos(min(1, abs(d @ d_true))))
    assert np.isclose(np.sqrt(np.mean(res**2)), 0.01, rtol=0.2)


def test_segment_members_3_3():
    s = Segment([1.0, -1.0], [1.0, 1.0])
    assert np.isclose(s.rho, 1.0) and np.isclose(s.theta, 0.0)
    assert np.allclose(s.closest_point, [1, 0]) and np.allclose(s.abc, [1, 0, -1])
    assert np.allclose(s.direction, [0, 1]) and np.isclose(s.length, 2.0)
    # a line below the origin: closest point (0, -2), theta = 3 pi / 2 in [0, 2 pi)
    s = Segment([3.0, -2.0], [-1.0, -2.0])
    assert np.isclose(s.rho, 2.0) and np.isclose(s.theta, 1.5 * np.pi)
    for p in (s.start, s.end, s.closest_point):  # the normal form x cos(theta) + y sin(theta) = rho (3.3)
        assert np.isclose(p[0] * np.cos(s.theta) + p[1] * np.sin(s.theta), s.rho)
    assert np.isclose(s.abc @ [*s.end, 1.0], 0.0)
    with pytest.raises(InvalidInputError, match="coincide"):
        Segment([1.0, 1.0], [1.0, 1.0])


@given(
    st.tuples(st.floats(-10, 10), st.floats(-10, 10)),
    st.floats(0.2, 5),
    st.floats(-np.pi, np.pi),
    st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(-np.pi, np.pi)),
)
@settings(max_examples=60, deadline=None)
def test_segment_transformed_is_the_motion_of_its_points_3_4(p0, length, ang, pose):
    pts = np.asarray(p0) + np.outer(np.linspace(0, length, 12), [np.cos(ang), np.sin(ang)])
    pts = pts + 0.01 * np.sin(np.arange(12))[:, None] * np.array([[-np.sin(ang), np.cos(ang)]])
    x, y, th = pose
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    moved_pts = pts @ R.T + [x, y]
    a = Segment.from_points(pts).transformed(pose)
    b = Segment.from_points(moved_pts)
    assert np.allclose(a.start, b.start, atol=1e-9) and np.allclose(a.end, b.end, atol=1e-9)
    assert np.allclose(a.sums, b.sums, rtol=1e-9, atol=1e-7)
    assert np.isclose(a.rho, b.rho, atol=1e-9) and abs(diff_theta(a.theta, b.theta, np.pi)) < 1e-7 or a.rho < 1e-6


def test_segment_hough_relative_to_a_point():
    s = Segment([2.0, 1.0], [2.0, 3.0])  # x = 2, sensor on the left (west): normal points east
    assert np.allclose(s.hough(), (2.0, 0.0))
    assert np.allclose(s.hough((5.0, 0.0)), (-3.0, 0.0))  # seen from behind: negative, same theta
    r = s.reversed()
    assert np.allclose(r.hough(), (-2.0, np.pi))  # the other face


# ---------------------------------------------------------------- extraction


def _seg_to_wall_distance(p, walls):
    a, b = walls[:, 0], walls[:, 1]
    v = b - a
    t = np.clip(((p - a) * v).sum(1) / (v * v).sum(1), 0, 1)
    return np.hypot(*(p - (a + t[:, None] * v)).T).min()


def test_extract_segments_in_the_room_lie_on_the_walls():
    room = load_scene("room")
    pose = np.array([3.0, 2.0, 0.0])
    r, a = simulate_scan(room, pose, np.random.default_rng(0))
    segs = extract_segments(r, a, max_range=5.0)
    assert len(segs) == 3  # south, east, north walls
    thetas = sorted(s.theta for s in segs)  # laser frame = world frame here (pose at angle 0, origin moved)
    assert np.allclose(thetas, [0.0, np.pi / 2, 1.5 * np.pi], atol=np.radians(0.5))
    for s in segs:
        g = s.transformed(pose)
        assert _seg_to_wall_distance(g.start, room.walls) < 0.02 and _seg_to_wall_distance(g.end, room.walls) < 0.02
        assert s.n_points > 50
    rhos = sorted(s.rho for s in segs)
    assert np.allclose(rhos, [2.0, 2.0, 3.0], atol=0.01)


def test_extract_segments_edges_at_door_jambs_not_at_range_limit():
    office = load_scene("office")
    pose = np.array([1.5, 4.5, np.pi / 2])  # in room 1 facing the door at x = 1.5 in the wall y = 5.8
    r, a = simulate_scan(office, pose)
    segs = extract_segments(r, a, max_range=5.0)
    world = [s.transformed(pose) for s in segs]
    jambs = np.array([[1.05, 5.75], [1.95, 5.75]])
    edge_pts = [p for g in world for p, e in ((g.start, g.start_is_edge), (g.end, g.end_is_edge)) if e]
    assert len(edge_pts) >= 2
    for jamb in jambs:
        assert min(np.hypot(*(p - jamb)) for p in edge_pts) < 0.08  # the jamb's 10 cm side hides its corner
    for p in edge_pts:  # every edge found is a corner of some polygon
        assert min(np.hypot(*(v - p)) for poly in office.polygons for v in poly) < 0.08


def test_extract_segments_ignores_chair_legs_and_merges_collinear_pieces():
    corridor = load_scene("corridor")
    pose = np.array([4.6, 1.4, -np.pi / 2])  # looking down at a chair's four 4 cm legs
    r, a = simulate_scan(corridor, pose, np.random.default_rng(2))
    segs = extract_segments(r, a, max_range=5.0)
    for s in segs:
        g = s.transformed(pose)
        assert g.length > 0.15 and s.n_points >= 6
    # a straight noisy wall comes out as one segment even with a tight split threshold
    ang = np.radians(np.arange(-60, 60.5, 0.5))
    rr = 2.0 / np.cos(ang) + np.random.default_rng(3).normal(0, 0.01, ang.size)
    assert len(extract_segments(rr, ang, xi=0.04)) == 1


def test_extract_segments_degenerate_input():
    a = np.linspace(-np.pi / 2, np.pi / 2, 361)
    assert extract_segments(np.full(361, np.inf), a) == []
    assert extract_segments(np.full(361, np.nan), a) == []
    r = np.full(361, np.inf)
    r[100:103] = 1.0  # three points: not a segment
    assert extract_segments(r, a) == []
    with pytest.raises(InvalidInputError, match="extract_segments"):
        extract_segments(np.ones(10), a)
    with pytest.raises(InvalidInputError, match="increasing"):
        extract_segments(np.ones(361), a[::-1])
