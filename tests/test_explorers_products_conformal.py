"""The explorers of notebooks 01 and 06 against closed forms, their redraws and their checks of slider values."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from cga_lessons import conformal as cga  # noqa: E402
from cga_lessons.viz.explore_conformal_map import CorrectionExplorer, conformal_correction, place  # noqa: E402
from cga_lessons.viz.explore_products import ProductExplorer, geometric_product, reflect  # noqa: E402


def _rotation(angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s], [s, c]])


def _pose_matrix(pose):
    """The rigid motion of a planar pose as a 3x3 homogeneous matrix (plain NumPy)."""
    H = np.eye(3)
    H[:2, :2] = _rotation(pose[2])
    H[:2, 2] = pose[:2]
    return H


def _sliders(widget):
    return {c.description: c for c in widget.children if getattr(c, "description", "")}


# ------------------------------------------------------------------ notebook 01: ProductExplorer


@pytest.fixture(scope="module")
def products():
    ex = ProductExplorer()
    yield ex
    matplotlib.pyplot.close(ex.fig)


@pytest.mark.parametrize(
    "angle, len_a, len_b, direction",
    [
        (35.0, 1.6, 1.2, 15.0),
        (-120.0, 2.0, 0.3, 80.0),
        (90.0, 0.5, 1.0, -170.0),
        (180.0, 1.0, 1.0, 0.0),
        (0.0, 1.3, 0.7, 45.0),
        (-175.0, 0.2, 2.0, -60.0),
    ],
)
def test_the_product_is_dot_plus_wedge_and_the_two_reflections_turn_by_twice_the_angle(
    products, angle, len_a, len_b, direction
):
    """(2.11): ab = |a||b| cos(angle) + |a||b| sin(angle) e12; (2.84, 2.98): the two reflections are the rotation
    matrix of twice the angle, whatever the lengths and the direction of a."""
    ex = products
    ex.update(angle=angle, len_a=len_a, len_b=len_b, direction=direction)
    phi = np.radians(angle)
    np.testing.assert_allclose(ex.a, len_a * np.array([np.cos(np.radians(direction)), np.sin(np.radians(direction))]))
    assert ex.dot == pytest.approx(len_a * len_b * np.cos(phi), abs=1e-12)
    assert ex.dot == pytest.approx(float(ex.a @ ex.b), abs=1e-12)
    assert ex.wedge == pytest.approx(len_a * len_b * np.sin(phi), abs=1e-12)
    assert ex.wedge == pytest.approx(ex.a[0] * ex.b[1] - ex.a[1] * ex.b[0], abs=1e-12)  # the signed area
    assert float(ex.ba.scalar()) == pytest.approx(ex.dot, abs=1e-12) and ex.ba["e12"] == pytest.approx(-ex.wedge)
    np.testing.assert_allclose(ex.rotated, _rotation(2 * phi) @ ex.test, atol=1e-12)
    mirror = np.array([-ex.a[1], ex.a[0]]) / len_a  # the first reflection keeps the mirror's direction, flips a's
    np.testing.assert_allclose(ex.reflected @ mirror, ex.test @ mirror, atol=1e-12)
    np.testing.assert_allclose(ex.reflected @ ex.a, -(ex.test @ ex.a), atol=1e-12)
    R = ex.rotor
    moved = R * _vector(ex.test) * ~R  # (2.98)
    np.testing.assert_allclose([moved["e1"], moved["e2"]], ex.rotated, atol=1e-12)
    assert float((R * ~R).scalar()) == pytest.approx(1.0)
    assert ex.turn_deg == pytest.approx(2 * angle, abs=1e-9)


def _vector(v):
    from cga_lessons.viz.explore_products import G2

    return G2.vector([float(v[0]), float(v[1])])


def test_the_helpers_agree_with_the_closed_forms():
    ab, dot, wedge = geometric_product([3.0, 1.0], [1.0, 2.0])  # the notebook's figure 2.2 pair
    assert (dot, wedge) == (5.0, 5.0) and ab.grades_present() == [0, 2]
    np.testing.assert_allclose(reflect([1.0, 2.0], [1.0, 0.0]), [-1.0, 2.0])  # the mirror is the e2 axis
    n = np.array([0.6, 0.8])
    v = np.array([0.3, -1.7])
    np.testing.assert_allclose(reflect(v, 5 * n), v - 2 * (v @ n) * n, atol=1e-12)  # Householder, any length of n


def test_the_product_explorer_redraws_in_place(products):
    ex = products
    ex.update(angle=35.0, len_a=1.6, len_b=1.2, direction=15.0)
    para = ex._para.get_xy().copy()
    point = np.array(ex._prod.get_data(), float)
    arrows = np.array([ex._vecs.U, ex._vecs.V], float)
    ex.update(angle=-60.0)
    assert not np.allclose(ex._para.get_xy(), para)
    np.testing.assert_allclose(np.array(ex._prod.get_data(), float).ravel(), [ex.dot, ex.wedge])
    np.testing.assert_allclose(np.array(ex._rev.get_data(), float).ravel(), [ex.dot, -ex.wedge])
    assert not np.allclose(np.array([ex._vecs.U, ex._vecs.V], float), arrows)
    np.testing.assert_allclose(np.array([ex._vecs.U, ex._vecs.V], float)[:, 2], ex.rotated)
    np.testing.assert_allclose(ex._para.get_xy()[2], ex.a + ex.b)
    assert not np.allclose(np.array(ex._prod.get_data(), float), point)
    assert "clockwise" in ex.ax_vec.get_title() and "anticlockwise" not in ex.ax_vec.get_title()  # a ^ b < 0
    assert "-120 deg = 2 x -60 deg" in ex.ax_rot.get_title()


@pytest.mark.parametrize("arg", ["angle", "len_a", "len_b", "direction"])
def test_the_product_explorer_refuses_nan(products, arg):
    with pytest.raises(ValueError, match=f"ProductExplorer.update: {arg}"):
        products.update(**{arg: float("nan")})


def test_the_product_explorer_refuses_bad_lengths():
    with pytest.raises(ValueError, match="ProductExplorer: len_a: must be positive"):
        ProductExplorer(len_a=0.0)
    with pytest.raises(ValueError, match="ProductExplorer: test"):
        ProductExplorer(test=(np.inf, 0.0))


def test_the_product_widget_drives_the_explorer(products):
    pytest.importorskip("ipywidgets")
    sliders = _sliders(products.widget())
    assert {"angle a->b", "|a|", "|b|", "a's direction"} <= set(sliders)
    assert all(not s.continuous_update for s in sliders.values())
    sliders["angle a->b"].value = 50.0
    assert products.angle == 50.0 and "2 x 50 deg" in products.ax_rot.get_title()


# ------------------------------------------------------------------ notebook 06: CorrectionExplorer


@pytest.fixture(scope="module")
def correction():
    ex = CorrectionExplorer()
    yield ex
    matplotlib.pyplot.close(ex.fig)


@pytest.mark.parametrize(
    "dx, dy, dtheta",
    [(0.4, -0.3, 10.0), (-1.0, 1.0, -29.0), (0.0, 0.0, 0.0), (0.25, 0.6, 0.0), (0.0, 0.0, 20.0), (-0.7, -0.05, 4.5)],
)
def test_the_recovered_correction_is_the_inverse_of_the_error(correction, dx, dy, dtheta):
    """The correction (3.8, 3.12) is minus the applied pose error, its motor the inverse of the error motor (plain
    3x3 matrices), and the corrected pose and segments are the true ones."""
    ex = correction
    ex.update(dx=dx, dy=dy, dtheta_deg=dtheta)
    np.testing.assert_allclose(ex.correction, [-dx, -dy, -np.radians(dtheta)], atol=1e-9)
    np.testing.assert_allclose(ex.corrected_pose, ex.pose, atol=1e-9)
    believed = ex.pose + [dx, dy, np.radians(dtheta)]
    error = _pose_matrix(believed) @ np.linalg.inv(_pose_matrix(ex.pose))  # takes the map onto the placed scan
    C = np.asarray(cga.motor_to_matrix(ex.result.motor))
    np.testing.assert_allclose(C[np.ix_([0, 1, 3], [0, 1, 3])], np.linalg.inv(error), atol=1e-9)
    E = np.asarray(cga.motor_to_matrix(ex.error_motor))
    np.testing.assert_allclose(E[np.ix_([0, 1, 3], [0, 1, 3])], error, atol=1e-9)
    truth = [s.transformed(ex.pose) for s in ex.segments]  # (3.4), plain vectors and matrices
    fixed_x, fixed_y = (np.asarray(v, float) for v in ex._fixed.get_data())
    np.testing.assert_allclose(fixed_x[0::3], [s.start[0] for s in truth], atol=1e-9)
    np.testing.assert_allclose(fixed_y[1::3], [s.end[1] for s in truth], atol=1e-9)
    placed_x = np.asarray(ex._placed.get_data()[0], float)
    moved = [s.transformed(believed) for s in ex.segments]
    np.testing.assert_allclose(placed_x[0::3], [s.start[0] for s in moved], atol=1e-9)


def test_conformal_correction_of_parallel_lines_fixes_only_their_normal():
    """(3.9): with one direction of lines only the offset along their normal is determined; the rest is kept."""
    from cga_lessons.mapping2d import Segment
    from cga_lessons.mapping2d import conformal as cmap

    local = cmap.segment_point_pair([Segment([1.0, -1.0], [1.0, 1.0]), Segment([3.0, 1.0], [3.0, -1.0])])
    truth, believed = np.array([0.0, 0.0, 0.0]), np.array([0.3, 0.2, 0.0])
    out = conformal_correction(place(local, truth)[0], place(local, believed)[0], believed[:2])
    np.testing.assert_allclose(out.t, [-0.3, 0.0], atol=1e-12)
    assert out.theta == pytest.approx(0.0, abs=1e-12)


def test_the_correction_explorer_redraws_in_place(correction):
    ex = correction
    ex.update(dx=0.4, dy=-0.3, dtheta_deg=10.0)
    placed = np.array(ex._placed.get_data(), float)
    believed = np.array(ex._believed.get_data(), float)
    hough = np.array(ex._h_placed.get_data(), float)
    fixed = np.array(ex._fixed.get_data(), float)
    ex.update(dtheta_deg=-15.0)
    assert not np.allclose(np.array(ex._placed.get_data(), float), placed, equal_nan=True)
    assert not np.allclose(np.array(ex._believed.get_data(), float), believed)
    new_hough = np.array(ex._h_placed.get_data(), float)
    np.testing.assert_allclose(np.mod(new_hough[0] - hough[0] + 180, 360) - 180, -25.0, atol=1e-9)  # theta shifts
    np.testing.assert_allclose(np.array(ex._fixed.get_data(), float), fixed, atol=1e-9, equal_nan=True)  # on the map
    turned = np.array(ex._h_turned.get_data(), float)
    mapped = np.array(ex._h_map.get_data(), float)
    np.testing.assert_allclose(turned[0], mapped[0], atol=1e-9)  # after (3.8) the angles agree with the map's
    assert "dtheta -15.0 deg" in ex.ax.get_title() and "= the true pose" in ex.ax.get_title()
    assert "+15.0 deg" in ex.ax_hough.get_title()


@pytest.mark.parametrize("arg", ["dx", "dy", "dtheta_deg"])
def test_the_correction_explorer_refuses_nan(correction, arg):
    with pytest.raises(ValueError, match=f"CorrectionExplorer.update: {arg}"):
        correction.update(**{arg: float("nan")})


def test_the_correction_explorer_refuses_a_turn_beyond_the_angle_gate(correction):
    with pytest.raises(ValueError, match="CorrectionExplorer.update: dtheta_deg: must lie within the angle gate"):
        correction.update(dtheta_deg=45.0)
    correction.update(dtheta_deg=5.0)  # still usable afterwards
    np.testing.assert_allclose(correction.corrected_pose, correction.pose, atol=1e-9)


def test_the_correction_widget_drives_the_explorer(correction):
    pytest.importorskip("ipywidgets")
    sliders = _sliders(correction.widget())
    assert {"dx (m)", "dy (m)", "dtheta (deg)"} <= set(sliders)
    assert all(not s.continuous_update for s in sliders.values())
    assert sliders["dtheta (deg)"].max < correction.theta_xi_deg
    sliders["dx (m)"].value = -0.5
    assert correction.error[0] == -0.5 and "dx -0.50 m" in correction.ax.get_title()
