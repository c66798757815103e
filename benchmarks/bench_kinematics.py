"""Forward kinematics of a 6-joint arm (the UR5) for 10,000 configurations at once: motors vs 4x4 matrices.

Run by hand from the repository root::

    python benchmarks/bench_kinematics.py            # N = 10,000 configurations, 30 rounds
    python benchmarks/bench_kinematics.py --quick    # fewer rounds
    python benchmarks/bench_kinematics.py --out benchmarks/results/bench_kinematics.json  # also the numbers as JSON

Cases (every one batched over the N configurations, none loops over them in Python):

* ``kinematics.forward_coefficients``: the product of motors ``M_1(q_1) ... M_6(q_6) M0``, each joint in
  closed form ``cos(q/2) - sin(q/2) L`` (2.109), one (N, 8) x (8, 8) product per joint;
* ``kinematics.forward_matrix``: the same, then the 4x4 matrices of the motors;
* NumPy 4x4 DH chain (the floor): the six DH link matrices ``Rz Tz Tx Rx`` built in closed form as (N, 4, 4)
  arrays and multiplied with ``np.matmul`` (also timed with ``np.einsum``; the faster of the two is the floor);
* NumPy 4x4, linear in (cos, sin): ``T_i = T_{i-1} (K0 + cos q K1 + sin q K2)`` with T flattened to (N, 16),
  one (N, 16) x (16, 48) product per joint: the same trick the motor chain uses, given to the matrices too;
* pytransform3d (if installed), as its docs recommend for batches: ``transforms_from_exponential_coordinates``
  per joint and ``concat_many_to_many`` along the chain; and its dual quaternions
  (``dual_quaternions_from_screw_parameters``, ``batch_concatenate_dual_quaternions``), the peer closest to
  motors;
* the package's general Multivector product of batched ``rotor_about_line`` motors, for scale.

Every route's result is checked against the DH matrices before timing.  Everything runs in one process with
one BLAS thread, in rounds (each round times every case once, so a slow spell of a shared machine hits all
alike).  ``x floor`` is the median over rounds of (case time / floor time in the same round); ``best`` is the
best time of the case over the best time of the floor.  Ratios, not absolute times, are what to compare.
"""

from __future__ import annotations

import json
import os
import pathlib
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))  # run from a checkout, installed or not

from cga_lessons import conformal as cga  # noqa: E402
from cga_lessons import kinematics as kin  # noqa: E402
from cga_lessons.kinematics.arms import UR5_DH, ur5  # noqa: E402

D, A, ALPHA = np.array(UR5_DH.d), np.array(UR5_DH.a), np.array(UR5_DH.alpha)


def dh_links(q):
    """The six standard DH link matrices (N, 4, 4) of the UR5, closed form."""
    N = len(q)
    c, s = np.cos(q), np.sin(q)
    ca, sa = np.cos(ALPHA), np.sin(ALPHA)
    out = []
    for i in range(6):
        L = np.zeros((N, 4, 4))
        L[:, 0, 0], L[:, 0, 1], L[:, 0, 2], L[:, 0, 3] = c[:, i], -s[:, i] * ca[i], s[:, i] * sa[i], A[i] * c[:, i]
        L[:, 1, 0], L[:, 1, 1], L[:, 1, 2], L[:, 1, 3] = s[:, i], c[:, i] * ca[i], -c[:, i] * sa[i], A[i] * s[:, i]
        L[:, 2, 1], L[:, 2, 2], L[:, 2, 3], L[:, 3, 3] = sa[i], ca[i], D[i], 1.0
        out.append(L)
    return out


def numpy_matmul(q):
    links = dh_links(q)
    T = links[0]
    for L in links[1:]:
        T = np.matmul(T, L)
    return T


def numpy_einsum(q):
    links = dh_links(q)
    T = links[0]
    for L in links[1:]:
        T = np.einsum("nij,njk->nik", T, L)
    return T


