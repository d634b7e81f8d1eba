"""Calibrate Hertz-Mindlin to Kharaz, Gorham & Salman's (2001) measurements: the posterior of the
friction coefficient mu and Poisson's ratio nu of 5 mm alumina spheres on a glass anvil from their
measured e_t and rebound spin (docs/model.md, "Calibration", the worked example).

    python examples/calibrate_kharaz.py --out kharaz_fit

Prints the posterior summary, the predictive check's worst points and one summary line; writes
kharaz_fit.png (data over the posterior band) and kharaz_corner.png.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import polars as pl

import restitution as rs

# Chung & Ooi's Test 4 sphere (alumina: E 380 GPa, nu 0.23, 4000 kg/m^3; head-on restitution 0.98)
# at 3.9 m/s on Kharaz's soda-lime glass anvil (E 70 GPa, nu 0.25); the adaptive integrator, whose
# tol the fit chooses from the data's smallest sigma.
SCENE = rs.Scene(shape=rs.Sphere(r=2.5e-3), normal_law="hertz", E=380e9, nu=0.23, rho=4000.0, cor=0.98, mu=0.092,
                 v=3.9, plate_E=70e9, plate_nu=0.25)
FREE = {"mu": rs.Uniform(0.0, 0.3), "nu": rs.Uniform(0.0, 0.49)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("kharaz_fit"))
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    data = rs.datasets.kharaz2001()
    post = rs.calibrate.fit(SCENE, data, FREE, seed=args.seed)
    with pl.Config(tbl_cols=-1, tbl_width_chars=160):
        print(post.summary())
        check = post.check().sort(pl.col("z").abs(), descending=True)
        print(check.head(4))
    post.plot_fit().savefig(args.out / "kharaz_fit.png")
    post.plot_corner().savefig(args.out / "kharaz_corner.png")

    s = {r["parameter"]: r for r in post.summary().iter_rows(named=True)}
    worst = check.row(0, named=True)
    print(f"kharaz: mu = {s['mu']['q50']:.4f} [{s['mu']['q05']:.4f}, {s['mu']['q95']:.4f}], "
          f"nu = {s['nu']['q50']:.3f} [{s['nu']['q05']:.3f}, {s['nu']['q95']:.3f}]; converged {post.converged}; "
          f"tol {post.tol:.2g}; p = {post.p_value:.3f}; worst z = {worst['z']:.1f} at theta_deg = "
          f"{worst['theta_deg']:.2f} ({worst['quantity']})")


if __name__ == "__main__":
    main()
