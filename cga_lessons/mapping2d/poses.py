"""Planar poses ``(x, y, theta)``: their composition (the rigid motion 3.4), inverse and difference, and angle wrapping.

A pose is the position in metres and the heading in radians of a frame (robot or laser) in the world frame;
``compose(a, b)`` is the pose ``b`` given in frame ``a``, expressed in the world.  The public functions check their
arguments; the ``*_unchecked`` ones are the same arithmetic for the map builder's inner loops, which pass arrays
they made themselves.  Every angle of the package is wrapped by :func:`wrap_unchecked` (through
:func:`wrap_angle` at the public boundary).
"""

from __future__ import annotations

import numpy as np

from .inputs import broadcast, numbers, pose_array

__all__ = [
    "wrap_angle",
    "compose",
    "invert",
    "relative",
    "wrap_unchecked",
    "compose_unchecked",
    "invert_unchecked",
    "relative_unchecked",
]

TWO_PI = 2.0 * np.pi


def wrap_unchecked(angle):
    """:func:`wrap_angle` without the input check: ``angle`` (a float or an array) into ``[-pi, pi)``."""
    return np.mod(angle + np.pi, TWO_PI) - np.pi


def wrap_angle(angle):
    """Wrap angles to ``[-pi, pi)``.

    >>> float(wrap_angle(3 * np.pi / 2))
    -1.5707963267948966
    """
    return wrap_unchecked(numbers(angle, "wrap_angle", "angle"))


def compose_unchecked(a, b):
    """:func:`compose` without the input checks (hot path); ``a`` and ``b`` of shape (3,) or (n, 3)."""
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    x = a[..., 0] + c * b[..., 0] - s * b[..., 1]
    y = a[..., 1] + s * b[..., 0] + c * b[..., 1]
    return np.stack([x, y, wrap_unchecked(a[..., 2] + b[..., 2])], axis=-1)


def invert_unchecked(a):
    """:func:`invert` without the input check."""
    a = np.asarray(a, float)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    x = -(c * a[..., 0] + s * a[..., 1])
    y = -(-s * a[..., 0] + c * a[..., 1])
    return np.stack([x, y, wrap_unchecked(-a[..., 2])], axis=-1)


def relative_unchecked(a, b):
    """:func:`relative` without the input checks."""
    return compose_unchecked(invert_unchecked(a), b)


def _pair(a, b, func: str):
    a, b = pose_array(a, func, "a"), pose_array(b, func, "b")
    broadcast(func, a=a, b=b)
    return a, b


def compose(a, b):
    """The pose ``b`` (given in the frame of pose ``a``) in the world frame.

    This is the rigid motion of (3.4), ``v' = R(theta_a) v + T_a``, applied to
    the position of ``b``, with the headings added.

    Parameters
    ----------
    a, b : array_like, shape (3,) or (N, 3)
        Poses ``(x, y, theta)``; they broadcast against each other.

    Returns
    -------
    ndarray, shape (3,) or (N, 3)

    >>> compose([1.0, 0.0, np.pi / 2], [1.0, 0.0, 0.0]).round(12)
    array([1.        , 1.        , 1.57079633])
    """
    return compose_unchecked(*_pair(a, b, "compose"))


def invert(a):
    """The inverse pose: ``compose(a, invert(a))`` is the identity.

    >>> compose([1.0, 2.0, 0.5], invert([1.0, 2.0, 0.5])).round(12) + 0.0
    array([0., 0., 0.])
    """
    return invert_unchecked(pose_array(a, "invert", "a"))


def relative(a, b):
    """The pose ``b`` seen from the frame of pose ``a`` (the odometry increment from ``a`` to ``b``)."""
    return relative_unchecked(*_pair(a, b, "relative"))
