"""The thread's scratch blocks (cga_lessons.scratch) and the batch ``down`` that works in them."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from cga_lessons import conformal as cga
from cga_lessons.algebra import Multivector
from cga_lessons.scratch import SCRATCH_LIMIT, scratch


def test_a_slot_is_reused_grown_and_kept_apart_from_other_slots():
    a = scratch(1000, "test a")
    b = scratch(1000, "test b")
    assert not np.shares_memory(a, b)
    assert np.shares_memory(scratch(500, "test a"), a)
    big = scratch(200_000, "test a")  # larger than the block: a new one, kept from then on
    assert big.shape == (200_000,) and np.shares_memory(scratch(10, "test a"), big)


def test_beyond_the_limit_every_call_gets_fresh_memory():
    one, two = scratch(SCRATCH_LIMIT + 1, "test big"), scratch(SCRATCH_LIMIT + 1, "test big")
    assert not np.shares_memory(one, two)


def test_threads_do_not_share_a_slot():
    mine = scratch(100, "test thread")
    theirs = []
    t = threading.Thread(target=lambda: theirs.append(scratch(100, "test thread")))
    t.start()
    t.join()
    assert not np.shares_memory(mine, theirs[0])


def test_batch_down_matches_one_point_at_a_time_on_every_layout():
    """The batch path (scratch rows) against the single-point path (plain floats), on a block made by ``up`` and
    moved by a motor, on separate arrays, and on a batch where blades are missing or are plain numbers."""
    rng = np.random.default_rng(5)
    pts = rng.normal(scale=50.0, size=(64, 3))
    M = cga.motor([0.3, -0.2, 0.9], 0.7, [1.0, 2.0, -0.5])
    moved = cga.apply(M, cga.up(pts))
    separate = Multivector(moved.algebra, {b: np.array(v, copy=True) for b, v in moved._c.items()})
    on_axis = cga.up(np.column_stack([pts[:, 0], np.zeros(64), np.zeros(64)]))
    sparse = Multivector(on_axis.algebra, {b: v for b, v in on_axis._c.items() if b in (1, 8, 16)})
    on_y = cga.up(np.column_stack([np.zeros(64), pts[:, 1], np.zeros(64)]))
    no_e1 = Multivector(on_y.algebra, {b: v for b, v in on_y._c.items() if b in (2, 8, 16)})  # e1 absent
    scaled = Multivector(moved.algebra, {b: 3.0 * v for b, v in moved._c.items()})  # weight 3: same points
    for X in (moved, separate, sparse, no_e1, scaled):
        got = cga.down(X)
        one = np.array([cga.down(X.batch_item(i)) for i in range(64)])
        assert np.array_equal(got, one)
    assert np.allclose(cga.down(scaled), cga.down(moved), rtol=1e-14, atol=1e-12)


def test_batch_down_still_refuses_a_sphere_among_points():
    X = cga.up(np.random.default_rng(6).normal(size=(10, 3)))
    c = {b: np.array(v, copy=True) for b, v in X._c.items()}
    c[16][4] += 0.5  # X . X != 0 for that one row
    with pytest.raises(ValueError, match="not null"):
        cga.down(Multivector(X.algebra, c))
