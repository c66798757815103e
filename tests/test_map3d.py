"""Tests of the fused 3D map (cga_lessons.map3d*, thesis 4.2.3) and its drawing (cga_lessons.viz.map3d).

The truth is the simulator's: objects, walls and true poses; the cameras are
rendered with plain 4x4 matrices (map3d_tour.homogeneous_chains), so the motor
chains that bring the entities back are checked end to end.
"""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cga_lessons import conformal as cga  # noqa: E402
from cga_lessons.algebra import DegenerateGeometryError, InvalidInputError  # noqa: E402
from cga_lessons.map3d import build_fused_map, entity_parameters, stereo_depth_limit  # noqa: E402
from cga_lessons.map3d.eval import COLUMNS, ResidualRow, match_board_segment, residual_table, view_errors  # noqa: E402
from cga_lessons.map3d.laser import fit_post_center, laser_posts, virtual_wall  # noqa: E402
from cga_lessons.map3d.robot import Robot  # noqa: E402
from cga_lessons.map3d.state import RobotGeometry, RobotState  # noqa: E402
from cga_lessons.map3d.tour import homogeneous_chains, simulate_tour, waypoint_tour  # noqa: E402
from cga_lessons.map3d.world import Board, Post, World3D, default_world  # noqa: E402
from cga_lessons.mapping2d.laser import OdometryModel, simulate_scan  # noqa: E402
from cga_lessons.viz import map3d as vz  # noqa: E402
from cga_lessons.viz.scene3d import Box, Quad, check_scene  # noqa: E402


@pytest.fixture(scope="module")
def fused():
    """The notebook's tour: default world, noise and seed."""
    return build_fused_map(simulate_tour(np.random.default_rng(2007)))


@pytest.fixture(scope="module")
def exact():
    """No pixel, range or odometry noise; the chains driven by the true poses."""
    still = OdometryModel(0.0, 0.0, 0.0, 0.0)
    tour = simulate_tour(np.random.default_rng(1), noise_px=0.0, range_noise=0.0, odometry_model=still)
    return build_fused_map(tour, poses_from="truth")


# ---------------------------------------------------------------- end to end
def test_noise_free_tour_recovers_the_truth(exact):
    world = exact.tour.world
    assert set(exact.objects) == {"ball", "board", "plate", "post_west", "post_east"}
    for name, obj in exact.objects.items():
        t, p = world.object(name).truth(), obj.params
        assert obj.kind == p.kind == t.kind
        if obj.kind in ("sphere", "circle"):
            assert np.allclose(p.center, t.center, atol=1e-6) and abs(p.radius - t.radius) < 1e-6
        elif obj.kind == "plane":
            assert abs(abs(p.normal @ t.normal) - 1) < 1e-9 and abs(abs(p.distance) - abs(t.distance)) < 1e-6
        else:
            assert abs(abs(p.direction[2]) - 1) < 1e-9
            assert np.allclose(p.point[:2], t.point[:2], atol=1e-6)
    # the laser: posts to the polygon's approximation of the circle (0.1 mm); the walls come from chapter 3's
    # map, whose corrections move even exact poses by up to 2 cm in this scene but keep its lines within mm
    rows = {r.object: r for r in residual_table(exact)}
    for post in ("post_west", "post_east"):
        assert rows[post].laser_pos_cm < 0.05 and rows[post].laser_stereo_cm < 0.05
    assert rows["board"].laser_pos_cm < 0.3 and rows["walls"].laser_pos_cm < 0.5


def test_default_tour_meets_the_targets(fused):
    rows = {r.object: r for r in residual_table(fused)}
    both = [k for k, r in rows.items() if r.seen_by == "stereo + laser"]
    assert set(both) == {"board", "post_west", "post_east"}
    for k in both:
        assert rows[k].laser_stereo_cm < 3.0, (k, rows[k].laser_stereo_cm)  # the 3 cm target
    assert rows["board"].laser_stereo_deg < 2.0
    assert rows["ball"].seen_by == "stereo" and rows["pedestal"].seen_by == "laser"
    for k in ("ball", "board", "plate", "post_west", "post_east"):
        assert rows[k].views >= 2 and rows[k].stereo_pos_cm < 6.0, k
    assert rows["walls"].laser_pos_cm < 6.0
    assert isinstance(rows["ball"], ResidualRow) and np.isnan(rows["pedestal"].stereo_pos_cm)
    assert COLUMNS == [f.name for f in dataclasses.fields(ResidualRow)]


def test_laser_and_stereo_agree_on_another_seed():
    rows = {r.object: r for r in residual_table(build_fused_map(simulate_tour(np.random.default_rng(5))))}
    for k in ("board", "post_west", "post_east"):
        assert rows[k].laser_stereo_cm < 3.0, (k, rows[k].laser_stereo_cm)


