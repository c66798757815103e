"""Tests of the exploration document (3.1-3.3): seen / occupied nodes and the path around an obstacle.

The truth is independent of the package: visibility by casting a ray from the
camera to every node against the sphere (a per-node loop solving the quadratic
|o + t d - c|^2 = r^2), occupancy by testing every node's cell against every
point, crossings by points that satisfy (3.2) and (3.3), the shortest path
around a disc by its closed form.
"""

import importlib
import math
from dataclasses import replace

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons import exploration as ex
from cga_lessons.algebra import DegenerateGeometryError, GeometryError, InvalidInputError
from cga_lessons.exploration import cases as cases
from cga_lessons.exploration import path as ep


# ------------------------------------------------------------ independent truth
def _segment_hits_ball(o, p, c, r) -> bool:
    """Does the segment o -> p meet the closed ball (c, r)?  (Plain floats; 2D or 3D.)"""
    d = [pi - oi for pi, oi in zip(p, o)]
    f = [oi - ci for oi, ci in zip(o, c)]
    a = sum(x * x for x in d)
    b = 2 * sum(x * y for x, y in zip(f, d))
    cc = sum(x * x for x in f) - r * r
    disc = b * b - 4 * a * cc
    if disc < 0:
        return False
    t1, t2 = (-b - math.sqrt(disc)) / (2 * a), (-b + math.sqrt(disc)) / (2 * a)
    return t1 <= 1.0 and t2 >= 0.0


def _in_fov(o, heading, fov, max_range, p) -> bool:
    vx, vy = p[0] - o[0], p[1] - o[1]
    rho = math.hypot(vx, vy)
    if rho <= 1e-12 or rho > max_range:
        return False
    cosang = (vx * math.cos(heading) + vy * math.sin(heading)) / rho
    return math.acos(max(-1.0, min(1.0, cosang))) <= fov / 2 + 1e-12


def _tangent_in_view(o, heading, fov, c, r) -> list[bool]:
    vx, vy = c[0] - o[0], c[1] - o[1]
    a = math.asin(r / math.hypot(vx, vy))
    out = []
    for s in (-a, a):
        tx, ty = math.cos(s) * vx - math.sin(s) * vy, math.sin(s) * vx + math.cos(s) * vy
        out.append(_in_fov(o, heading, fov, math.inf, (o[0] + tx, o[1] + ty)))
    return out


def brute_force(nodes, view, obstacle):
    """Per node: (in view, 3D ray blocked, 2D ray blocked, nearer than the centre horizontally)."""
    o, c, r = list(view.position), list(obstacle.center), obstacle.radius
    dc = math.hypot(c[0] - o[0], c[1] - o[1])
    rows = []
    for p in nodes.tolist():
        rows.append(
            (
                _in_fov(o, view.heading, view.fov, view.max_range, p),
                _segment_hits_ball(o, p, c, r),
                _segment_hits_ball(o[:2], p[:2], c[:2], r),
                math.hypot(p[0] - o[0], p[1] - o[1]) < dc,
            )
        )
    return np.array(rows, dtype=bool).reshape(-1, 4)


def classify(doc_seen, truth, view, obstacle) -> list[str]:
    """Name the document's rule behind every disagreement; 'UNEXPLAINED' when none applies."""
    any_tangent = any(_tangent_in_view(view.position, view.heading, view.fov, obstacle.center, obstacle.radius))
    out = []
    for doc, (in_fov, hit3, hit2, nearer) in zip(doc_seen, truth):
        seen = in_fov and not hit3
        if doc == seen:
            out.append("agree")
        elif not doc and in_fov and hit2 and not nearer and not hit3:
            out.append("2D shadow: the rule uses the circle, the 3D ray passes above/below the sphere")
        elif doc and in_fov and hit3 and nearer and any_tangent:
            out.append("rule 3 compares with the centre: node inside/behind the obstacle but nearer than its centre")
        elif doc and in_fov and hit3 and not any_tangent:
            out.append("no projection to the obstacle in view: the document treats the view as free (3.1.1)")
        else:
            out.append("UNEXPLAINED")
    return out