def linear_tables():
    """Per link, (4, 12) = [K0 | K1 | K2] with link(q) = K0 + cos q K1 + sin q K2."""
    out = []
    for i in range(6):
        ca, sa = np.cos(ALPHA[i]), np.sin(ALPHA[i])
        K0, K1, K2 = np.zeros((4, 4)), np.zeros((4, 4)), np.zeros((4, 4))
        K0[2, 1], K0[2, 2], K0[2, 3], K0[3, 3] = sa, ca, D[i], 1.0
        K1[0, 0], K1[0, 3], K1[1, 1], K1[1, 2] = 1.0, A[i], ca, -sa
        K2[0, 1], K2[0, 2], K2[1, 0], K2[1, 3] = -ca, sa, 1.0, A[i]
        out.append(np.hstack([K0, K1, K2]))
    return out


# T (N, 16) times a constant K on the right is T @ kron(I4, K); per link [kron(I, K0) | kron(I, K1) | kron(I, K2)]
WIDE = [np.hstack([np.kron(np.eye(4), t[:, 4 * k : 4 * k + 4]) for k in range(3)]) for t in linear_tables()]


def numpy_linear(q):
    c, s = np.cos(q), np.sin(q)
    T = np.tile(np.eye(4).ravel(), (len(q), 1))
    for i in range(6):
        Y = T @ WIDE[i]  # (N, 16) x (16, 48), one BLAS product
        T = Y[:, :16] + c[:, i, None] * Y[:, 16:32] + s[:, i, None] * Y[:, 32:]
    return T.reshape(-1, 4, 4)


def peer_cases(ch, q):
    """pytransform3d's batched routes with the chain's screw axes (omega, p x omega) and home M0."""
    try:
        import pytransform3d.trajectories as ptr
    except ImportError:
        return {}
    S = kin.spatial_jacobian(ch, np.zeros(ch.n)).T  # the screw axes at home
    M0 = cga.motor_to_matrix(ch.home)
    points = np.array([j.point for j in ch.joints])
    dirs = np.array([j.direction for j in ch.joints])

    def exp_coords(q=q):
        T = ptr.transforms_from_exponential_coordinates(S[0] * q[:, :1])
        for i in range(1, ch.n):
            T = ptr.concat_many_to_many(ptr.transforms_from_exponential_coordinates(S[i] * q[:, i : i + 1]), T)
        return ptr.concat_one_to_many(M0, T)

    dq0 = ptr.dual_quaternions_from_transforms(M0[None])[0]

    def dual_quaternions(q=q):
        N = len(q)
        zeros = np.zeros(N)
        dq = ptr.dual_quaternions_from_screw_parameters(
            np.broadcast_to(points[0], (N, 3)), np.broadcast_to(dirs[0], (N, 3)), zeros, q[:, 0].copy()
        )
        for i in range(1, ch.n):
            dqi = ptr.dual_quaternions_from_screw_parameters(
                np.broadcast_to(points[i], (N, 3)), np.broadcast_to(dirs[i], (N, 3)), zeros, q[:, i].copy()
            )
            dq = ptr.batch_concatenate_dual_quaternions(dq, dqi)
        return ptr.transforms_from_dual_quaternions(ptr.batch_concatenate_dual_quaternions(dq, np.tile(dq0, (N, 1))))

    return {
        "pytransform3d exp. coordinates + concat_many_to_many": exp_coords,
        "pytransform3d dual quaternions (screw parameters)": dual_quaternions,
    }


def multivector_product(ch, q):
    M = ch.home
    for i in reversed(range(ch.n)):
        M = cga.rotor_about_line(ch.joints[i].line, q[:, i]) * M
    return M


def run_rounds(cases: dict, rounds: int, floor: str) -> dict:
    for fn in cases.values():
        fn()
        fn()
    times = {name: [] for name in cases}
    for _ in range(rounds):
        for name, fn in cases.items():
            t0 = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t0)
    base = np.array(times[floor])
    return {name: (float(np.median(t)), float(np.min(t)), float(np.median(np.array(t) / base)),
                   float(np.min(t) / base.min())) for name, t in times.items()}  # fmt: skip


