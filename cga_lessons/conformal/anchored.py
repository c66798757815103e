"""Entities that carry a local frame, so that their properties are exact at any distance from the origin (section
2.4, the translator 2.100).

**Why.**  A round (sphere, circle, point pair) at distance |c| from the origin stores |c|^2-sized e+/e- coefficients
whose difference is its squared size (see :mod:`cga_lessons.conformal.entities_frame`): the 32 float64 coefficients
of a unit sphere 1e6 out do not hold its radius to better than about 1e-4.  No reader can do better than the blade
holds, so the entities the library builds carry more: an :class:`Anchored` is a
:class:`~cga_lessons.algebra.Multivector` (the ordinary global coefficients: every product, dual, meet, ... works on
them exactly as on a plain multivector, bit for bit) with two read-only slots,

* ``anchor``: a Euclidean point f of the data, shape (3,), or (..., 3) for a batch;
* ``local``: the same entity about the anchor, ``T_{-f} X ~T_{-f}`` (2.100): a plain multivector with small,
  well-conditioned coefficients, built in closed form from the data translated by -f (never by translating the
  global coefficients).

The readers (``sphere_center_radius``, ``circle_center_radius``, ``point_pair_endpoints``, ``point_sphere_side``,
``point_pair_sphere``, ``classify``, the line readers, ``plane_normal_distance``) read ``local`` and add the anchor
back: sizes and directions to a few eps relative, positions to that plus the rounding of the coordinates themselves.
Both describe the same entity; the global coefficients are its rounding onto the e+/e- storage (the e0 part of a round
is put on the grid of its e+/e- coefficients, a change of ~eps |c|^2 relative), ``local`` is the entity of the data.

**What keeps the frame.**  Every translation-covariant operation (:mod:`~cga_lessons.conformal.anchored_ops`):
``T (X o Y) ~T = (T X ~T) o (T Y ~T)`` for a translator T (2.100) and each of the geometric, outer and inner
products, the contractions, sums and differences, scalar multiples, negation, grade projection, the reverse and the
other involutions, the inverse, powers, normalisation and the dual (Ic commutes with T).  The result of such an
operation on anchored entities X (anchor f) and Y (anchor g), or on one and a number or a translation-invariant
multivector (1, e and ``e ^ A``, Ic: :func:`~cga_lessons.conformal.anchored_ops.invariant`), is anchored at f, its
local blade the same operation on X's local and Y's local moved into f's frame, ``T_{g-f} Y.local ~T_{g-f}``.  A
plain conformal point is an anchored entity too (``w up(x) = T_x (w e0) ~T_x``: anchor x, local ``w e0``,
:func:`~cga_lessons.conformal.anchored_ops.point_frame`): with one the frame follows, and ``^``, ``+`` and ``-`` of
plain points make anchored entities (``up(a) ^ up(b) ^ up(c) ^ up(d)``, :mod:`~cga_lessons.conformal.point_wedges`).  So
the circle ``s1 ^ s2`` of two spheres (2.79), the point pair where a line cuts a sphere, a circle's plane, a scaled
sphere are as exact as the entities they are made of, at any distance (when those are near each other: ``g - f``
is their distance, not theirs from the origin).  The functions of :mod:`~cga_lessons.conformal.blades`
(contractions, ``dual``, ``regressive_product``, ``join``, ``meet``, ``project``, ``reject``) and ``intersect``
carry it the same way.  The dual and standard forms keep it, and so do :meth:`Anchored.batch_item` and ``apply`` (and
``reflect_in_plane``, ``invert_in_sphere``) of a versor that maps points to points as follows.  The anchor f goes
to its image f' and the local blade is moved by ``W = T_{-f'} V T_f``, which fixes the origin and is built from
V's geometry, never from products of the global coefficients:

* a motor M = T_t R (``M T_f = T_{M f} R``, 2.102): ``local`` turns by the rotor part;
* a reflection in a plane ``n + d e`` (2.89-2.91; standard or dual form) or its product with a motor, an odd
  isometry ``T_t U``: W is U, the reflection in the plane n through the origin (``U L^ U^-1``, 2.82);
* an inversion in a sphere of centre p and squared radius r2 (2.84-2.88; real or imaginary, standard or dual form):
  with q = p - f, ``f' = f + u``, ``u = q (1 - r2 / q^2)``, and ``W = (q - u/2) + e0 + (u/2) E``
  (:func:`inverted`), of the size of q; the centre and radius are read off the sphere's own local blade when it is
  anchored (exact at any distance), else off its coefficients;
* a dilation (the dilator ``a - b E``) or a similarity ``T_t U D_s`` (its product with a motor or a reflection):
  W = U D_s (:mod:`.similarities`); an inversion times a motor (S M or M S): its two motions in turn
  (:mod:`.anchored_versors`).

An anchored versor (two anchored spheres multiplied: two inversions) is applied in its own frame
(:func:`~cga_lessons.conformal.anchored_versors.in_versor_frame`; where its global coefficients no longer hold
it, 1e5 out or more, the global result is the local one translated back:
:func:`~cga_lessons.conformal.anchored_versors.lost_versor_apply`).  Other versors without a frame (an inversion
times a reflection: a plane carries none) drop the frame, as does an
inversion that sends the anchor to infinity (when first read); so do an operation with a multivector that
translations change and that is no point (e1, a rotor, a motor: move an entity with ``apply``; a sphere that carries
no frame), ``map`` and ``simplify`` (a plain :class:`~cga_lessons.algebra.Multivector`: the frame is dropped, never
stale).

The global coefficients of every result are those of the plain operation, bit for bit, and so are the numbers read
off them (``scalar()``, ``norm2()``, ``X["e1"]``), with two exceptions: apply of an anchored versor whose global
coefficients no longer hold it (above; a grade they lost to cancellation stays in the local blade,
:data:`~cga_lessons.conformal.anchored_ops.LOST_GRADE`), and join and meet of two anchored blades.  Whether
the spans overlap (``tol`` bounds the sines of the principal angles in the coefficient space) is decided on the
local blades (the second moved into the first's frame), which hold the geometry; 1e5 out or more the global
4-spaces of two unit spheres are less than the default ``tol = 1e-10`` apart (8e-13 times their size at 1e6), a
decision of round-off (a plain blade's meet is there a blade of grade 4).  Where the local and the global blades
decide the same grade the result is the plain one, bit for bit, with its frame (where the weight depends on the
frame, a partial overlap or a null join, the local blade is scaled to match the global one); where they differ the
result is the local decision, anchored, its global coefficients its local blade translated back by the anchor
(``T_f L ~T_f``): ``meet``/``intersect`` of two far spheres is their circle, exact, at the default ``tol``.  An
:class:`Anchored` cannot be changed in place: its coefficient map refuses writes and its arrays are read-only;
``copy.copy`` and ``copy.deepcopy`` return it as it is.  It prints and compares as the multivector of its global
coefficients.

**Cost.**  The local blade and a motion are built when first read (:meth:`Anchored.settle`): a constructor adds
the choice of the anchor, ``apply`` a few microseconds whatever the batch, an operation the closure that builds its
local blade (a chain of unread results is built from its end, at most 48 deep), a reader one small closed form.

Lines are anchored too (at one of their points): ``point_line_distance`` takes ``x - f`` first, which keeps a
distance far below the coordinates' resolution to its relative accuracy, and a derived line (``PP ^ e``) keeps the
direction of its pair.  Planes of ``plane`` and ``plane_from_points`` are not anchored (every property is held by
parts without cancellation, :mod:`cga_lessons.conformal.entities_frame`); a derived plane (a circle's plane) is.
SymPy input is exact and never anchored.
"""