def random_config(rng, fov_max=5.9):
    """A random robot, cameras and sphere with the robot outside the sphere's circle.

    One configuration in five puts a large sphere close in front of a narrow view.
    """
    heading, fov = rng.uniform(-np.pi, np.pi), rng.uniform(np.radians(10), fov_max)
    robot = np.r_[rng.uniform(-100, 100, 2), rng.uniform(0, 40)]
    if rng.random() < 0.2:
        radius = rng.uniform(10, 45)
        ahead = heading + rng.uniform(-0.2, 0.2)
        center = np.r_[
            robot[:2] + rng.uniform(1.05, 1.5) * radius * np.array([np.cos(ahead), np.sin(ahead)]), rng.uniform(0, 40)
        ]
        fov = rng.uniform(np.radians(10), np.radians(60))
    else:
        while True:
            center = np.r_[rng.uniform(-110, 110, 2), rng.uniform(0, 40)]
            radius = rng.uniform(3, 45)
            if np.hypot(*(center[:2] - robot[:2])) > radius * 1.01:
                break
    max_range = np.inf if rng.random() < 0.5 else rng.uniform(60, 250)
    view = ex.CameraView(robot, heading, fov, max_range)
    grid = ex.make_grid((-120, 120), (-120, 120), (0, rng.choice([30.0, 60.0])), rng.choice([20.0, 30.0]))
    return grid, view, ex.SphereObstacle(center, radius)


# ------------------------------------------------------------------------- grid
def test_grid_nodes_and_cells():
    g = ex.make_grid()
    nodes = g.nodes
    assert nodes.shape == (162, 3)
    assert np.array_equal(np.unique(nodes[:, 0]), np.arange(-120, 121, 30))
    assert np.array_equal(np.unique(nodes[:, 2]), [0, 30])
    rng = np.random.default_rng(0)
    pts = rng.uniform([-130, -130, -5], [160, 160, 65], size=(500, 3))
    cells = g.cell_of(pts)
    for p, k in zip(pts, cells):
        owners = np.flatnonzero(np.all((p >= nodes) & (p < nodes + 30), axis=1))
        assert list(owners) == ([] if k < 0 else [k])
    assert ex.make_grid((-200, 200), (-200, 200), (0, 60), 20).shape == (21, 21, 4)


@pytest.mark.parametrize(
    "args", [((0, -1), (0, 1), (0, 1), 1), ((0, 1), (0, 1), (0, 1), 0), ((0, np.nan), (0, 1), (0, 1), 1)]
)
def test_grid_bad_input(args):
    with pytest.raises(InvalidInputError, match="make_grid"):
        ex.make_grid(*args)


# -------------------------------------------------------------- seen / unseen
def test_seen_without_obstacle_is_the_field_of_view():
    """Exploration 3.1.1: seen iff the bearing lies between the two edges (and within range)."""
    rng = np.random.default_rng(1)
    for _ in range(40):
        grid, view, _ = random_config(rng)
        truth = [_in_fov(view.position, view.heading, view.fov, view.max_range, p) for p in grid.nodes.tolist()]
        assert np.array_equal(ex.seen_nodes(grid.nodes, view), truth)


def test_seen_matches_ray_casting_up_to_the_documents_rules():
    """Document rules (3.1.2) vs 3D ray casting: every disagreement is named by a rule of the document."""
    rng = np.random.default_rng(2)
    tally, case_count = {}, {}
    for _ in range(150):
        grid, view, obstacle = random_config(rng)
        doc = ex.seen_nodes(grid.nodes, view, obstacle)
        truth = brute_force(grid.nodes, view, obstacle)
        kinds = classify(doc, truth, view, obstacle)
        for k in kinds:
            tally[k] = tally.get(k, 0) + 1
        case = ex.projections(view, obstacle).case
        case_count[case] = case_count.get(case, 0) + 1
        # the package's own ray casting is the same truth, node for node
        assert np.array_equal(ex.ray_cast_seen(grid.nodes, view, obstacle), truth[:, 0] & ~truth[:, 1])
    assert "UNEXPLAINED" not in tally, tally
    assert set(case_count) == {"free", "whole", "first", "second"}  # all four cases exercised
    assert tally["agree"] / sum(tally.values()) > 0.9
    assert len(tally) == 4  # each explained kind of disagreement occurs


