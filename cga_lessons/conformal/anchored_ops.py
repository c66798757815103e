"""The operations of anchored entities (:mod:`cga_lessons.conformal.anchored`): the frame follows products, sums
and the unary operations, so that derived entities (the circle where two spheres meet, a point pair on a line, a
scaled sphere, ...) keep the accuracy of the entities they are made of.

**Covariance.**  A translator T = T_t (2.100) is a unit even versor, ``T ~T = 1``, and ``X -> T X ~T`` is an
automorphism of the algebra that keeps grades (its outermorphism, 2.82).  So it commutes with the geometric product
(``T (X Y) ~T = (T X ~T)(T Y ~T)``), with grade projection and hence with the outer product, the inner product and
the contractions (grade parts of the geometric product), with sums and scalar multiples, with the reverse
(``~(T X ~T) = T ~X ~T``), the grade involution (T is even), the inverse (``(T X ~T)^-1 = T X^-1 ~T``), powers,
norms (``<X ~X>_0`` is a scalar: unchanged) and the dual (the pseudoscalar Ic commutes with every even element).
The result of such an operation on X (anchor f, local ``T_{-f} X ~T_{-f}``) and Y (anchor g) is therefore, about
f, the same operation on X's local and on Y's local moved into f's frame, ``T_{g-f} Y.local ~T_{g-f}``: that is
the local blade of the result, anchored at f.  ``g - f`` is rounded once, to its own relative accuracy.

**Invariant operands.**  A plain multivector K takes part in that only when ``T K ~T = K`` for every T.  With
``T = 1 + e t / 2``, ``T K ~T = K + (e t K - K e t) / 2 - e t K e t / 4`` and ``(e t)^2 = 0``: K is invariant
exactly when it commutes with ``e e1``, ``e e2``, ``e e3``.  Those K span the scalars, ``e ^ A`` for every
Euclidean A (e itself, free vectors, the translators ``1 + e t / 2``) and the pseudoscalar Ic: in coefficients, no
Euclidean blade but the scalar, equal e+ and e- coefficients of each Euclidean blade A (``e ^ A`` is
``-(A e+ + A e-)`` up to order), and no e+e- blade but Ic (:func:`invariant`, an exact test).  Numbers (and arrays
of them, a batch) are invariant.

**Points.**  A conformal point is not invariant but covariant itself: ``w up(x) = T_x (w e0) ~T_x`` (2.62, 2.100),
the entity anchored at x whose local blade is ``w e0``, and its coefficients hold x (``E / w``, 2.114).  A plain
vector whose coefficients are a point's to their resolution (``e0`` is one, at the origin;
:func:`~cga_lessons.conformal.anchored_points.point_frame`) takes part as an anchored operand: its local blade in
f's frame is ``w up(x - f)``, in closed form (:func:`~cga_lessons.conformal.anchored_points.point_about`), and the
result is anchored at the anchor of the first anchored entity among the operands (of the first point when there is
none: the operation hook of G41 makes such results, ``up(a) ^ up(b)``, :mod:`~cga_lessons.conformal.point_wedges`).
``e1``, a rotor, a sphere without a frame or any other multivector that is neither: an operation with it returns
the plain multivector, as before.

**Bits.**  The global coefficients are computed as for plain multivectors (the same routine on the same
coefficients): an anchored result equals, prints and compares as the plain one, bit for bit.  Only its local
blade is added, built when first read (see :class:`Pending`).  An operation with no anchored operand gets here only
through G41's operation hook (``^``, ``+``, ``-``, :mod:`~cga_lessons.conformal.point_wedges`), which declines in
about a microsecond what is no point (the cheap tests first: :func:`operand_kinds`).  The one exception to the bits
is the join and meet of two anchored blades, which decide on their local blades
(:func:`cga_lessons.conformal.blades.meet`): where that decision is another grade than the global one, the result's
global coefficients are its local blade translated back (:func:`translated`).
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from cga_lessons.algebra import GeometryError, Multivector

from .anchored_points import VECTOR, point_about, point_parts
from .versors_build import translator

__all__ = [
    "FrameOps",
    "Pending",
    "about",
    "chain_depth",
    "follow",
    "invariant",
    "operand_kinds",
    "read_only",
    "translated",
    "unhooked",
]

#: A chain of derived entities none of which was read is built from its end when first read, one level after the
#: other; beyond this depth the operands are built at once, so that a long chain (a sum in a loop) never nests deep.
MAX_DEPTH = 48
_NUMBERS = (numbers.Real, np.ndarray)
_F64 = np.float64
#: The blades an invariant multivector may hold: the scalar, Ic and the blades with exactly one of e+, e- (2.100).
_PAIRED = frozenset([0, 31] + [b for b in range(32) if b & 24 in (8, 16)])
_IC = 31  # e123+-


class NoFrame(GeometryError):
    """An operand lost its frame, or the local blade could not be built: the result is read as a plain blade."""


class Pending:
    """The local blade of a derived entity, built when first read: ``build()`` returns ``(anchor, local)``.
    ``depth`` is the number of derived entities, none of them read yet, it is built through."""

    __slots__ = ("build", "depth")

    def __init__(self, build, depth: int):
        self.build, self.depth = build, depth

    def __call__(self):
        return self.build()


def invariant(K: Multivector) -> bool:
    """True when ``T K ~T = K`` for every translator T (2.100): K commutes with e e1, e e2, e e3 (module docstring),
    that is K is a combination of 1, ``e ^ A`` (A Euclidean) and Ic.  Exact: the e+ and e- coefficients of each
    Euclidean blade must be equal, not close."""
    c = K._c
    if not c.keys() <= _PAIRED:  # a Euclidean blade, or one with e+e- (Ic excepted): zero (a batch's zeros) or not K's
        for b in c.keys() - _PAIRED:
            v = c[b]
            t = type(v)
            if (v != 0.0) if t is float or t is _F64 else np.any(v):
                return False
    for b, v in c.items():
        if b & 24 != 8 and b & 24 != 16:
            continue
        w, t = c.get(b ^ 24, 0.0), type(v)  # the coefficient of the twin (e+ for e-, e- for e+): equal, or not K
        if (t is float or t is _F64) and (type(w) is float or type(w) is _F64):
            if v != w:
                return False
        elif not (v is w or np.all(np.asarray(v) == np.asarray(w))):
            return False
    return True


def translated(L: Multivector, t) -> Multivector:
    """``T_t L ~T_t`` (2.100, :func:`~cga_lessons.conformal.translator`) for t of shape (3,) or (N, 3), L's grades
    kept (a versor keeps grades; the other grades of the products are round-off)."""
    T = translator(np.asarray(t, dtype=float))
    return (T * L * ~T).grade(*L.grades_present())


def about(L: Multivector, g, f) -> Multivector:
    """The local blade L of an entity anchored at g, moved into the frame of the anchor f (``T_{g-f} L ~T_{g-f}``);
    L itself when the anchors are one."""
    return L if g is f or np.array_equal(g, f) else translated(L, g - f)


def read_only(f, shape: tuple) -> np.ndarray:
    """An anchor: f broadcast to ``shape + (3,)`` (one anchor for a whole batch), as a read-only array."""
    if type(f) is np.ndarray and f.shape == shape + (3,) and f.dtype == float:
        if not f.flags.writeable and f.flags.owndata:
            return f  # already one (a read-only array of its own: shared, never changed)
    f = np.array(np.broadcast_to(f, shape + (3,)), dtype=float)
    f.flags.writeable = False
    return f


def chain_depth(*framed) -> int:
    """The depth of a result derived from the anchored entities ``framed``: one more than the deepest pending
    chain among them; beyond :data:`MAX_DEPTH` they are built now and the chain starts again at one."""
    depth = 1 + max(x._local.depth if isinstance(x._local, Pending) else 0 for x in framed)
    if depth > MAX_DEPTH:
        for x in framed:
            x.settle()
        depth = 1
    return depth


def operand_kinds(operands):
    """Per operand: True (anchored), False (invariant: a number or an invariant multivector), ``(anchor, weight)``
    (a plain conformal point, :func:`~cga_lessons.conformal.anchored_points.point_parts`); None when some operand is
    none of these (the result is plain).
    Points are recognised last, once every other operand has passed (the cheap tests first)."""
    kinds = []
    for x in operands:
        if isinstance(x, Multivector):
            if isinstance(x, FrameOps) and x._anchor is not None:
                kinds.append(True)
            elif (16 in x._c or 8 in x._c) and x._c.keys() <= VECTOR:  # perhaps a point (or e: invariant)
                kinds.append(None)
            elif invariant(x):
                kinds.append(False)
            else:
                return None
        elif isinstance(x, _NUMBERS) and not isinstance(x, (bool, np.bool_)):
            kinds.append(False)
        else:
            return None
    for i, k in enumerate(kinds):
        if k is None:
            k = point_parts(operands[i])
            if k is None:
                if not invariant(operands[i]):
                    return None
                k = False
            kinds[i] = k
    return kinds


#: A grade of a local blade that the global result lacks is kept when its largest coefficient passes this much of the
#: local blade's largest (the package's relative accuracy): below it, it is the local operation's round-off.
LOST_GRADE = 1e-9


def _finite(L: Multivector) -> bool:
    """Whether every coefficient of L is finite: one ``fsum`` for floats (NaN and inf propagate), else each array."""
    try:
        if math.isfinite(math.fsum(L._c.values())):
            return True
    except (TypeError, ValueError, OverflowError):  # arrays (a batch), inf - inf, a sum beyond float range
        pass
    return all(np.all(np.isfinite(v)) for v in L._c.values())


def follow(Y, op, *operands, anchor_arg: bool = False, derive=None, kinds=None):
    """``Y`` (the result of an operation, computed from the global coefficients) with a local frame: anchored at the
    anchor f of its first anchored operand (with none, of its first plain point), its local blade ``op(*locals)``,
    where each anchored operand gives its local blade moved into f's frame (``T_{g-f} L ~T_{g-f}``), a plain
    conformal point its own in closed form (``w up(g - f)``, :func:`~.anchored_points.point_about`), and every other
    operand is passed as it is (it must be a number or an invariant multivector; else Y is returned
    plain).  ``op`` must be translation-covariant (see the module docstring); ``anchor_arg``: it takes f first.
    ``derive`` makes the result when no operand is anchored (points only; the anchored class's ``derive``): without
    it such a Y is returned plain.  ``kinds``: the operands' :func:`operand_kinds`, when the caller has them.  Built
    when first read; should that fail (an operand's frame dropped, the local blade overflows or has no inverse), Y is
    read as a plain blade."""
    if type(Y) is not Multivector or not Y._c:
        return Y
    kinds = operand_kinds(operands) if kinds is None else kinds
    if not kinds:
        return Y
    framed = [x for x, k in zip(operands, kinds) if k is True]
    if not framed and not any(kinds):  # only invariant operands
        return Y
    if framed:
        depth, derive = chain_depth(*framed), type(framed[0]).derive
    elif derive is None:
        return Y
    else:
        depth = 1

    def build():
        shape, grades = Y.shape, Y.grades_present()
        frames = []  # (anchor, local) of the anchored operands; the first one's anchor is the result's
        for x in framed:
            x.settle()
            if x._anchor is None:
                raise NoFrame("an operand lost its frame")
            frames.append((x._anchor, x._local))
        f = frames[0][0] if frames else None
        args, at = [], iter(frames)
        for x, k in zip(operands, kinds):
            if k is False:
                args.append(x)
            elif k is True:
                g, L = next(at)
                args.append(about(L, g, f))
            else:  # a plain point (anchor, weight): in closed form about f (or its own anchor, when it is f)
                g, w = k
                g = np.array(g) if type(g) is tuple else g
                f = g if f is None else f
                args.append(point_about(w, g, f))
        L = op(f, *args) if anchor_arg else op(*args)
        if not isinstance(L, Multivector) or L.shape != shape:
            raise NoFrame("the local blade has another batch shape")
        if not _finite(L):
            raise NoFrame("the local blade is not finite")
        extra = [g for g in L.grades_present() if g not in grades]
        if extra:
            # A grade the global result does not have is round-off of the local operation, and is dropped, unless
            # it is beyond LOST_GRADE of the local blade: then the global coefficients lost it to cancellation (the
            # scalar S1 . S2 of two spheres 1e6 out is a difference of 1e12-sized terms) and the local keeps it.
            size = max(float(np.max(np.abs(v))) for v in L._c.values())
            keep = [g for g in extra if float(np.max(np.abs(L.grade(g).to_array()))) > LOST_GRADE * size]
            L = L.grade(*grades, *keep)
        return read_only(f, shape), L

    def guarded():
        try:
            return build()
        except NoFrame:
            raise
        except (ValueError, ArithmeticError) as exc:  # GeometryError is a ValueError
            raise NoFrame(str(exc)) from None

    return derive(Y, Pending(guarded, depth))


def view(X):
    """A plain multivector holding X's (read-only) coefficients, not copied: what the global computation reads, so
    that it is the plain routine's, bit for bit.  Anything else as it is."""
    if not isinstance(X, FrameOps):
        return X
    m = object.__new__(Multivector)
    m.algebra, m._c = X.algebra, X._c
    return m


# ------------------------------------------------------------------------------- the operators
def unhooked(symbol: str, fallback):
    """The operator ``symbol`` (``"+"``, ``"-"``, ``"^"``) on local blades without the algebra's operation hook
    (:meth:`~cga_lessons.algebra.Multivector.plain_operation`): a local blade's frame is the caller's to follow;
    ``fallback(a, b)`` when ``a`` is a number."""
    return lambda a, b: a.plain_operation(symbol, b) if isinstance(a, Multivector) else fallback(a, b)


def _binary(name: str, rname: str | None, fn, symbol: str | None = None):
    """The operator ``name`` and its reflection ``__r...__``: the plain result, followed (:func:`follow`) by
    ``fn(left, right)`` on the local blades.  ``symbol``: an operator the algebra's operation hook follows
    (:meth:`~cga_lessons.algebra.Multivector.plain_operation`): the global result and ``fn`` on multivectors are
    computed without it (the frame is this class's to follow)."""
    plain = getattr(Multivector, name)
    rplain, doc = getattr(Multivector, rname, None) if rname else None, plain.__doc__
    if symbol is not None:

        def plain(a, b):
            return a.plain_operation(symbol, b)

        fn = unhooked(symbol, fn)

    def forward(self, other):
        Y = plain(view(self), view(other))
        return Y if Y is NotImplemented else follow(Y, fn, self, other)

    def reflected(self, other):  # other (a number, or a plain multivector: Python asks the subclass first) op self
        if isinstance(other, Multivector):
            Y = plain(view(other), view(self))
        elif rplain is not None:
            Y = rplain(view(self), other)
        else:
            return NotImplemented
        return Y if Y is NotImplemented else follow(Y, fn, other, self)

    forward.__name__, reflected.__name__ = name, name.replace("__", "__r", 1)
    forward.__doc__ = f"{doc or name} The frame follows (:func:`cga_lessons.conformal.anchored_ops.follow`)."
    return forward, reflected


def _unary(name: str):
    """The method ``name`` (its extra arguments passed on): the plain result, followed by the same method on the
    local blade."""
    plain = getattr(Multivector, name)

    def method(self, *args):
        Y = plain(view(self), *args)
        return follow(Y, lambda L: plain(L, *args), self)

    method.__name__ = name
    method.__doc__ = f"{plain.__doc__ or name} The frame follows (same operation on the local blade)."
    return method


def _global(name: str):
    """A method whose result is a coefficient (a number, not a multivector), read from the global coefficients."""
    plain = getattr(Multivector, name)

    def method(self, *args):
        return plain(view(self), *(view(a) for a in args))

    method.__name__, method.__doc__ = name, plain.__doc__
    return method


class FrameOps:
    """The operators of :class:`~cga_lessons.conformal.anchored.Anchored`: each computes the plain result from the
    global coefficients and lets the frame follow when every operand is anchored or invariant (module docstring).
    A mixin before :class:`~cga_lessons.algebra.Multivector`; ``_anchor``, ``_local`` and ``settle`` are the
    anchored entity's."""

    __slots__ = ()

    __add__, __radd__ = _binary("__add__", "__radd__", lambda a, b: a + b, "+")
    __sub__, __rsub__ = _binary("__sub__", "__rsub__", lambda a, b: a - b, "-")
    __mul__, __rmul__ = _binary("__mul__", "__rmul__", lambda a, b: a * b)
    __truediv__, __rtruediv__ = _binary("__truediv__", "__rtruediv__", lambda a, b: a / b)
    __xor__, __rxor__ = _binary("__xor__", "__rxor__", lambda a, b: a ^ b, "^")
    __or__, __ror__ = _binary("__or__", "__ror__", lambda a, b: a | b)
    __lshift__, __rlshift__ = _binary("__lshift__", None, lambda a, b: a << b)
    __rshift__, __rrshift__ = _binary("__rshift__", None, lambda a, b: a >> b)
    inner = _binary("inner", None, Multivector.inner)[0]
    left_contraction = _binary("left_contraction", None, Multivector.left_contraction)[0]

    __neg__ = _unary("__neg__")
    __invert__ = reverse = _unary("reverse")
    involute = _unary("involute")
    conjugate = _unary("conjugate")
    grade = _unary("grade")
    even = _unary("even")
    odd = _unary("odd")
    dual = _unary("dual")
    undual = _unary("undual")
    normalized = _unary("normalized")
    inv = _unary("inv")
    __pow__ = _unary("__pow__")

    scalar_product = _global("scalar_product")
    norm2 = _global("norm2")
    norm = _global("norm")
