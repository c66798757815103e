"""How a multivector reads: its text and LaTeX forms, and tidying of SymPy coefficients.

``repr(X)`` writes ``1.5 e1 + 2 e+ - 1 e-``, blades in the order of (2.9);
``X._repr_latex_()`` is what Jupyter shows for a derivation, with SymPy
coefficients in LaTeX.  :func:`simplify`, :func:`expand` and
:func:`subs` apply SymPy to every coefficient and drop the ones that
vanish, which is how a symbolic derivation is brought to the form printed in
the thesis; :func:`map_coefficients` (``X.map``) applies any function.

Plain functions of a multivector X, each one of the methods of
:class:`~cga_lessons.algebra.multivector.Multivector` (``repr(X)`` is :func:`text`, ``X.simplify()``
:func:`simplify`, ...).
"""

from __future__ import annotations

import numbers

import numpy as np

from cga_lessons.checks import fail

from .coefficients import is_sympy
from .operands import coefficient, finite_out


def simplify(X, fn=None):
    """Apply ``sympy.simplify`` (or ``fn``) to every coefficient and drop zeros."""
    import sympy

    if fn is not None and not callable(fn):
        raise fail("Multivector.simplify", "fn", f"expected a function, got {type(fn).__name__} {fn!r:.40}")
    fn = fn or sympy.simplify
    return type(X)(X.algebra, {b: fn(v) if is_sympy(v) else v for b, v in X._c.items()}, _prune=True)


def expand(X):
    import sympy

    return simplify(X, sympy.expand)


def subs(X, *args, **kwargs):
    """SymPy substitution in every coefficient: ``X.subs(old, new)``, ``X.subs({old: new})``."""
    news = list(args[0].values()) if len(args) == 1 and isinstance(args[0], dict) else list(args[1:2])
    for v in news:
        if isinstance(v, (numbers.Number, np.ndarray)) and not is_sympy(v):
            coefficient(v, "Multivector.subs", "new")
    try:
        out = {b: v.subs(*args, **kwargs) if is_sympy(v) else v for b, v in X._c.items()}
    except (TypeError, ValueError, AttributeError) as exc:
        raise fail("Multivector.subs", "old, new", f"SymPy cannot substitute {args!r:.60}: {exc}") from None
    return finite_out(type(X)(X.algebra, out, _prune=True), "Multivector.subs", "old, new")


def map_coefficients(X, fn):
    """Apply ``fn`` to every coefficient (its results must be finite numbers, arrays or SymPy expressions)."""
    if not callable(fn):
        raise fail("Multivector.map", "fn", f"expected a function, got {type(fn).__name__} {fn!r:.40}")
    return finite_out(type(X)(X.algebra, {b: fn(v) for b, v in X._c.items()}, _prune=True), "Multivector.map", "fn")


# ------------------------------------------------------------- display
def format_coefficient(v) -> str:
    """One coefficient as text: a float to 6 significant digits, an array by its shape, SymPy as it prints."""
    if isinstance(v, np.ndarray):
        return f"array{v.shape}"
    if isinstance(v, (float, np.floating)):
        return f"{float(v):.6g}"
    return str(v)


def text(X) -> str:
    """``repr(X)``: ``1.5 e1 + 2 e+ - 1 e-``, blades in the order of (2.9)."""
    if not X._c:
        return "0"
    parts = []
    for name, v in X.items():
        s = format_coefficient(v)
        if is_sympy(v) and (len(getattr(v, "args", ())) > 1 and v.is_Add):
            s = f"({s})"
        term = s if name == "1" else f"{s} {name}"
        parts.append(term)
    out = parts[0]
    for t in parts[1:]:
        out += " - " + t[1:] if t.startswith("-") else " + " + t
    return out


def latex(X) -> str:
    """``X._repr_latex_()``: the LaTeX form Jupyter shows, SymPy coefficients in LaTeX."""
    if not X._c:
        return "$0$"
    alg = X.algebra
    parts = []
    for b in alg.blade_order:
        if b not in X._c:
            continue
        v = X._c[b]
        if is_sympy(v):
            import sympy

            s = sympy.latex(v)
            if v.is_Add:
                s = f"\\left({s}\\right)"
        else:
            s = format_coefficient(v)
        if b == 0:
            parts.append(s)
        else:
            sub = "".join(alg.labels[i] for i in range(alg.n) if b >> i & 1)
            parts.append(f"{s}\\,\\mathbf{{e}}_{{{sub}}}")
    out = parts[0]
    for t in parts[1:]:
        out += " - " + t[1:] if t.startswith("-") else " + " + t
    return f"${out}$"