def test_package_disagreement_codes_match_the_independent_classification():
    rng = np.random.default_rng(3)
    names = {1: "2D shadow", 2: "rule 3", 3: "no projection"}
    for _ in range(40):
        grid, view, obstacle = random_config(rng, fov_max=np.radians(170))
        sc = cases.Scenario(
            x_range=(-120, 120), y_range=(-120, 120), z_range=(0, grid.origin[2] + grid.spacing * (grid.shape[2] - 1)),
            spacing=grid.spacing, robot=view.position, heading=view.heading, fov=view.fov,
            max_range=view.max_range, sphere_center=obstacle.center, sphere_diameter=2 * obstacle.radius,
        )  # fmt: skip
        res = cases.run_scenario(sc)
        codes = cases.ray_cast_disagreements(res)
        kinds = classify(res.labels.seen, brute_force(res.grid.nodes, res.view, res.obstacle), view, obstacle)
        for code, kind in zip(codes, kinds):
            assert kind.startswith(names[code]) if code else kind == "agree"


def test_partial_view_figure_3_5():
    """Only one projection to the obstacle in view (figure 3.5 a and b), checked on nodes placed by hand."""
    view = ex.CameraView((0.0, 0.0, 10.0), 0.0, np.radians(90.0))
    d, r = 50.0, 10.0

    def at(deg, dist):
        return [dist * np.cos(np.radians(deg)), dist * np.sin(np.radians(deg)), 10.0]

    for sign, case in ((1, "first"), (-1, "second")):
        obstacle = ex.SphereObstacle(at(sign * 45.0, d), r)  # centre on an edge: one tangent in, one out
        assert ex.projections(view, obstacle).case == case
        nodes = [at(sign * 40, 30), at(sign * 40, 80), at(sign * 20, 80), at(-sign * 40, 80), at(sign * 50, 30)]
        # near side of the obstacle: seen; behind it: not; outside its wedge: seen; beyond the edge: not
        assert ex.seen_nodes(nodes, view, obstacle).tolist() == [True, False, True, True, False]


def test_narrower_field_of_view_sees_a_subset():
    wide = cases.run_scenario()
    narrow = cases.run_scenario(fov=np.radians(100.0))
    assert np.all(wide.labels.seen[narrow.labels.seen])
    assert narrow.labels.seen.sum() < wide.labels.seen.sum()


# --------------------------------------------------------------------- occupied
def _occupied_truth(grid, points):
    """A node is occupied when some point satisfies Xn <= x < Xn + Delta (and y, z): every node x every point."""
    n, p = grid.nodes[:, None, :], np.asarray(points)[None, :, :]
    return np.any(np.all((p >= n) & (p < n + grid.spacing), axis=2), axis=1)


def test_l1_distance_equation_3_1():
    rng = np.random.default_rng(4)
    nodes, p = rng.normal(size=(20, 3)), rng.normal(size=3)
    manual = [abs(n[0] - p[0]) + abs(n[1] - p[1]) + abs(n[2] - p[2]) for n in nodes]
    assert np.allclose(ex.l1_distances(nodes, p), manual, rtol=0, atol=1e-15)


def test_loop_matches_indexed_and_brute_force():
    """The nearest-node loop of exploration (3.1) and the one-pass cell index give the same occupied nodes."""
    rng = np.random.default_rng(5)
    for i in range(40):
        grid = ex.make_grid((-120, 120), (-120, 120), (0, 60), rng.choice([20.0, 30.0]))
        if i % 2:
            pts = ex.sphere_points(
                rng.uniform([-110, -110, 0], [110, 110, 60]), rng.uniform(3, 40), rng.integers(4, 30)
            )
        else:
            pts = rng.uniform([-150, -150, -10], [170, 170, 90], size=(rng.integers(1, 80), 3))
        loop = ex.occupied_nodes_loop(grid, pts)
        truth = _occupied_truth(grid, pts)
        assert np.array_equal(loop.occupied, truth)
        assert np.array_equal(ex.occupied_nodes(grid, pts), truth)
        assert not np.any(loop.analysed & loop.occupied)
        assert np.array_equal(np.sort(loop.outside), np.flatnonzero(grid.cell_of(pts) < 0))
        # every node analysed for a point was L1-nearer to it than the node that finally held it (3.1)
        nodes, last = grid.nodes, {}
        for p, n, ok in reversed(loop.steps):
            if ok:
                last[p] = n
            else:
                assert ex.l1_distances(nodes[[n]], pts[p])[0] <= ex.l1_distances(nodes[[last[p]]], pts[p])[0]


