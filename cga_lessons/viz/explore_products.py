"""An explorer for notebook 01: the geometric product of two vectors and the rotor made of two reflections.

:class:`ProductExplorer` takes two vectors of the plane in G(2) (:class:`cga_lessons.algebra.Algebra`): ``a`` at
``direction`` degrees and ``b`` turned ``angle`` degrees further, of lengths ``len_a`` and ``len_b``.  It draws

* ``a``, ``b`` and the oriented parallelogram of ``a ^ b`` (2.6, figure 2.2): its area is ``|a||b| sin(angle)``
  and its sign the sense of turning from ``a`` to ``b`` (2.7);
* the product ``ab = a . b + a ^ b`` (2.8, 2.11) as a point of the plane of scalars and ``e12``: it lies
  ``|a||b|`` from the origin at the angle from ``a`` to ``b``, and ``ba = a . b - a ^ b`` (2.12) is its mirror
  image;
* a test vector ``v`` reflected in the line orthogonal to ``a`` (``-a v a^-1``, 2.84 with the inverse 2.19),
  then in the line orthogonal to ``b``: the result is ``R v ~R`` (2.98) with the rotor ``R = ba / |a||b|``
  (2.95), ``v`` turned by twice the angle from ``a`` to ``b``, whatever the lengths.

:meth:`update` changes the vectors and redraws in place; :meth:`widget` adds sliders for a live session.

    >>> ex = ProductExplorer(angle=30.0, len_a=2.0, len_b=1.0, direction=0.0)
    >>> round(ex.dot, 12) == round(3**0.5, 12), round(ex.wedge, 12), round(ex.turn_deg, 9)
    (True, 1.0, 60.0)
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from cga_lessons.algebra import Algebra, Multivector
from cga_lessons.checks import fail, real

from .controls import slider_panel
from .inputs import SQUARED, SQUARED_WHY, vector

__all__ = ["ProductExplorer", "geometric_product", "reflect"]

#: Why the products' vectors are limited to +-1e100: ``n v n^-1`` multiplies three of them, and (1e100)^3 stays
#: within a float's range.
_CUBED = "the products multiply up to three of them: (1e100)^3 must stay within a float's range"

G2 = Algebra(2)


def geometric_product(a, b) -> tuple[Multivector, float, float]:
    """``ab`` of two plane vectors (2.8) with its scalar part ``a . b`` (2.5) and the ``e12`` coefficient of ``a ^ b``.

    >>> ab, dot, wedge = geometric_product([3.0, 1.0], [1.0, 2.0])
    >>> dot, wedge, str(ab)
    (5.0, 5.0, '5 + 5 e12')
    """
    a, b = (vector(x, "geometric_product", k, (2,), limit=1e100, why=_CUBED) for k, x in (("a", a), ("b", b)))
    ab = G2.vector([float(a[0]), float(a[1])]) * G2.vector([float(b[0]), float(b[1])])
    return ab, float(ab.scalar()), float(ab["e12"])


def reflect(v, n) -> np.ndarray:
    """``-n v n^-1``: ``v`` reflected in the line orthogonal to ``n`` (2.84, with ``n^-1 = n / n^2``, 2.19)."""
    v, n = (vector(x, "reflect", k, (2,), limit=1e100, why=_CUBED) for k, x in (("v", v), ("n", n)))
    if not np.hypot(*n) > 0:
        raise fail("reflect", "n", "the zero vector has no inverse (n^2 = 0): no line to reflect in")
    V, N = G2.vector([float(v[0]), float(v[1])]), G2.vector([float(n[0]), float(n[1])])
    out = -(N * V * N.inv())
    return np.array([float(out["e1"]), float(out["e2"])])


def _check(value, func: str, name: str, positive: bool = False) -> float:
    """A slider's value as a float; NaN, inf, a bool or a string raise InvalidInputError (a ValueError) naming both.

    Angles lie within +-1e6 degrees, lengths in (0, 1e6]."""
    v = real(value, func, name, low=-1e6, high=1e6)
    if positive and v <= 0:
        raise fail(func, name, f"must be positive, got {v!r}")
    return v


def _arc(radius: float, start: float, stop: float, n: int = 40) -> np.ndarray:
    t = np.linspace(start, stop, n)
    return radius * np.stack([np.cos(t), np.sin(t)])


class ProductExplorer:
    """Two plane vectors: their geometric product and the rotation by two reflections; redrawn by :meth:`update`.

    Angles in degrees; ``test`` is the vector the rotor turns.
    """

    def __init__(self, angle: float = 35.0, len_a: float = 1.6, len_b: float = 1.2, direction: float = 15.0,
                 test=(1.1, 0.35)):  # fmt: skip
        func = "ProductExplorer"
        self.angle, self.direction = _check(angle, func, "angle"), _check(direction, func, "direction")
        self.len_a, self.len_b = _check(len_a, func, "len_a", True), _check(len_b, func, "len_b", True)
        self.test = vector(test, func, "test", (2,), limit=SQUARED, why=SQUARED_WHY)
        if not np.hypot(*self.test) > 0:
            raise fail(func, "test", "the vector to turn must not be zero")
        self.fig, (self.ax_vec, self.ax_prod, self.ax_rot) = plt.subplots(1, 3, figsize=(13.5, 4.6))
        ax = self.ax_vec
        (self._para,) = ax.fill([0, 0], [0, 0], alpha=0.35, lw=1.2)
        (self._arc_ab,) = ax.plot([], [], color="0.3", lw=1)
        self._ab = ax.quiver([0, 0], [0, 0], [1, 0], [0, 1], color=["tab:blue", "tab:orange"], angles="xy",
                             scale_units="xy", scale=1, width=0.012)  # fmt: skip
        self._label_a, self._label_b = ax.text(0, 0, "a", color="tab:blue"), ax.text(0, 0, "b", color="tab:orange")
        ax = self.ax_prod
        ax.axhline(0, color="0.6", lw=0.8)
        ax.axvline(0, color="0.6", lw=0.8)
        (self._circle,) = ax.plot([], [], ":", color="0.5", lw=1, label="|ab| = |a||b|")
        (self._parts,) = ax.plot([], [], "--", color="tab:purple", lw=1)
        (self._arc_prod,) = ax.plot([], [], color="0.3", lw=1)
        (self._prod,) = ax.plot([], [], "o", color="tab:purple", ms=9, label="ab = a.b + a^b  (2.11)")
        (self._rev,) = ax.plot([], [], "o", mfc="white", mec="tab:purple", ms=9, label="ba = a.b - a^b  (2.12)")
        ax.set_xlabel("scalar part  a.b")
        ax.set_ylabel("e12 part  (a^b)")
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=8, ncol=2)
        ax = self.ax_rot
        (self._mirror_a,) = ax.plot([], [], "--", color="tab:blue", lw=1, label="mirror orthogonal to a")
        (self._mirror_b,) = ax.plot([], [], "--", color="tab:orange", lw=1, label="mirror orthogonal to b")
        (self._arc_turn,) = ax.plot([], [], color="tab:green", lw=1)
        self._vecs = ax.quiver([0, 0, 0], [0, 0, 0], [1, 1, 1], [0, 0, 0], color=["0.35", "0.7", "tab:green"],
                               angles="xy", scale_units="xy", scale=1, width=0.012)  # fmt: skip
        box = {"fc": "white", "ec": "none", "alpha": 0.8, "pad": 1.0}
        self._labels_v = [ax.text(0, 0, s, color=c, ha="center", va="center", bbox=box) for s, c in
                          (("v", "0.35"), ("-a v a^-1", "0.55"), ("R v ~R", "tab:green"))]  # fmt: skip
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=8, ncol=2)
        for ax in (self.ax_vec, self.ax_prod, self.ax_rot):
            ax.set_aspect("equal")
            ax.grid(alpha=0.25)
        self.ax_rot.set_xlim(-1.9, 1.9)
        self.ax_rot.set_ylim(-1.9, 1.9)
        self.update()

    def update(self, angle=None, len_a=None, len_b=None, direction=None) -> None:
        """Change the angle from ``a`` to ``b``, the lengths or ``a``'s direction (degrees), recompute and redraw."""
        func = "ProductExplorer.update"
        if angle is not None:
            self.angle = _check(angle, func, "angle")
        if len_a is not None:
            self.len_a = _check(len_a, func, "len_a", positive=True)
        if len_b is not None:
            self.len_b = _check(len_b, func, "len_b", positive=True)
        if direction is not None:
            self.direction = _check(direction, func, "direction")
        ta, tb = np.radians(self.direction), np.radians(self.direction + self.angle)
        self.a = self.len_a * np.array([np.cos(ta), np.sin(ta)])
        self.b = self.len_b * np.array([np.cos(tb), np.sin(tb)])
        self.ab, self.dot, self.wedge = geometric_product(self.a, self.b)  # (2.8), (2.11)
        self.ba = geometric_product(self.b, self.a)[0]  # (2.12)
        self.rotor = self.ba * (1.0 / (self.len_a * self.len_b))  # (2.95): cos(angle) - sin(angle) e12
        self.reflected = reflect(self.test, self.a)  # (2.84)
        self.rotated = reflect(self.reflected, self.b)  # = R v ~R (2.98)
        v, w = self.test, self.rotated
        turn = np.degrees(np.arctan2(v[0] * w[1] - v[1] * w[0], v @ w))  # measured, in (-180, 180]
        self.turn_deg = float(turn + 360.0 * np.round((2 * self.angle - turn) / 360.0))  # the turn nearest 2 angle
        self._draw(ta, tb)

    def _draw(self, ta: float, tb: float) -> None:
        a, b = self.a, self.b
        self._para.set_xy(np.array([[0, 0], a, a + b, b]))
        self._para.set_facecolor("tab:green" if self.wedge >= 0 else "tab:red")
        self._arc_ab.set_data(*_arc(0.35 * min(self.len_a, self.len_b), ta, tb))
        self._ab.set_UVC([a[0], b[0]], [a[1], b[1]])
        self._label_a.set_position(a + 0.12 * a / self.len_a)
        self._label_b.set_position(b + 0.12 * b / self.len_b)
        sense = "anticlockwise" if self.wedge >= 0 else "clockwise"
        self.ax_vec.set_title(f"a ^ b = {self.wedge:+.2f} e12 (2.6)\narea {abs(self.wedge):.2f}, turning {sense} "
                              "from a to b (2.7)", fontsize=10)  # fmt: skip
        lim = 1.15 * max(np.hypot(*(a + b)), self.len_a, self.len_b, 1.0)
        self.ax_vec.set_xlim(-lim, lim)
        self.ax_vec.set_ylim(-lim, lim)
        r = self.len_a * self.len_b
        self._circle.set_data(*_arc(r, 0.0, 2 * np.pi, 120))
        self._arc_prod.set_data(*_arc(0.3 * r, 0.0, np.radians(self.angle)))
        self.ax_prod.set_xlim(-1.3 * r, 1.3 * r)
        self.ax_prod.set_ylim(-1.3 * r, 1.3 * r)
        self._parts.set_data([self.dot, self.dot, 0.0], [0.0, self.wedge, self.wedge])
        self._prod.set_data([self.dot], [self.wedge])
        self._rev.set_data([self.dot], [-self.wedge])
        self.ax_prod.set_title(f"ab = {self.dot:.2f} {self.wedge:+.2f} e12 (2.11)\n|a||b| = {r:.2f}, at "
                               f"{self.angle:.0f} deg from the scalar axis", fontsize=10)  # fmt: skip
        for line, n in ((self._mirror_a, a), (self._mirror_b, b)):
            m = 1.8 * np.array([-n[1], n[0]]) / np.hypot(*n)
            line.set_data([-m[0], m[0]], [-m[1], m[1]])
        start = np.arctan2(self.test[1], self.test[0])
        self._arc_turn.set_data(*_arc(0.45, start, start + np.radians(self.turn_deg)))
        vs = np.array([self.test, self.reflected, self.rotated])
        self._vecs.set_UVC(vs[:, 0], vs[:, 1])
        for text, v in zip(self._labels_v, vs):
            u = v / np.hypot(*v)
            side = np.array([u[1], -u[0]])  # to the right of the arrow, inside the axes
            text.set_position(0.75 * v + 0.12 * side)
            text.set_horizontalalignment("left" if side[0] >= 0 else "right")
        self.ax_rot.set_title(f"two reflections: R v ~R (2.84, 2.98)\nv turned by {self.turn_deg:.0f} deg = "
                              f"2 x {self.angle:.0f} deg", fontsize=10)  # fmt: skip
        self.fig.tight_layout()
        self.fig.canvas.draw_idle()

    def widget(self):
        """ipywidgets sliders for the angle, the lengths and ``a``'s direction, bound to :meth:`update`."""
        from ipywidgets import FloatSlider

        def show(angle, len_a, len_b, direction):
            self.update(angle=angle, len_a=len_a, len_b=len_b, direction=direction)
            return self.fig

        def slider(value, lo, hi, step, description):
            return FloatSlider(value=value, min=lo, max=hi, step=step, description=description,
                               continuous_update=False)  # fmt: skip

        return slider_panel(
            show,
            angle=slider(self.angle, -180, 180, 5, "angle a->b"),
            len_a=slider(self.len_a, 0.2, 2.0, 0.1, "|a|"),
            len_b=slider(self.len_b, 0.2, 2.0, 0.1, "|b|"),
            direction=slider(self.direction, -180, 180, 5, "a's direction"),
        )
