"""Motor on points: this project vs a plain NumPy 4x4 floor vs kingdon and clifford.

Run by hand from the repository root::

    python benchmarks/bench_motor.py            # N = 100,000 points, 25 rounds
    python benchmarks/bench_motor.py --quick    # fewer rounds

Everything runs in one process, with one BLAS thread.  The cases are timed in
*rounds*: each round times every case once, so a slow spell of a shared machine
hits all cases alike.  A batch case is three calls in a row per round; a
single-point case is a loop of 25 calls, in eight times as many rounds (short
loops are rarely preempted).  The table gives per call the median and the best
time over the rounds, ``x floor``, the median over the rounds of (time of the
case / time of the floor in the same round), and ``best``, the best time of the
case over the best of the floor.  Absolute times drift between machines and
minutes; the ratios are what to compare.

Peers (optional, ``pip install -e ".[bench]"``): kingdon's ``M >> X`` with array
coefficients (one multivector whose coefficients are arrays of N values), and
clifford's sandwich as a 32x32 matrix (``layout.get_right_gmt_matrix(~M) @
layout.get_left_gmt_matrix(M)``) applied to the (N, 32) value array; for one
point, each library's own sandwich operator.  Before timing, every route's
result is checked against the 4x4 matrix.
"""

from __future__ import annotations

import itertools
import os
import pathlib
import resource
import sys
import time

# One BLAS thread: the machines are shared, and a second BLAS thread waiting for a busy core makes the
# timings of every route that calls BLAS swing tenfold.  Set OPENBLAS_NUM_THREADS yourself to override.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))  # run from a checkout, installed or not

from cga_lessons import conformal as cga  # noqa: E402

AXIS, ANGLE, SHIFT = [0.3, -0.2, 0.9], 0.7, [1.0, 2.0, -0.5]


def run_rounds(cases: dict, rounds: int, floor: str) -> dict:
    """Median and best seconds per call, median ratio and best-to-best ratio to ``floor``, per case.

    ``cases`` maps a name to ``(fn, number)``: ``fn`` is called ``number``
    times per round.
    """
    for fn, _ in cases.values():  # warm-up (JIT, caches, first allocation)
        fn()
        fn()
    times = {name: [] for name in cases}
    faults = dict.fromkeys(cases, 0)
    for _ in range(rounds):
        for name, (fn, number) in cases.items():
            f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            times[name].append((time.perf_counter() - t0) / number)
            faults[name] += resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0
    base = np.array(times[floor])
    out = {}
    for name, t in times.items():
        t = np.array(t)
        out[name] = (
            float(np.median(t)),
            float(t.min()),
            float(np.median(t / base)),
            float(t.min() / base.min()),
            faults[name] / (rounds * cases[name][1]),
        )
    return out


def kingdon_setup(M, X, X1, L):
    """kingdon versions of the motor, the point batch, one point and the line batch (or None)."""
    try:
        import kingdon
    except ImportError:
        return None
    K = kingdon.Algebra(4, 1)  # e1 e2 e3 e4 = e+ (+1), e5 = e- (-1): the same bitmap order as G41

    def name(b):
        return "e" + "".join(str(i + 1) for i in range(5) if b >> i & 1) if b else "e"

    def conv(mv):
        return K.multivector({name(b): v for b, v in mv.coeffs.items()})

    return K, conv(M), conv(X), conv(X1), conv(L), name


def clifford_setup(M):
    """clifford's layout, value-index map and 32x32 sandwich matrix of M (or None)."""
    try:
        import clifford
    except ImportError:
        return None
    layout, _ = clifford.Cl(4, 1)
    index = {}
    for b in range(32):
        tup = tuple(i + 1 for i in range(5) if b >> i & 1)
        index[b] = layout.bladeTupList.index(tup)

    def conv(mv):
        shape = mv.shape
        vals = np.zeros(shape + (32,))
        for b, v in mv.coeffs.items():
            vals[..., index[b]] = v
        return vals

    cm = layout.MultiVector(conv(M))
    S = layout.get_right_gmt_matrix(~cm) @ layout.get_left_gmt_matrix(cm)  # b -> (M b) ~M
    return layout, conv, cm, S, index


