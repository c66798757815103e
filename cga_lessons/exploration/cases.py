"""The test cases of the exploration document's section 3.1.4, and the check against ray casting.

A :class:`Scenario` holds one configuration (workspace, Delta, robot, cameras,
sphere) in centimetres and radians; :data:`DOCUMENT_CASES` lists the document's
six tests as changes to the base scenario; :func:`run_scenario` labels the nodes
(:mod:`cga_lessons.exploration`).  :func:`ray_cast_disagreements` compares the
document's 2D rules with 3D ray casting and names the rule behind each difference.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from cga_lessons import checks
from cga_lessons.algebra import GeometryError

from .grid import (
    CameraView,
    Grid,
    SphereObstacle,
    check_grid_size,
    check_point,
    check_positive,
    check_range,
    check_reach,
    make_grid,
    node_count,
)
from .nodes import (
    NodeLabels,
    OccupancyLoop,
    Projections,
    occupied_nodes,
    occupied_nodes_loop,
    projections,
    ray_cast_seen,
    seen_nodes,
)
from .spheres import sphere_points

__all__ = [
    "Scenario",
    "DOCUMENT_CASES",
    "ScenarioResult",
    "run_scenario",
    "summary",
    "occupied_counts_random_centres",
    "DISAGREEMENTS",
    "ray_cast_disagreements",
]


@dataclass(frozen=True)
class Scenario:
    """One configuration of section 3.1.4 (centimetres, radians).

    The document gives the workspace, Delta, the field of view, the robot's initial
    heading (180 deg, figure 3.3) and the sphere's diameter; it does not give the
    sphere's centre or the cameras' height: ours are choices (see DOCUMENT_CASES).
    """

    x_range: tuple = (-120.0, 120.0)
    y_range: tuple = (-120.0, 120.0)
    z_range: tuple = (0.0, 30.0)
    spacing: float = 30.0
    robot: tuple = (0.0, 0.0, 20.0)
    heading: float = np.pi
    fov: float = np.radians(150.0)
    max_range: float = np.inf
    sphere_center: tuple | None = (-63.0, 6.0, 24.0)
    sphere_diameter: float = 15.0
    sphere_samples: int = 20

    def __post_init__(self):
        f = "Scenario"
        d = check_positive(self.spacing, f, "spacing")
        counts = []
        for name in ("x_range", "y_range", "z_range"):
            lo, hi = check_range(getattr(self, name), f, name)
            counts.append(node_count(lo, hi, d, f, name))
            object.__setattr__(self, name, (lo, hi))
        check_grid_size(counts, f, "x_range, y_range, z_range, spacing")
        object.__setattr__(self, "spacing", d)
        object.__setattr__(self, "robot", tuple(float(v) for v in check_point(self.robot, f, "robot")))
        object.__setattr__(self, "heading", checks.real(self.heading, f, "heading"))
        fov = checks.real(self.fov, f, "fov", low=0.0, high=2 * np.pi, strict_low=True, strict_high=True)
        object.__setattr__(self, "fov", fov)
        object.__setattr__(self, "max_range", check_reach(self.max_range, f, "max_range"))
        if self.sphere_center is not None:
            c = tuple(float(v) for v in check_point(self.sphere_center, f, "sphere_center"))
            object.__setattr__(self, "sphere_center", c)
        object.__setattr__(self, "sphere_diameter", check_positive(self.sphere_diameter, f, "sphere_diameter"))
        object.__setattr__(self, "sphere_samples", checks.integer(self.sphere_samples, f, "sphere_samples", low=3,
                                                                  high=3000))  # fmt: skip

    def grid(self) -> Grid:
        return make_grid(self.x_range, self.y_range, self.z_range, self.spacing)

    def view(self) -> CameraView:
        return CameraView(self.robot, self.heading, self.fov, self.max_range)

    def obstacle(self) -> SphereObstacle | None:
        if self.sphere_center is None:
            return None
        return SphereObstacle(self.sphere_center, self.sphere_diameter / 2)


#: The test cases of section 3.1.4, each a change to the base scenario (figure 3.4).
DOCUMENT_CASES = {
    "base (fig. 3.4)": {},
    "obstacle out of view (fig. 3.7a)": {"sphere_center": (63.0, -36.0, 24.0)},
    "robot turned (fig. 3.7b)": {"heading": np.radians(225.0)},
    "field of view 100 deg (fig. 3.8a)": {"fov": np.radians(100.0)},
    "sphere diameter 25 cm (fig. 3.8b)": {"sphere_diameter": 25.0},
    "spacing 20 cm (fig. 3.9a)": {"spacing": 20.0},
    "workspace enlarged (fig. 3.9b)": {"x_range": (-200.0, 200.0), "y_range": (-200.0, 200.0), "z_range": (0.0, 60.0)},
}


@dataclass(frozen=True)
class ScenarioResult:
    """Everything computed for a :class:`Scenario` (for printing and drawing)."""

    scenario: Scenario
    grid: Grid
    view: CameraView
    obstacle: SphereObstacle | None
    points: np.ndarray | None
    projections: Projections
    labels: NodeLabels
    loop: OccupancyLoop | None


def run_scenario(scenario: Scenario | None = None, **changes) -> ScenarioResult:
    """Label the nodes of a scenario (the base one, with ``changes`` applied: any of :class:`Scenario`'s fields)."""
    f = "run_scenario"
    if scenario is not None:
        checks.instance(scenario, f, "scenario", Scenario, "a Scenario or None")
    known = [fl.name for fl in fields(Scenario)]
    for name in changes:
        if name not in known:
            raise checks.fail(f, name, f"is not a setting of Scenario; the settings are {', '.join(known)}")
    try:
        return _run(replace(scenario or Scenario(), **changes))
    except GeometryError as exc:  # a bad change, or a robot inside the obstacle: say which call
        raise type(exc)(f"{f}: {exc}") from None


def _run(sc: Scenario) -> ScenarioResult:
    grid, view, obstacle = sc.grid(), sc.view(), sc.obstacle()
    points = None if obstacle is None else sphere_points(obstacle.center, obstacle.radius, sc.sphere_samples)
    loop = None if points is None else occupied_nodes_loop(grid, points)
    seen = seen_nodes(grid.nodes, view, obstacle)
    z = np.zeros(grid.size, bool)
    labels = NodeLabels(seen, z if loop is None else loop.occupied, z if loop is None else loop.analysed)
    return ScenarioResult(sc, grid, view, obstacle, points, projections(view, obstacle), labels, loop)


def summary(result: ScenarioResult) -> str:
    """One line: node counts per label, the case of 3.1.2 and the projections' bearings in degrees."""
    checks.instance(result, "summary", "result", ScenarioResult, "a ScenarioResult (run_scenario)")
    c = result.labels.counts()
    pr = result.projections
    text = (
        f"{result.grid.size} nodes: seen {c['seen']}, not seen {c['not seen']}, occupied {c['occupied']}, "
        f"analysed {c['analysed']} | case {pr.case}"
    )
    absolute = lambda a: (np.degrees(result.view.heading + a)) % 360.0  # noqa: E731
    text += " | edges " + "/".join(f"{absolute(a):.1f}" for a in pr.edges)
    if pr.tangents is not None:
        text += " | tangents " + "/".join(f"{absolute(a):.1f}" for a in pr.tangents) + " deg"
    return text


def occupied_counts_random_centres(rng, n: int = 500, diameters=(15.0, 25.0), scenario: Scenario | None = None):
    """Occupied-node counts for spheres of the given diameters at ``n`` random centres; int array (n, len(diameters)).

    Centres are uniform over the workspace, kept one largest radius inside it.
    """
    f = "occupied_counts_random_centres"
    checks.generator(rng, f)
    n = checks.integer(n, f, "n", low=0, high=10**5)
    diameters = checks.array(diameters, f, "diameters", (None,), at_least=1)
    if np.any(diameters <= 0):
        raise checks.fail(f, "diameters", f"must be > 0, got {diameters.tolist()}")
    if scenario is not None:
        checks.instance(scenario, f, "scenario", Scenario, "a Scenario or None")
    sc = scenario or Scenario()
    grid = sc.grid()
    hi = np.asarray(grid.origin) + grid.spacing * (np.asarray(grid.shape) - 1)
    margin = float(diameters.max()) / 2
    low, high = np.asarray(grid.origin) + margin, hi + grid.spacing - margin
    if np.any(low > high):
        raise checks.degenerate(f, "diameters", f"a sphere of diameter {2 * margin:g} does not fit in the workspace")
    out = np.zeros((n, len(diameters)), int)
    for k in range(n):
        c = rng.uniform(low, high)
        for j, d in enumerate(diameters):
            out[k, j] = occupied_nodes(grid, sphere_points(c, d / 2, sc.sphere_samples)).sum()
    return out


#: Why the document's label differs from 3D ray casting, by the rule responsible.
DISAGREEMENTS = {
    0: "agree",
    1: "2D shadow: the document hides the node, the 3D ray passes above or below the sphere",
    2: "nearer than the centre: the document sees the node, it is inside or behind the obstacle",
    3: "obstacle fills the view: no tangent in view, the document treats the view as free",
}


def ray_cast_disagreements(result: ScenarioResult) -> np.ndarray:
    """Code (0-3 of :data:`DISAGREEMENTS`) of each node: where and why the document's rule and 3D ray casting differ."""
    checks.instance(result, "ray_cast_disagreements", "result", ScenarioResult, "a ScenarioResult (run_scenario)")
    nodes = result.grid.nodes
    doc = result.labels.seen
    truth = ray_cast_seen(nodes, result.view, result.obstacle)
    out = np.zeros(len(nodes), int)
    out[~doc & truth] = 1
    out[doc & ~truth] = 3 if result.projections.case == "free" else 2
    return out
