"""The study's Fig. 2: e_N, e_T and e_kin against the impact angle for mu = 0, 0.1 ... 1, and for
mu = 0 and 1 with half and double the normal damping; rigid-body theory dashed.

Run: python examples/fig2_restitution.py [--disc] [--out DIR] [--quick]
(the study's 120-gon by default, about 20 s on two cores; --disc: an exact disc, a second)
"""

import argparse
from pathlib import Path

import numpy as np
import polars as pl

import restitution as rs
from restitution.study import analysis, figures

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--disc", action="store_true", help="exact disc instead of the 120-gon")
ap.add_argument("--out", type=Path, default=Path("results"))
ap.add_argument("--quick", action="store_true", help="a 2-degree theta grid (seconds; what the tests run)")
args = ap.parse_args()

scene = rs.Scene.paper(shape=rs.Disc(r=0.01)) if args.disc else rs.Scene.paper()
theta = np.arange(4.0, 89.0 + 1e-9, 2.0 if args.quick else 0.5)
mus = np.round(np.linspace(0.0, 1.0, 11), 10)
df = rs.sweep(scene, theta_deg=theta, mu=mus)
gammas = [scene.gamma / 2, scene.gamma * 2]
df_gamma = rs.sweep(scene, theta_deg=theta, mu=[0.0, 1.0], gamma=gammas)

# e_T is the study's Eq. 2 while the impact slides, with the measured e_N:
res = analysis.sondergaard_residuals(df).filter((pl.col("mu") > 0) & pl.col("sliding") & (pl.col("theta_deg") == 4.0))
print(f"largest |e_T - (1 - mu (1 + e_N) tan theta)| at 4 deg: {res['e_t_residual'].abs().max():.1e}")
for g in gammas:
    print(f"gamma = {g:.3f}: e_N(90 deg) = {rs.simulate(scene.replace(gamma=g), 90.0).e_n:.4f}")

args.out.mkdir(parents=True, exist_ok=True)
figures.fig2(df, df_gamma, r=scene.r, v=scene.v, gamma=scene.gamma, path=args.out / "fig2_restitution.png",
             title=f"paper preset on {'an exact disc' if args.disc else 'the 120-gon'}")
print(f"wrote {args.out / 'fig2_restitution.png'}")
