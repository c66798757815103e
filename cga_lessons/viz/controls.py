"""The explorers' sliders: one place that binds them to a drawing function and shows its figure in the widget.

``ipywidgets.interactive`` calls the function at every move of a control but
displays what it returns only with ``auto_display``; without it a figure that
was created (and shown) in an earlier cell is never drawn again in a live
front end, and the sliders move nothing visible.  Every explorer's ``widget()``
goes through :func:`slider_panel`.
"""

from __future__ import annotations

__all__ = ["slider_panel"]


def slider_panel(show, **controls):
    """``interactive(show, **controls)`` whose output shows the figure ``show`` returns after every move.

    Sliders redraw when released (``continuous_update`` off): a redraw of an explorer takes up to a second.
    """
    from ipywidgets import interactive

    for control in controls.values():
        if getattr(control, "continuous_update", False):
            control.continuous_update = False  # redraw when the slider is released, not at every pixel
    return interactive(show, {"auto_display": True}, **controls)
