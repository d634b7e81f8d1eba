"""What a scene field varied per case costs (issue 39): a calibration or a sensitivity study
gives every impact its own parameters, so no field may cost much more per case than a fixed one.

    python benchmarks/percase_bench.py                  # 2000 impacts per row, best of 5, one thread
    python benchmarks/percase_bench.py --n 4000 --repeat 5

For each scene and field: 8 values drawn uniformly over the range below, and ``n`` impacts at
angles drawn in [10, 80] deg, impact i taking value i mod 8. "Per case": one sweep over a
``cases`` frame holding each impact's value. "Fixed": the same impacts as 8 sweeps, one per value
(a constant column: what a scene's own value costs). The same impacts, so the ratio is the cost of
varying the field per case, not of the values' physics. Prints us per impact (best of the
repeats, each sweep's whole call: its up-front check included) and, measured in the same run,
per case against fixed and per case against a per-case ``mu`` on the same scene. Target: every
field within 3x of ``mu`` per case. (The 8 calls of "fixed" cost ~1 ms more than one: a few %
in favour of "per case".)
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np
import polars as pl

import restitution as rs

#: Alumina on Kharaz's glass anvil (Chung & Ooi's Test 4 material, R = 2.5 mm, 3.9 m/s).
KHARAZ = dict(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98,
              mu=0.092, plate_E=70e9, plate_nu=0.25, v=3.9)

#: Scene name -> (scene, {field: (lo, hi) of its per-case draws}).
SCENES = {
    "sphere hertz, gear5": (rs.Scene(**KHARAZ, integrator="gear5"), {
        "mu": (0.05, 0.3), "cor": (0.5, 0.99), "nu": (0.1, 0.45), "E": (1e11, 5e11), "rho": (2e3, 6e3),
        "r": (1e-3, 5e-3), "v": (1.0, 5.0), "plate_E": (3e10, 1.5e11), "plate_nu": (0.1, 0.4),
        "omega_in": (-100.0, 100.0)}),
    "sphere hertz, adaptive": (rs.Scene(**KHARAZ, integrator="adaptive"), {
        "mu": (0.05, 0.3), "cor": (0.5, 0.99), "nu": (0.1, 0.45), "E": (1e11, 5e11), "plate_E": (3e10, 1.5e11)}),
    "disc area, gear5": (rs.Scene.paper(shape=rs.Disc(r=0.01)), {
        "mu": (0.05, 1.0), "gamma": (0.1, 0.6), "gamma_t": (0.0, 1.0), "kt": (1e6, 5e6), "E": (5e6, 2e7),
        "rho": (1e3, 4e3)}),
    "disc linear, gear5": (rs.Scene.paper(shape=rs.Disc(r=0.01), normal_law="linear"), {
        "mu": (0.05, 1.0), "kn": (5e6, 2e7), "cn": (0.0, 20.0), "kt": (1e6, 5e6)}),
}


def elapsed(scene: rs.Scene, cases: pl.DataFrame, threads: int) -> float:
    """Wall time (s) of one sweep over ``cases``."""
    t0 = time.perf_counter()
    rs.sweep(scene, cases=cases, progress=False, threads=threads)
    return time.perf_counter() - t0


#: Distinct values per field.
VALUES = 8


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=2000, help="impacts per row")
    parser.add_argument("--repeat", type=int, default=5, help="runs per row (best counts)")
    parser.add_argument("--threads", type=int, default=1, help="engine threads (one: least exposed to load)")
    args = parser.parse_args()
    rng = np.random.default_rng(39)
    theta = rng.uniform(10.0, 80.0, args.n)
    group = np.arange(args.n) % VALUES
    print(f"{platform.machine()}, {args.n} impacts per row, {VALUES} values, {args.threads} thread(s), "
          f"best of {args.repeat}")
    print("| scene | field | fixed us/impact | per case us/impact | per case / fixed | per case / per-case mu |")
    print("|---|---|---|---|---|---|")
    for label, (scene, fields) in SCENES.items():
        times = {}
        for field, (lo, hi) in fields.items():
            values = rng.uniform(lo, hi, VALUES)
            per_case = pl.DataFrame({"theta_deg": theta, field: values[group]})
            fixed = [pl.DataFrame({"theta_deg": theta[group == k], field: np.full((group == k).sum(), values[k])})
                     for k in range(VALUES)]
            # Alternated, best of each: a load that comes and goes hits both alike.
            runs = [(sum(elapsed(scene, part, args.threads) for part in fixed), elapsed(scene, per_case, args.threads))
                    for _ in range(args.repeat)]
            times[field] = (min(r[0] for r in runs) / args.n, min(r[1] for r in runs) / args.n)
        for field, (t_fixed, t_case) in times.items():
            print(f"| {label} | {field} | {t_fixed * 1e6:.1f} | {t_case * 1e6:.1f} | {t_case / t_fixed:.2f} "
                  f"| {t_case / times['mu'][1]:.2f} |")


if __name__ == "__main__":
    main()