from __future__ import annotations

import numpy as np

from cga_lessons.algebra import GeometryError, Multivector
from cga_lessons.checks import fail

from .anchored_ops import FrameOps, NoFrame, Pending, chain_depth, read_only, view
from .entities_frame import dot, nearest, parts, put_vec, sphere_std
from .model import G41, E, eo
from .points import vector

__all__ = [
    "Anchored",
    "frame",
    "plain",
    "times_invariant",
    "moved",
    "inverted",
    "from_points",
    "pair_about_an_end",
    "sphere_at",
]


class FrozenCoeffs(dict):
    """The coefficient map of an :class:`Anchored` entity: a dict that refuses writes (its local frame would go
    stale); ``dict(X.coeffs)`` is a writable copy."""

    __slots__ = ()

    def refuse(self, *args, **kwargs):
        raise fail("Anchored", "coeffs", "an anchored entity's coefficients are read-only; copy them: dict(X.coeffs)")

    __setitem__ = __delitem__ = update = pop = popitem = clear = setdefault = __ior__ = refuse

    def copy(self) -> dict:
        return dict(self)

    def __reduce__(self):
        return (FrozenCoeffs, (dict(self),))


def _frozen(c: dict) -> FrozenCoeffs:
    """``c`` as a :class:`FrozenCoeffs`, its arrays as read-only views."""
    out = {}
    for b, v in c.items():
        if type(v) is np.ndarray and v.flags.writeable:
            v = v.view()
            v.flags.writeable = False
        out[b] = v
    return FrozenCoeffs(out)


