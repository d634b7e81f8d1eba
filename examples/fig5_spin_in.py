"""The study's Fig. 5: e_T and e_kin against the impact angle for spins before impact from -50 to
+50 deg/s, mu = 0.1 and 1 (rigid-body theory with spin dashed).

Run: python examples/fig5_spin_in.py [--disc] [--out DIR] [--quick]
"""

import argparse
from pathlib import Path

import numpy as np

import restitution as rs
from restitution.study import figures

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--disc", action="store_true", help="exact disc instead of the 120-gon")
ap.add_argument("--out", type=Path, default=Path("results"))
ap.add_argument("--quick", action="store_true", help="a 2-degree theta grid (seconds; what the tests run)")
args = ap.parse_args()

scene = rs.Scene.paper(shape=rs.Disc(r=0.01)) if args.disc else rs.Scene.paper()
spins_deg = np.array([-50.0, -20.0, -10.0, -5.0, 0.0, 5.0, 10.0, 20.0, 50.0])
df = rs.sweep(scene, theta_deg=np.arange(4.0, 89.0 + 1e-9, 2.0 if args.quick else 0.5), mu=[0.1, 1.0], omega_in=np.radians(spins_deg))
print(f"e_T from {df['e_t'].min():.3f} to {df['e_t'].max():.3f} (the study: -4.17 to 5.37)")

args.out.mkdir(parents=True, exist_ok=True)
figures.fig5(df, r=scene.r, v=scene.v, path=args.out / "fig5_spin_in.png",
             title=f"paper preset on {'an exact disc' if args.disc else 'the 120-gon'}")
print(f"wrote {args.out / 'fig5_spin_in.png'}")