def main(n: int = 100_000, seed: int = 0, rounds: int = 25):
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(n, 3))
    M = cga.motor(AXIS, ANGLE, SHIFT)
    H = cga.motor_to_matrix(M)
    homog = np.hstack([pts, np.ones((n, 1))])
    X = cga.up(pts)
    lines = cga.line_from_points(pts, pts + rng.normal(size=(n, 3)))  # grade 3 (dual lines): the 10x10 matrix
    p1 = pts[0]
    X1 = cga.up(p1)
    h1 = homog[0].copy()
    truth = (homog @ H.T)[:, :3]

    def dev(y):
        return float(np.max(np.abs(np.asarray(y) - truth)))

    checks = {
        "cga.apply_to_points": dev(cga.apply_to_points(M, pts)),
        "cga.apply (conformal)": dev(cga.down(cga.apply(M, X))),
        "M >> X": dev(cga.down(M >> X)),
    }
    moved_lines = lines_block = cga.apply(M, lines)  # its coefficient arrays are the rows of one block
    plain_line = M * lines.batch_item(7) * ~M
    checks["cga.apply (lines) vs sandwich, one line"] = max(
        abs(float(moved_lines.batch_item(7)[b] - plain_line[b])) for b in range(32)
    )

    nb = 3  # calls per round of each batch case (steady state, not the cache left by the previous case)

    def floor_round_trip():  # from Euclidean points to Euclidean points, with the perspective division
        h = np.hstack([pts, np.ones((n, 1))]) @ H.T
        return h[:, :3] / h[:, 3:]

    checks["round trip down(apply(M, up(P)))"] = dev(cga.down(cga.apply(M, cga.up(pts))))
    batch = {
        "numpy 4x4 homogeneous (floor)": (lambda: (homog @ H.T)[:, :3], nb),
        "round trip: numpy [x 1] @ H^T, divide (floor)": (floor_round_trip, nb),
        "round trip: cga.down(cga.apply(M, cga.up(P)))": (lambda: cga.down(cga.apply(M, cga.up(pts))), nb),
        "cga.apply_to_points(M, x)  [3x4 affine]": (lambda: cga.apply_to_points(M, pts), nb),
        "cga.apply(M, X)  [conformal, 5x5]": (lambda: cga.apply(M, X), nb),
        "M >> X  [conformal, 5x5]": (lambda: M >> X, nb),
        "cga.apply(M, L)  [lines, 10x10]": (lambda: cga.apply(M, lines), nb),
        "cga.apply(M, L')  [L' = apply(M, L): one block]": (lambda: cga.apply(M, lines_block), nb),
    }
    fresh = [cga.motor(rng.normal(size=3), rng.uniform(-3, 3), rng.normal(size=3)) for _ in range(997)]
    cycle = itertools.cycle(fresh)
    reps = 25  # short loops, many rounds: most loops run without being preempted on a busy machine
    single = {
        "numpy 4x4 @ homogeneous point (floor)": (lambda: H @ h1, reps),
        "M >> X": (lambda: M >> X1, reps),
        "cga.apply(M, X)": (lambda: cga.apply(M, X1), reps),
        "M * X * ~M  [general products]": (lambda: M * X1 * ~M, reps),
        "cga.apply_to_points(M, x)": (lambda: cga.apply_to_points(M, p1), reps),
        "round trip: numpy H @ [x 1], divide (floor)": (lambda: (lambda h: h[:3] / h[3])(H @ np.append(p1, 1.0)), reps),
        "round trip: cga.down(cga.apply(M, cga.up(x)))": (lambda: cga.down(cga.apply(M, cga.up(p1))), reps),
        "M >> X, a new motor every call": (lambda: next(cycle) >> X1, reps),
    }

    k = kingdon_setup(M, X, X1, lines)
    if k is not None:
        K, km, kx, kx1, kl, kname = k
        kres = km >> kx
        ky = np.stack(
            [np.broadcast_to(np.asarray(getattr(kres, kname(b)), dtype=float), (n,)) for b in (1, 2, 4, 8, 16)], axis=-1
        )
        w = ky[:, 4] - ky[:, 3]
        checks["kingdon M >> X"] = dev(ky[:, :3] / w[:, None])
        batch["kingdon M >> X  [array coefficients]"] = (lambda: km >> kx, nb)

        def kingdon_round_trip(P=pts):  # the null vector from the arrays, the sandwich, the division
            x2 = 0.5 * np.einsum("ij,ij->i", P, P)
            X = K.vector(e1=P[:, 0], e2=P[:, 1], e3=P[:, 2], e4=x2 - 0.5, e5=x2 + 0.5)
            Y = km >> X
            w = Y.e5 - Y.e4
            return np.stack([Y.e1 / w, Y.e2 / w, Y.e3 / w], axis=-1)

        checks["kingdon round trip"] = dev(kingdon_round_trip())
        batch["round trip: kingdon point, M >> X, divide"] = (kingdon_round_trip, nb)

        def kingdon_round_trip_one(p=p1):  # one point: float coefficients
            x, y, z = (float(v) for v in p)
            x2 = 0.5 * (x * x + y * y + z * z)
            Y = km >> K.vector(e1=x, e2=y, e3=z, e4=x2 - 0.5, e5=x2 + 0.5)
            w = Y.e5 - Y.e4
            return np.array([Y.e1 / w, Y.e2 / w, Y.e3 / w])

        checks["kingdon round trip, one point"] = float(np.max(np.abs(kingdon_round_trip_one() - truth[0])))
        single["round trip: kingdon point, M >> X, divide"] = (kingdon_round_trip_one, reps)
        batch["kingdon M >> L  [lines]"] = (lambda: km >> kl, nb)
        single["kingdon M >> X"] = (lambda: km >> kx1, reps)
    c = clifford_setup(M)
    if c is not None:
        layout, conv, cm, S, index = c
        xv = conv(X)
        yv = xv @ S.T
        w = yv[:, index[16]] - yv[:, index[8]]
        checks["clifford 32x32"] = dev(np.stack([yv[:, index[b]] for b in (1, 2, 4)], axis=-1) / w[:, None])
        cx1 = layout.MultiVector(conv(X1))
        batch["clifford (N, 32) @ 32x32 sandwich"] = (lambda: xv @ S.T, nb)
        single["clifford M * X * ~M"] = (lambda: cm * cx1 * ~cm, reps)
        single["clifford 32x32 @ value vector"] = (lambda: S @ cx1.value, reps)

    print(f"Motor on N = {n:,} random points, {rounds} rounds, one process")
    print("largest deviation from the 4x4 result (or from the plain sandwich):")
    for name, d in checks.items():
        print(f"  {name:45s} {d:.1e}")
    res_b = run_rounds(batch, rounds, "numpy 4x4 homogeneous (floor)")
    res_s = run_rounds(single, 8 * rounds, "numpy 4x4 @ homogeneous point (floor)")
    print()
    head = f"{'median':>9s} {'best':>9s} {'x floor':>8s} {'best':>6s} {'faults':>7s}"
    print(f"{'batch of ' + format(n, ',') + ', per call [ms]':45s} {head}")
    for name, (t, tb, r, b, pf) in res_b.items():
        print(f"{name:45s} {t * 1e3:9.3f} {tb * 1e3:9.3f} {r:8.2f} {b:6.2f} {pf:7.0f}")
    print()
    print(f"{'one point, per call (loops of ' + str(reps) + ') [us]':45s} {head}")
    for name, (t, tb, r, b, pf) in res_s.items():
        print(f"{name:45s} {t * 1e6:9.2f} {tb * 1e6:9.2f} {r:8.1f} {b:6.1f} {pf:7.1f}")
    print()
    ours = res_b["cga.apply_to_points(M, x)  [3x4 affine]"]
    conf = res_b["cga.apply(M, X)  [conformal, 5x5]"]
    print(
        f"targets: batched motor within 1.3x of the floor (median ratio): apply_to_points {ours[2]:.2f}x, "
        f"apply {conf[2]:.2f}x"
    )
    kb = res_b.get("kingdon M >> X  [array coefficients]")
    if kb is not None:
        print(
            f"         >= 2x faster than kingdon's M >> X (ratio of the median ratios): "
            f"apply_to_points {kb[2] / ours[2]:.1f}x, apply {kb[2] / conf[2]:.1f}x"
        )
    for name in ("M >> X", "cga.apply(M, X)"):
        t, tb, r, *_ = res_s[name]
        floor_t = res_s["numpy 4x4 @ homogeneous point (floor)"][0]
        print(
            f"         one point <= 20 us: {name}: median {t * 1e6:.1f} us, best {tb * 1e6:.1f} us, "
            f"{r:.1f} x the floor's median {floor_t * 1e6:.2f} us = {r * floor_t * 1e6:.1f} us"
        )
    rt = (
        res_b["round trip: cga.down(cga.apply(M, cga.up(P)))"][2]
        / res_b["round trip: numpy [x 1] @ H^T, divide (floor)"][2]
    )
    print(f"         round trip down(apply(M, up(P))) <= 1.5x its floor (median ratios): {rt:.2f}x")
    kr = res_b.get("round trip: kingdon point, M >> X, divide")
    if kr is not None:
        print(
            f"         round trip >= 2x faster than kingdon's (median ratios): "
            f"{kr[2] / res_b['round trip: cga.down(cga.apply(M, cga.up(P)))'][2]:.1f}x"
        )
        one = res_s["round trip: cga.down(cga.apply(M, cga.up(x)))"][2]
        print(
            f"         one point, round trip, at most half of kingdon's time: ours / kingdon "
            f"{one / res_s['round trip: kingdon point, M >> X, divide'][2]:.2f}"
        )
    ks = res_s.get("kingdon M >> X")
    if ks is not None:
        print(
            f"         kingdon's M >> X on one point: median {ks[0] * 1e6:.1f} us, best {ks[1] * 1e6:.1f} us "
            f"(ratio to ours, median ratios: {ks[2] / res_s['M >> X'][2]:.1f}x)"
        )


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    main(rounds=7 if quick else 25)