def _frozen_mv(X: Multivector) -> Multivector:
    """A plain multivector with X's coefficients, frozen (:func:`_frozen`); X itself when frozen already."""
    if type(X) is Multivector and isinstance(X._c, FrozenCoeffs):
        return X
    m = Multivector(X.algebra)
    m._c = _frozen(X._c)
    return m


#: The anchor of a derived entity before its local blade is built (its ``Pending`` gives both).
_DERIVED = np.zeros(0)
_DERIVED.flags.writeable = False


class Anchored(FrameOps, Multivector):
    """A conformal entity with its local frame: global coefficients plus ``anchor`` (a Euclidean point) and
    ``local`` (the entity translated by -anchor, 2.100); see the module docstring.

    Made by the constructors of :mod:`cga_lessons.conformal`, and by the operations between anchored entities
    (:mod:`~cga_lessons.conformal.anchored_ops`).  Called as the operations of
    :class:`~cga_lessons.algebra.Multivector` call their own type, without an anchor, it builds a plain
    :class:`~cga_lessons.algebra.Multivector`: that is how an operation that is not translation-covariant drops the
    frame.
    """

    __slots__ = ("_anchor", "_local", "_motion")

    def __new__(cls, algebra, coeffs=None, _prune=False, *, anchor=None, local=None):
        if anchor is None and local is None:
            return Multivector(algebra, coeffs, _prune)
        return object.__new__(cls)

    def __init__(self, algebra, coeffs=None, _prune=False, *, anchor=None, local=None):
        super().__init__(algebra, coeffs, _prune)
        if not isinstance(local, Multivector) or local.algebra is not algebra:
            raise fail("Anchored", "local", f"expected a Multivector of {algebra!r}, got {type(local).__name__}")
        if not set(local.grades_present()) <= set(self.grades_present()):  # exact zeros where the global has round-off
            raise fail(
                "Anchored", "local", f"grades {local.grades_present()}, the entity's are {self.grades_present()}"
            )
        try:
            f = np.array(anchor, dtype=float)
        except (TypeError, ValueError):
            raise fail("Anchored", "anchor", f"expected a Euclidean point, got {anchor!r:.40}") from None
        if f.shape != self.shape + (3,) or local.shape != self.shape or not np.all(np.isfinite(f)):
            raise fail(
                "Anchored",
                "anchor, local",
                f"expected finite points of shape {self.shape + (3,)} and a local entity of the batch shape "
                f"{self.shape}, got {f.shape} and {local.shape}",
            )
        f.flags.writeable = False
        self._c = _frozen(self._c)
        self._anchor, self._local, self._motion = f, _frozen_mv(local), None

    def settle(self):
        """Build what is pending: the local blade of a constructor (its closed form on the translated data) and a
        motion (see :func:`moved`: anchor ``R f + t``, local ``r L ~r``, 2.102, r the unit rotor part).  Fixed by what
        the entity was made of; computed once, on the first read.  Should the local blade not be storable (the
        translated data overflow where the data did not: coordinates near 1e102), the frame is dropped."""
        L = self._local
        if callable(L):
            try:
                L = L()
                if self._anchor is _DERIVED:  # a derived entity: its anchor comes with its local blade
                    self._anchor, L = L
                self._local = L = _frozen_mv(L)
            except GeometryError:
                self._anchor = self._local = self._motion = None
                return
        m = self._motion
        if m is not None:
            rotor, R, t, inv = m
            rotor = rotor / float(np.sqrt((rotor * ~rotor).scalar()))
            f = self._anchor @ R.T + t
            f.flags.writeable = False
            if inv:  # an odd versor (a reflection): V L^ V^-1, 2.82
                L = L.involute()
            self._anchor, self._local, self._motion = f, _frozen_mv(rotor >> L), None

    @property
    def anchor(self) -> np.ndarray | None:
        """The Euclidean point the local frame is centred on (read-only), shape (3,) or the batch's (..., 3)."""
        self.settle()
        return self._anchor

    @property
    def local(self) -> Multivector | None:
        """The entity translated by -anchor, ``T_{-f} X ~T_{-f}`` (2.100), built from the data (read-only)."""
        self.settle()
        return self._local

    def plain(self) -> Multivector:
        """The plain multivector of the global coefficients (a writable copy)."""
        return plain(self)

    def batch_item(self, index):
        """One anchored entity of a batch (a slice gives a sub-batch), its frame kept."""
        X = Multivector.batch_item(plain(self), index)
        f, local = frame(self)
        return X if f is None else Anchored(X.algebra, X._c, anchor=f[index], local=local.batch_item(index))

    @staticmethod
    def derive(Y: Multivector, local: Pending) -> Anchored:
        """``Y`` (a plain result) anchored with a pending local blade and anchor, both built by ``local`` when first
        read (:func:`~cga_lessons.conformal.anchored_ops.follow` makes it)."""
        return _made(Y, _DERIVED, local)

    def __copy__(self):
        return self  # immutable

    def __deepcopy__(self, memo):
        return self

    def __reduce__(self):
        f, local = frame(self)
        if f is None:
            return (Multivector, (self.algebra, dict(self._c)))
        return (_rebuild, (self.algebra, dict(self._c), np.array(f), plain(local)))


