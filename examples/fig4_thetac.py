"""The study's Fig. 4: theta_c and e_kin,min against mu, fitted with a exp(-b mu) + c, beside the
study's fits and rigid-body theory; prints both sets of parameters and flags 2-sigma differences.

Run: python examples/fig4_thetac.py [--disc] [--out DIR] [--quick]
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
mus = np.round(np.arange(0.1, 1.0 + 1e-9, 0.1), 10)  # the study's friction coefficients
df = rs.sweep(scene, theta_deg=np.round(np.arange(4.0, 89.0 + 1e-9, 2.0 if args.quick else 0.25), 10), mu=mus)
crit = analysis.critical_angles(df, r=scene.r, v=scene.v).sort("mu")  # refined between grid points
fits = {q: analysis.fit_exp(crit["mu"].to_numpy(), crit[q].to_numpy()) for q in ("theta_c", "e_kin_min")}

for q, fit in fits.items():
    print(f"{q}:")
    for name, val, err in zip("abc", fit.params, fit.errors):
        study = figures.STUDY_FITS[q][name]
        dist, flag = analysis.compare((val, err), study)
        print(f"  {name} = {val:9.4f} +- {err:.4f}   study {study[0]} +- {study[1]}   "
              f"{dist:.1f} sigma{'  <- beyond 2 sigma' if flag else ''}")
print(crit.select("mu", "theta_c", "theta_c_theory", "e_kin_min"))

args.out.mkdir(parents=True, exist_ok=True)
figures.fig4(crit, fits, path=args.out / "fig4_thetac.png",
             title=f"paper preset on {'an exact disc' if args.disc else 'the 120-gon'}")
print(f"wrote {args.out / 'fig4_thetac.png'}")