def test_analysed_nodes_are_skipped_for_one_point_only():
    """A point just below a cell face analyses the node above it; a later point in that node's cell must still
    find it (removing analysed nodes for good, a literal reading, would lose it)."""
    grid = ex.make_grid((0, 90), (0, 90), (0, 30), 30)
    pts = np.array([[29.0, 10.0, 10.0], [31.0, 10.0, 10.0]])
    loop = ex.occupied_nodes_loop(grid, pts)
    above = int(grid.cell_of(pts[1:])[0])  # the node at x = 30, owner of the second point
    assert loop.steps[0] == (0, above, False)  # L1-nearest to the first point, but not its owner
    assert loop.steps[-1] == (1, above, True)
    assert loop.occupied[above] and not loop.analysed[above]
    assert np.array_equal(loop.occupied, _occupied_truth(grid, pts))


def test_sampled_sphere_occupies_a_subset_of_the_exact_cells():
    rng = np.random.default_rng(6)
    grid = ex.make_grid((-120, 120), (-120, 120), (0, 60), 30)
    missed = 0
    for _ in range(15):
        obs = ex.SphereObstacle(rng.uniform([-100, -100, 10], [100, 100, 50]), rng.uniform(4, 20))
        exact = ex.cells_touched_by_sphere(grid, obs)
        assert np.all(exact[ex.occupied_nodes(grid, ex.sphere_points(obs.center, obs.radius, 20))])
        dense = ex.occupied_nodes(grid, ex.sphere_points(obs.center, obs.radius, 200))
        assert np.all(exact[dense])
        # a cell missed by the dense sampling holds only a sliver of the sphere (depth < 1% of r) at its corner
        lo = grid.nodes[exact & ~dense]
        c = np.asarray(obs.center)
        near = np.linalg.norm(np.clip(c, lo, lo + 30) - c, axis=1)
        far = np.linalg.norm(np.maximum(abs(c - lo), abs(c - lo - 30)), axis=1)
        assert np.all(np.minimum(obs.radius - near, far - obs.radius) < 1e-2 * obs.radius)
        missed += len(lo)
    assert missed <= 2


def test_sphere_points():
    c = np.array([1.0, -2.0, 3.0])
    pts = ex.sphere_points(c, 7.5, 20)
    assert pts.shape == (20 * 19 + 2, 3)
    assert np.allclose(np.linalg.norm(pts - c, axis=1), 7.5)
    assert len(np.unique(pts.round(9), axis=0)) == len(pts)


# ------------------------------------------------------------ conformal sphere
def _circumsphere(p):
    """Closed form: the centre solves 2 (p_i - p_0) . c = |p_i|^2 - |p_0|^2."""
    A = 2 * (p[1:] - p[0])
    b = np.sum(p[1:] ** 2, axis=1) - np.sum(p[0] ** 2)
    c = np.linalg.solve(A, b)
    return c, np.linalg.norm(p[0] - c)


def test_fit_sphere_against_closed_forms():
    rng = np.random.default_rng(7)
    for _ in range(30):
        p = rng.uniform(-100, 100, size=(4, 3))
        c, r = _circumsphere(p)
        fc, fr = ex.fit_sphere(p)
        sc, sr = cga.sphere_center_radius(cga.sphere_from_points(*p))
        assert np.allclose(fc, c, rtol=0, atol=1e-7 * (1 + r)) and abs(fr - r) <= 1e-7 * (1 + r)
        assert np.allclose(sc, c, rtol=0, atol=1e-7 * (1 + r))
        # many exact points and a translated, scaled copy
        c0, r0 = rng.uniform(-100, 100, 3), rng.uniform(1, 50)
        u = rng.normal(size=(50, 3))
        q = c0 + r0 * u / np.linalg.norm(u, axis=1, keepdims=True)
        fc, fr = ex.fit_sphere(q)
        assert np.allclose(fc, c0, atol=1e-8 * r0) and abs(fr - r0) <= 1e-8 * r0
        fc2, fr2 = ex.fit_sphere(3.0 * q + 7.0)
        assert np.allclose(fc2, 3.0 * c0 + 7.0, atol=1e-7 * r0) and abs(fr2 - 3.0 * r0) <= 1e-7 * r0