def _rebuild(algebra, coeffs: dict, anchor, local: Multivector) -> Anchored:
    """An :class:`Anchored` from its parts (unpickling; 2.100 relates them)."""
    return Anchored(algebra, coeffs, anchor=anchor, local=local)


def _made(Y: Multivector, anchor, local, motion=None) -> Anchored:
    """``Y`` anchored at ``anchor`` (a read-only array of the batch shape + (3,)) with ``local``: a frozen
    multivector, or a function that builds it (the constructors' closed form on the translated data, 2.100: built
    when first read), and a pending ``motion`` (:func:`moved`).  The parts are the callers' (not checked here)."""
    out = object.__new__(Anchored)
    out.algebra, out._c = Y.algebra, _frozen(Y._c)
    out._anchor, out._local, out._motion = anchor, local, motion
    return out


def times_invariant(X: Multivector, K: Multivector) -> Multivector:
    """``X K`` for a K that commutes with every translator (the pseudoscalar Ic of 2.60: the dual forms, 2.31,
    commute with 2.100): an anchored X stays anchored, its local blade times K too (and K commutes with a pending
    rotor as well); the global coefficients are those of the plain product."""
    Y = view(X) * K
    if frame(X, settle=False)[0] is None:
        return Y
    if X._motion is not None and X._motion[3]:  # a pending reflection involutes the local blade: not K's
        X.settle()
        if X._anchor is None:
            return Y
    L = X._local
    if isinstance(L, Pending):  # derived, not read yet: (anchor, local) when read

        def build():
            f, loc = L()
            return f, loc * K

        local = Pending(build, L.depth)
    else:
        local = (lambda: L() * K) if callable(L) else _frozen_mv(L * K)
    return _made(Y, X._anchor, local, X._motion)


