"""Automatic registration of conformal entities (future work 6.2.2): quality and speed of the detector.

Run: ``python benchmarks/bench_stereo_detect.py`` (add ``--quick`` for 3 seeds instead of 10 and fewer levels;
``--out FILE`` also writes every table as JSON, e.g. ``benchmarks/results/bench_stereo_detect.json``, which
notebook 11 reads).  Prints numbers only; nothing here is asserted.

1. Precision / recall per kind over seeds and noise levels: scenes of 3 planes, 3 spheres, 3 circles and
   3 lines with 300 clutter points (:mod:`cga_lessons.stereo.detect_scenes`), seen through the simulated
   stereo head (0.25-2 px) with the triangulation covariances as the sensor fact; and as clouds with
   isotropic noise that the detector estimates itself.
2. The bundled head of ``data/stereo_rig.json`` (12 cm baseline, 700 px) on nearer scenes.
3. Time per cloud size (the same scenes sampled 0.5-4 times as densely).
4. The Middlebury motorcycle pair (bundled with scikit-image): the dominant planes of its dense points.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from cga_lessons.stereo import detect as sd
from cga_lessons.stereo import detect_scenes as ss
from cga_lessons.stereo import detect_scores as sc
from cga_lessons.stereo.detect_params import present
from cga_lessons.stereo.rig import load_rig

QUICK = "--quick" in sys.argv
SEEDS = range(3) if QUICK else range(10)
KINDS = ss.KINDS
RESULTS = {"quick": QUICK, "seeds": len(SEEDS), "kinds": list(KINDS), "sections": [], "motorcycle": None}


def run(make, seeds, noise_of=lambda scene: scene.noise, config=None):
    """Totals (tp, detected, true) per kind, mean time per cloud and mean cloud size."""
    tot = {k: np.zeros(3, int) for k in KINDS}
    times, sizes = [], []
    for s in seeds:
        scene = make(np.random.default_rng(s))
        t0 = time.perf_counter()
        ents = sd.detect_entities(scene.points, np.random.default_rng(1000 + s), config, noise_of(scene))
        times.append(time.perf_counter() - t0)
        sizes.append(len(scene.points))
        ev = sc.evaluate(scene, ents)
        for k in KINDS:
            tot[k] += [ev.kinds[k].tp, ev.kinds[k].detected, ev.kinds[k].truth]
    return tot, float(np.mean(times)), float(np.mean(sizes))


def row(label, tot, t, n):
    cells = []
    for k in KINDS:
        tp, det, tru = tot[k]
        cells.append(f"{tp / max(det, 1):5.2f} {tp / max(tru, 1):5.2f}")
    print(f"{label:<28}" + "  ".join(cells) + f"   {n:6.0f} {t:6.2f}")
    if RESULTS["sections"]:
        kinds = {k: dict(zip(("tp", "detected", "truth"), map(int, tot[k]))) for k in KINDS}
        RESULTS["sections"][-1]["rows"].append(dict(label=label, kinds=kinds, points=n, seconds=t))


def header(title):
    print(f"\n{title}")
    RESULTS["sections"].append(dict(title=title, rows=[]))
    print(f"{'':<28}" + "  ".join(f"{k:^11}" for k in KINDS) + "   points   time")
    print(f"{'':<28}" + "  ".join(f"{'prec':>5} {'rec':>5}" for _ in KINDS) + "        (s/cloud)")


def precision_recall():
    header(f"1. precision / recall per kind, {len(SEEDS)} seeds, through the stereo head (40 cm, 1200 px)")
    levels = (0.5, 1.0, 2.0) if QUICK else (0.25, 0.5, 0.75, 1.0, 1.5, 2.0)
    for px in levels:
        cfg = ss.SceneConfig(noise_px=px)
        row(f"stereo {px:4.2f} px", *run(lambda g, cfg=cfg: ss.stereo_scene(g, cfg), SEEDS))
    for sigma in (0.005, 0.01) if QUICK else (0.0025, 0.005, 0.01, 0.015):
        cfg = ss.SceneConfig(noise_m=sigma)
        row(f"cloud {1e3 * sigma:4.1f} mm, estimated", *run(lambda g, cfg=cfg: ss.cloud_scene(g, cfg), SEEDS,
                                                             noise_of=lambda scene: None))  # fmt: skip
    cfg = ss.SceneConfig(noise_px=1.0, clutter=1500)
    row("stereo 1 px, 1500 clutter", *run(lambda g: ss.stereo_scene(g, cfg), SEEDS))


def bundled_head():
    rig = load_rig()
    header("2. the bundled head (12 cm, 700 px, 640 x 480), objects at 0.8-1.6 m, smaller and fewer")
    for px in (0.5, 1.0):
        cfg = ss.SceneConfig(n_planes=2, n_spheres=2, n_circles=2, n_lines=2, plane_sides=(0.25, 0.4),
                             sphere_radius=(0.1, 0.15), circle_radius=(0.08, 0.12), line_length=(0.3, 0.45),
                             surface_density=4000.0, curve_density=250.0, clutter=150, depth=(0.8, 1.6),
                             gap=0.05, noise_px=px)  # fmt: skip
        row(f"bundled head {px:3.1f} px", *run(lambda g, cfg=cfg: ss.stereo_scene(g, cfg, rig), SEEDS))


def timing():
    header("3. time per cloud size (stereo, 0.75 px; density x 0.5 ... x 4, clutter scaled alike)")
    for f in (0.5, 1.0, 2.0, 4.0):
        cfg = ss.SceneConfig(noise_px=0.75, surface_density=1500.0 * f, curve_density=100.0 * f,
                             clutter=int(300 * f))  # fmt: skip
        row(f"density x {f:3.1f}", *run(lambda g, cfg=cfg: ss.stereo_scene(g, cfg), range(2) if QUICK else range(3)))


def motorcycle(step=6, sigma_px=0.5):
    from cga_lessons.stereo import detect_models as dm
    from cga_lessons.stereo import real as real
    from cga_lessons.stereo.detect_noise import triangulation_covariance

    try:
        _, _, disp, calib = real.load_motorcycle()
    except Exception as exc:  # scikit-image missing or without its data
        print(f"\n4. Middlebury motorcycle: not available ({exc})")
        return
    X, px = real.disparity_to_points(disp, calib, step=step)
    P1, P2 = real.motorcycle_cameras(calib)
    d = disp[px[:, 1].astype(int), px[:, 0].astype(int)]
    cov = triangulation_covariance(P1, P2, px, px - np.column_stack([d, np.zeros_like(d)]), sigma_px)
    print(f"\n4. Middlebury motorcycle, every {step}th pixel: {len(X)} points (left camera frame: x right, y down, "
          f"z forward), {sigma_px} px disparity noise as the sensor fact")  # fmt: skip
    floor = None
    RESULTS["motorcycle"] = dict(step=step, sigma_px=sigma_px, points=len(X), runs=[])
    for label, cfg in (("planes only", sd.DetectConfig(kinds=("plane",))), ("all kinds", sd.DetectConfig())):
        t0 = time.perf_counter()
        ents = sd.detect_entities(X, np.random.default_rng(0), cfg, cov)
        dt = time.perf_counter() - t0
        found = {k: sum(e.kind == k for e in ents) for k in KINDS}
        cover = sum(len(e.inliers) for e in ents) / len(X)
        print(f"  {label}: {dt:.1f} s, {len(ents)} entities {found}, {cover:.0%} of the points on one")
        RESULTS["motorcycle"]["runs"].append(
            dict(
                label=label,
                seconds=dt,
                found=found,
                cover=cover,
                entities=[
                    dict(
                        kind=e.kind,
                        inliers=len(e.inliers),
                        rms=e.rms,
                        chi2=e.chi2,
                        params={k: np.asarray(v).tolist() for k, v in present(e.params).items()},
                    )
                    for e in ents
                ],
            )
        )
        floor = floor or ents[0]  # the largest plane of the planes-only run: the floor (normal along image y)
        for e in ents[:6]:
            if e.kind == "plane":
                ang = np.degrees(np.arccos(min(1.0, abs(e.params.normal @ floor.params.normal))))
                what = (f"normal {np.round(e.params.normal, 3)}  n.x = {e.params.distance:.3f} m  "
                        f"{ang:4.1f} deg to the floor")  # fmt: skip
            elif e.kind == "sphere":
                what = f"centre {np.round(e.params.center, 2)}  radius {e.params.radius:.2f} m"
            else:
                what = str({k: np.round(v, 2) for k, v in present(e.params).items()})
            print(f"    {e.kind:<6} {len(e.inliers):5d} pts  rms {1e3 * e.rms:5.1f} mm  chi2 {e.chi2:4.2f}  {what}")
        if label == "planes only":
            Xf = X[floor.inliers]
            sph = dm.fit("sphere", Xf)
            if sph is not None:
                r = np.linalg.norm(Xf - sph.center, axis=1) - sph.radius
                print(f"    the floor's points: plane rms {1e3 * floor.rms:.1f} mm, best sphere (radius "
                      f"{sph.radius:.0f} m) rms {1e3 * np.sqrt(np.mean(r**2)):.1f} mm")  # fmt: skip


if __name__ == "__main__":
    precision_recall()
    bundled_head()
    timing()
    motorcycle()
    if "--out" in sys.argv:
        out = Path(sys.argv[sys.argv.index("--out") + 1])
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps(RESULTS, indent=1) + "\n")
        print(f"\nwrote {out}")
