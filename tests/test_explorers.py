"""The notebooks' explorers: their logic, without a browser (the callbacks change the figure's data as asserted)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cga_lessons.viz.explore_motion import ScrewExplorer  # noqa: E402


def _axis_distance(points, point, direction):
    d = direction / np.linalg.norm(direction)
    rel = points - point
    return np.linalg.norm(rel - np.outer(rel @ d, d), axis=1)


@pytest.mark.parametrize(
    "change",
    [
        {},
        {"angle": -200.0, "pitch": -0.5, "azimuth": 100.0},
        {"angle": 360.0},
        {"angle": 0.0, "pitch": 1.0},
        {"elevation": -30.0, "angle": 45.0},
    ],
)
def test_the_screw_explorer_moves_the_tool_along_the_true_helix(change):
    ex = ScrewExplorer()
    ex.update(**change)
    p = ex.params
    path = ex.tip_path()
    np.testing.assert_allclose(path[-1], ex.expected_tip(), atol=1e-12)  # Rodrigues about the axis + slide
    r = _axis_distance(path, np.asarray(p.point), p.axis())
    np.testing.assert_allclose(r, r[0], atol=1e-12)  # a helix: constant distance to the axis
    rise = (path - path[0]) @ p.axis()
    np.testing.assert_allclose(rise, np.linspace(0, p.distance(), len(path)), atol=1e-12)  # uniform slide


def test_update_redraws_the_lines_in_place():
    ex = ScrewExplorer()
    before = [np.array(line.get_data_3d()) for line in ex._tools[-1]]
    helix_before = np.array(ex._helix.get_data_3d())
    ex.update(angle=30.0)
    after = [np.array(line.get_data_3d()) for line in ex._tools[-1]]
    assert not all(np.allclose(a, b) for a, b in zip(before, after))
    assert not np.allclose(np.array(ex._helix.get_data_3d()), helix_before)
    assert "30 deg" in ex.ax.get_title()
    first = [np.array(line.get_data_3d()) for line in ex._tools[0]]  # s = 0: the start pose does not move
    ex.update(angle=-90.0, pitch=0.3)
    np.testing.assert_allclose([np.array(line.get_data_3d()) for line in ex._tools[0]], first)


def test_the_widget_drives_the_explorer():
    pytest.importorskip("ipywidgets")
    ex = ScrewExplorer()
    w = ex.widget()
    sliders = {c.description: c for c in w.children if hasattr(c, "description") and c.description}
    assert {"azimuth", "elevation", "angle (deg)", "pitch (m)"} <= set(sliders)
    sliders["angle (deg)"].value = 75.0
    assert ex.params.angle == 75.0 and "75 deg" in ex.ax.get_title()


def test_the_pair_explorer_reads_the_true_points_back_and_marks_the_guard():
    from cga_lessons.viz.explore_entities import PairExplorer, pair_readback

    far = pair_readback(1e-2, 4.0)
    np.testing.assert_allclose(far["p1"], far["a"], atol=1e-9)
    np.testing.assert_allclose(far["p2"], far["b"], atol=1e-9)
    assert far["guard"] == "accepted" and np.linalg.norm(far["a"] - far["b"]) == pytest.approx(1e-2)
    assert pair_readback(1e-9, 4.0)["guard"] == "refused"
    ex = PairExplorer(separation=1e-2, distance=4.0, grid=np.logspace(0, -9, 10))
    marker = np.array(ex._marker.get_data())
    ex.update(separation=1e-6, distance=16.0)
    assert not np.allclose(np.array(ex._marker.get_data()), marker)
    assert ex._marker.get_data()[0][0] == pytest.approx(1e-6)
    assert "16 m" in ex.ax.get_title() and ex.result["guard"] in ex.ax.get_title()
    refused_x = ex._refused.get_data()[0]
    assert len(refused_x) and min(refused_x) == pytest.approx(1e-9)  # the smallest separations are refused


def test_the_pair_widget_drives_the_explorer():
    pytest.importorskip("ipywidgets")
    from cga_lessons.viz.explore_entities import PairExplorer

    ex = PairExplorer(grid=np.logspace(0, -9, 10))
    w = ex.widget()
    sliders = {c.description: c for c in w.children if getattr(c, "description", "")}
    sliders["distance (m)"].value = 8.0
    assert ex.distance == 8.0 and "8 m" in ex.ax.get_title()


def test_turning_on_the_spot_moves_the_hough_points_along_theta_only():
    """Section 5.1: a turn by delta shifts every local line's theta by -delta and keeps its rho (noise-free scan)."""
    from cga_lessons.viz.explore_scan import HoughExplorer

    ex = HoughExplorer(seed=None)
    before = ex.hough.copy()
    ex.update(theta_deg=np.degrees(ex.pose[2]) + 30.0)
    after = ex.hough
    shifted = np.column_stack([before[:, 0], np.mod(before[:, 1] - np.radians(30.0), 2 * np.pi)])
    matched = 0
    for rho, th in shifted:  # every line still in view after the turn lands where 5.1 says
        d = np.hypot(after[:, 0] - rho, np.angle(np.exp(1j * (after[:, 1] - th))))
        matched += bool(d.min() < 1e-6)
    assert matched >= len(before) // 2 and matched >= 2
    world = np.array(ex._segs.get_data())
    ex.update(x=ex.pose[0] + 0.5)  # driving changes rho, and the drawing
    assert not np.array_equal(np.array(ex._segs.get_data()), world, equal_nan=True)
    assert "segments at" in ex.ax_world.get_title()


