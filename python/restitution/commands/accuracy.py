"""``restitution accuracy``: argument parsing for :mod:`restitution.study.accuracy` (error against
the reference integrator vs cost, per integrator, dt_factor or tol, and shape)."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

NAME = "accuracy"
HELP = ("error against the reference integrator vs cost, per integrator, dt_factor (gear5, verlet) or tol "
        "(adaptive) and shape: table + Pareto plot")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--out", type=Path, default=Path("results"), help="output folder (default: results)")
    p.add_argument("--quick", action="store_true", help="a small grid (seconds): 2 shapes, 2 steps or tolerances each")


def run(args: argparse.Namespace) -> int:
    from ..study.accuracy import TARGETS, markdown, recommend, write_study

    start = time.perf_counter()
    table, paths = write_study(args.out, quick=args.quick)
    print(markdown(table))
    for target in TARGETS:
        for shape, what in recommend(table, target).items():
            print(f"for {target:.0e} on the {shape}: use {what}")
    print(f"accuracy study: {table.height} configurations in {time.perf_counter() - start:.1f} s; "
          f"wrote {', '.join(str(p) for p in paths)}")
    return 0
