"""The inverse map: every impact (theta, mu, omega_in) that gives a measured e_T, here the study's
example e_T = 0.9 (+- 0.01): about 28 deg for every spin at mu = 0.1, and steep angles (70 ... 88 deg)
for forward spin at any mu.

Run: python examples/inverse_map.py [--value 0.9] [--tol 0.01] [--quantity e_t] [--disc] [--out DIR] [--quick]
"""

import argparse
from pathlib import Path

import numpy as np
import polars as pl

import restitution as rs
from restitution.study import inverse

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--quantity", default="e_t", choices=("e_t", "e_kin"))
ap.add_argument("--value", type=float, default=0.9)
ap.add_argument("--tol", type=float, default=0.01)
ap.add_argument("--disc", action="store_true", help="exact disc instead of the 120-gon")
ap.add_argument("--out", type=Path, default=Path("results"))
ap.add_argument("--quick", action="store_true", help="a 2-degree theta grid (seconds; what the tests run)")
args = ap.parse_args()

scene = rs.Scene.paper(shape=rs.Disc(r=0.01)) if args.disc else rs.Scene.paper()
spins_deg = np.array([-50.0, -20.0, -10.0, -5.0, 0.0, 5.0, 10.0, 20.0, 50.0])
df = rs.sweep(scene, theta_deg=np.arange(4.0, 89.0 + 1e-9, 2.0 if args.quick else 0.5), mu=[0.1, 1.0], omega_in=np.radians(spins_deg))

sol = inverse.find(df, args.quantity, args.value, tol=args.tol)
with pl.Config(tbl_rows=50):
    print(sol.select(pl.col("mu"), (pl.col("omega_in").degrees()).round(1).alias("omega_in_deg"),
                     pl.col("theta_deg").round(2), pl.col("theta_lo").round(2), pl.col("theta_hi").round(2),
                     "kind", pl.col("e_kin").round(4)))

args.out.mkdir(parents=True, exist_ok=True)
path = args.out / f"inverse_{args.quantity}_{args.value:g}.png"
inverse.plot(sol, df, quantity=args.quantity, value=args.value, tol=args.tol, path=path, r=scene.r, v=scene.v)
print(f"wrote {path}")