def test_the_depth_explorer_follows_the_first_order_law_and_the_sliders():
    """Triangulated depth errors against sigma_Z = Z^2 sqrt(2) sigma / (f b): within 20 % at every depth (400 points
    each); doubling the baseline halves them (the same noise draws)."""
    from cga_lessons.viz.explore_stereo import DepthErrorExplorer

    ex = DepthErrorExplorer(seed=3)
    np.testing.assert_allclose(ex.measured / ex.predicted, 1.0, atol=0.2)
    narrow = ex.measured.copy()
    ex.update(baseline=2 * ex.baseline)
    np.testing.assert_allclose(narrow / ex.measured, 2.0, rtol=0.05)
    assert "24 cm" in ex.ax.get_title()
    np.testing.assert_allclose(ex._measured.get_data()[1], ex.measured)
    pytest.importorskip("ipywidgets")
    sliders = {c.description: c for c in ex.widget().children if getattr(c, "description", "")}
    sliders["noise (px)"].value = 1.0
    assert ex.noise_px == 1.0 and "1.00 px" in ex.ax.get_title()


@pytest.mark.parametrize("heading, fov", [(180.0, 150.0), (225.0, 100.0), (30.0, 300.0)])
def test_the_node_explorer_sees_what_lies_within_the_field_of_view(heading, fov):
    """Without a sphere a node is seen exactly when its bearing from the robot lies within half the field of view
    of the heading (the closed form, in the horizontal plane)."""
    from cga_lessons.viz.explore_nodes import NodeExplorer

    ex = NodeExplorer(heading_deg=heading, fov_deg=fov, diameter=0.0)
    nodes = ex.result.grid.nodes
    robot = np.asarray(ex.result.scenario.robot)
    d = nodes[:, :2] - robot[:2]
    away = np.hypot(d[:, 0], d[:, 1]) > 1e-9
    bearing = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
    off = np.abs((bearing - heading + 180.0) % 360.0 - 180.0)
    inside = away & (off < fov / 2 - 1e-6)
    outside = away & (off > fov / 2 + 1e-6)
    assert np.all(ex.result.labels.seen[inside]) and not np.any(ex.result.labels.seen[outside])
    before = dict(ex.counts)
    ex.update(diameter=25.0)  # the sphere (west of the robot) occludes and occupies nodes when in view
    if heading == 180.0:
        assert ex.counts["occupied"] > 0 and ex.counts["seen"] < before["seen"]
    assert f"{fov:.0f} deg" in ex.ax.get_title()


@pytest.mark.parametrize("x", [-3.7, -1.0, 0.0, 0.4, 2.5])
def test_the_stereographic_explorer_puts_the_image_on_the_ray_and_the_circle(x):
    """(2.48): the image lies on the unit circle and on the line from the pole e+ through x e1; up(x) is null with
    X . e = -1 (2.61), on the parabola X_- = (X_1^2 + 1)/2 drawn beside."""
    from cga_lessons.viz.explore_null_cone import StereographicExplorer

    ex = StereographicExplorer(x=0.0)
    ex.update(x)
    a, b = ex.image
    assert a * a + b * b == pytest.approx(1.0, abs=1e-12)
    assert (a - 0.0) * (0.0 - 1.0) - (b - 1.0) * (x - 0.0) == pytest.approx(0.0, abs=1e-12)  # collinear with pole, x
    assert ex.null_check == pytest.approx(0.0, abs=1e-12) and ex.weight == pytest.approx(-1.0, abs=1e-12)
    px, py = ex._cone_pt.get_data()
    assert px[0] == pytest.approx(x) and py[0] == pytest.approx((x * x + 1) / 2)
    assert ex._img.get_data()[0][0] == pytest.approx(a)


def test_the_sliders_show_what_the_drawing_returns_after_every_move(capsys):
    from ipywidgets import FloatSlider

    from cga_lessons.viz.controls import slider_panel

    seen = []
    panel = slider_panel(lambda a: seen.append(a) or f"drawn at {a}", a=FloatSlider(value=1.0, continuous_update=True))
    panel.children[0].value = 2.0
    assert seen == [1.0, 2.0]
    assert panel.auto_display and not panel.children[0].continuous_update
    assert "drawn at 2.0" in capsys.readouterr().out  # displayed (outside a front end: printed)