def test_fit_sphere_noisy_points_near_truth():
    rng = np.random.default_rng(8)
    u = rng.normal(size=(400, 3))
    q = np.array([10.0, -20.0, 5.0]) + 12.0 * u / np.linalg.norm(u, axis=1, keepdims=True)
    fc, fr = ex.fit_sphere(q + rng.normal(scale=0.05, size=q.shape))
    assert np.linalg.norm(fc - [10, -20, 5]) < 0.05 and abs(fr - 12.0) < 0.05


def test_enclosing_sphere_encloses_any_object():
    rng = np.random.default_rng(9)
    for _ in range(20):
        size = rng.uniform(2, 30, 3)
        center = rng.uniform(-50, 50, 3)
        pts = ex.box_surface_points(rng, center, size, 300)
        c, r = ex.enclosing_sphere(pts)
        assert np.all(np.linalg.norm(pts - c, axis=1) <= r + 1e-9)
        assert r <= np.linalg.norm(size) / 2 + 1e-9  # never larger than the box's circumscribed sphere
    u = rng.normal(size=(200, 3))
    cap = 20.0 * u / np.linalg.norm(u, axis=1, keepdims=True)
    cap = cap[cap[:, 2] > 10.0] + [5.0, 6.0, 7.0]  # one side of a ball: the conformal fit finds the ball,
    c, r = ex.fit_sphere(cap)
    assert np.linalg.norm(c - [5.0, 6.0, 7.0]) < 1e-6 and abs(r - 20.0) < 1e-6
    c, r = ex.enclosing_sphere(cap)  # but a smaller sphere encloses the points seen
    assert np.all(np.linalg.norm(cap - c, axis=1) <= r + 1e-9) and r < 20.0
    flat = np.c_[rng.uniform(0, 10, (50, 2)), np.zeros(50)]  # coplanar: falls back to the bounding box
    c, r = ex.enclosing_sphere(flat)
    assert np.all(np.linalg.norm(flat - c, axis=1) <= r + 1e-9)


# ----------------------------------------------------------- degenerate input
def test_degenerate_input_raises_clear_errors():
    view = ex.CameraView((0.0, 0.0, 10.0), np.pi, np.radians(150))
    nodes = ex.make_grid().nodes
    with pytest.raises(DegenerateGeometryError, match="robot is inside the obstacle"):
        ex.seen_nodes(nodes, view, ex.SphereObstacle((5.0, 0.0, 50.0), 8.0))
    for fov in (0.0, -1.0, 2 * np.pi, np.nan):
        with pytest.raises(InvalidInputError, match="fov"):
            ex.CameraView((0.0, 0.0, 0.0), 0.0, fov)
    empty = np.zeros((0, 3))
    for func in (ex.fit_sphere, ex.enclosing_sphere, lambda p: ex.occupied_nodes(ex.make_grid(), p),
                 lambda p: ex.occupied_nodes_loop(ex.make_grid(), p), lambda p: ex.seen_nodes(p, view)):  # fmt: skip
        with pytest.raises(InvalidInputError, match="empty"):
            func(empty)
        with pytest.raises(InvalidInputError, match="NaN"):
            func(np.array([[0.0, np.nan, 1.0]] * 5))
    with pytest.raises(InvalidInputError, match="radius"):
        ex.SphereObstacle((0, 0, 0), 0.0)
    with pytest.raises(DegenerateGeometryError, match="coplanar"):
        ex.fit_sphere(np.c_[np.random.default_rng(0).normal(size=(10, 2)), np.ones(10)])
    with pytest.raises(DegenerateGeometryError, match="at least 4"):
        ex.fit_sphere(np.eye(3))
    assert issubclass(DegenerateGeometryError, GeometryError) and issubclass(GeometryError, ValueError)


