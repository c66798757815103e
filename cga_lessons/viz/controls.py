"""The explorers' sliders: one place that binds them to a drawing function and shows its figure in the widget.

``ipywidgets.interactive`` calls the function at every move of a control but
displays what it returns only with ``auto_display``; without it a figure that
was created (and shown) in an earlier cell is never drawn again in a live
front end, and the sliders move nothing visible.  Every explorer's ``widget()``
goes through :func:`slider_panel`.
"""

from __future__ import annotations

import inspect

from cga_lessons.checks import fail

from .inputs import function

__all__ = ["slider_panel"]


def slider_panel(show, **controls):
    """``interactive(show, **controls)`` whose output shows the figure ``show`` returns after every move.

    Each control is an ipywidgets value widget (a slider, a dropdown, ...) named after an argument of ``show``.
    Sliders redraw when released (``continuous_update`` off): a redraw of an explorer takes up to a second.
    """
    from ipywidgets import ValueWidget, interactive

    func = "slider_panel"
    function(show, func, "show")
    if not controls:
        raise fail(func, "controls", "expected at least one control (a slider) for an argument of show")
    for name, control in controls.items():
        if not isinstance(control, ValueWidget):
            raise fail(func, name, f"expected an ipywidgets control (a slider), got {type(control).__name__}")
    try:
        inspect.signature(show).bind(**controls)
    except TypeError as exc:
        raise fail(func, "show", f"cannot take the controls {sorted(controls)} as arguments ({exc})") from None
    except ValueError:  # a callable without a signature (a builtin): let ipywidgets call it
        pass
    for control in controls.values():
        if getattr(control, "continuous_update", False):
            control.continuous_update = False  # redraw when the slider is released, not at every pixel
    return interactive(show, {"auto_display": True}, **controls)
