"""Scratch arrays reused by a thread: working space for batch operations that must not cost a page fault (layer 0).

An operation on a batch of a hundred thousand points needs megabytes of working space for its intermediate rows.
Allocated fresh on every call, that space is often returned to the operating system when the call ends (glibc
trims the top of its heap once more than twice its mmap threshold is free there), and the next call pays a page
fault per 4 kB page on first touch: measured here on the conformal round trip ``down(apply(M, up(P)))`` of 100,000
points, 1,700-2,400 faults and 5.6-7.2 ms a call instead of 1.7 ms (``benchmarks/bench_motor.py`` prints the faults
per call).  A scratch block kept by the thread costs its faults once.

Only working space goes here, never a result: a result is handed to the caller, who may keep it.  Each caller names
its ``slot``, so that two operations that run one inside the other never share a block.

Layer 0: imports NumPy only.
"""

from __future__ import annotations

import threading

import numpy as np

__all__ = ["SCRATCH_LIMIT", "scratch"]

#: Working space up to this many float64 values (32 MB) per slot is kept by the thread; larger requests get a fresh
#: array (a batch that large costs far more in arithmetic than in page faults).
SCRATCH_LIMIT = 1 << 22

_LOCAL = threading.local()


def scratch(size: int, slot: str) -> np.ndarray:
    """A float64 array of ``size`` elements (contents undefined) for the calling thread's ``slot``.

    The same slot returns the same memory (grown when a larger size is asked for) until the thread ends; sizes
    above :data:`SCRATCH_LIMIT` get a fresh array.  Use it only for working space that does not outlive the call.

    >>> a = scratch(10, "doctest")
    >>> a.shape, scratch(4, "doctest").base is a.base
    ((10,), True)
    """
    if size > SCRATCH_LIMIT:
        return np.empty(size)
    blocks = getattr(_LOCAL, "blocks", None)
    if blocks is None:
        blocks = _LOCAL.blocks = {}
    buf = blocks.get(slot)
    if buf is None or buf.size < size:
        buf = blocks[slot] = np.empty(max(size, 1 << 16))
    return buf[:size]
