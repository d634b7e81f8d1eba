"""The study's Fig. 3: spin after the impact against the impact angle; |omega_out| peaks at theta_c,
where the sliding branch meets the rolling one (rigid-body theory dashed).

Run: python examples/fig3_spin.py [--disc] [--out DIR] [--quick]
"""

import argparse
from pathlib import Path

import numpy as np

import restitution as rs
from restitution.study import analysis, figures

ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("--disc", action="store_true", help="exact disc instead of the 120-gon")
ap.add_argument("--out", type=Path, default=Path("results"))
ap.add_argument("--quick", action="store_true", help="a 2-degree theta grid (seconds; what the tests run)")
args = ap.parse_args()

scene = rs.Scene.paper(shape=rs.Disc(r=0.01)) if args.disc else rs.Scene.paper()
df = rs.sweep(scene, theta_deg=np.arange(4.0, 89.0 + 1e-9, 2.0 if args.quick else 0.5), mu=np.round(np.linspace(0.0, 1.0, 11), 10))
crit = analysis.critical_angles(df, r=scene.r, v=scene.v)
print(crit.select("mu", "theta_c", "theta_c_theory", "omega_out_max"))

args.out.mkdir(parents=True, exist_ok=True)
figures.fig3(df, crit, r=scene.r, v=scene.v, path=args.out / "fig3_spin.png",
             title=f"paper preset on {'an exact disc' if args.disc else 'the 120-gon'}")
print(f"wrote {args.out / 'fig3_spin.png'}")