def moved(X: Anchored, Y: Multivector, V: Multivector, R, t, involute: bool = False) -> Anchored:
    """``Y = V X V^-1`` for a motor V = T_t R (2.102) with rotation matrix R and translation t (``rigid_motion``),
    anchored: since ``V T_f = T_{R f + t} R``, the anchor becomes ``R f + t`` and the local blade turns by the rotor
    part of V (its Euclidean blades).  ``involute``: V is an odd isometry ``T_t U`` (a reflection in a plane, U its
    normal, or its product with a motor; R then has determinant -1), ``Y = V X^ V^-1`` (2.82), and the local blade
    is ``U L^ U^-1``.  Both are left pending until read (:meth:`Anchored.settle`), so that moving an anchored batch
    costs no more than moving a plain one; a second motion composes with the first."""
    rotor = Multivector(V.algebra, {b: v for b, v in V._c.items() if b < 8})
    m = X._motion
    if m is not None:
        rotor, R, t, involute = rotor * m[0], R @ m[1], R @ m[2] + t, involute != m[3]
    return _made(Y, X._anchor, X._local, (rotor, R, t, involute))


def inverted(X: Anchored, Y: Multivector, p, r2: float, involute: bool = True) -> Anchored:
    """``Y = V X^ V^-1`` for V the sphere of centre p and signed squared radius r2 (an inversion, 2.84-2.88:
    ``x -> p + r2 (x - p) / |x - p|^2``), anchored.  With q = p - f (f X's anchor), the anchor goes to its image
    ``f' = f + u``, ``u = q (1 - r2 / q^2)``, and ``T_{-f'} V T_f`` is the map ``y -> p' + r2 (y - q) / |y - q|^2 - u``
    (p' = q): the inversion in the sphere S_q of centre q and squared radius r2, then the translation by -u.  So the
    local blade is ``W L^ W^-1`` with ``W = T_{-u} S_q``, in closed form (``S_q = q + (q^2 - r2) e / 2 + e0``;
    ``e u q = (q^2 - r2) e`` since u is parallel to q, ``e u e = 0``, ``e u e0 = u - u E``):
    ``W = (q - u/2) + e0 + (u/2) E``, with ``W ~W = r2``: its coefficients are of the size of q, where the product
    holds q^2-sized ones that cancel; all are
    built from q, r2 and u, small where the sphere is near the entity.  Built when first read; an anchor at the
    centre (sent to infinity) drops the frame."""
    depth = chain_depth(X)

    def build():
        X.settle()
        f, L = X._anchor, X._local
        if f is None:
            raise NoFrame("the inverted entity lost its frame")
        q = p - f
        qq = dot(q, q)
        if np.any(qq == 0.0):
            raise NoFrame("the anchor is the centre of the inversion: its image is at infinity")
        u = q * (1.0 - r2 / qq)[..., None]
        g = f + u
        if not np.all(np.isfinite(g)):
            raise NoFrame("the anchor's image overflows")
        W = vector(q - 0.5 * u) + vector(0.5 * u) * E + eo
        loc = W * (L.involute() if involute else L) * ~W
        loc = loc.grade(*L.grades_present()) * (1.0 / (W * ~W).scalar())
        g.flags.writeable = False
        return g, loc

    return _made(Y, _DERIVED, Pending(build, depth))


