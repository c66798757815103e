"""Motor on points: this project vs a plain NumPy 4x4 floor vs kingdon and clifford.

Run by hand: ``python benchmarks/bench_motor.py``.  Prints medians of repeats in
one process and ratios (absolute times drift between machines; ratios less so).
kingdon and clifford are optional (``pip install -e ".[bench]"``).
"""

from __future__ import annotations

import time

import numpy as np

from cga_lessons import conformal as cga


def median_time(fn, repeats=15, number=1):
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return float(np.median(times))


def main(n: int = 100_000, seed: int = 0):
    rng = np.random.default_rng(seed)
    pts = rng.normal(size=(n, 3))
    M = cga.motor([0.3, -0.2, 0.9], 0.7, [1.0, 2.0, -0.5])
    H = cga.motor_to_matrix(M)
    rows = []

    homog = np.hstack([pts, np.ones((n, 1))])
    floor = median_time(lambda: (homog @ H.T)[:, :3])
    floor_incl = median_time(lambda: pts @ H[:3, :3].T + H[:3, 3])
    rows.append(("numpy 4x4 homogeneous (floor)", floor))
    rows.append(("numpy 3x3 + t", floor_incl))
    rows.append(("cga.apply_to_points (batched)", median_time(lambda: cga.apply_to_points(M, pts))))
    X = cga.up(pts)
    rows.append(("cga.apply on conformal batch", median_time(lambda: cga.apply(M, X))))
    single_x = cga.up(pts[0])
    single = median_time(lambda: M * single_x * ~M, repeats=7, number=2000)
    try:
        import kingdon

        K = kingdon.Algebra(4, 1)
        km = K.multivector({("e" + "".join(str(i + 1) for i in range(5) if b >> i & 1)) if b else "e": v
                            for b, v in M.coeffs.items()})
        kx = K.vector([X[1], X[2], X[4], X[8], X[16]])
        rows.append(("kingdon M >> X (array coefficients)", median_time(lambda: km >> kx, repeats=7)))
        kx1 = K.vector([float(single_x[b]) for b in (1, 2, 4, 8, 16)])
        k_single = median_time(lambda: km >> kx1, repeats=7, number=2000)
    except ImportError:
        k_single = None
    print(f"Motor on N = {n:,} points (median of repeats, one process)")
    print(f"{'method':42s} {'time [ms]':>10s} {'x floor':>8s}")
    for name, t in rows:
        print(f"{name:42s} {t * 1e3:10.2f} {t / floor:8.2f}")
    print()
    print(f"single-point sandwich M X ~M: {single * 1e6:.1f} us", end="")
    if k_single is not None:
        print(f"; kingdon M >> X: {k_single * 1e6:.1f} us (ratio {single / k_single:.2f})")
    else:
        print()


if __name__ == "__main__":
    main()