def test_wrong_kinds_and_sizes_are_refused_by_name():
    grid, view = ex.make_grid(), ex.CameraView((0.0, 0.0, 10.0), np.pi, np.radians(150))
    with pytest.raises(InvalidInputError, match="seen_nodes: view: expected a CameraView"):
        ex.seen_nodes(grid.nodes, ex.SphereObstacle((0.0, 0.0, 0.0), 1.0))
    with pytest.raises(InvalidInputError, match="cells_touched_by_sphere: obstacle: expected a SphereObstacle"):
        ex.cells_touched_by_sphere(grid, view)
    with pytest.raises(InvalidInputError, match="NodeLabels: seen: expected a 1-D array of bools"):
        ex.NodeLabels(np.array([1, 0]), np.zeros(2, bool), np.zeros(2, bool))  # 0/1 would index nodes, not mask them
    with pytest.raises(InvalidInputError, match=r"make_grid: x_range, spacing: .* nodes"):
        ex.make_grid((0.0, 1e12), (0.0, 1.0), (0.0, 1.0), 1.0)
    with pytest.raises(InvalidInputError, match="detour: n_arc: must be >= 2"):
        ep.detour([0.0, 0.0], [100.0, 0.0], [50.0, 1.0], 10.0, n_arc=1)


# ------------------------------------------------------------ document cases
def test_document_cases_3_1_4():
    """The six tests of 3.1.4.  The document gives no sphere centre; ours reproduces its 6 -> 8 occupied nodes,
    which the exact sphere/cell test (independent of the sampling) confirms."""
    res = {name: cases.run_scenario(**ch) for name, ch in cases.DOCUMENT_CASES.items()}
    base = res["base (fig. 3.4)"]
    assert base.projections.case == "whole"
    out = res["obstacle out of view (fig. 3.7a)"]
    assert out.projections.case == "free"
    assert np.array_equal(out.labels.seen, ex.seen_nodes(out.grid.nodes, out.view))
    assert res["robot turned (fig. 3.7b)"].projections.case != "free"
    for name, diameter in (("base (fig. 3.4)", 15.0), ("sphere diameter 25 cm (fig. 3.8b)", 25.0)):
        r = res[name]
        truth = _occupied_truth(r.grid, r.points)
        assert r.labels.occupied.sum() == truth.sum()
        assert (
            truth.sum() == ex.cells_touched_by_sphere(r.grid, ex.SphereObstacle(r.obstacle.center, diameter / 2)).sum()
        )
    assert (base.labels.occupied.sum(), res["sphere diameter 25 cm (fig. 3.8b)"].labels.occupied.sum()) == (6, 8)
    assert res["spacing 20 cm (fig. 3.9a)"].grid.shape == (13, 13, 2)
    assert res["workspace enlarged (fig. 3.9b)"].grid.shape == (14, 14, 3)
    with pytest.raises(InvalidInputError, match="run_scenario: not_a_field: is not a setting of Scenario"):
        cases.run_scenario(not_a_field=1)
    assert replace(cases.Scenario(), sphere_center=None).obstacle() is None


# ------------------------------------------------------------------ the detour
def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def _random_path_case(rng):
    while True:
        c, r = rng.uniform(-100, 100, 2), rng.uniform(5, 40)
        s, g = rng.uniform(-150, 150, 2), rng.uniform(-150, 150, 2)
        if min(np.linalg.norm(s - c), np.linalg.norm(g - c)) > r * 1.01 and np.linalg.norm(g - s) > 1:
            return s, g, c, r


def test_crossings_document_vs_conformal():
    """(3.2) into (3.3) by the document's algebra and the conformal point pair (2.131) agree to 1e-9."""
    rng = np.random.default_rng(10)
    crossing = 0
    for i in range(300):
        s, g, c, r = _random_path_case(rng)
        if i % 50 == 0:
            g = np.array([s[0], g[1]])  # a vertical path: no slope m
        a = ep.line_circle_intersections(s, g, c, r)
        b = ep.line_circle_intersections_conformal(s, g, c, r)
        dist = abs(_cross(g - s, c - s)) / np.linalg.norm(g - s)
        assert (a is None) == (b is None) == (dist >= r)
        if a is None:
            continue
        crossing += 1
        assert np.max(np.abs(a - b)) < 1e-9
        for p in a:  # on the circle (3.3) and on the line (3.2)
            assert (
                abs(np.linalg.norm(p - c) - r) < 1e-9 * r
                and abs(_cross(g - s, p - s)) < 1e-9 * np.linalg.norm(g - s) ** 2
            )
        assert (a[1] - a[0]) @ (g - s) > 0  # entry first
    assert crossing > 30


