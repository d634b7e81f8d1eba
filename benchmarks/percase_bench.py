"""What a scene field varied per case costs (issue 39): a calibration or a sensitivity study
gives every impact its own parameters, so no field may cost much more per case than a fixed one.

    python benchmarks/percase_bench.py                  # 1500 impacts per row, best of 3
    python benchmarks/percase_bench.py --n 4000 --repeat 5

For each scene and field: a sweep over a ``cases`` frame whose ``theta_deg`` is drawn in
[10, 80] deg and whose field column holds either the scene's own value in every row ("fixed") or
a uniform draw over the range below ("per case"). Prints us per impact (best of the repeats,
the sweep's whole call: its up-front check included) and two ratios measured in the same run:
per case against fixed, and per case against a per-case ``mu`` on the same scene. Target: every
field within 3x of ``mu``.
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


def per_impact(scene: rs.Scene, cases: pl.DataFrame, repeat: int) -> float:
    """Best wall time per impact (s) of ``repeat`` sweeps over ``cases``."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        rs.sweep(scene, cases=cases, progress=False)
        best = min(best, time.perf_counter() - t0)
    return best / cases.height


def fixed_value(scene: rs.Scene, field: str) -> float:
    """The scene's own value of ``field`` (its default where the scene leaves it unset)."""
    value = getattr(scene, field, None) if field != "omega_in" else 0.0
    if value is None:
        value = {"kt": 2.0 * scene.E / 7.0, "kn": scene.E, "cn": 0.0}[field]
    return float(getattr(scene.shape, "r", value) if field == "r" else value)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=1500, help="impacts per sweep")
    parser.add_argument("--repeat", type=int, default=3, help="sweeps per row (best counts)")
    args = parser.parse_args()
    rng = np.random.default_rng(39)
    theta = rng.uniform(10.0, 80.0, args.n)
    print(f"{platform.machine()}, {args.n} impacts per sweep, best of {args.repeat}")
    print("| scene | field | fixed us/impact | per case us/impact | per case / fixed | per case / per-case mu |")
    print("|---|---|---|---|---|---|")
    for label, (scene, fields) in SCENES.items():
        times = {}
        for field, (lo, hi) in fields.items():
            fixed = pl.DataFrame({"theta_deg": theta, field: np.full(args.n, fixed_value(scene, field))})
            drawn = pl.DataFrame({"theta_deg": theta, field: rng.uniform(lo, hi, args.n)})
            times[field] = (per_impact(scene, fixed, args.repeat), per_impact(scene, drawn, args.repeat))
        for field, (t_fixed, t_case) in times.items():
            print(f"| {label} | {field} | {t_fixed * 1e6:.1f} | {t_case * 1e6:.1f} | {t_case / t_fixed:.2f} "
                  f"| {t_case / times['mu'][1]:.2f} |")


if __name__ == "__main__":
    main()
