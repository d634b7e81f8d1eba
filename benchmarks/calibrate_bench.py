"""Issue 39, item 8: wall time of a Kharaz calibration to a converged posterior.

Fits Hertz-Mindlin to Kharaz et al. (2001)'s e_t and rebound spin (rs.datasets.kharaz2001(), 20
points) with 2 free fields (mu, nu) and with 4: (mu, nu, cor, plate_nu), and (mu, nu, plate_nu,
plate_E) (a per-case cor costs what a per-case mu does: the damping's calibration is a table
lookup, docs/model.md 14.3), each run until the fit's convergence tests pass (chain > 50 tau, ESS >= 400, split R-hat
<= 1.01). Prints, per run, the seconds, iterations, impacts, the cost per impact and the medians.
Targets: 2 free <= 10 s, 4 free <= 60 s on 2 cores.

    python benchmarks/calibrate_bench.py [--only 2 4 4e] [--seed 1]
"""

from __future__ import annotations

import argparse
import os

import restitution as rs

SCENE = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98, mu=0.092,
                 v=3.9, plate_E=70e9, plate_nu=0.25)
FREE = {
    "2": {"mu": rs.Uniform(0.0, 0.3), "nu": rs.Uniform(0.0, 0.49)},
    "4": {"mu": rs.Uniform(0.0, 0.3), "nu": rs.Uniform(0.0, 0.49), "cor": rs.Uniform(0.9, 1.0),
          "plate_nu": rs.Uniform(0.0, 0.49)},
    "4e": {"mu": rs.Uniform(0.0, 0.3), "nu": rs.Uniform(0.0, 0.49), "plate_nu": rs.Uniform(0.0, 0.49),
           "plate_E": rs.LogNormal(24.97, 0.5)},  # median 70 GPa, a factor 1.65 either way (1 sd)
}
TARGET_S = {"2": 10.0, "4": 60.0, "4e": 60.0}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", nargs="+", choices=tuple(FREE), default=tuple(FREE))
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    data = rs.datasets.kharaz2001()
    print(f"cores: {os.cpu_count()}; tol chosen: {rs.calibrate.sampler.choose_tol(SCENE, data):.3g}")
    for k in args.only:
        post = rs.calibrate.fit(SCENE, data, FREE[k], seed=args.seed)
        medians = ", ".join(f"{r['parameter']} {r['q50']:.4g}" for r in post.summary().iter_rows(named=True))
        print(f"{', '.join(FREE[k])} free: {post.seconds:.1f} s (target {TARGET_S[k]:.0f} s), {post.iterations} iterations x "
              f"{post.walkers} walkers, {post.impacts:,} impacts, {post.seconds / post.impacts * 1e6:.0f} us/impact "
              f"overall; converged {post.converged}; medians {medians}; p = {post.p_value:.3f}")


if __name__ == "__main__":
    main()