def main(n: int = 10_000, rounds: int = 30, seed: int = 0, out=None):
    rng = np.random.default_rng(seed)
    q = rng.uniform(-np.pi, np.pi, (n, 6))
    ch = ur5()
    truth = numpy_matmul(q)
    cases = {
        "NumPy 4x4 DH chain, np.matmul": lambda: numpy_matmul(q),
        "NumPy 4x4 DH chain, np.einsum": lambda: numpy_einsum(q),
        "NumPy 4x4, linear in (cos, sin), (N,16)x(16,48)": lambda: numpy_linear(q),
        "kinematics.forward_coefficients (motor numbers)": lambda: kin.forward_coefficients(ch, q),
        "kinematics.forward_matrix (motors, then 4x4)": lambda: kin.forward_matrix(ch, q),
    }
    cases.update({k: (lambda f=f: f()) for k, f in peer_cases(ch, q).items()})
    checks = {name: float(np.abs(fn() - truth).max()) for name, fn in cases.items()
              if "coefficients" not in name}  # fmt: skip
    checks["kinematics.forward_coefficients (motor numbers)"] = float(
        np.abs(kin.coefficients_to_matrix(kin.forward_coefficients(ch, q)) - truth).max()
    )
    small = q[:500]
    Mv = multivector_product(ch, small)
    checks["package Multivector product (500 configurations)"] = float(
        np.abs(kin.coefficients_to_matrix(kin.motor_coefficients(Mv)) - truth[:500]).max()
    )
    print(f"forward kinematics of the UR5 (6 joints), N = {n:,} configurations, {rounds} rounds, one BLAS thread")
    print("\nlargest deviation from the NumPy 4x4 DH chain (every entry of the 4x4 matrices):")
    for name, dev in checks.items():
        print(f"  {name:<55} {dev:.1e}")
        if dev > 1e-12:
            print("  ^ DISAGREES")
    floor_name = min(("NumPy 4x4 DH chain, np.matmul", "NumPy 4x4 DH chain, np.einsum"),
                     key=lambda k: np.median([run_rounds({k: cases[k]}, 5, k)[k][0] for _ in range(3)]))  # fmt: skip
    res = run_rounds(cases, rounds, floor_name)
    print(f"\nfloor: {floor_name} (the faster of matmul and einsum)")
    print(f"\n  {'case':<55} {'median ms':>10} {'best ms':>9} {'x floor':>8} {'best':>6}")
    for name, (med, best, ratio, bratio) in res.items():
        print(f"  {name:<55} {med * 1e3:10.2f} {best * 1e3:9.2f} {ratio:8.2f} {bratio:6.2f}")
    t0 = time.perf_counter()
    multivector_product(ch, q)
    t_mv = time.perf_counter() - t0
    print(f"\n  {'package Multivector product of rotor_about_line motors':<55} {t_mv * 1e3:10.2f}"
          f"{'':>10} {t_mv / res[floor_name][0]:8.2f}   (one run)")  # fmt: skip
    print(f"\nmotor chain (4x4 out) / NumPy 4x4 floor: {res['kinematics.forward_matrix (motors, then 4x4)'][2]:.2f}x"
          f"; motor numbers only: {res['kinematics.forward_coefficients (motor numbers)'][2]:.2f}x"
          " (target: within 2x)")  # fmt: skip
    if out is not None:
        cols = ("median_ms", "best_ms", "x_floor", "best_x_floor")
        record = dict(arm="UR5", joints=ch.n, configurations=n, rounds=rounds, seed=seed, floor=floor_name,
                      max_deviation=checks, cases={name: dict(zip(cols, (r[0] * 1e3, r[1] * 1e3, r[2], r[3])))
                                                   for name, r in res.items()},
                      multivector_product_ms=t_mv * 1e3, multivector_x_floor=t_mv / res[floor_name][0])  # fmt: skip
        path = pathlib.Path(out)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(record, indent=1) + "\n")
        print(f"\nwrote {path}")


if __name__ == "__main__":
    quick = "--quick" in sys.argv[1:]
    out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv[1:-1] else None
    main(rounds=8 if quick else 30, out=out)
