"""``restitution fig2``: the study's main figure, e_N, e_T and e_kin against theta for
mu = 0, 0.1 ... 1, on the paper preset; writes the sweep as Parquet and the figure as PNG."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

NAME = "fig2"
HELP = "e_N, e_T, e_kin against theta for mu = 0 ... 1 (the study's Fig. 2): Parquet + PNG"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results"), help="output folder (default: results)")
    p.add_argument("--shape", choices=("polygon", "disc"), default="polygon",
                   help="the study's 120-gon (default) or an exact disc")
    p.add_argument("--step", type=float, default=1.0, help="theta step in degrees (default 1; theta from 4 to 89)")
    p.add_argument("--threads", type=int, default=None, help="worker threads (default: all cores)")


def run(args: argparse.Namespace) -> int:
    import restitution as rs
    from ..study import figures

    if not (0.0 < args.step <= 85.0):
        raise ValueError(f"require `--step` in (0, 85] degrees (found {args.step})")
    scene = rs.Scene.paper() if args.shape == "polygon" else rs.Scene.paper(shape=rs.Disc(r=0.01))
    theta = np.arange(4.0, 89.0 + 1e-9, args.step)
    mu = np.round(np.arange(0.0, 1.0 + 1e-9, 0.1), 10)
    start = time.perf_counter()
    df = rs.sweep(scene, theta_deg=theta, mu=mu, threads=args.threads)
    elapsed = time.perf_counter() - start
    args.out.mkdir(parents=True, exist_ok=True)
    parquet = args.out / "fig2.parquet"
    df.write_parquet(parquet)
    png = args.out / "fig2.png"
    figures.fig2(df, r=scene.r, v=scene.v, gamma=scene.gamma, path=png,
                 title=f"{args.shape}, paper preset (v = {scene.v} m/s, gamma = {scene.gamma})")
    worst = float(df["energy_residual"].abs().max())
    print(f"{df.height} impacts in {elapsed:.2f} s; |energy residual| <= {worst:.1e}")
    print(f"wrote {parquet} and {png}")
    return 0

