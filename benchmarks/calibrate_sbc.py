"""Issue 39, item 7: simulation-based calibration of rs.calibrate.fit (Talts et al. 2018).

Draws a truth from the prior, simulates noisy e_t at three sliding-branch angles of the default
disc (sigma 0.02), fits, and counts the replicates whose 90 % interval holds the truth; a right
sampler and likelihood give 90 % (binomial sd 3 % at 100 replicates) and ranks of the truth
among the draws spread uniformly. docs/model.md, section 18.8 quotes the result.

    python benchmarks/calibrate_sbc.py [--replicates 100] [--two]

``--two``: mu and gamma free, with e_n head-on measured too.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import polars as pl

import restitution as rs
from restitution.calibrate.sbc import sbc


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--replicates", type=int, default=100)
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--two", action="store_true")
    args = parser.parse_args()
    points = pl.DataFrame({"theta_deg": [10.0, 20.0, 30.0], "quantity": ["e_t"] * 3, "sigma": [0.02] * 3})
    free = {"mu": rs.Uniform(0.05, 0.3)}
    if args.two:
        points = pl.concat([points, pl.DataFrame({"theta_deg": [90.0], "quantity": ["e_n"], "sigma": [0.02]})])
        free["gamma"] = rs.Uniform(0.1, 1.0)
    t0 = time.perf_counter()
    result = sbc(rs.Scene(), points, free, replicates=args.replicates, seed=args.seed)
    for (name,), part in result.group_by("parameter", maintain_order=True):
        n, inside = part.height, int(part["inside"].sum())
        hist = np.histogram(part["rank"].to_numpy(), bins=5, range=(0.0, 1.0))[0]
        print(f"{name}: truth inside the 90 % interval in {inside}/{n} = {inside / n:.0%} "
              f"(binomial sd {math.sqrt(0.09 / n):.1%}); ranks in fifths {hist.tolist()}; "
              f"converged {int(part['converged'].sum())}/{n}")
    print(f"{args.replicates} replicates in {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