def _shortest_around_disc(s, g, c, R):
    ds, dg = np.linalg.norm(s - c), np.linalg.norm(g - c)
    phi = np.arccos(np.clip((s - c) @ (g - c) / (ds * dg), -1, 1))
    arc = phi - np.arccos(R / ds) - np.arccos(R / dg)
    return np.sqrt(ds**2 - R**2) + np.sqrt(dg**2 - R**2) + R * arc


def test_detour_is_smooth_stays_outside_and_is_shortest():
    rng = np.random.default_rng(11)
    detours = 0
    for _ in range(200):
        s, g, c, r = _random_path_case(rng)
        clearance = rng.choice([0.0, 5.0])
        R = r + clearance
        if min(np.linalg.norm(s - c), np.linalg.norm(g - c)) <= R:
            continue
        d = ep.detour(s, g, c, r, clearance=clearance, method=rng.choice(["conformal", "document"]))
        # no sampled point and no straight piece enters the circle
        assert np.all(np.linalg.norm(d.path - c, axis=1) >= R - 1e-9)
        for p, q in (d.path[:2], d.path[-2:]):  # the two straight pieces (the rest samples the arc)
            t = np.clip((c - p) @ (q - p) / ((q - p) @ (q - p)), 0, 1)
            assert np.linalg.norm(p + t * (q - p) - c) >= R - 1e-9 * R
        if d.direction == 0:
            assert d.crossings is None or not 0 <= (d.crossings[0] - s) @ (g - s) <= (g - s) @ (g - s)
            continue
        detours += 1
        T1, T2 = d.tangent_points
        for T, u in ((T1, T1 - s), (T2, g - T2)):  # heading along the line == heading along the arc
            along = d.direction * np.array([-(T - c)[1], (T - c)[0]]) / R
            assert abs(u @ along / np.linalg.norm(u) - 1.0) < 1e-9
        assert abs(d.length - _shortest_around_disc(s, g, c, R)) < 1e-9 * d.length
        assert d.length >= np.linalg.norm(g - s)
    assert detours > 20


def test_detour_straight_when_clear_and_errors():
    d = ep.detour([0.0, 0.0], [100.0, 0.0], [50.0, 30.0], 10.0)
    assert d.direction == 0 and d.crossings is None and d.length == 100.0
    d = ep.detour([0.0, 0.0], [100.0, 0.0], [-50.0, 0.0], 10.0)  # obstacle behind the robot
    assert d.direction == 0 and d.crossings is not None
    with pytest.raises(DegenerateGeometryError, match="start lies inside"):
        ep.detour([49.0, 1.0], [100.0, 0.0], [50.0, 0.0], 10.0)
    with pytest.raises(DegenerateGeometryError, match="goal lies inside"):
        ep.detour([0.0, 0.0], [52.0, 0.0], [50.0, 0.0], 10.0)
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        ep.line_circle_intersections([1.0, 1.0], [1.0, 1.0], [50.0, 0.0], 10.0)
    with pytest.raises(InvalidInputError, match="NaN"):
        ep.detour([0.0, np.nan], [1.0, 1.0], [50.0, 0.0], 10.0)


def test_registry_entries_resolve():
    from cga_lessons.equations.registry.exploration import ENTRIES

    assert sorted(e.label for e in ENTRIES) == ["3.1", "3.2", "3.3"]
    for e in ENTRIES:
        assert e.document == "exploration" and e.status == "numeric"
        for dotted in e.implementation.split(","):
            module, _, name = dotted.strip().rpartition(".")
            assert callable(getattr(importlib.import_module(module), name))
        for node in e.test.split(","):
            path, _, name = node.strip().partition("::")
            assert path == "tests/test_exploration.py" and callable(globals()[name])
