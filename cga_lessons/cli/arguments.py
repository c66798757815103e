"""The argument types of the command line's parsers: numbers checked as argparse reads them."""

from __future__ import annotations

import argparse
import math

__all__ = ["non_negative_int", "positive"]


def non_negative_int(text: str) -> int:
    """An argument that is a whole number >= 0 (argparse's ``type``)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 0")
    return value


def positive(kind):
    """An argument that is a positive finite number of type ``kind`` (``int`` or ``float``; argparse's ``type``)."""

    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
        if not (value > 0 and math.isfinite(value)):
            raise argparse.ArgumentTypeError(f"{text!r} must be positive")
        return value

    return parse
