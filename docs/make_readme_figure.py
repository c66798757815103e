"""Draw docs/overview.png for the README: a screw motion and the entities of table 2.1.

Run from the project root: ``python docs/make_readme_figure.py``.
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cga_lessons import conformal as cga  # noqa: E402

a, b, c = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.3]), np.array([-1.0, 0.2, 0.0])
center, radius, normal = cga.circle_center_radius(cga.circle_from_points(a, b, c))
S = cga.screw([0, 0, 1.0], [0.0, 0.0, 0.0], np.pi / 12, 0.08)  # Eq. (2.110)
pts = [np.array([1.5, 0.0, 0.0])]
for _ in range(48):
    pts.append(cga.apply_to_points(S, pts[-1]))
pts = np.array(pts)

fig = plt.figure(figsize=(6, 4.5), dpi=90)
ax = fig.add_subplot(projection="3d")
ax.plot(*pts.T, "o-", ms=3, color="tab:blue", label="a point under repeated screws (2.110)")
u = np.cross(normal, [0, 0, 1.0]) if abs(normal[2]) < 0.9 else np.cross(normal, [1.0, 0, 0])
u /= np.linalg.norm(u)
v = np.cross(normal, u)
t = np.linspace(0, 2 * np.pi, 100)
ring = center + radius * (np.outer(np.cos(t), u) + np.outer(np.sin(t), v))
ax.plot(*ring.T, color="tab:orange", label="circle a^b^c (2.80)")
ax.scatter(*np.array([a, b, c]).T, color="k", s=20, label="its three points")
L = cga.line_from_points(a, b)
p, r = cga.line_closest_point(L), cga.line_direction(L)
seg = p + np.outer(np.linspace(-2, 2, 2), r)
ax.plot(*seg.T, color="tab:green", label="line e^a^b (2.81)")
ax.scatter(*p, color="tab:green", s=30, marker="x")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_zlabel("z [m]")
ax.legend(loc="upper left", fontsize=7)
ax.set_title("cga-lessons: entities and motions of G(4,1)")
out = Path(__file__).with_name("overview.png")
fig.savefig(out, bbox_inches="tight")
print(out)