def test_odometry_alone_misplaces_the_objects(fused):
    raw = {r.object: r for r in residual_table(build_fused_map(fused.tour, poses_from="odometry", laser=fused.laser))}
    good = {r.object: r for r in residual_table(fused)}
    assert np.nanmean([raw[k].stereo_pos_cm for k in raw if k != "walls"]) > 2 * np.nanmean(
        [good[k].stereo_pos_cm for k in good if k != "walls"]
    )


def test_view_entities_are_the_fits_of_the_moved_points(fused):
    """(4.10) on the fitted entity equals the same fit of the points moved by the same motor (a rigid motion)."""
    from cga_lessons.map3d.fits import fit_entity as _fit

    for e in fused.views[:8]:
        p = entity_parameters(e.kind, _fit(e.kind, e.points_world).blade)
        assert type(p) is type(e.params)
        for key in (f.name for f in dataclasses.fields(p)):
            v, w = getattr(e.params, key), getattr(p, key)
            if v is None and w is None:  # an optional field neither sets (a plane's center, a line's length)
                continue
            same = np.allclose(v, w, atol=1e-7) or (key in ("normal", "direction") and np.allclose(v, -w))
            assert same or (key == "distance" and np.isclose(abs(v), abs(w), atol=1e-7)), (e.name, key)


def test_scan_segments_land_at_laser_height_on_the_walls(fused):
    h = fused.laser_height
    segs = np.concatenate([s for s in fused.scan_segments if len(s)])
    assert len(segs) > 100 and np.allclose(segs[:, :, 2], h, atol=1e-9)
    # each segment sent by (4.4) lies on a true outline (walls, board, pedestal) to a few cm
    outlines = [fused.tour.world.wall_segments()] + [
        np.stack([fp, np.roll(fp, -1, axis=0)], axis=1)
        for fp in (o.footprint() for o in fused.tour.world.objects)
        if fp is not None
    ]
    lines = np.concatenate(outlines)
    a, v = lines[:, 0], lines[:, 1] - lines[:, 0]
    pts = segs[:, :, :2].reshape(-1, 2)
    t = np.clip(np.einsum("pwi,wi->pw", pts[:, None] - a, v) / np.einsum("wi,wi->w", v, v), 0, 1)
    d = np.linalg.norm(pts[:, None] - (a + t[..., None] * v), axis=-1).min(axis=1)
    assert np.percentile(d, 95) < 0.08


def test_every_view_is_reported(fused):
    rows = view_errors(fused)
    assert len(rows) == len(fused.views) and all(r.distance_m > 0.3 for r in rows)
    near = [r for r in rows if r.entity == "plane"]
    assert all(r.stereo_pos_cm < 5 for r in near)
    assert all(np.isnan(r.stereo_radius_cm) for r in near) and not any(np.isnan(r.stereo_angle_deg) for r in near)


# ---------------------------------------------------------------- building blocks
def test_virtual_wall_is_the_vertical_plane_of_the_segment():
    w = virtual_wall([1.0, 2.0], [3.0, 2.5], 0.35, 1.2)
    n, d = cga.plane_normal_distance(w.plane)
    assert abs(n[2]) < 1e-12
    for p in (w.start, w.end, *w.corners):
        assert abs(n @ p - d) < 1e-12
    assert np.allclose(w.corners[:, 2], [0.0, 0.0, 1.2, 1.2]) and np.allclose(w.start, [1.0, 2.0, 0.35])
    assert np.allclose(np.sort(np.array(cga.point_pair_endpoints(w.pair)), axis=0), np.sort([w.start, w.end], axis=0))
    with pytest.raises(InvalidInputError, match="height"):
        virtual_wall([0, 0], [1, 0], 0.35, 0.0)


def test_laser_posts_finds_a_free_standing_post():
    post = Post("p", (2.0, 0.3), 0.05, 1.5)
    world = World3D([np.array([[-1.0, -3.0], [5.0, -3.0], [5.0, 3.0], [-1.0, 3.0]])], 2.5, [post])
    scene = world.laser_scene(0.35, np.zeros((1, 3)))
    r, a = simulate_scan(scene, [0.0, 0.0, 0.0])
    centres, counts = laser_posts(r, a, radius=0.05)
    assert len(centres) == 1 and counts[0] >= 3
    assert np.allclose(centres[0], [2.0, 0.3], atol=1e-3)
    r, a = simulate_scan(World3D(world.walls, 2.5).laser_scene(0.35, np.zeros((1, 3))), [0.0, 0.0, 0.0])
    assert len(laser_posts(r, a)[0]) == 0  # walls alone: no post
    with pytest.raises(InvalidInputError):
        laser_posts(r, a[:-1])


