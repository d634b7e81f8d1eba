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
    plot(df, png, title=f"{args.shape}, paper preset (v = {scene.v} m/s, gamma = {scene.gamma})")
    worst = float(df["energy_residual"].abs().max())
    print(f"{df.height} impacts in {elapsed:.2f} s; |energy residual| <= {worst:.1e}")
    print(f"wrote {parquet} and {png}")
    return 0


def plot(df, path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mus = sorted(df["mu"].unique().to_list())
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.9, len(mus)))  # perceptually ordered, colourblind-safe
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), constrained_layout=True)
    for mu, colour in zip(mus, colours):
        part = df.filter(df["mu"] == mu).sort("theta_deg")
        for ax, col in zip(axes, ("e_n", "e_t", "e_kin")):
            ax.plot(part["theta_deg"], part[col], color=colour, label=f"mu = {mu:g}")
    for ax, label in zip(axes, ("normal restitution $e_N$", "tangential restitution $e_T$",
                                "kinematic restitution $e_{kin}$")):
        ax.set_xlabel(r"impact angle $\theta$ (deg from the plate)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle(title)
    fig.savefig(path, dpi=150)
    plt.close(fig)
