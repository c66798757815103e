"""Generate the synthetic 2D scenes of chapter 3 (``room.json``, ``corridor.json``, ``office.json``,
``office_twins.json``).

Run from anywhere: ``python data/scenes/make_scenes.py``.  Only NumPy and the
standard library are used, so the scenes can be regenerated without the package.

A scene is a set of closed polygons (walls with a thickness, furniture, chair
legs), in metres, in the z = 0 plane, plus a ground-truth trajectory of robot
poses ``(x, y, theta)`` sampled once per laser scan.  The trajectory is drawn
through hand-placed waypoints: the robot drives in straight lines at ``step``
metres per scan and turns in place at each waypoint by at most ``turn_step``
radians per scan.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
WALL = 0.10  # wall thickness (m)


def rect(x0, y0, x1, y1):
    """Axis-aligned rectangle as a counter-clockwise polygon."""
    x0, x1 = min(x0, x1), max(x0, x1)
    y0, y1 = min(y0, y1), max(y0, y1)
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def wall(x0, y0, x1, y1, doors=(), t=WALL):
    """An axis-aligned wall from (x0, y0) to (x1, y1) of thickness ``t``, cut by doors.

    ``doors`` is a list of ``(position, width)`` along the wall, measured from its
    first end.  Returns one rectangle per solid piece.
    """
    horizontal = abs(y1 - y0) < 1e-12
    a, b = (x0, x1) if horizontal else (y0, y1)
    lo, hi = min(a, b), max(a, b)
    cuts = sorted((lo + p - w / 2, lo + p + w / 2) for p, w in doors)
    pieces, start = [], lo
    for c0, c1 in cuts:
        pieces.append((start, c0))
        start = c1
    pieces.append((start, hi))
    out = []
    for p0, p1 in pieces:
        if p1 - p0 < 1e-9:
            continue
        if horizontal:
            out.append(rect(p0 - t / 2, y0 - t / 2, p1 + t / 2, y0 + t / 2))
        else:
            out.append(rect(x0 - t / 2, p0 - t / 2, x0 + t / 2, p1 + t / 2))
    return out


def box(cx, cy, w, h, angle=0.0):
    """A rectangle of size w x h centred at (cx, cy), rotated by ``angle``."""
    c, s = np.cos(angle), np.sin(angle)
    pts = []
    for dx, dy in ((-w / 2, -h / 2), (w / 2, -h / 2), (w / 2, h / 2), (-w / 2, h / 2)):
        pts.append([cx + c * dx - s * dy, cy + s * dx + c * dy])
    return pts


def trajectory(waypoints, step=0.10, turn_step=0.14, initial_heading=None):
    """Poses (x, y, theta) along straight legs between waypoints, turning in place at each."""
    wp = np.asarray(waypoints, float)
    heading = np.arctan2(*(wp[1] - wp[0])[::-1]) if initial_heading is None else initial_heading
    poses = [[wp[0, 0], wp[0, 1], heading]]
    for a, b in zip(wp[:-1], wp[1:]):
        target = np.arctan2(b[1] - a[1], b[0] - a[0])
        turn = (target - heading + np.pi) % (2 * np.pi) - np.pi
        n_turn = int(np.ceil(abs(turn) / turn_step))
        for k in range(1, n_turn + 1):
            poses.append([a[0], a[1], heading + turn * k / n_turn])
        heading = heading + turn
        length = np.hypot(*(b - a))
        n = max(1, int(round(length / step)))
        for k in range(1, n + 1):
            p = a + (b - a) * k / n
            poses.append([p[0], p[1], heading])
    out = np.array(poses)
    out[:, 2] = np.mod(out[:, 2] + np.pi, 2 * np.pi) - np.pi
    return out


def room():
    """A plain 6 m x 4 m rectangular room; the robot drives a loop inside it."""
    t = WALL
    polys = [rect(-t, -t, 6 + t, 0), rect(-t, 4, 6 + t, 4 + t), rect(-t, 0, 0, 4), rect(6, 0, 6 + t, 4)]
    traj = trajectory([[1.0, 1.0], [5.0, 1.0], [5.0, 3.0], [1.0, 3.0], [1.0, 1.2], [4.0, 1.2]])
    return {
        "name": "room",
        "description": "A plain 6 m x 4 m rectangular room (10 cm walls); one loop around the inside.",
        "polygons": polys,
        "trajectory": traj,
    }


def corridor():
    """An L-shaped corridor, 2.4 m wide, with desks, a shelf and chair legs along it."""
    polys = []
    # outer and inner walls of the L: leg A along x from (0, 0) to (14, 2.4); leg B along y up from x in [11.6, 14]
    polys += wall(0, 0, 14, 0)          # south wall of leg A
    polys += wall(14, 0, 14, 12)        # east wall (outer) of leg B
    polys += wall(0, 2.4, 11.6, 2.4)    # north wall of leg A (inner corner at 11.6, 2.4)
    polys += wall(11.6, 2.4, 11.6, 12)  # west wall of leg B
    polys += wall(0, 0, 0, 2.4)         # end of leg A
    polys += wall(11.6, 12, 14, 12)     # end of leg B
    # thin furniture: desks (1.2 x 0.6) against the walls, a narrow shelf, chair legs (4 cm squares)
    polys.append(rect(2.0, 0.05, 3.2, 0.65))     # desk against the south wall
    polys.append(rect(6.0, 1.75, 7.2, 2.35))     # desk against the north wall
    polys.append(rect(13.35, 5.0, 13.95, 6.2))   # desk against the east wall of leg B
    polys.append(rect(11.65, 8.0, 11.95, 9.5))   # a narrow shelf (30 cm deep)
    for cx, cy in ((4.4, 0.5), (4.8, 0.5), (4.4, 0.9), (4.8, 0.9), (13.2, 7.2), (13.6, 7.2), (13.2, 7.6), (13.6, 7.6)):
        polys.append(rect(cx - 0.02, cy - 0.02, cx + 0.02, cy + 0.02))  # chair legs
    traj = trajectory([[1.0, 1.2], [12.8, 1.2], [12.8, 11.0], [12.6, 11.0], [12.6, 1.4], [1.5, 1.4]])
    return {
        "name": "corridor",
        "description": (
            "An L-shaped corridor 2.4 m wide (legs 14 m and 12 m) with two desks, a shelf and two chairs "
            "(four 4 cm legs each): the thin objects the thesis warns about. The robot drives to the end and back."
        ),
        "polygons": polys,
        "trajectory": traj,
    }


def office():
    """An office floor 24 m x 14 m: a 2.4 m corridor along x, four rooms each side, no two alike.

    Real floors are not made of copies: the rooms differ in width, door
    position and furniture (a desk, desks in a row, a meeting table, shelves,
    a table set at an angle).  ``office_twins`` is the same floor made of
    eight identical rooms, the hard case for relocalization (chapter 5).
    """
    polys = []
    W, H = 24.0, 14.0
    y_c0, y_c1 = 5.8, 8.2  # corridor between these y
    polys += wall(0, 0, W, 0)
    polys += wall(0, H, W, H)
    polys += wall(0, 0, 0, H)
    polys += wall(W, 0, W, H)
    south = [0.0, 5.0, 11.0, 15.5, 24.0]  # partitions; rooms 5, 6, 4.5 and 8.5 m wide
    north = [0.0, 7.0, 10.5, 17.0, 24.0]  # rooms 7, 3.5, 6.5 and 7 m wide
    polys += wall(0, y_c0, W, y_c0, doors=[(1.5, 0.9), (9.0, 0.9), (13.2, 0.9), (16.7, 0.9), (21.0, 1.6)])
    polys += wall(0, y_c1, W, y_c1, doors=[(4.5, 0.9), (8.0, 0.9), (15.5, 0.9), (18.5, 0.9)])
    for x in south[1:-1]:
        polys += wall(x, 0, x, y_c0)
    for x in north[1:-1]:
        polys += wall(x, y_c1, x, H)
    # south rooms
    polys.append(rect(3.2, 0.4, 4.6, 1.1))  # S1: a desk against the outer wall
    polys.append(rect(0.1, 2.0, 0.5, 3.6))  # S1: a bookshelf on the west wall
    polys.append(rect(6.8, 2.0, 9.2, 3.2))  # S2: a meeting table
    polys.append(rect(5.1, 4.6, 5.6, 5.6))  # S2: a cabinet
    polys.append(rect(11.4, 0.4, 12.8, 1.1))  # S3: two desks in a row
    polys.append(rect(13.6, 0.4, 15.0, 1.1))
    polys.append(rect(21.5, 0.4, 23.5, 1.1))  # S4: an L-shaped desk
    polys.append(rect(22.8, 1.1, 23.5, 2.6))
    polys.append(rect(16.0, 2.8, 16.8, 4.8))  # S4: a sofa
    # north rooms
    polys.append(rect(0.8, 12.9, 2.2, 13.6))  # N1: a desk
    polys.append(rect(6.4, 9.0, 6.9, 10.0))  # N1: a cabinet
    polys.append(rect(7.1, 9.0, 7.5, 13.5))  # N2: storage shelves on both long walls
    polys.append(rect(10.0, 9.0, 10.4, 12.0))
    polys.append(rect(12.0, 12.9, 13.4, 13.6))  # N3: a desk and a table set at an angle
    polys.append(box(14.6, 10.8, 1.4, 0.8, np.radians(30.0)))
    polys.append(rect(20.5, 12.9, 21.9, 13.6))  # N4: two desks and a cabinet
    polys.append(rect(22.3, 12.9, 23.7, 13.6))
    polys.append(rect(17.2, 10.5, 17.7, 11.5))
    yc = 0.5 * (y_c0 + y_c1)
    waypoints = [
        [2.0, yc], [1.5, yc], [1.5, 3.5], [3.0, 2.5], [1.5, 4.0], [1.5, yc],          # S1 (south west)
        [8.0, yc], [8.0, 9.5], [8.8, 11.5], [8.0, 9.5], [8.0, yc],                   # N2 (the narrow store)
        [13.2, yc], [13.2, 3.0], [14.0, 2.5], [13.2, 4.0], [13.2, yc],               # S3
        [18.5, yc], [18.5, 10.5], [20.5, 11.5], [18.5, 10.0], [18.5, yc],            # N4 (north east)
        [4.0, yc],
    ]
    return _office_scene(
        "office",
        "An office floor 24 m x 14 m: a corridor 2.4 m wide along x, four rooms on each side, no two alike "
        "(3.5 to 8.5 m wide, doors in different places, desks, shelves, a meeting table, a sofa, a table "
        "set at an angle). The robot visits four rooms and returns along the corridor.",
        polys,
        waypoints,
    )


def _office_scene(name, description, polys, waypoints):
    """A scene of the office floor: the robot drives 20 cm per scan and turns up to 12 degrees per scan."""
    traj = trajectory(waypoints, step=0.2, turn_step=np.radians(12.0), initial_heading=np.pi)
    return {"name": name, "description": description, "polygons": polys, "trajectory": traj}


def office_twins():
    """The office floor made of eight identical rooms (same size, door and desk): a hard case for chapter 5."""
    polys = []
    W, H = 24.0, 14.0
    y_c0, y_c1 = 5.8, 8.2  # corridor between these y
    polys += wall(0, 0, W, 0)
    polys += wall(0, H, W, H)
    polys += wall(0, 0, 0, H)
    polys += wall(W, 0, W, H)
    xs = [0.0, 6.0, 12.0, 18.0, 24.0]
    # corridor walls with one door (0.9 m) per room, 1.5 m from the room's west wall
    polys += wall(0, y_c0, W, y_c0, doors=[(x + 1.5, 0.9) for x in xs[:-1]])
    polys += wall(0, y_c1, W, y_c1, doors=[(x + 4.5, 0.9) for x in xs[:-1]])
    for x in xs[1:-1]:
        polys += wall(x, 0, x, y_c0)
        polys += wall(x, y_c1, x, H)
    # furniture: a desk in each room, a cabinet in some
    for x in xs[:-1]:
        polys.append(rect(x + 3.2, 0.4, x + 4.6, 1.1))
        polys.append(rect(x + 0.8, H - 1.1, x + 2.2, H - 0.4))
    polys.append(rect(6.3, 4.6, 6.8, 5.6))
    polys.append(rect(17.2, 8.5, 17.7, 9.5))
    yc = 0.5 * (y_c0 + y_c1)
    waypoints = [
        [2.0, yc], [1.5, yc], [1.5, 3.5], [3.0, 2.5], [1.5, 4.0], [1.5, yc],   # room 1 (south west)
        [10.5, yc], [10.5, 9.5], [9.0, 11.0], [10.5, 9.5], [10.5, yc],          # room 6 (north, second)
        [13.5, yc], [13.5, 3.0], [15.5, 2.5], [13.5, 4.0], [13.5, yc],          # room 3 (south, third)
        [22.5, yc], [22.5, 10.5], [20.5, 11.5], [22.5, 10.0], [22.5, yc],       # room 8 (north east)
        [4.0, yc],
    ]
    return _office_scene(
        "office_twins",
        "The office floor built from copies: a corridor 2.4 m wide along x, four identical rooms on each side "
        "(6 m x 5.8 m, the same 0.9 m door, the same desk) and two cabinets. From inside a room a single "
        "scan cannot tell which room it is (chapter 5). The robot visits four rooms and returns along the corridor.",
        polys,
        waypoints,
    )


def write(scene, folder=HERE):
    out = dict(scene)
    out["trajectory"] = np.round(np.asarray(scene["trajectory"]), 6).tolist()
    out["polygons"] = [np.round(np.asarray(p, float), 6).tolist() for p in scene["polygons"]]
    out["units"] = "metres, radians; trajectory rows are (x, y, theta), one per laser scan"
    out["generator"] = "data/scenes/make_scenes.py"
    path = Path(folder) / f"{scene['name']}.json"
    path.write_text(json.dumps(out, indent=1) + "\n")
    return path


if __name__ == "__main__":
    for make in (room, corridor, office, office_twins):
        p = write(make())
        s = json.loads(p.read_text())
        print(f"{p.name}: {len(s['polygons'])} polygons, {len(s['trajectory'])} poses")