def frame(X: Multivector, settle: bool = True):
    """``(anchor, local)`` of an anchored entity, ``(None, X)`` of any other multivector: what a reader reads
    (``local`` about ``anchor``, 2.100); ``settle=False`` leaves what is pending pending (the parts are then those
    before it, ``local`` perhaps the function that builds it)."""
    if isinstance(X, Anchored) and getattr(X, "_anchor", None) is not None:
        if settle:
            X.settle()
            if X._anchor is None:
                return None, X
        return X._anchor, X._local
    return None, X


def plain(X: Multivector) -> Multivector:
    """The plain multivector of X's coefficients (writable copies of its arrays); X itself when plain already."""
    if type(X) is Multivector:
        return X
    return Multivector(X.algebra, {b: v.copy() if type(v) is np.ndarray else v for b, v in X._c.items()})


# ------------------------------------------------------------ constructors
def from_points(build, func: str, *pts, local=None) -> Anchored:
    """``build(*pts, func)`` (a closed form of :mod:`~cga_lessons.conformal.entities_frame`) anchored at the point of
    the data nearest the origin, f: its local blade is ``local(*(p - f))`` (default ``build(*(p - f), func)``, the
    same closed form on the data translated by -f, 2.100; the differences ``p - f`` are the ones the closed forms
    take anyway), built when first read."""
    X = build(*pts, func)
    f = read_only(nearest(*pts), X.shape)
    rel = [p - f for p in pts]
    return _made(X, f, (lambda: build(*rel, func)) if local is None else (lambda: local(*rel)))


def pair_about_an_end(a, b) -> Multivector:
    """The point pair a ^ b (2.68) with one end at the origin (a = 0 or b = 0), in closed form: with y = a - b and
    s = +1 when b = 0, -1 when a = 0, ``a ^ b = y ^ e0 + s |y|^2 / 2 E`` (no e part), stored as e+/e- parts
    ``-+ y / 2``, so that ``M - P = y`` exactly: the local blade of an anchored pair."""
    y = a - b
    s = np.where(np.all(b == 0, axis=-1), 1.0, -1.0)
    D = parts(y.shape[:-1])
    D[..., 0] = 0.5 * s * dot(y, y)
    return _coefficients(
        parts(y.shape[:-1]), put_vec(parts(y.shape[:-1]), -0.5 * y), put_vec(parts(y.shape[:-1]), 0.5 * y), D
    )


def _coefficients(E, P, M, D) -> Multivector:
    """The multivector of the parts arrays (..., 8) on (1, e+, e-, E) times the Euclidean blades, zeros left out
    (as :func:`entities_frame.join <cga_lessons.conformal.entities_frame.join>` leaves them)."""
    a = np.concatenate([E, P, M, D], axis=-1)
    if a.ndim == 1:
        return Multivector(G41, {int(k): float(a[k]) for k in np.flatnonzero(a)})
    keys = np.flatnonzero(np.any(a != 0, axis=tuple(range(a.ndim - 1))))
    rows = np.ascontiguousarray(np.moveaxis(a[..., keys], -1, 0))  # one block: each blade contiguous
    return Multivector(G41, dict(zip(keys.tolist(), rows)))


def sphere_at(f, c, r2, func: str, args: str) -> Anchored:
    """The sphere of centre ``f + c`` and squared radius r2, ``p - r2 e / 2`` (2.72, weight 1), anchored at f:
    ``local`` is the sphere of centre c (small: the centre's offset from the anchor), built when first read."""
    p = f + c
    X = sphere_std(p, dot(p, p) - r2, 1.0, func, args)
    return _made(X, read_only(f, X.shape), lambda: sphere_std(c, dot(c, c) - r2, 1.0, func, args))
