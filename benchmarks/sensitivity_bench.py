"""Sobol' sensitivity of Kharaz's impact (issue 39): 4 parameters, n = 1024, 8 angles.

    python benchmarks/sensitivity_bench.py               # n 1024, 999 bootstrap resamples
    python benchmarks/sensitivity_bench.py --n 256

Alumina on Kharaz's glass anvil (Chung & Ooi's Test 4 sphere, adaptive path at its default
tol) with mu, cor, nu and E drawn from uniform priors; e_N, e_T and the rebound spin at 8 angles
from 10 to 80 deg. Prints the wall time of the whole call, of the engine's share (the same
impacts run by ``predict`` alone) and impacts per second. Target: <= 30 s on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import restitution as rs
from restitution.calibrate import sobol

SCENE = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98, mu=0.092,
                 plate_E=70e9, plate_nu=0.25, v=3.9)
VARY = {"mu": rs.Uniform(0.05, 0.3), "cor": rs.Uniform(0.8, 0.99), "nu": rs.Uniform(0.15, 0.3),
        "E": rs.Uniform(2e11, 4.5e11)}
THETA = np.linspace(10.0, 80.0, 8)
QUANTITIES = ["e_n", "e_t", "omega_out"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=1024)
    parser.add_argument("--resamples", type=int, default=999)
    args = parser.parse_args()
    impacts = args.n * (len(VARY) + 2) * len(THETA)
    t0 = time.perf_counter()
    frame = rs.calibrate.sensitivity(SCENE, VARY, n=args.n, theta_deg=THETA, quantities=QUANTITIES,
                                     n_resamples=args.resamples)
    total = time.perf_counter() - t0
    # The engine's share: the same parameter sets through the forward model alone.
    stats = sobol._scipy.stats()
    sets = sobol._saltelli_sets(stats, list(VARY.values()), args.n, np.random.default_rng(3))
    t0 = time.perf_counter()
    sobol.predict(SCENE, dict(zip(VARY, sets)), sobol.pl.DataFrame({"theta_deg": THETA}), QUANTITIES)
    engine = time.perf_counter() - t0
    print(f"{os.cpu_count()} cores, n {args.n}, {len(VARY)} parameters, {len(THETA)} angles: {impacts} impacts, "
          f"{args.resamples} bootstrap resamples")
    print(f"sensitivity: {total:.1f} s (engine {engine:.1f} s, {impacts / engine:.0f} impacts/s; "
          f"estimators and bootstrap {total - engine:.1f} s)")
    st = frame.filter(frame["quantity"] == "e_t").pivot(on="parameter", index="theta_deg", values="ST")
    print("ST of e_t:")
    print(st)


if __name__ == "__main__":
    main()
