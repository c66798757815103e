"""How a multivector reads: its text and LaTeX forms, and tidying of SymPy coefficients.

``repr(X)`` writes ``1.5 e1 + 2 e+ - 1 e-``, blades in the order of (2.9);
``X._repr_latex_()`` is what Jupyter shows for a derivation, with SymPy
coefficients in LaTeX.  :meth:`DisplayMixin.simplify`, :meth:`DisplayMixin.expand` and
:meth:`DisplayMixin.subs` apply SymPy to every coefficient and drop the ones that
vanish, which is how a symbolic derivation is brought to the form printed in
the thesis; :meth:`DisplayMixin.map` applies any function.

:class:`DisplayMixin` is mixed into :class:`~cga_lessons.algebra.multivector.Multivector`;
it is not used alone.
"""

from __future__ import annotations

import numbers

import numpy as np

from cga_lessons.checks import fail

from .coefficients import is_sympy
from .operands import coefficient, finite_out


class DisplayMixin:
    """Display and SymPy helpers of :class:`~cga_lessons.algebra.multivector.Multivector`."""

    __slots__ = ()  # Multivector keeps only its two slots, no __dict__

    def simplify(self, fn=None):
        """Apply ``sympy.simplify`` (or ``fn``) to every coefficient and drop zeros."""
        import sympy

        if fn is not None and not callable(fn):
            raise fail("Multivector.simplify", "fn", f"expected a function, got {type(fn).__name__} {fn!r:.40}")
        fn = fn or sympy.simplify
        return type(self)(self.algebra, {b: fn(v) if is_sympy(v) else v for b, v in self._c.items()}, _prune=True)

    def expand(self):
        import sympy

        return self.simplify(sympy.expand)

    def subs(self, *args, **kwargs):
        """SymPy substitution in every coefficient: ``X.subs(old, new)``, ``X.subs({old: new})``."""
        news = list(args[0].values()) if len(args) == 1 and isinstance(args[0], dict) else list(args[1:2])
        for v in news:
            if isinstance(v, (numbers.Number, np.ndarray)) and not is_sympy(v):
                coefficient(v, "Multivector.subs", "new")
        try:
            out = {b: v.subs(*args, **kwargs) if is_sympy(v) else v for b, v in self._c.items()}
        except (TypeError, ValueError, AttributeError) as exc:
            raise fail("Multivector.subs", "old, new", f"SymPy cannot substitute {args!r:.60}: {exc}") from None
        return finite_out(type(self)(self.algebra, out, _prune=True), "Multivector.subs", "old, new")

    def map(self, fn):
        """Apply ``fn`` to every coefficient (its results must be finite numbers, arrays or SymPy expressions)."""
        if not callable(fn):
            raise fail("Multivector.map", "fn", f"expected a function, got {type(fn).__name__} {fn!r:.40}")
        return finite_out(
            type(self)(self.algebra, {b: fn(v) for b, v in self._c.items()}, _prune=True), "Multivector.map", "fn"
        )

    # ------------------------------------------------------------- display
    def _fmt_coeff(self, v) -> str:
        if isinstance(v, np.ndarray):
            return f"array{v.shape}"
        if isinstance(v, (float, np.floating)):
            return f"{float(v):.6g}"
        return str(v)

    def __repr__(self) -> str:
        if not self._c:
            return "0"
        parts = []
        for name, v in self.items():
            s = self._fmt_coeff(v)
            if is_sympy(v) and (len(getattr(v, "args", ())) > 1 and v.is_Add):
                s = f"({s})"
            term = s if name == "1" else f"{s} {name}"
            parts.append(term)
        out = parts[0]
        for t in parts[1:]:
            out += " - " + t[1:] if t.startswith("-") else " + " + t
        return out

    def _repr_latex_(self) -> str:
        if not self._c:
            return "$0$"
        alg = self.algebra
        parts = []
        for b in alg.blade_order:
            if b not in self._c:
                continue
            v = self._c[b]
            if is_sympy(v):
                import sympy

                s = sympy.latex(v)
                if v.is_Add:
                    s = f"\\left({s}\\right)"
            else:
                s = self._fmt_coeff(v)
            if b == 0:
                parts.append(s)
            else:
                sub = "".join(alg.labels[i] for i in range(alg.n) if b >> i & 1)
                parts.append(f"{s}\\,\\mathbf{{e}}_{{{sub}}}")
        out = parts[0]
        for t in parts[1:]:
            out += " - " + t[1:] if t.startswith("-") else " + " + t
        return f"${out}$"