def test_fit_post_center_and_fit_line_closed_form():
    t = np.linspace(-1.0, 1.0, 9)
    pts = np.array([3.0, -1.0]) + 0.07 * np.column_stack([-np.cos(t), np.sin(t)])  # the near side of a circle
    assert np.allclose(fit_post_center(pts, (0.0, 0.0), 0.07), [3.0, -1.0], atol=1e-9)
    X = np.array([1.0, 2.0, 0.5]) + np.outer(np.linspace(-1, 2, 7), [0.0, 0.6, 0.8])
    f = cga.fit_line(X)
    assert np.allclose(np.abs(f.direction), [0.0, 0.6, 0.8]) and f.rms < 1e-12
    assert np.allclose(cga.line_direction(f.blade), f.direction)
    assert cga.point_line_distance(X[3], f.blade) < 1e-9
    with pytest.raises(DegenerateGeometryError):
        cga.fit_line(np.ones((4, 3)))
    with pytest.raises(InvalidInputError):
        cga.fit_line(np.array([[0.0, np.nan, 1.0], [1.0, 1.0, 1.0]]))


def test_stereo_depth_limit_is_the_first_order_error():
    g = RobotGeometry()
    z = stereo_depth_limit(g, 0.5, 0.05)
    assert np.isclose(z**2 * np.sqrt(2) * 0.5 / (g.focal_px * g.baseline), 0.05)
    assert stereo_depth_limit(g, 0.0) == np.inf
    with pytest.raises(InvalidInputError):
        stereo_depth_limit(g, -1.0)


def test_waypoint_tour_steps_and_turns():
    T = waypoint_tour([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0]], step=0.25, turn_step=0.3)
    steps = np.hypot(*np.diff(T[:, :2], axis=0).T)
    assert steps.max() <= 0.25 + 1e-12 and np.allclose(T[-1], [2.0, 1.0, np.pi / 2])
    assert np.abs(np.diff(np.unwrap(T[:, 2]))).max() <= 0.3 + 1e-12
    with pytest.raises(InvalidInputError):
        waypoint_tour([[0.0, 0.0], [0.0, 0.0]])


def test_homogeneous_chains_match_the_robot():
    state = RobotState(1.0, 2.0, 0.5, -0.6, 0.3)
    H = homogeneous_chains(RobotGeometry(), x=1.0, y=2.0, theta=0.5, pan=-0.6, tilt=0.3)
    F = Robot(state=state).frames()
    assert np.allclose(H.camera_left, F.camera_left, atol=1e-12) and np.allclose(H.laser, F.laser)


def test_the_board_is_matched_to_its_laser_line(fused):
    k = match_board_segment(fused, "board")
    s = fused.laser.segments[k]
    board = fused.tour.world.object("board")
    assert isinstance(board, Board) and abs(abs(s.direction @ board.along[:2]) - 1) < 1e-3
    assert match_board_segment(fused, "ball") is None


def test_bad_input_raises():
    with pytest.raises(InvalidInputError, match="rng"):
        simulate_tour(None)
    with pytest.raises(InvalidInputError, match="joint range"):
        simulate_tour(np.random.default_rng(0), tilts=(2.0,))
    with pytest.raises(InvalidInputError, match="stops"):
        simulate_tour(np.random.default_rng(0), stops=(10_000,))
    with pytest.raises(InvalidInputError, match="Tour"):
        build_fused_map("tour")
    with pytest.raises(InvalidInputError, match="unique"):
        World3D(default_world().walls, 2.5, [Post("a", (0, 0), 0.05, 1.0), Post("a", (1, 0), 0.05, 1.0)])
    with pytest.raises(InvalidInputError, match="kind"):
        entity_parameters("cone", None)


# ---------------------------------------------------------------- drawing
def test_robot_and_map_primitives(fused):
    robot = Robot()
    prims = vz.robot_primitives(robot, RobotState(2.0, 1.0, 0.3, 0.5, 0.2))
    names = {p.name for p in check_scene(prims)}
    assert {"robot/base", "robot/laser", "robot/camera_left", "robot/camera_right", "robot/pan_tilt"} <= names
    cam = next(p for p in prims if p.name == "robot/camera_left")
    H = robot.frames().camera_left
    assert (
        isinstance(cam, Box) and np.allclose(cam.rotation, H[:3, :3]) and np.linalg.norm(cam.center - H[:3, 3]) < 0.05
    )
    m = vz.map_primitives(fused)
    check_scene(m + prims)
    walls = [p for p in m if isinstance(p, Quad) and p.name.startswith("map/walls/")]
    assert len(walls) == len(fused.laser.segments)
    assert not any(p.name.startswith("map/walls/") for p in vz.map_primitives(fused, virtual_walls=False))
    fig = vz.plot_virtual_walls(fused)
    assert len(fig.axes) == 2
    plt.close(fig)
    with pytest.raises(InvalidInputError):
        vz.map_primitives("not a map")


def test_scene_exports_to_a_self_contained_page(fused, tmp_path):
    from cga_lessons.viz import meshcat_scene as mc

    scene = vz.map_primitives(fused, points=True) + vz.robot_primitives(Robot()) + vz.truth_primitives(fused)
    page = mc.export_html(scene, tmp_path / "map.html")
    text = page.read_text(encoding="utf-8")
    assert page.exists() and text.count('run("') >= len(scene)  # one scene command (or more) per primitive
    assert "http://" not in text.split("<script>")[-1]  # nothing fetched from a network
